#!/usr/bin/python3
"""Reproduce Fig. 2 of Vola, Pratt, Jean, Raous: the contact velocity of the
1D two-bar impact with the four schemes and the exact solution.

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/two_bars_1d/run_fig2.py [--build build] [--out doc]

Runs build/bin/two_bars_1d on parameter_files/two_bars_1d*.prm (the paper's
Table 1 data), prints err_v, err_f, energy_ratio and the CPU seconds of the
time loop per scheme, and writes doc/fig2_two_bars_1d.png. The paper plots
the contact velocity in the centre-of-mass frame, normalised by v0/2: it goes
1 -> 0 -> -1. Here: (v_c - v0/2) / (v0/2) with v_c bar 1's contact node.
"""
import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEMES = [("theta", "theta-method, θ = 0.55", "two_bars_1d_theta.prm"),
           ("theta-euler", "θ-Euler, θ = 0.55", "two_bars_1d.prm"),
           ("modified-theta", "modified θ-method, θ = 0.55", "two_bars_1d_modified_theta.prm"),
           ("newmark", "Newmark, β = 1/4, γ = 1/2", "two_bars_1d_newmark.prm")]


def read_history(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    args = parser.parse_args()
    program = os.path.join(args.build, "bin", "two_bars_1d")
    if not os.path.exists(program):
        sys.exit(f"{program} not found: build first (see README.md)")

    results = {}
    with tempfile.TemporaryDirectory() as tmp:
        for scheme, label, prm in SCHEMES:
            out = os.path.join(tmp, scheme)
            wrapper = os.path.join(tmp, scheme + ".prm")
            with open(wrapper, "w") as f:
                f.write(f"include parameter_files/{prm}\n"
                        "subsection Output\n"
                        f"  set Output directory = {out}\n"
                        "  set VTU output = false\n  set Plot = false\nend\n")
            subprocess.run([program, wrapper], check=True, stdout=subprocess.DEVNULL)
            results[scheme] = (label, read_history(os.path.join(out, "history.csv")),
                               json.load(open(os.path.join(out, "summary.json"))))

    print(f"{'scheme':16s} {'err_v':>10s} {'err_f':>10s} {'energy_ratio':>13s} {'loop CPU s':>11s}")
    for scheme, (label, h, s) in results.items():
        print(f"{scheme:16s} {s['err_v']:10.4g} {s['err_f']:10.4g} "
              f"{s['energy_ratio']:13.4g} {s['loop_cpu_seconds']:11.3g}")

    fig, axes = plt.subplots(2, 2, figsize=(10, 6), sharex=True, sharey=True)
    for ax, (scheme, (label, h, s)) in zip(axes.flat, results.items()):
        v0 = h["contact_velocity"][0]
        t = [1e3 * x for x in h["time"]]
        normalise = lambda v: [(x - v0 / 2) / (v0 / 2) for x in v]  # noqa: E731
        ax.step(t, normalise(h["exact_contact_velocity"]), "k--", where="post",
                lw=1.2, label="exact")
        ax.plot(t, normalise(h["contact_velocity"]), "o-", ms=2.5, lw=1, label=label)
        ax.set_title(f"{label}: err_v = {s['err_v']:.3g}", fontsize=9)
        ax.grid(alpha=0.3)
        ax.set_ylim(-4.5, 4.5)
        ax.legend(fontsize=7, loc="lower left")
    for ax in axes[1]:
        ax.set_xlabel("time [ms]")
    for ax in axes[:, 0]:
        ax.set_ylabel("(v_c − v0/2) / (v0/2)")
    fig.suptitle("Two bars in 1D (paper Table 1, 20 P1 cells per bar): contact velocity, "
                 "centre-of-mass frame", fontsize=10)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    png = os.path.join(args.out, "fig2_two_bars_1d.png")
    fig.savefig(png, dpi=120)
    print(f"figure: {png}")


if __name__ == "__main__":
    main()
