#!/usr/bin/python3
"""Plot columns of an impactfe history.csv against time.

usage: plot_history.py HISTORY.csv OUT.png [--title T] COLUMN [COLUMN ...]

One panel per COLUMN; if the file also has `exact_<COLUMN>`, it is drawn
beside it as a dashed line. Uses Debian's python3-matplotlib.
"""
import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

LABELS = {
    "contact_velocity": "contact velocity [m/s]",
    "target_contact_velocity": "target contact velocity [m/s]",
    "normal_force": "normal contact force [N]",
    "tangential_force": "tangential contact force [N]",
    "kinetic_energy": "kinetic energy [J]",
    "elastic_energy": "elastic energy [J]",
    "length_mm": "length [mm]",
    "footprint_radius_mm": "footprint radius [mm]",
}


def read(path):
    with open(path, newline="") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], rows[1:]
    return {name: [float(r[i]) for r in data] for i, name in enumerate(header)}


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("history")
    parser.add_argument("png")
    parser.add_argument("--title", default="")
    parser.add_argument("columns", nargs="+")
    args = parser.parse_args()

    data = read(args.history)
    missing = [c for c in args.columns if c not in data]
    if missing:
        sys.exit(f"{args.history}: no column(s) {', '.join(missing)}")
    fig, axes = plt.subplots(len(args.columns), 1, sharex=True,
                             figsize=(7, 2.6 * len(args.columns)), squeeze=False)
    t = data["time"]
    for ax, column in zip(axes[:, 0], args.columns):
        ax.plot(t, data[column], "o-", ms=2.5, lw=1, label="computed")
        exact = "exact_" + column
        if exact in data:
            ax.step(t, data[exact], "k--", lw=1, where="post", label="exact")
        ax.set_ylabel(LABELS.get(column, column))
        ax.grid(alpha=0.3)
        ax.legend(loc="best", fontsize=8)
    axes[-1, 0].set_xlabel("time [s]")
    if args.title:
        fig.suptitle(args.title)
    fig.tight_layout()
    fig.savefig(args.png, dpi=120)


if __name__ == "__main__":
    main()
