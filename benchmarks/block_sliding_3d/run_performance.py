#!/usr/bin/python3
"""The 3D performance scene of issue 12: a cube of n^3 Q1 cells (0.1 m, the
material and loads of parameter_files/block_sliding_3d.prm) sliding on a
rigid plane with Coulomb friction (mu = 0.5), every node of the bottom face
a frictional contact, with the exact circular cone and with the polygonal
cone of 8 facets. The active set method solves
each step, with W x either as a dense product with the Schur complement of
M~ on the contact DoFs (the default where it pays off) or as a sparse solve
pair ('Dense Schur complement = false'); both answers pass the same
verification. The cost of a step is split into free velocity, contact
problem and update (the program's `Print performance data`), and the
once-only costs into the factorisation of M~ and the Delassus operator (here
the dense Schur complement).

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/block_sliding_3d/run_performance.py \
        [--build build] [--out doc] [--quick] [--large]
--quick runs n = 16 and 24 only; --large adds n = 40 (1681 contacts,
206763 DoFs). Writes <out>/block_sliding_3d_performance.{csv,png},
results/block_sliding_3d_performance/summary.json, and ends with a RESULT
line for the largest dense case. Not a test: timings depend on the machine.
"""
import argparse
import csv
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRM = "parameter_files/block_sliding_3d.prm"
TIME_STEP = 5e-4  # [s], the default file's
FACETS = 8
FIELDS = ["cells_per_edge", "cone", "products", "dofs", "contacts", "steps",
          "seconds_per_step", "free_velocity_per_step", "lcp_per_step",
          "update_per_step", "factorization_seconds", "delassus_seconds",
          "active_set_iterations_per_step", "gmres_iterations_per_step",
          "largest_violation", "largest_cone_error", "fallbacks",
          "impulse_balance_error", "distance_error", "returncode"]


def overrides(n, steps, dense, cone, height=0.1, cells_up=None):
    """The block as n x cells_up x n cells (a cube of n^3 by default) of
    0.1 m x height x 0.1 m; also used by run_contact_scaling_3d.py."""
    return ("subsection Geometry\n"
            f"  set Length = 0.1\n  set Height = {height}\n  set Width = 0.1\n"
            f"  set Number of cells along x = {n}\n"
            f"  set Number of cells up = {cells_up or n}\n"
            f"  set Number of cells along z = {n}\nend\n"
            "subsection Time stepping\n"
            f"  set End time = {steps * TIME_STEP}\nend\n"
            "subsection Contact solver\n"
            f"  set Friction cone = {cone}\n  set Number of facets = {FACETS}\n"
            "  set Method = active set\n"
            f"  set Dense Schur complement = {'true' if dense else 'false'}\n"
            "end\n"
            "subsection Output\n  set Print performance data = true\nend\n"
            # the polygon turns the block towards a vertex direction: the
            # rigid block's circular-cone distance is not its reference
            + ("subsection Verification\n"
               "  set Maximum sliding distance error = 0.5\nend\n"
               if cone == "facets" else ""))


def measure(build, n, steps, dense, cone="exact"):
    out_dir = os.path.join("results", "block_sliding_3d_performance",
                           f"n{n}_{cone}_{'dense' if dense else 'sparse'}")
    r = runs.run_measured(build, "block_sliding_3d", os.path.abspath(PRM),
                          out_dir, overrides(n, steps, dense, cone))
    s = r["summary"]
    if r["returncode"] != 0 or s is None:
        sys.exit(f"n = {n}: block_sliding_3d failed: {r['message']}")
    cost, lcp = s["cost"], s["lcp"]
    used_dense = bool(lcp.get("active_set_dense_schur_complement", 0))
    if used_dense != dense:
        sys.exit(f"n = {n}: asked for dense = {dense}, the run used {used_dense}")
    return {"cells_per_edge": n,
            "cone": cone if cone == "exact" else f"{FACETS} facets",
            "products": "dense Schur" if dense else "sparse solves",
            "dofs": 3 * s["nodes"], "contacts": s["contact_candidates"],
            "steps": s["n_steps"],
            "seconds_per_step": cost["free_velocity_per_step"] +
            cost["lcp_per_step"] + cost["update_per_step"],
            "free_velocity_per_step": cost["free_velocity_per_step"],
            "lcp_per_step": cost["lcp_per_step"],
            "update_per_step": cost["update_per_step"],
            "factorization_seconds": cost["factorization_seconds"],
            "delassus_seconds": cost["delassus_seconds"],
            "active_set_iterations_per_step":
            lcp["active_set_iterations"] / s["n_steps"],
            "gmres_iterations_per_step":
            lcp["active_set_gmres_iterations"] / s["n_steps"],
            "largest_violation": lcp["active_set_largest_violation"],
            "largest_cone_error": lcp["active_set_largest_cone_error"],
            "fallbacks": lcp["active_set_fallbacks"],
            "impulse_balance_error": s["checks"]["impulse_balance_error"],
            "distance_error": s["sliding"]["distance_error"],
            "returncode": r["returncode"]}


