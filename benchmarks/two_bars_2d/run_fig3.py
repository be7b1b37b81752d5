#!/usr/bin/python3
"""Reproduce Fig. 3 of Vola, Pratt, Jean, Raous: the normal velocity at the
centre of the contact zone of both bars, 2D, nu = 0.45, for the three
theta-schemes (theta = 0.55).

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/two_bars_2d/run_fig3.py [--build build] [--out doc]

Velocities are normalised as in Fig. 2: (v - v0/2) / (v0/2), so that the
impacting bar goes 1 -> 0 -> -1 in the 1D solution (dotted). Runs plane
stress (the default .prm) and plane strain, prints the contact interval and
the errors against the 1D solution, and writes doc/fig3_two_bars_2d.png.
"""
import argparse
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEMES = [("theta", "θ-method"), ("theta-euler", "θ-Euler"),
           ("modified-theta", "modified θ")]
MODELS = [("plane stress", "plane stress"), ("plane strain", "plane strain")]


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    args = parser.parse_args()
    v0 = 5.13588
    fig, axes = plt.subplots(len(MODELS), len(SCHEMES), figsize=(13, 6.5),
                             sharex=True, sharey=True)
    print(f"{'model':13s} {'scheme':15s} {'contact from':>12s} {'to':>10s} "
          f"{'err_v(1D)':>9s} {'err_f(1D)':>9s} {'E_end/E_0':>9s}")
    with tempfile.TemporaryDirectory() as tmp:
        for row, (model, model_label) in enumerate(MODELS):
            for col, (scheme, label) in enumerate(SCHEMES):
                out = os.path.join(tmp, f"{row}_{scheme}")
                s = runs.run(args.build, "two_bars_2d",
                             "parameter_files/two_bars_2d.prm", out,
                             f"subsection Material\n  set Plane model = {model}\nend\n"
                             f"subsection Time stepping\n  set Scheme = {scheme}\nend\n")
                h = runs.read_columns(os.path.join(out, "history.csv"))
                t = [x * 1e3 for x in h["time"]]
                norm = lambda v: [(x - 0.5 * v0) / (0.5 * v0) for x in v]  # noqa: E731
                ax = axes[row][col]
                ax.plot(t, norm(h["exact_contact_velocity"]), "k:", lw=1,
                        label="1D exact, impacting bar")
                ax.plot(t, norm(h["contact_velocity"]), "b-", lw=1.3,
                        label="bar 1 (impacting)")
                ax.plot(t, norm(h["target_contact_velocity"]), "r--", lw=1.3,
                        label="bar 2")
                ax.set_title(f"{label}, {model_label}", fontsize=10)
                ax.grid(alpha=0.3)
                if row == len(MODELS) - 1:
                    ax.set_xlabel("time [ms]")
                if col == 0:
                    ax.set_ylabel("(v - v0/2) / (v0/2)")
                print(f"{model:13s} {scheme:15s} {s['first_contact']:12.4g} "
                      f"{s['last_contact']:10.4g} {s['err_v']:9.4f} "
                      f"{s['err_f']:9.4f} {s['energy_ratio']:9.4f}")
    axes[0][0].legend(fontsize=8, loc="lower left")
    fig.suptitle("Two bars in 2D, ν = 0.45, θ = 0.55: normal velocity at the "
                 "centre of the contact zone (paper Fig. 3)\n" +
                 runs.machine_and_commit(), fontsize=10)
    fig.tight_layout()
    os.makedirs(args.out, exist_ok=True)
    png = os.path.join(args.out, "fig3_two_bars_2d.png")
    fig.savefig(png, dpi=110)
    print("wrote", png)


if __name__ == "__main__":
    main()
