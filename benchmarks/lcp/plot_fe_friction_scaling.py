#!/usr/bin/env python3
"""Plot the output of fe_friction_scaling (CSV) into doc/lcp_scaling.png and
print the Markdown table of doc/lcp.md.

    python3 benchmarks/lcp/plot_fe_friction_scaling.py results.csv [doc/lcp_scaling.png]

Per n_c, the steps from the second on are averaged (the first step has no
previous states to start from). Cold: Lemke's method on the Klarbring form
from the all-slack basis. Warm: block pivoting from the previous step's
contact states (Lemke only if it gives up), counted in linear solves plus
Lemke pivots.
"""
import csv
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def mean(values):
    return sum(values) / len(values) if values else float("nan")


def main():
    if len(sys.argv) < 2:
        print(__doc__)
        return 2
    csv_file = sys.argv[1]
    png_file = sys.argv[2] if len(sys.argv) > 2 else "doc/lcp_scaling.png"

    rows = defaultdict(list)
    with open(csv_file) as f:
        # the program ends with a "RESULT key=value ..." line: not a CSV row
        lines = [line for line in f if not line.startswith("RESULT")]
        for r in csv.DictReader(lines):
            if int(r["step"]) >= 2:
                rows[int(r["n_contacts"])].append(r)

    table = []
    for nc in sorted(rows):
        rs = rows[nc]
        cold = [r for r in rs if r["cold_pivots"] != ""]
        table.append(
            dict(
                nc=nc,
                size=int(rs[0]["lcp_size"]),
                setup=float(rs[0]["setup_seconds"]),
                cold_pivots=mean([float(r["cold_pivots"]) for r in cold]),
                cold_seconds=mean([float(r["cold_seconds"]) for r in cold]),
                n_cold=len(cold),
                warm_solves=mean([float(r["warm_block_iterations"]) for r in rs]),
                warm_pivots=mean([float(r["warm_pivots"]) for r in rs]),
                warm_seconds=mean([float(r["warm_seconds"]) for r in rs]),
                open_solves=mean([float(r["open_start_block_iterations"]) for r in rs]),
                open_pivots=mean([float(r["open_start_pivots"]) for r in rs]),
                open_seconds=mean([float(r["open_start_seconds"]) for r in rs]),
                cold_assembly=mean([float(r["cold_assembly_seconds"]) for r in cold]),
                paths=sorted(set(r["warm_path"] for r in rs)),
                states="/".join(
                    str(round(mean([float(r[k]) for r in rs]))) for k in ("open", "stick", "slip")
                ),
                diff=max([float(r["relative_difference"]) for r in cold] or [float("nan")]),
                steps=len(rs),
            )
        )

    print(
        "| n_c | LCP size (Klarbring) | open/stick/slip | cold pivots | cold s (assembly) | "
        "warm solves + pivots | warm s | all-open solves + pivots | all-open s | "
        "max rel. diff P | set-up s |"
    )
    print("|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    for t in table:
        print(
            f"| {t['nc']} | {t['size']} | {t['states']} | {t['cold_pivots']:.0f} | "
            f"{t['cold_seconds']:.3g} ({t['cold_assembly']:.2g}) | "
            f"{t['warm_solves']:.1f} + {t['warm_pivots']:.0f} | {t['warm_seconds']:.3g} | "
            f"{t['open_solves']:.1f} + {t['open_pivots']:.0f} | {t['open_seconds']:.3g} | "
            f"{t['diff']:.1e} | {t['setup']:.2g} |"
        )
    print("warm paths:", {t["nc"]: t["paths"] for t in table})

    nc = [t["nc"] for t in table]
    fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
    ax1.loglog(nc, [t["cold_pivots"] for t in table], "o-", label="cold: Lemke pivots")
    ax1.loglog(
        nc,
        [t["warm_solves"] + t["warm_pivots"] for t in table],
        "s-",
        label="warm: block pivoting solves + Lemke pivots",
    )
    ax1.loglog(
        nc,
        [t["open_solves"] + t["open_pivots"] for t in table],
        "^--",
        label="no history (all open): solves + Lemke pivots",
    )
    ax1.set_xlabel("contacts $n_c$")
    ax1.set_ylabel("pivots / linear solves per step")
    ax2.loglog(nc, [t["cold_seconds"] for t in table], "o-", label="cold (Lemke, Klarbring form)")
    ax2.loglog(nc, [t["warm_seconds"] for t in table], "s-", label="warm (contact states of the previous step)")
    ax2.loglog(nc, [t["open_seconds"] for t in table], "^--", label="no history (block pivoting from all open)")
    ax2.axhline(1.0, color="gray", lw=0.8, ls="--")
    ax2.set_xlabel("contacts $n_c$")
    ax2.set_ylabel("seconds per step (one core)")
    for ax in (ax1, ax2):
        ax.axvline(700, color="k", lw=0.8, ls=":")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    near = min(table, key=lambda t: abs(t["nc"] - 700))
    ax2.annotate(
        f"n_c = {near['nc']}: cold {near['cold_seconds']:.2g} s, warm {near['warm_seconds']:.2g} s",
        xy=(near["nc"], near["warm_seconds"]),
        xytext=(0.35, 0.08),
        textcoords="axes fraction",
        fontsize=8,
        arrowprops=dict(arrowstyle="->", lw=0.6),
    )
    fig.suptitle(
        "2D frictional contact LCP on FE Delassus operators (block on a rigid plane, $\\mu$ = 0.3)",
        fontsize=10,
    )
    fig.tight_layout()
    fig.savefig(png_file, dpi=120)
    print(f"\nwrote {png_file}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
