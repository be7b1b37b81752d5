#!/usr/bin/python3
"""Reproduce Figs. 5 and 6 of Vola, Pratt, Jean, Raous: the frictionless
cylinder on a rigid plane (theta-Euler), deformed shapes at t = 0, 2.1,
3.3, 4.3 and the total contact force for h = 0.02 and h = 0.15.

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/cylinder_impact/run_fig5_fig6.py [--build build] [--out doc]

Prints, per time step: the contact interval, the peak force, the impulse
and its balance error, the energy ratio and the CPU seconds of the loop;
writes doc/fig5_cylinder_shapes.png and doc/fig6_cylinder_force.png.
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

PRM = "parameter_files/cylinder_impact.prm"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    caption = runs.machine_and_commit()
    histories, shapes = {}, None
    print(f"{'h':>6s} {'contact from':>12s} {'to':>6s} {'peak force':>10s} "
          f"{'impulse':>8s} {'balance err':>11s} {'E_end/E_0':>9s} {'loop CPU s':>10s}")
    with tempfile.TemporaryDirectory() as tmp:
        for h in (0.02, 0.15):
            out = os.path.join(tmp, f"h{h}")
            s = runs.run(args.build, "cylinder_impact", PRM, out,
                         f"subsection Time stepping\n  set Time step = {h}\nend\n")
            histories[h] = runs.read_columns(os.path.join(out, "history.csv"))
            if h == 0.02:
                shapes = runs.read_shapes(os.path.join(out, "shapes.csv"))
            print(f"{h:6.2f} {s['first_contact']:12.3f} {s['last_contact']:6.2f} "
                  f"{s['peak_normal_force']:10.2f} {s['normal_impulse']:8.2f} "
                  f"{s['checks']['impulse_balance_error']:11.1e} "
                  f"{s['energy_ratio']:9.4f} {s['loop_cpu_seconds']:10.3f}")

    fig, ax = plt.subplots(figsize=(7, 4.2))
    for h, style in ((0.02, "b-"), (0.15, "r--o")):
        ax.plot(histories[h]["time"], histories[h]["normal_force"], style,
                ms=3, lw=1.3, label=f"Δt = {h}")
    ax.set_xlabel("time")
    ax.set_ylabel("total contact force (per unit thickness)")
    ax.set_title("Cylinder on a rigid plane, θ-Euler (paper Fig. 6)\n" + caption,
                 fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend()
    fig.tight_layout()
    png6 = os.path.join(args.out, "fig6_cylinder_force.png")
    fig.savefig(png6, dpi=110)

    times = sorted(shapes)
    fig, axes = plt.subplots(1, len(times), figsize=(3.2 * len(times), 3.6),
                             sharey=True)
    for ax, t in zip(axes, times):
        for x0, y0, x1, y1 in shapes[t]:
            ax.plot([x0, x1], [y0, y1], "b-", lw=0.4)
        ax.axhline(0., color="k", lw=1.5)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t:.2f}", fontsize=10)
        ax.set_xlim(-11, 11)
        ax.set_ylim(-1, 22)
    fig.suptitle("Deformed shapes, Δt = 0.02, displacements to scale "
                 "(paper Fig. 5)", fontsize=10)
    fig.tight_layout()
    png5 = os.path.join(args.out, "fig5_cylinder_shapes.png")
    fig.savefig(png5, dpi=110)
    print("wrote", png5, "and", png6)


if __name__ == "__main__":
    main()
