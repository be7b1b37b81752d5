#!/usr/bin/python3
"""Reproduce Figs. 8 and 9 of Vola, Pratt, Jean, Raous: the oblique impact
of a plate with a round side (mu = 0.1, modified theta, theta = 0.55):
nodal normal reactions against time, deformed shapes at t = 1e-3, 2e-3,
2.25e-3 s, and the stick/slip state of each contact node over time.

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/oblique_plate/run_fig8_fig9.py [--build build] [--out doc]

Prints the contact interval, peak force, normal and tangential impulses,
the impulse-balance error and the final velocity; writes
doc/fig8_plate_reactions.png, doc/fig9_plate_shapes.png and
doc/plate_stick_slip.png.
"""
import argparse
import csv
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
from matplotlib.colors import ListedColormap  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

PRM = "parameter_files/oblique_plate.prm"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)
    caption = runs.machine_and_commit()
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "plate")
        s = runs.run(args.build, "oblique_plate", PRM, out)
        nodes = {}
        with open(os.path.join(out, "contact_nodes.csv"), newline="") as f:
            for r in csv.DictReader(f):
                nodes.setdefault(float(r["x"]), []).append(
                    (float(r["time"]), float(r["normal_force"]), int(r["state"])))
        shapes = runs.read_shapes(os.path.join(out, "shapes.csv"))
    print(f"contact from {s['first_contact']:.3g} s to {s['last_contact']:.4g} s, "
          f"peak total normal force {s['peak_normal_force']:.4g} N")
    print(f"normal impulse {s['normal_impulse']:.5g} N s, tangential "
          f"{s['tangential_impulse']:.5g} N s (ratio "
          f"{s['tangential_impulse'] / s['normal_impulse']:.4f})")
    print(f"impulse balance error {s['checks']['impulse_balance_error']:.1e}, "
          f"Coulomb excess {s['checks']['coulomb_excess']:.1e}, "
          f"final velocity ({s['final_velocity_x']:.4f}, "
          f"{s['final_velocity_y']:.4f}) m/s, energy ratio {s['energy_ratio']:.4f}")

    xs = sorted(nodes)
    fig, ax = plt.subplots(figsize=(7.5, 4.5))
    cmap = plt.get_cmap("viridis")
    for i, x in enumerate(xs):
        t = [r[0] * 1e3 for r in nodes[x]]
        f = [r[1] for r in nodes[x]]
        ax.plot(t, f, color=cmap(i / max(1, len(xs) - 1)), lw=1.2,
                label=f"x0 = {x * 1e3:+.0f} mm")
    ax.set_xlabel("time [ms]")
    ax.set_ylabel("nodal normal reaction [N]")
    ax.set_title("Oblique plate, μ = 0.1, modified θ (θ = 0.55): nodal normal "
                 "reactions (paper Fig. 8)\n" + caption, fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "fig8_plate_reactions.png"), dpi=110)

    times = [t for t in sorted(shapes) if t > 0.] or sorted(shapes)
    fig, axes = plt.subplots(1, len(times), figsize=(3.6 * len(times), 3.2),
                             sharey=True)
    for ax, t in zip(axes, times):
        for x0, y0, x1, y1 in shapes[0.0] if 0.0 in shapes else []:
            ax.plot([x0 * 1e3, x1 * 1e3], [y0 * 1e3, y1 * 1e3], color="0.8", lw=0.4)
        for x0, y0, x1, y1 in shapes[t]:
            ax.plot([x0 * 1e3, x1 * 1e3], [y0 * 1e3, y1 * 1e3], "b-", lw=0.6)
        ax.axhline(0., color="k", lw=1.5)
        ax.set_aspect("equal")
        ax.set_title(f"t = {t * 1e3:.2f} ms", fontsize=10)
        ax.set_xlabel("x [mm]")
    axes[0].set_ylabel("y [mm]")
    fig.suptitle("Deformed shapes (grey: t = 0), to scale (paper Fig. 9)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "fig9_plate_shapes.png"), dpi=110)

    fig, ax = plt.subplots(figsize=(7.5, 3.6))
    t_all = [r[0] * 1e3 for r in nodes[xs[0]]]
    grid = [[r[2] for r in nodes[x]] for x in xs]
    ax.imshow(grid, aspect="auto", origin="lower", interpolation="nearest",
              cmap=ListedColormap(["white", "tab:green", "tab:red"]), vmin=0, vmax=2,
              extent=[t_all[0], t_all[-1], -0.5, len(xs) - 0.5])
    ax.set_yticks(range(len(xs)))
    ax.set_yticklabels([f"{x * 1e3:+.0f}" for x in xs], fontsize=7)
    ax.set_ylabel("node x0 [mm]")
    ax.set_xlabel("time [ms]")
    ax.set_title("Contact state of each node: white open, green stick, red slip",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "plate_stick_slip.png"), dpi=110)
    print("wrote fig8_plate_reactions.png, fig9_plate_shapes.png, "
          "plate_stick_slip.png in", args.out)


if __name__ == "__main__":
    main()
