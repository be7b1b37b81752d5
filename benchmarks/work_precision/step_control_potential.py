#!/usr/bin/python3
"""Does time-step control near impacts pay? (issue 16)

A step control that refines the step around the closing and opening of
contacts can at best remove the error made in those windows, and a control
that coarsens the step in free flight can at best save the steps made there.
This script measures both bounds on the runs of the work-precision grid
(run_work_precision.py first; it reads <runs>/<benchmark>/<run>/history.csv
and summary.json, nothing is run here):

1. 1D bars (exact solution): the integral in time of |v_c - v_exact| inside
   windows of +-2 dx/c around the closing (t = 0) and the opening
   (t = 2L/c) and outside them, at a fixed mesh for every Courant number.
   If the window part shrinks when h shrinks, refining h there pays.
2. 2D scenes (fine reference): the share of the L1 force error (against the
   reference) made within +-2 steps of a change of the number of active
   contacts, and the share of steps made with no contact at all (what
   coarse free-flight steps could save at most).

usage: /usr/bin/python3 benchmarks/work_precision/step_control_potential.py
           [--runs results/work_precision/runs] [--out results/step_control]
Writes <out>/summary.json and ends with a RESULT line.
"""
import argparse
import csv
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(HERE, ".."))
from common import runs  # noqa: E402
sys.path.insert(0, HERE)
import run_work_precision as work_precision  # noqa: E402  (err_force's norm)


def history(run_dir):
    path = os.path.join(run_dir, "history.csv")
    if not os.path.exists(path):
        return None
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}


def bars_1d(runs_dir, schemes, meshes, courants):
    """Window and outside parts of the err_v integral (both / (v0/2 T))."""
    prm = os.path.join(TOP, "parameter_files/two_bars_1d.prm")
    values = {}
    for line in open(prm):
        parts = line.split("#")[0].split("=")
        if len(parts) == 2 and parts[0].strip().startswith("set "):
            values[parts[0].strip()[4:].strip()] = parts[1].strip()
    E = float(values["Young's modulus"])
    rho = float(values["Density"])
    L = float(values["Bar length"])
    c = math.sqrt(E / rho)
    t_open = 2 * L / c
    table = []
    for scheme in schemes:
        for cells in meshes:
            for C in courants:
                h = history(os.path.join(runs_dir, "two_bars_1d", f"{scheme}_{cells}_{C}"))
                if h is None:
                    continue
                t, dt = h["time"][1:], np.diff(h["time"])
                v0_half = h["exact_contact_velocity"][0]
                err = np.abs(h["contact_velocity"] - h["exact_contact_velocity"])[1:]
                half_width = 2 * (L / cells) / c
                window = (np.abs(t) <= half_width) | (np.abs(t - t_open) <= half_width)
                T = h["time"][-1]
                table.append({"scheme": scheme, "cells": cells, "courant": float(C),
                              "time_step": float(dt[0]),
                              "err_v": float(err.mean() / v0_half),
                              "window": float((err * dt)[window].sum() / (v0_half * T)),
                              "outside": float((err * dt)[~window].sum() / (v0_half * T))})
    return table