def plot(rows, path):
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.2))
    for products, cone, marker in (("dense Schur", "exact", "o"),
                                   ("dense Schur", f"{FACETS} facets", "^"),
                                   ("sparse solves", "exact", "s")):
        sel = [r for r in rows
               if r["products"] == products and r["cone"] == cone]
        if not sel:
            continue
        x = [r["contacts"] for r in sel]
        left.loglog(x, [r["seconds_per_step"] for r in sel], marker + "-",
                    label=f"step, {cone} cone, W x by {products}")
        if products == "dense Schur" and cone == "exact":
            left.loglog(x, [r["lcp_per_step"] for r in sel], marker + ":",
                        label="contact problem (dense)")
            left.loglog(x, [r["free_velocity_per_step"] for r in sel],
                        marker + "--", label="free velocity (one solve pair)")
        if cone == "exact":
            right.loglog(x, [r["factorization_seconds"] + r["delassus_seconds"]
                             for r in sel], marker + "-",
                         label=f"set-up, {products}")
    left.axhline(1.0, color="grey", lw=0.8)
    left.text(left.get_xlim()[0] * 1.05, 1.05, "1 s per step (issue 12)",
              fontsize=8, color="grey")
    left.set_xlabel("frictional contacts")
    left.set_ylabel("CPU seconds per step")
    left.legend(fontsize=8)
    right.set_xlabel("frictional contacts")
    right.set_ylabel("CPU seconds once: factorisation + Delassus")
    right.legend(fontsize=8)
    for ax, r in ((left, rows), (right, rows)):
        for row in r:
            if row["products"] == "dense Schur" and row["cone"] == "exact":
                ax.annotate(f"{row['dofs']} DoFs", (row["contacts"],
                            row["seconds_per_step"] if ax is left else
                            row["factorization_seconds"] +
                            row["delassus_seconds"]),
                            fontsize=7, textcoords="offset points",
                            xytext=(4, -10))
    fig.suptitle("Cube of n^3 Q1 cells sliding on a plane, mu = 0.5, "
                 f"exact and {FACETS}-facet cones, active set method\n" + runs.machine_and_commit(),
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--large", action="store_true")
    args = parser.parse_args()

    sizes = [16, 24] if args.quick else [16, 24, 32] + ([40] if args.large else [])
    rows = []
    for n in sizes:
        rows.append(measure(args.build, n, 20, True))
        print(rows[-1], flush=True)
        rows.append(measure(args.build, n, 20, True, "facets"))
        print(rows[-1], flush=True)
        # The sparse products take seconds per step at n = 32: fewer steps.
        rows.append(measure(args.build, n, 20 if n < 32 else 6, False))
        print(rows[-1], flush=True)

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "block_sliding_3d_performance.csv"),
              "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, os.path.join(args.out, "block_sliding_3d_performance.png"))

    print(f"{'n':>3} {'cone':>8} {'products':>14} {'DoFs':>7} {'contacts':>8} "
          f"{'s/step':>8} {'free':>7} {'contact':>8} {'update':>7} "
          f"{'set-up':>7} {'cone err':>9}")
    for r in rows:
        print(f"{r['cells_per_edge']:>3} {r['cone']:>8} {r['products']:>14} {r['dofs']:>7} "
              f"{r['contacts']:>8} {r['seconds_per_step']:>8.3f} "
              f"{r['free_velocity_per_step']:>7.3f} {r['lcp_per_step']:>8.3f} "
              f"{r['update_per_step']:>7.4f} "
              f"{r['factorization_seconds'] + r['delassus_seconds']:>7.1f} "
              f"{r['largest_cone_error']:>9.1e}")

    largest = max((r for r in rows if r["products"] == "dense Schur" and
                   r["cone"] == "exact"), key=lambda r: r["contacts"])
    polygonal = max((r for r in rows if r["cone"] != "exact"),
                    key=lambda r: r["contacts"])
    summary_dir = os.path.join("results", "block_sliding_3d_performance")
    with open(os.path.join(summary_dir, "summary.json"), "w") as f:
        json.dump({"machine": runs.machine_and_commit(), "runs": rows,
                   "largest": largest}, f, indent=1)
    print(f"RESULT contacts={largest['contacts']} dofs={largest['dofs']} "
          f"ranks=1 seconds_per_step={largest['seconds_per_step']:.3g} "
          f"cone=exact cone_error={largest['largest_cone_error']:.2g} "
          f"lcp_relative_error={largest['largest_violation']:.2g} "
          f"fallbacks={largest['fallbacks']} "
          f"facets{FACETS}_seconds_per_step={polygonal['seconds_per_step']:.3g} "
          f"facets{FACETS}_fallbacks={polygonal['fallbacks']} "
          f"setup_seconds={largest['factorization_seconds'] + largest['delassus_seconds']:.3g}")


if __name__ == "__main__":
    main()
