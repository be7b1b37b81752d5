#!/usr/bin/python3
"""Mesh convergence of hertz_impact (issue 12): the steel ball of
parameter_files/hertz_impact.prm on graded balls of decreasing cell size h
in the contact zone, against Hertz's closed forms (peak force, contact
duration, largest approach). The time step stays at 2.5e-7 s (150 steps in
contact): the resolution of the duration is one step, 0.7 %.

For the two finest meshes the first-order Richardson extrapolation
e(0) ~ 2 e(h) - e(2h) is printed too: it estimates what is left at h -> 0
(the model error: Hertz neglects the waves and a_max/R = 0.08).

With --block the same meshes of the ball fall on an elastic block
(hertz_on_block, node-to-face contact, the block's cells under the ball as
small as the ball's), with the block's top face as the master surface, with
the ball's curved lower half, and with both (two passes), against Hertz's
theory for two elastic bodies; it writes hertz_on_block_convergence.*
instead.

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/hertz_impact/run_hertz_study.py \
        [--build build] [--out doc] [--block]
Writes <out>/hertz_impact_convergence.png and .csv,
results/hertz_impact_study/summary.json and ends with a RESULT line.
"""
import argparse
import csv
import json
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRM = "parameter_files/hertz_impact.prm"
# (refinements, pole cell factor): the cell size in the contact zone is
# (pi/2) 2^-n gamma R, halved from one mesh to the next.
MESHES = [(2, 0.5), (3, 0.5), (3, 0.25), (4, 0.25)]
KEYS = ["peak_force_error", "contact_duration_error", "max_approach_error"]


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="doc")
    ap.add_argument("--block", action="store_true",
                    help="the ball on an elastic block (hertz_on_block)")
    a = ap.parse_args()
    program = "hertz_on_block" if a.block else "hertz_impact"
    prm = "parameter_files/hertz_on_block.prm" if a.block else PRM
    masters = ["block", "ball", "both"] if a.block else [None]
    work = tempfile.mkdtemp(prefix="hertz_")
    rows = []
    for (n, gamma), master in [(m, s) for m in MESHES for s in masters]:
        overrides = ("subsection Geometry\n"
                     f"  set Number of refinements = {n}\n"
                     f"  set Pole cell factor = {gamma}\n" +
                     (f"  set Master surface = {master}\n" if master else "") +
                     "end\n")
        s = runs.run(a.build, program, prm,
                     os.path.join(work, f"n{n}_g{gamma}_{master}"), overrides)
        h_over_a = (3.14159265 / 2) * 2 ** -n * gamma * 0.01 / \
            s["hertz_max_contact_radius"]
        cells = s["cells"] if not a.block else s["ball_cells"] + s["block_cells"]
        rows.append({"refinements": n, "pole_cell_factor": gamma,
                     **({"master": master} if master else {}),
                     "cells": int(cells), "h_over_a": h_over_a,
                     **{k: s[k] for k in KEYS},
                     "setup_seconds": s["setup_cpu_seconds"],
                     "loop_seconds": s["loop_cpu_seconds"],
                     "largest_lcp": s["lcp"]["largest_lcp"]})
        r = rows[-1]
        print(f"n={n} gamma={gamma}" + (f" master {master}" if master else "") +
              f": {r['cells']} cells, h/a_max = "
              f"{h_over_a:.3f}, errors: peak force {r[KEYS[0]]:+.4f}, "
              f"duration {r[KEYS[1]]:+.4f}, approach {r[KEYS[2]]:+.4f}; "
              f"CPU set-up {r['setup_seconds']:.2f} s, loop "
              f"{r['loop_seconds']:.2f} s, largest LCP {r['largest_lcp']}")
    # the two finest meshes of the first master (block, or the plane)
    finest = [r for r in rows if r.get("master") == masters[0]][-2:]
    extrapolated = {k: 2 * finest[-1][k] - finest[-2][k] for k in KEYS}
    print("Richardson (first order, two finest): " +
          ", ".join(f"{k} {v:+.4f}" for k, v in extrapolated.items()))

    os.makedirs(a.out, exist_ok=True)
    name = "hertz_on_block" if a.block else "hertz_impact"
    with open(os.path.join(a.out, f"{name}_convergence.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    fig, ax = plt.subplots(figsize=(6, 4.2))
    for master, style in zip(masters, ["-", "--", ":"]):
        sel = [r for r in rows if r.get("master") == master]
        h = [r["h_over_a"] for r in sel]
        for k, label, m in zip(KEYS, ["peak force", "contact duration",
                                      "largest approach"], "osd"):
            ax.loglog(h, [abs(r[k]) for r in sel], m + style,
                      label=label + (f", master {master}" if master else ""))
    h = [r["h_over_a"] for r in rows]
    ax.loglog([max(h), min(h)], [0.5 * abs(rows[0][KEYS[0]]),
                                 0.5 * abs(rows[0][KEYS[0]]) * min(h) / max(h)],
              "k:", label="slope 1")
    ax.set_xlabel("cell size in the contact zone / Hertz's a_max")
    ax.set_ylabel("|relative error| against Hertz")
    ax.set_title("Ball on an elastic block (node-to-face), Hertz impact"
                 if a.block else "Ball on a rigid plane, Hertz impact",
                 fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    fig.text(0.01, 0.01, runs.machine_and_commit(), fontsize=6)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, f"{name}_convergence.png"), dpi=120)

    os.makedirs(f"results/{name}_study", exist_ok=True)
    with open(f"results/{name}_study/summary.json", "w") as f:
        json.dump({"runs": rows, "richardson": extrapolated}, f, indent=2)
    fin = finest[-1]
    print(f"RESULT meshes={len(rows)} finest_cells={fin['cells']} "
          f"h_over_a={fin['h_over_a']:.3f} "
          f"peak_force_error={fin[KEYS[0]]:.4f} "
          f"duration_error={fin[KEYS[1]]:.4f} "
          f"approach_error={fin[KEYS[2]]:.4f} "
          f"richardson_peak_force_error={extrapolated[KEYS[0]]:.4f} "
          f"richardson_duration_error={extrapolated[KEYS[1]]:.4f} "
          f"seconds_finest={fin['setup_seconds'] + fin['loop_seconds']:.1f}")


if __name__ == "__main__":
    main()