def scene_2d(runs_dir, name, tags, reference_tag):
    """Shares of the L1 force error near contact changes, and free steps."""
    ref = history(os.path.join(runs_dir, name, reference_tag))
    if ref is None:
        return []
    table = []
    for tag in tags:
        h = history(os.path.join(runs_dir, name, tag))
        if h is None:
            continue
        t, f, active = h["time"], h["normal_force"], h["active_contacts"]
        grid = np.union1d(t, ref["time"])
        grid = grid[grid <= t[-1] * (1 + 1e-12)]
        mid = 0.5 * (grid[1:] + grid[:-1])
        index = np.minimum(np.searchsorted(t, mid), len(t) - 1)
        fa = f[index]
        fb = ref["normal_force"][np.minimum(np.searchsorted(ref["time"], mid),
                                            len(ref["time"]) - 1)]
        density = np.abs(fa - fb) * np.diff(grid)
        changes = np.nonzero(np.diff(active) != 0)[0] + 1  # row of the new count
        near = np.zeros(len(t), bool)
        for i in changes:
            near[max(i - 2, 0):min(i + 3, len(t))] = True
        norm = work_precision.reference_impulse((ref["time"], ref["normal_force"]))
        table.append({"scene": name, "run": tag, "steps": len(t) - 1,
                      "err_force": float(density.sum() / norm),
                      "err_force_near_changes": float(density[near[index]].sum() / norm),
                      "contact_changes": int(len(changes)),
                      "steps_near_changes": int(near[1:].sum()),
                      "error_share_near_changes":
                          float(density[near[index]].sum() / density.sum()),
                      "steps_without_contact": int((active[1:] == 0).sum())})
    return table


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--runs", default=os.path.join(TOP, "results/work_precision/runs"))
    parser.add_argument("--out", default=os.path.join(TOP, "results/step_control"))
    args = parser.parse_args()
    os.makedirs(args.out, exist_ok=True)

    bars = bars_1d(args.runs, ["theta+mr_0.51", "modified-theta_0.55", "theta_0.55"],
                   [40, 160, 640], ["4.0", "2.0", "0.9", "0.5", "0.25"])
    if not bars:
        sys.exit(f"no 1D runs under {args.runs}: run run_work_precision.py first")
    print("1D bars: err_v integral inside +-2 dx/c of the closing and the opening, "
          "and outside (both relative to v0/2 x T)")
    print(f"{'scheme':22s} {'cells':>5s} {'C':>5s} {'err_v':>8s} {'window':>8s} "
          f"{'outside':>8s}")
    for r in bars:
        print(f"{r['scheme']:22s} {r['cells']:5d} {r['courant']:5.2f} {r['err_v']:8.4f} "
              f"{r['window']:8.4f} {r['outside']:8.4f}")
    # At each scheme and mesh: the best Courant number, and what halving h
    # from it does to the window part.
    halving = []
    for scheme in sorted({r["scheme"] for r in bars}):
        for cells in sorted({r["cells"] for r in bars}):
            line = sorted((r for r in bars if r["scheme"] == scheme and r["cells"] == cells),
                          key=lambda r: -r["courant"])
            if len(line) < 2:
                continue
            best = min(range(len(line)), key=lambda i: line[i]["err_v"])
            if best + 1 < len(line):
                a, b = line[best], line[best + 1]
                halving.append({"scheme": scheme, "cells": cells,
                                "best_courant": a["courant"],
                                "window_share": a["window"] / (a["window"] + a["outside"]),
                                "window_change_when_h_halved": b["window"] / a["window"] - 1.,
                                "err_v_change_when_h_halved": b["err_v"] / a["err_v"] - 1.})
    print("\nFrom the best Courant number of each line, h halved:")
    for r in halving:
        print(f"  {r['scheme']:22s} {r['cells']:5d} cells: best C = {r['best_courant']:.2f}, "
              f"window share {r['window_share']:.2f}, window part "
              f"{100 * r['window_change_when_h_halved']:+.0f} %, err_v "
              f"{100 * r['err_v_change_when_h_halved']:+.0f} %")

    scenes = []
    for name, meshes, factors, reference in (
            ("bars2d", ["20x4", "80x16"], [1, 0.25], "reference"),
            ("cylinder", ["12x9", "24x18"], [1, 0.5], "reference"),
            ("plate", ["10x8", "40x32"], [1, 2], "reference")):
        tags = [f"{s}_{m}_{f}" for s in ("modified-theta_0.55", "theta+mr_0.51")
                for m in meshes for f in factors]
        scenes += scene_2d(args.runs, name, tags, reference)
    if scenes:
        print("\n2D scenes: share of the L1 force error (against the fine reference) "
              "made within +-2 steps of a change of the active contacts; steps "
              "without contact")
        for r in scenes:
            print(f"  {r['scene']:8s} {r['run']:30s} err_force {r['err_force']:.4f} "
                  f"(near changes {r['err_force_near_changes']:.4f}), {r['steps']:5d} steps, "
                  f"{r['contact_changes']:4d} changes, {r['steps_near_changes']:5d} steps "
                  f"near them: {100 * r['error_share_near_changes']:5.1f} % of the error; "
                  f"{r['steps_without_contact']:5d} steps without contact")

    summary = {"machine_and_commit": runs.machine_and_commit(), "bars_1d": bars,
               "bars_1d_h_halved": halving, "scenes_2d": scenes}
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    worst = max((r["window_change_when_h_halved"] for r in halving), default=float("nan"))
    best = min((r["window_change_when_h_halved"] for r in halving), default=float("nan"))
    share = max((r["window_share"] for r in halving), default=float("nan"))
    free = max((r["steps_without_contact"] / r["steps"] for r in scenes), default=float("nan"))
    print(f"\nsummary: {os.path.join(args.out, 'summary.json')}")
    print(f"RESULT lines_1d={len(halving)} max_window_share_1d={share:.3f} "
          f"window_change_h_halved_min={best:+.3f} window_change_h_halved_max={worst:+.3f} "
          f"max_free_step_share_2d={free:.3f}")


if __name__ == "__main__":
    main()
