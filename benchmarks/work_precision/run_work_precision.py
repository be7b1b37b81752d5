#!/usr/bin/python3
"""Work-precision benchmark: error against CPU seconds for the four time
schemes (θ-method at θ = 0.5 and 0.55, θ-Euler, modified θ, Newmark, and
the mass-redistribution variants) on the 1D two-bar impact, the two bars in
2D, the cylinder on a plane and the oblique plate.

usage (from anywhere; the script works from the repository top):
    /usr/bin/python3 benchmarks/work_precision/run_work_precision.py \
        [--build build] [--out doc] [--quick] [--only 1d,bars2d,cylinder,plate]
        [--plot-only] [--rescore] [--repeats 3] [--repeat-below 0.2]
        [--extend-budget 120]

--build DIR      executables DIR/bin/<program>; if DIR/lib exists it is put
                 in LD_LIBRARY_PATH (a copy of a build, e.g. /work/snap)
--quick          a small grid (< 1 min); writes to results/work_precision_quick
                 unless --out is given
--only           run only these benchmarks (the others' CSVs in --out are kept
                 and still plotted)
--plot-only      no runs: redraw the figures and the tables of
                 <out>/work_precision.md from the CSVs in <out>
--rescore        2D: no runs; the errors of the CSVs' rows computed again
                 from the run files in --runs, then --plot-only

What is measured (see benchmarks/work_precision/README.md):
- cpu_run_seconds: user + system CPU of the whole process, from
  getrusage(RUSAGE_CHILDREN) around the subprocess (includes loading the
  libraries and MPI, ~0.3-0.5 s);
- cpu_loop_seconds: the program's own CPU clock around the time loop
  (summary.json), without the output;
- cheap runs (loop < --repeat-below, default 0.2 s) are repeated (best
  of --repeats) and the
  smallest of each CPU figure is kept; all schemes at one grid point (mesh
  and step) run in turn, round after round, so that they share the
  machine's state (measured_runs).
Errors: 1D err_v, err_f, energy_ratio from summary.json (the program's
definitions against the exact solution). 2D: err_force = the L1 norm in time
of the total normal contact force minus that of a fine reference run,
divided by the reference's total normal impulse (a relative L1 error),
with the force of each step its momentum-changing impulse / h
(step_force(): the history's column for the θ-schemes, the θ- or γ-weighted
mean of its end-of-step values with mass redistribution and for Newmark).

Run files go to results/work_precision/ (git-ignored); the CSV, PNG and the
generated part of work_precision.md go to --out (default doc). Every
invocation (--plot-only too) ends with summary.json beside the run folder
(results/work_precision/summary.json) and one line `RESULT program=...
<scene>_leader=... <scene>_budgets_won=... <scene>_budgets_lost=...
<scene>_largest_loss=... <scene>_failed_runs=...`: per scene, the variant
that wins most of the 41 budgets of equal loop CPU, and how much it loses
elsewhere (relative error excess).
"""
import argparse
import csv
import datetime
import json
import math
import os
import re
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
import runs  # noqa: E402

import numpy as np  # noqa: E402
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

# The schemes: (scheme entry, theta or None for Newmark, label).
# A scheme entry "<scheme>+mr" runs <scheme> with `Mass redistribution =
# true` (the contact nodes carry no mass, ElasticBody::redistribute_mass()),
# "<scheme>+ff<k>" with `Free-flight step factor = k` (steps in which no
# contact can act are k h long); "+mr+ff<k>" both. "<scheme>+courant" runs
# <scheme> with `Theta rule = courant`: its "theta" is then kappa (`Theta
# damping`), and each run's theta is 1/2 + kappa / C (C the mesh's Courant
# number, summary.json's "theta").
SCHEMES = [("theta", 0.5, "θ-method, θ = 0.5"),
           ("theta", 0.55, "θ-method, θ = 0.55"),
           ("theta-euler", 0.55, "θ-Euler, θ = 0.55"),
           ("modified-theta", 0.55, "modified θ, θ = 0.55"),
           ("newmark", None, "Newmark, β = 1/4, γ = 1/2"),
           ("theta+mr", 0.55, "θ-method, θ = 0.55, mass redistribution"),
           ("theta+mr", 0.51, "θ-method, θ = 0.51, mass redistribution"),
           ("theta+mr", 0.5, "θ-method, θ = 0.5, mass redistribution"),
           ("modified-theta", 0.5, "modified θ, θ = 0.5"),
           ("modified-theta+ff4", 0.55, "modified θ, θ = 0.55, free flight 4 h"),
           ("theta+mr+ff4", 0.51, "θ-method, θ = 0.51, mass redistribution, free flight 4 h"),
           ("modified-theta+courant+ff4", 0.025,
            "modified θ, θ = 1/2 + 0.025/C, free flight 4 h"),
           ("theta+mr+courant+ff4", 0.025,
            "θ-method, θ = 1/2 + 0.025/C, mass redistribution, free flight 4 h")]
COLORS = ["tab:orange", "tab:red", "tab:blue", "tab:green", "tab:purple",
          "magenta", "black", "darkgoldenrod", "lime", "teal", "gray", "crimson",
          "deepskyblue"]
PEER_COLORS = ["tab:brown", "tab:gray", "tab:olive", "tab:cyan", "tab:pink",
               "black", "gold", "navy"]

COLUMNS_1D = ["code", "scheme", "theta", "beta", "gamma", "level", "cells", "dx",
              "time_step", "courant", "n_steps", "cpu_run_seconds",
              "cpu_loop_seconds", "cpu_setup_seconds", "repeats", "err_v",
              "err_f", "energy_ratio", "status"]
COLUMNS_2D = ["code", "scheme", "theta", "beta", "gamma", "level", "mesh", "cells",
              "dx", "h_factor", "time_step", "courant", "n_steps",
              "cpu_run_seconds", "cpu_loop_seconds", "cpu_setup_seconds",
              "repeats", "err_force", "err_force_time", "err_impulse", "peak_force",
              "normal_impulse", "energy_ratio", "max_penetration",
              "coulomb_excess", "wrong_slip_count", "status"]

TARGET_ERR_V = 1e-2
BEGIN_MARK = "<!-- BEGIN GENERATED by benchmarks/work_precision/run_work_precision.py -->"
END_MARK = "<!-- END GENERATED -->"


# ---------------------------------------------------------------------------
# Small utilities

def prm_value(path, name, last=False):
    """The value of `set <name> = ...` in a parameter file (comments
    removed): the first match, or with <last> the last one (the one that
    holds when an override follows the base file's entry)."""
    found = None
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].strip()
            if line.startswith("set ") and "=" in line:
                key, value = line[4:].split("=", 1)
                if key.strip() == name:
                    found = value.strip()
                    if not last:
                        break
    if found is None:
        raise KeyError(f"{name} not in {path}")
    return found


def scheme_label(scheme, theta):
    for s, t, label in SCHEMES:
        if s == scheme and (t is None or theta is None or abs(t - theta) < 1e-12):
            return label
    return f"{scheme}, θ = {theta}" if theta is not None else scheme


def row_theta(row):
    t = row.get("theta", "")
    return float(t) if t not in ("", None) else None


def row_label(row):
    code = row.get("code", "impactfe")
    label = scheme_label(row["scheme"], row_theta(row))
    return label if code == "impactfe" else f"{code}: {label}"


def scheme_key(scheme, theta):
    """"<scheme>:<theta>" as --schemes names a SCHEMES entry."""
    return f"{scheme}:{'' if theta is None else theta}"


def time_stepping_overrides(scheme, theta, h, end_time=None):
    # "<scheme>[+mr][+courant][+ff<k>]", the options in any order
    scheme, *options = scheme.split("+")
    s = ""
    courant_rule = False
    for option in options:
        if option.startswith("ff"):
            s += ("subsection Time stepping\n  set Free-flight step factor = "
                  f"{int(option[2:])}\nend\n")
        elif option == "mr":
            s += "subsection Discretization\n  set Mass redistribution = true\nend\n"
        elif option == "courant":
            courant_rule = True
        else:
            sys.exit(f"scheme option '+{option}' unknown (mr, courant, ff<k>)")
    s += "subsection Time stepping\n"
    s += f"  set Scheme = {scheme}\n"
    if courant_rule:
        s += f"  set Theta rule = courant\n  set Theta damping = {theta!r}\n"
    elif theta is not None:
        s += f"  set Theta = {theta!r}\n"
    else:
        s += "  set Newmark beta = 0.25\n  set Newmark gamma = 0.5\n"
    s += f"  set Time step = {h!r}\n"
    if end_time is not None:
        s += f"  set End time = {end_time!r}\n"
    return s + "end\n"


def measured_runs(build, program, prm, cases, repeats, repeat_below):
    """Run each case (out_dir, overrides) of one grid point, the cases in
    turn: up to <repeats> rounds, in which every case whose runs so far
    were cheap (loop CPU < <repeat_below> s) runs once more; keep each case's
    smallest run and loop CPU. The schemes at one point so share the
    machine's state (frequency, cache sharing, other load), which moves by
    more than the schemes differ at the cheap end when each scheme runs its
    whole grid on its own. Returns [(result, n_runs)] in the order of
    <cases>."""
    best = [None] * len(cases)
    count = [0] * len(cases)
    for _ in range(max(1, repeats)):
        for i, (out_dir, overrides) in enumerate(cases):
            b = best[i]
            if b is not None and (b["summary"] is None
                                  or b["summary"]["loop_cpu_seconds"] >= repeat_below):
                continue
            result = runs.run_measured(build, program, prm, out_dir, overrides)
            count[i] += 1
            if b is None or result["summary"] is None:
                best[i] = result
                continue
            b["cpu_run_seconds"] = min(b["cpu_run_seconds"], result["cpu_run_seconds"])
            for key in ("loop_cpu_seconds", "setup_cpu_seconds"):
                b["summary"][key] = min(b["summary"][key], result["summary"][key])
    return list(zip(best, count))


def status_of(result):
    if result["summary"] is None:
        return "failed: " + (result["message"] or f"exit code {result['returncode']}")
    if result["returncode"] != 0:
        return "check failed: " + result["message"]
    return "ok"


def fmt(x, spec=".4g"):
    if x is None or (isinstance(x, float) and not math.isfinite(x)):
        return ""
    return format(x, spec)


def write_csv(path, columns, rows):
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: ("" if r.get(k) is None else r.get(k)) for k in columns})


def read_csv(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(row, key):
    try:
        v = float(row.get(key, ""))
        return v if math.isfinite(v) else None
    except (TypeError, ValueError):
        return None


def cells_of(row):
    """Cells per bar of a 1D row (the peers' CSV names the column
    cells_per_bar)."""
    c = num(row, "cells")
    c = num(row, "cells_per_bar") if c is None else c
    return int(c) if c is not None else "?"


def slope(xs, ys):
    """Least-squares slope of log y against log x (None if < 2 points)."""
    pts = [(math.log(x), math.log(y)) for x, y in zip(xs, ys)
           if x and y and x > 0 and y > 0]
    if len(pts) < 2:
        return None
    a = np.array(pts)
    return float(np.polyfit(a[:, 0], a[:, 1], 1)[0])


def cost_at_error(front, target):
    """Interpolate log-log along a Pareto front [(cost, err)] sorted by cost
    (errors decreasing) the cost at which err = target. None if the front
    never gets down to target."""
    if not front:
        return None
    if front[0][1] <= target:
        return front[0][0]
    for (c0, e0), (c1, e1) in zip(front, front[1:]):
        if e0 >= target >= e1:
            s = (math.log(target) - math.log(e0)) / (math.log(e1) - math.log(e0))
            return math.exp(math.log(c0) + s * (math.log(c1) - math.log(c0)))
    return None


def error_at_cost(front, budget):
    """The error reachable for a CPU budget along a Pareto front [(cost,
    err)] sorted by cost: log-log interpolation between its points (a run at
    an intermediate step or mesh), its last error beyond its dearest point,
    None below its cheapest one."""
    if not front or budget < front[0][0]:
        return None
    for (c0, e0), (c1, e1) in zip(front, front[1:]):
        if c0 <= budget <= c1:
            s = (math.log(budget) - math.log(c0)) / (math.log(c1) - math.log(c0))
            return math.exp(math.log(e0) + s * (math.log(e1) - math.log(e0)))
    return front[-1][1]


BUDGETS = 41


def budget_table(fronts, own, error_of=error_at_cost):
    """Which scheme has the smallest error at equal CPU. fronts: {label:
    Pareto front}; own: the labels of impactfe's schemes (the budgets span
    their cheapest to their dearest run). Returns (table rows, the leader's
    label, the budgets the leader loses) over BUDGETS budgets evenly spaced
    in log CPU. A scheme wins a budget if no other scheme's error there
    (error_of(front, budget), by default interpolated) is smaller."""
    costs = [c for lab in own for c, _ in fronts[lab]]
    lo, hi = math.log(min(costs)), math.log(max(costs))
    budgets = [math.exp(lo + (hi - lo) * i / (BUDGETS - 1)) for i in range(BUDGETS)]
    at = {lab: [error_of(f, b) for b in budgets] for lab, f in fronts.items()}
    wins = {lab: 0 for lab in fronts}
    for i in range(BUDGETS):
        errs = [at[lab][i] for lab in fronts if at[lab][i] is not None]
        for lab in fronts:
            if at[lab][i] is not None and at[lab][i] <= min(errs):
                wins[lab] += 1
    leader = max(own, key=lambda lab: wins[lab])
    losses = []
    for i, b in enumerate(budgets):
        others = [(at[lab][i], lab) for lab in fronts
                  if lab != leader and at[lab][i] is not None]
        if not others:
            continue
        best, best_label = min(others)
        mine = at[leader][i]
        if mine is None or mine > best:
            losses.append((b, mine, best, best_label))
    rows = [[lab, wins[lab]] for lab in fronts]
    return rows, leader, losses


def budget_section(fronts, own, err_name, error_of=error_at_cost, cost="CPU (loop CPU)",
                   cost_header="loop CPU s", cost_scale=1.,
                   how="every scheme's error interpolated log-log along its Pareto "
                       "front (none below its cheapest run)"):
    """Markdown: the budget table and the budgets its leader loses; returns
    (text, leader, its wins, the budgets it loses as (budget, its error,
    smallest error, that scheme)). The cost is shown divided by
    cost_scale."""
    rows, leader, losses = budget_table(fronts, own, error_of)
    lines = [f"\nBest {err_name} at equal {cost}: {BUDGETS} budgets evenly spaced "
             f"in log {cost.split()[0]} from impactfe's cheapest to its dearest run; at "
             f"each, {how}; a scheme wins a budget where no other is smaller (ties count "
             "for both):\n",
             md_table(["scheme", f"budgets won (of {BUDGETS})"], rows)]
    if not losses:
        lines.append(f"\n{leader} has the smallest error at every budget.")
    else:
        lines.append(f"\nBudgets that {leader} (most wins) loses:\n")
        lines.append(md_table(
            [cost_header, f"its {err_name}", f"smallest {err_name}", "by", "scheme"],
            [[fmt(b / cost_scale, ".3g"),
              "no run this cheap" if mine is None else fmt(mine, ".3g"),
              fmt(best, ".3g"),
              "" if mine is None else f"{100 * (mine / best - 1):.1f} %", lab]
             for b, mine, best, lab in losses]))
    return "\n".join(lines), leader, dict(rows)[leader], losses


def budget_outcome(leader, wins, losses):
    """The budget table's result for summary.json and the RESULT line."""
    margins = [mine / best - 1 for _, mine, best, _ in losses if mine is not None]
    return {"leader": leader, "budgets": BUDGETS, "budgets_won": wins,
            "budgets_lost": len(losses),
            "largest_loss": max(margins) if margins else 0.}


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |",
           "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out)


def progress(msg):
    print(f"[{time.strftime('%H:%M:%S')}] {msg}", flush=True)


# ---------------------------------------------------------------------------
# 1D bars

BARS_PRM = "parameter_files/two_bars_1d.prm"
BARS_END_TIME = 0.2e-3  # [s], fixed so that the errors are comparable


def bars_data():
    E = float(prm_value(BARS_PRM, "Young's modulus"))
    rho = float(prm_value(BARS_PRM, "Density"))
    L = float(prm_value(BARS_PRM, "Bar length"))
    return math.sqrt(E / rho), L


def bars_case(args, scheme, theta, cells, courant, end_time):
    """(out_dir, overrides) of one 1D run."""
    c, L = bars_data()
    h = courant * (L / cells) / c
    tag = f"{scheme}_{theta}_{cells}_{courant}"
    return (os.path.join(args.runs, "two_bars_1d", tag),
            f"subsection Geometry\n  set Number of cells per bar = {cells}\nend\n"
            + time_stepping_overrides(scheme, theta, h, end_time))


def run_bars_points(args, points, level, end_time):
    """The 1D runs of <points> [(scheme, theta, cells, courant)], measured
    together (measured_runs); returns their rows."""
    cases = [bars_case(args, *p, end_time) for p in points]
    measured = measured_runs(args.build, "two_bars_1d", BARS_PRM, cases, args.repeats,
                             args.repeat_below)
    return [bars_row(p, level, result, n) for p, (result, n) in zip(points, measured)]


def bars_row(point, level, result, n):
    scheme, theta, cells, courant = point
    c, L = bars_data()
    dx = L / cells
    h = courant * dx / c
    s = result["summary"] or {}
    row = {"code": "impactfe", "scheme": scheme,
           "theta": "" if theta is None else theta,
           "beta": 0.25 if theta is None else "", "gamma": 0.5 if theta is None else "",
           "level": level, "cells": cells, "dx": fmt(dx, ".6g"),
           "time_step": fmt(h, ".6g"), "courant": courant,
           "n_steps": int(s["n_steps"]) if s else "",
           "cpu_run_seconds": fmt(result["cpu_run_seconds"], ".4g"),
           "cpu_loop_seconds": fmt(s.get("loop_cpu_seconds"), ".4g"),
           "cpu_setup_seconds": fmt(s.get("setup_cpu_seconds"), ".4g"),
           "repeats": n, "err_v": fmt(s.get("err_v"), ".6g"),
           "err_f": fmt(s.get("err_f"), ".6g"),
           "energy_ratio": fmt(s.get("energy_ratio"), ".6g"),
           "status": status_of(result)}
    progress(f"two_bars_1d {scheme:14s} θ={theta} cells={cells:5d} C={courant:<4} "
             f"err_v={row['err_v']:>10s} loop={row['cpu_loop_seconds']:>8s}s "
             f"run={row['cpu_run_seconds']:>6s}s x{n} {row['status'] if row['status'] != 'ok' else ''}")
    return row


def extrapolate(rows, target=TARGET_ERR_V):
    """For one scheme's 1D rows: at each Courant number, the slope p of
    err_v against dx over the 4 finest levels, and the cells per bar and
    loop CPU seconds (∝ cells², h ∝ dx) at which err_v would reach <target>.
    Returns the cheapest (cost, courant, cells, p, last row), or None if the
    error decreases at no Courant number (p < 0.1)."""
    best = None
    for courant in sorted({num(r, "courant") for r in rows}):
        line = sorted((r for r in rows if num(r, "courant") == courant
                       and num(r, "err_v") is not None),
                      key=lambda r: num(r, "cells"))[-4:]
        p = slope([num(r, "cells") for r in line], [num(r, "err_v") for r in line])
        if p is None or -p < 0.1:
            continue
        last = line[-1]
        need = num(last, "cells") * (num(last, "err_v") / target) ** (1. / -p)
        cost = num(last, "cpu_loop_seconds") * (need / num(last, "cells")) ** 2
        if best is None or cost < best[0]:
            best = (cost, courant, need, -p, last)
    return best


def selected_schemes(args):
    """The SCHEMES entries that --schemes names (all without it)."""
    if not args.schemes:
        return SCHEMES
    keys = args.schemes.split(",")
    unknown = set(keys) - {scheme_key(s, t) for s, t, _ in SCHEMES}
    if unknown:
        sys.exit(f"--schemes: unknown {', '.join(sorted(unknown))}; known: "
                 + ", ".join(scheme_key(s, t) for s, t, _ in SCHEMES))
    return [e for e in SCHEMES if scheme_key(e[0], e[1]) in keys]


def merged_with_kept(args, path, new_rows):
    """With --schemes: the rows of <path> of the schemes not run now, then
    the new rows; without it, the new rows."""
    if not args.schemes or not os.path.exists(path):
        return new_rows
    run_now = {scheme_key(s, t) for s, t, _ in selected_schemes(args)}
    # The references (level "") are run again with the new rows.
    kept = [r for r in read_csv(path)
            if r.get("code", "impactfe") != "impactfe"
            or (r.get("level", "") != ""
                and scheme_key(r["scheme"], row_theta(r)) not in run_now)]
    return kept + new_rows


def scheme_major(rows):
    """<rows> (measured point by point) in the order of SCHEMES, each
    scheme's rows in the order they were run: the CSVs read scheme by
    scheme."""
    order = [scheme_key(s, t) for s, t, _ in SCHEMES]
    return sorted(rows, key=lambda r: order.index(scheme_key(r["scheme"], row_theta(r))))


def run_bars(args):
    if args.quick:
        cells_list, courants = [10, 20, 40, 80, 160], [0.9, 2.0]
    else:
        cells_list, courants = [10, 20, 40, 80, 160, 320, 640, 1280], [0.25, 0.5, 0.9, 2.0, 4.0]
    rows = []
    for level, cells in enumerate(cells_list):
        for courant in courants:
            rows += run_bars_points(args, [(s, t, cells, courant)
                                           for s, t, _ in selected_schemes(args)],
                                    level, BARS_END_TIME)
    return extend_bars(args, scheme_major(rows))


def extend_bars(args, rows):
    """Finer meshes for the schemes whose err_v decreases but stays above
    1e-2 on the grid, at the Courant number where the extrapolated cost is
    smallest, if that cost is <= --extend-budget: meshes doubled, the last
    one cut to 1.2 x the extrapolated need."""
    for scheme, theta, label in selected_schemes(args):
        mine = [r for r in rows if r["scheme"] == scheme
                and str(r["theta"]) == ("" if theta is None else str(theta))
                and r["status"] == "ok"]
        if not mine or min(float(r["err_v"]) for r in mine) <= TARGET_ERR_V:
            continue
        best = extrapolate(mine)
        if best is None:
            progress(f"extension: {label} does not converge in err_v at any Courant "
                     "number: not extended")
            continue
        cost, courant, need, p, last = best
        progress(f"extension: {label}: err_v ~ h^{p:.2f} at C = {courant}; about "
                 f"{need:.0f} cells per bar and {cost:.3g} s of loop CPU needed")
        if cost > args.extend_budget:
            progress(f"extension: {label}: more than --extend-budget "
                     f"{args.extend_budget} s: not extended")
            continue
        # Double the mesh while that is cheap next to the run that should reach
        # the target (4 x cells < need), then jump to 1.2 x the need,
        # re-extrapolated at this Courant number after each run.
        cells, level = int(num(last, "cells")), int(num(last, "level"))
        while cells < 4 * need:
            nxt = 2 * cells if 4 * cells < need else \
                max(cells + 10, int(math.ceil(1.2 * need / 10.)) * 10)
            cells, level = nxt, level + 1
            row, = run_bars_points(args, [(scheme, theta, cells, courant)], level,
                                   BARS_END_TIME)
            rows.append(row)
            mine.append(row)
            if row["status"] != "ok" or float(row["err_v"]) <= TARGET_ERR_V:
                break
            line = [r for r in mine if num(r, "courant") == courant]
            again = extrapolate(line)
            if again is None:
                progress(f"extension: {label}: err_v stopped decreasing: stopped")
                break
            need = again[2]
            progress(f"extension: {label}: now about {need:.0f} cells per bar needed "
                     f"({again[0]:.3g} s loop CPU)")
            if again[0] > args.extend_budget:
                # Without this check a slowly converging scheme went on
                # doubling its mesh (theta = 0.5: 40960 cells, > 15 min).
                progress(f"extension: {label}: more than --extend-budget "
                         f"{args.extend_budget} s: stopped")
                break
    return rows


# ---------------------------------------------------------------------------
# 2D scenes

def disc_area(prm):
    return math.pi * float(prm_value(prm, "Radius")) ** 2


def plate_area(prm):
    w = float(prm_value(prm, "Width"))
    hs = float(prm_value(prm, "Side height"))
    R = float(prm_value(prm, "Radius of the round side"))
    half = w / 2.
    sagitta = R - math.sqrt(R * R - half * half)
    segment = R * R * math.asin(half / R) - half * math.sqrt(R * R - half * half)
    assert sagitta > 0.
    return w * hs + segment


def p_wave_speed(prm):
    E = float(prm_value(prm, "Young's modulus"))
    nu = float(prm_value(prm, "Poisson's ratio"))
    rho = float(prm_value(prm, "Density"))
    if prm_value(prm, "Plane model") == "plane strain":
        return math.sqrt(E * (1 - nu) / (rho * (1 + nu) * (1 - 2 * nu)))
    return math.sqrt(E / (rho * (1 - nu * nu)))


def bars_2d_area(prm):
    return 2. * float(prm_value(prm, "Bar length")) * float(prm_value(prm, "Bar height"))


SCENES = {
    "bars2d": {
        "program": "two_bars_2d", "prm": "parameter_files/two_bars_2d.prm",
        "csv": "work_precision_two_bars_2d.csv",
        "title": "Two bars in 2D (ν = 0.45, plane stress)",
        "entries": ("Number of cells along", "Number of cells across"),
        "cells": lambda m: 2 * m[0] * m[1],  # two bars
        "area": bars_2d_area,
        # Factor 1 is the paper's step on its 20 x 4 mesh: C = 1.42 with
        # dx = sqrt(cell area) and the dilatational speed, 0.9 along the bar
        # with the bar speed, as the 1D program's C = 0.9.
        "full": {"meshes": [(10, 2), (20, 4), (40, 8), (80, 16), (120, 24)],
                 "factors": [0.25, 0.5, 1, 2, 4],
                 # h of the reference: a quarter of the finest grid step (120 x 24
                 # at factor 0.25). At that step itself the reference's scheme
                 # shared the reference's time error and looked 3x too good.
                 # 480 x 96 since 2026-12-07: 240 x 48 at h/2 differed from
                 # it by err_force 0.0035, the size of the finest runs'
                 # differences.
                 "reference": ((480, 96), 0.2226e-5 / 192.), "same_mesh_factor": 1. / 16.},
        "quick": {"meshes": [(10, 2), (20, 4)], "factors": [1, 4],
                  "reference": ((40, 8), 0.2226e-5 / 4.), "same_mesh_factor": 1. / 8.},
        "extra": "",
    },
    "cylinder": {
        "program": "cylinder_impact", "prm": "parameter_files/cylinder_impact.prm",
        "csv": "work_precision_cylinder.csv", "title": "Cylinder on a rigid plane",
        "entries": ("Number of core cells", "Number of rings"),
        "cells": lambda m: m[0] * m[0] + 4 * m[0] * m[1],
        "area": disc_area,
        "full": {"meshes": [(4, 3), (8, 6), (12, 9), (16, 12), (24, 18)],
                 "factors": [0.5, 1, 2, 4, 8],
                 # 64 x 48, 2.7 times finer than the finest grid mesh: the
                 # 32 x 24 reference of before differed from it by err_force
                 # 0.0055, half the finest runs' errors (2026-12-07).
                 "reference": ((64, 48), 0.000625), "same_mesh_factor": 1. / 16.},
        "quick": {"meshes": [(4, 3), (12, 9)], "factors": [1, 4],
                  "reference": ((16, 12), 0.01), "same_mesh_factor": 1. / 8.},
        "extra": "",
    },
    "plate": {
        "program": "oblique_plate", "prm": "parameter_files/oblique_plate.prm",
        "csv": "work_precision_plate.csv", "title": "Oblique plate with friction",
        "entries": ("Number of cells across", "Number of cells up"),
        "cells": lambda m: m[0] * m[1],
        "area": plate_area,
        "full": {"meshes": [(5, 4), (10, 8), (20, 16), (30, 24), (40, 32)],
                 "factors": [1, 2, 4, 8, 16],
                 # 320 x 256, 8 times finer than the finest grid mesh: the
                 # 80 x 64 reference of before differed from it by err_force
                 # 0.0085, 70 % of the 40 x 32 runs' errors (2026-12-07).
                 "reference": ((320, 256), 3.125e-7), "same_mesh_factor": 1. / 16.},
        "quick": {"meshes": [(5, 4), (10, 8)], "factors": [1, 4],
                  "reference": ((20, 16), 5e-6), "same_mesh_factor": 1. / 8.},
        # Lemke from scratch, as in every run of this grid so far: an old
        # build's warm start returned sticking nodes with |P_T| > mu P_N on
        # refined meshes (fixed in e1f88d0, see the doc).
        "extra": "subsection Contact solver\n  set Warm start = false\nend\n",
    },
}


def scene_geometry(name):
    sc = SCENES[name]
    prm = sc["prm"]
    paper_mesh = (int(prm_value(prm, sc["entries"][0])), int(prm_value(prm, sc["entries"][1])))
    h_paper = float(prm_value(prm, "Time step"))
    return prm, paper_mesh, h_paper, sc["area"](prm), p_wave_speed(prm)


def mesh_overrides(name, mesh):
    e = SCENES[name]["entries"]
    return f"subsection Geometry\n  set {e[0]} = {mesh[0]}\n  set {e[1]} = {mesh[1]}\nend\n"


def read_force(out_dir):
    h = runs.read_columns(os.path.join(out_dir, "history.csv"))
    return np.array(h["time"]), np.array(h["normal_force"])


def step_force(out_dir, scheme):
    """The normal force of each step as err_force defines it for every
    scheme: the normal impulse that changes the momentum in the step, over
    h. For the θ-schemes that is the history's column (P / h). With mass
    redistribution the column is the force at the end of the step, F^{i+1}
    = P / (h θ), and the step's impulse is h (θ F^{i+1} + (1 − θ) F^i) (the
    carry to the massless rows, MultibodySystem::do_time_step()); for
    Newmark the column is r^{i+1} and the impulse h (γ r^{i+1} + (1 − γ)
    r^i). Read as it stands, such a column held on (t_i, t_{i+1}] is half
    a step early."""
    t, f = read_force(out_dir)
    base, *options = scheme.split("+")
    if base == "newmark":
        weight = float(prm_value(os.path.join(out_dir, "run.prm"), "Newmark gamma", last=True))
    elif "mr" in options:
        with open(os.path.join(out_dir, "summary.json")) as file:
            weight = json.load(file)["theta"]
    else:
        return t, f
    # A step that carries a force follows a step of the same length: a
    # free-flight step (k h) is taken only after a step without impulses.
    g = f.copy()
    g[1:] = weight * f[1:] + (1. - weight) * f[:-1]
    return t, g


def l1_force_difference(a, b, t_end):
    """∫_0^T |F_a − F_b| dt with both forces piecewise constant: the value
    of row i holds on (t_{i-1}, t_i] (it is the impulse of that step / h).
    Exact on the union of both time grids."""
    ta, fa = a
    tb, fb = b
    grid = np.union1d(ta, tb)
    grid = grid[grid <= t_end * (1 + 1e-12)]
    mid = 0.5 * (grid[1:] + grid[:-1])
    va = fa[np.minimum(np.searchsorted(ta, mid), len(ta) - 1)]
    vb = fb[np.minimum(np.searchsorted(tb, mid), len(tb) - 1)]
    return float(np.sum(np.abs(va - vb) * np.diff(grid)))


def impulse_difference(a, b, t_end):
    """max over t in [0, T] of |∫_0^t (F_a − F_b) ds| / ∫_0^T F_b ds: a weak
    (impulse) measure of the force error, which, unlike the L1 norm of the
    force, converges when a node's impact gives a force spike of one step."""
    def cumulative(t, f, grid):
        impulse = np.concatenate(([0.], np.cumsum(f[1:] * np.diff(t))))
        return np.interp(grid, t, impulse)
    grid = np.union1d(a[0], b[0])
    grid = grid[grid <= t_end * (1 + 1e-12)]
    ia, ib = cumulative(*a, grid), cumulative(*b, grid)
    return float(np.max(np.abs(ia - ib)) / ib[-1])


def reference_impulse(reference):
    """∫_0^T F_ref dt, the norm of err_force: the reference's total normal
    impulse, with the force piecewise constant as in l1_force_difference.
    (Its peak force, the norm until 2026-11-28, is a one-step spike where
    the 2D bars' faces meet, and grew like h_ref^-0.6.)"""
    t, f = reference
    return float(np.sum(f[1:] * np.diff(t)))


def contact_duration(summary, h):
    """t_last − t_first + h, the end times of the first and last steps with
    a positive force."""
    return summary["last_contact"] - summary["first_contact"] + h


def scene_row(name, scheme, theta, level, mesh, dx, factor, h, c_p, result, n,
              err, err_time, err_impulse=None):
    s = result["summary"] or {}
    checks = s.get("checks", {})
    return {"code": "impactfe", "scheme": scheme,
            "theta": "" if theta is None else theta,
            "beta": 0.25 if theta is None else "", "gamma": 0.5 if theta is None else "",
            "level": level, "mesh": f"{mesh[0]}x{mesh[1]}",
            "cells": SCENES[name]["cells"](mesh), "dx": fmt(dx, ".6g"),
            "h_factor": factor, "time_step": fmt(h, ".6g"),
            "courant": fmt(c_p * h / dx, ".4g"),
            "n_steps": int(s["n_steps"]) if s else "",
            "cpu_run_seconds": fmt(result["cpu_run_seconds"], ".4g"),
            "cpu_loop_seconds": fmt(s.get("loop_cpu_seconds"), ".4g"),
            "cpu_setup_seconds": fmt(s.get("setup_cpu_seconds"), ".4g"),
            "repeats": n, "err_force": fmt(err, ".6g"),
            "err_force_time": fmt(err_time, ".6g"),
            "err_impulse": fmt(err_impulse, ".6g"),
            "peak_force": fmt(s.get("peak_normal_force"), ".6g"),
            "normal_impulse": fmt(s.get("normal_impulse"), ".6g"),
            "energy_ratio": fmt(s.get("energy_ratio"), ".6g"),
            "max_penetration": fmt(checks.get("max_penetration"), ".3g"),
            "coulomb_excess": fmt(checks.get("coulomb_excess"), ".3g"),
            "wrong_slip_count": "" if "wrong_slip_count" not in checks
            else int(checks["wrong_slip_count"]),
            "status": status_of(result)}


def run_scene(args, name):
    sc = SCENES[name]
    grid = sc["quick" if args.quick else "full"]
    prm, paper_mesh, h_paper, area, c_p = scene_geometry(name)
    program = sc["program"]
    end_time = float(prm_value(prm, "End time"))
    dx_of = lambda mesh: math.sqrt(area / sc["cells"](mesh))  # noqa: E731
    base_scheme = prm_value(prm, "Scheme")
    base_theta = float(prm_value(prm, "Theta")) if base_scheme != "newmark" else None
    rows = []

    def run_ref(tag, mesh, h):
        out = os.path.join(args.runs, name, tag)
        progress(f"{name}: reference run '{tag}': {mesh[0]}x{mesh[1]} "
                 f"({sc['cells'](mesh)} cells), h = {h:g}, {base_scheme}")
        result = runs.run_measured(args.build, program, prm, out,
                                   mesh_overrides(name, mesh) + sc["extra"]
                                   + time_stepping_overrides(base_scheme, base_theta, h))
        if result["summary"] is None:
            sys.exit(f"{name}: the reference run failed: {result['message']}")
        progress(f"{name}: reference '{tag}' done, {result['cpu_run_seconds']:.1f} s CPU "
                 f"({status_of(result)})")
        return result

    # The fine reference, the same at 2h (its uncertainty), and the
    # reference on the paper's mesh with a small step (time error alone).
    ref_mesh, ref_h = grid["reference"]
    finest_grid_h = min(h_paper * f * dx_of(m) / dx_of(paper_mesh)
                        for m in grid["meshes"] for f in grid["factors"])
    if ref_h > 0.5 * finest_grid_h:
        # A grid run of the reference's scheme at the reference's step
        # shares its time error, and its error would look too small.
        sys.exit(f"{name}: the reference step {ref_h:g} must be at most half the "
                 f"finest grid step {finest_grid_h:g}")
    ref = run_ref("reference", ref_mesh, ref_h)
    ref_force = read_force(ref["out_dir"])
    norm = reference_impulse(ref_force)
    duration = contact_duration(ref["summary"], ref_h)
    ref2 = run_ref("reference_2h", ref_mesh, 2 * ref_h)
    h_same = h_paper * grid["same_mesh_factor"]
    same = run_ref("same_mesh_reference", paper_mesh, h_same)
    same_force = read_force(same["out_dir"])
    for tag, result, mesh, h in (("reference", ref, ref_mesh, ref_h),
                                 ("reference at 2h", ref2, ref_mesh, 2 * ref_h),
                                 ("same-mesh reference", same, paper_mesh, h_same)):
        force = read_force(result["out_dir"])
        err = l1_force_difference(force, ref_force, end_time) / norm
        row = scene_row(name, base_scheme, base_theta, "", mesh, dx_of(mesh),
                        h / (h_paper * dx_of(mesh) / dx_of(paper_mesh)), h, c_p,
                        result, 1, err, None,
                        impulse_difference(force, ref_force, end_time))
        row["status"] = tag + ("" if status_of(result) == "ok" else "; " + status_of(result))
        rows.append(row)
    progress(f"{name}: reference peak force {np.max(ref_force[1]):.6g}, contact "
             f"duration {duration:.6g}, norm {norm:.6g}; uncertainty (2h vs h) "
             f"{rows[1]['err_force']}")

    grid_rows = []
    for level, mesh in enumerate(grid["meshes"]):
        dx = dx_of(mesh)
        for factor in grid["factors"]:
            h = h_paper * factor * dx / dx_of(paper_mesh)
            schemes = selected_schemes(args)
            outs = [os.path.join(args.runs, name, f"{scheme}_{theta}_{mesh[0]}x{mesh[1]}_{factor}")
                    for scheme, theta, _ in schemes]
            measured = measured_runs(
                args.build, program, prm,
                [(out, mesh_overrides(name, mesh) + sc["extra"]
                  + time_stepping_overrides(scheme, theta, h))
                 for out, (scheme, theta, _) in zip(outs, schemes)], args.repeats,
                args.repeat_below)
            for out, (scheme, theta, _), (result, n) in zip(outs, schemes, measured):
                err = err_time = err_impulse = None
                if result["summary"] is not None:
                    force = step_force(out, scheme)
                    err = l1_force_difference(force, ref_force, end_time) / norm
                    err_impulse = impulse_difference(force, ref_force, end_time)
                    if mesh == paper_mesh:
                        err_time = l1_force_difference(force, same_force, end_time) / norm
                row = scene_row(name, scheme, theta, level, mesh, dx, factor, h, c_p,
                                result, n, err, err_time, err_impulse)
                grid_rows.append(row)
                progress(f"{name} {scheme:14s} θ={theta} {row['mesh']:>5s} h={h:<10.4g} "
                         f"C={row['courant']:>6s} err={row['err_force']:>10s} "
                         f"loop={row['cpu_loop_seconds']:>8s}s run={row['cpu_run_seconds']:>6s}s"
                         f" x{n} {row['status'] if row['status'] != 'ok' else ''}")
    rows += scheme_major(grid_rows)
    return rows


def rescore_scene(args, name):
    """The CSV's rows of scene <name> with err_force, err_impulse and
    err_force_time computed again from the histories the runs left in
    <args.runs> (step_force()), without running anything: the CPU columns
    stay those of the CSV. Stops if a run's folder is missing or its step
    count is not the CSV's."""
    sc = SCENES[name]
    prm, paper_mesh, h_paper, _, _ = scene_geometry(name)
    end_time = float(prm_value(prm, "End time"))
    base = os.path.join(args.runs, name)
    rows = read_csv(os.path.join(args.out, sc["csv"]))
    for tag, status in (("reference", "reference"),
                        ("same_mesh_reference", "same-mesh reference")):
        summary = os.path.join(base, tag, "summary.json")
        if not os.path.isfile(summary):
            sys.exit(f"{name}: no {tag} run in {base} to rescore against "
                     "(--rescore needs the runs that made the CSV; --only names the scenes)")
        with open(summary) as file:
            n_steps = str(json.load(file)["n_steps"])
        if not any(r["level"] == "" and r["status"].split(";")[0] == status
                   and r["n_steps"] == n_steps for r in rows):
            sys.exit(f"{name}: the {tag} run in {base} made {n_steps} steps, "
                     "not the CSV's")
    ref_force = read_force(os.path.join(base, "reference"))
    norm = reference_impulse(ref_force)
    same_force = read_force(os.path.join(base, "same_mesh_reference"))
    changed = 0
    for row in rows:
        if row.get("code", "impactfe") != "impactfe" or row["level"] == "":
            continue
        if row["n_steps"] == "":  # a failed run: no errors to compute
            continue
        theta = row_theta(row)
        for scheme, t, _ in SCHEMES:
            if scheme == row["scheme"] and (t is None) == (theta is None) and (
                    t is None or abs(t - theta) < 1e-12):
                theta_tag = t
                break
        else:
            sys.exit(f"{name}: row scheme {row['scheme']} θ={row['theta']} not in SCHEMES")
        out = os.path.join(base, f"{row['scheme']}_{theta_tag}_{row['mesh']}_{row['h_factor']}")
        if not os.path.isfile(os.path.join(out, "history.csv")):
            sys.exit(f"{name}: no run in {out} to rescore")
        with open(os.path.join(out, "summary.json")) as file:
            n_steps = json.load(file)["n_steps"]
        if str(n_steps) != row["n_steps"]:
            sys.exit(f"{name}: {out} made {n_steps} steps, the CSV {row['n_steps']}")
        force = step_force(out, row["scheme"])
        new = {"err_force": fmt(l1_force_difference(force, ref_force, end_time) / norm, ".6g"),
               "err_impulse": fmt(impulse_difference(force, ref_force, end_time), ".6g")}
        if row["mesh"] == f"{paper_mesh[0]}x{paper_mesh[1]}":
            new["err_force_time"] = fmt(
                l1_force_difference(force, same_force, end_time) / norm, ".6g")
        if any(row[k] != v for k, v in new.items()):
            changed += 1
        row.update(new)
    progress(f"{name}: {changed} of {len(rows)} rows have new errors")
    return rows


# ---------------------------------------------------------------------------
# Figures and tables

def ok_rows(rows):
    return [r for r in rows if r.get("status", "ok") == "ok"
            or r.get("status", "").startswith("check failed")]


def groups(rows):
    """{label: rows} in the order of SCHEMES, then others."""
    out = {}
    for r in rows:
        out.setdefault(row_label(r), []).append(r)
    order = [lab for _, _, lab in SCHEMES]
    return dict(sorted(out.items(), key=lambda kv: order.index(kv[0])
                       if kv[0] in order else len(order)))


def color_of(label, peer_index={}):
    for (_, _, lab), c in zip(SCHEMES, COLORS):
        if lab == label:
            return c
    if label not in peer_index:
        peer_index[label] = PEER_COLORS[len(peer_index) % len(PEER_COLORS)]
    return peer_index[label]


def points(rows, cost_key, err_key):
    pts = []
    for r in rows:
        c, e = num(r, cost_key), num(r, err_key)
        if c is not None and e is not None and c > 0 and e > 0:
            pts.append((c, e))
    return pts


def log_axes(ax):
    """Log-log axes, with labels on the minor ticks when a decade is short."""
    from matplotlib.ticker import LogFormatterSciNotation
    ax.set_xscale("log")
    ax.set_yscale("log")
    for axis in (ax.xaxis, ax.yaxis):
        axis.set_minor_formatter(LogFormatterSciNotation(labelOnlyBase=False,
                                                         minor_thresholds=(1.5, 0.6)))
    ax.tick_params(which="minor", labelsize=7)
    ax.grid(alpha=0.3, which="both")


def caption_line(build):
    """Machine, commit of the working tree, and the binaries' folder with
    the date of its two_bars_1d (a copied build may be older than HEAD)."""
    exe = os.path.join(build, "bin", "two_bars_1d")
    built = (time.strftime(" built %Y-%m-%d %H:%M", time.localtime(os.path.getmtime(exe)))
             if os.path.exists(exe) else "")
    return f"{runs.machine_and_commit()}; binaries {os.path.abspath(build)}{built}"


def plot_bars(rows, peers, out, caption, fixed_courant):
    fig, axes = plt.subplots(2, 2, figsize=(12, 9))
    for col, cost_key in enumerate(("cpu_loop_seconds", "cpu_run_seconds")):
        for row_i, err_key in enumerate(("err_v", "err_f")):
            ax = axes[row_i, col]
            for label, rs in groups(ok_rows(rows)).items():
                color = color_of(label)
                front = runs.pareto_front(points(rs, cost_key, err_key))
                if front:
                    ax.plot(*zip(*front), "-o", color=color, ms=4, lw=1.6,
                            label=f"{label} (Pareto front)")
                line = sorted((r for r in rs if num(r, "courant") == fixed_courant),
                              key=lambda r: num(r, "cells"))
                pts = points(line, cost_key, err_key)
                if pts:
                    ax.plot(*zip(*pts), ":", marker=".", color=color, lw=1, ms=4)
            # The peers' cpu_run_seconds is set-up + loop inside their
            # process (no start-up): drawn on the loop-CPU panels only.
            for label, rs in groups(ok_rows(peers) if col == 0 else []).items():
                front = runs.pareto_front(points(rs, cost_key, err_key))
                if front:
                    ax.plot(*zip(*front), "--s", color=color_of(label), ms=3, lw=1.3,
                            label=f"{label} (Pareto front)")
            if err_key == "err_v":
                ax.axhline(TARGET_ERR_V, color="k", lw=0.6, alpha=0.5)
            log_axes(ax)
            ax.set_xlabel("CPU seconds, " + ("time loop (summary.json)" if col == 0
                                             else "whole process (getrusage)"))
            ax.set_ylabel(err_key)
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=3, fontsize=8)
    fig.suptitle("Two bars in 1D, T = 0.2 ms: error against CPU seconds; solid: Pareto "
                 f"front over the grid, dotted: Courant {fixed_courant} for all meshes"
                 + (", dashed: peers (left panels only)" if peers else "") + "\n" + caption,
                 fontsize=9)
    fig.tight_layout(rect=(0, 0.11 if peers else 0.07, 1, 1))
    png = os.path.join(out, "work_precision_two_bars_1d.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    courants = sorted({num(r, "courant") for r in ok_rows(rows)})
    shown = [c for c in (fixed_courant, 4.0 if 4.0 in courants else courants[-1])]
    for ax, err_key in zip(axes, ("err_v", "err_f")):
        for label, rs in groups(ok_rows(rows)).items():
            for courant, style in zip(shown, ("-o", "--^")):
                line = sorted((r for r in rs if num(r, "courant") == courant),
                              key=lambda r: num(r, "cells"))
                pts = points(line, "dx", err_key)
                if pts:
                    ax.plot(*zip(*pts), style, color=color_of(label), ms=4, lw=1.3,
                            label=f"{label}, C = {courant}")
        log_axes(ax)
        ax.set_xlabel("dx = L / cells per bar [m]  (h = C dx / c)")
        ax.set_ylabel(err_key)
    axes[0].legend(fontsize=6.5, ncol=2)
    fig.suptitle("Two bars in 1D: convergence at fixed Courant number C = c h / dx\n"
                 + caption, fontsize=9)
    fig.tight_layout()
    png2 = os.path.join(out, "convergence_two_bars_1d.png")
    fig.savefig(png2, dpi=110)
    plt.close(fig)
    return png, png2


def bars_tables(rows, peers):
    good = ok_rows(rows)
    courants = sorted({num(r, "courant") for r in good})
    lines = []
    # Rates.
    header = ["scheme"] + [f"C = {c:g}" for c in courants]
    table = []
    for label, rs in groups(good).items():
        cells = []
        for courant in courants:
            line = [r for r in rs if num(r, "courant") == courant]
            pv = slope([num(r, "dx") for r in line], [num(r, "err_v") for r in line])
            pf = slope([num(r, "dx") for r in line], [num(r, "err_f") for r in line])
            levels = sorted({int(num(r, "cells")) for r in line})
            cells.append(f"{fmt(pv, '.2f')} / {fmt(pf, '.2f')}" if levels else "")
        table.append([label] + cells)
    counts = {}
    for r in good:
        counts[int(num(r, "cells"))] = counts.get(int(num(r, "cells")), 0) + 1
    levels = sorted(c for c, n in counts.items() if n >= len(courants))
    extra = sorted(c for c, n in counts.items() if n < len(courants))
    lines.append("Convergence rates: least-squares slope of log err against log dx at "
                 "fixed Courant number (h ∝ dx), over all the mesh levels of that line "
                 f"(grid: {', '.join(map(str, levels))} cells per bar"
                 + (f"; extension runs, at one Courant number: {', '.join(map(str, extra))}"
                    if extra else "")
                 + "). Each entry: err_v rate / err_f rate. A negative rate: "
                 "the error grows under refinement.\n")
    lines.append(md_table(header, table))
    # CPU to reach err_v = 1e-2.
    lines.append(f"\nCPU seconds to reach err_v ≈ {TARGET_ERR_V:g} (log-log interpolation "
                 "along each scheme's Pareto front of the grid; the run column is the whole "
                 "process, dominated by loading the libraries):\n")
    table = []
    for label, rs in list(groups(good).items()) + list(groups(ok_rows(peers)).items()):
        loop_front = runs.pareto_front(points(rs, "cpu_loop_seconds", "err_v"))
        run_front = runs.pareto_front(points(rs, "cpu_run_seconds", "err_v"))
        c_loop = cost_at_error(loop_front, TARGET_ERR_V)
        c_run = cost_at_error(run_front, TARGET_ERR_V)
        errs = [num(r, "err_v") for r in rs if num(r, "err_v") is not None]
        best_err = min(errs) if errs else None
        best_row = min((r for r in rs if num(r, "err_v") is not None),
                       key=lambda r: num(r, "err_v"), default=None)
        # The cheapest run that reaches the target.
        reaching = [r for r in rs if num(r, "err_v") is not None
                    and num(r, "err_v") <= TARGET_ERR_V and num(r, "cpu_loop_seconds")]
        first = min(reaching, key=lambda r: num(r, "cpu_loop_seconds"), default=None)
        if c_loop is None:
            note = (f"not reached: best err_v = {fmt(best_err, '.3g')}"
                    + (f" ({cells_of(best_row)} cells, C = {num(best_row, 'courant'):g},"
                       f" {fmt(num(best_row, 'cpu_loop_seconds'), '.3g')} s loop)"
                       if best_row else ""))
            guess = extrapolate(rs) if rs and rs[0].get("code", "impactfe") == "impactfe" \
                else None
            if guess:
                note += (f"; extrapolated at C = {guess[1]:g} (err_v ∝ dx^{guess[3]:.2f}):"
                         f" ≈ {guess[2]:.3g} cells per bar, ≈ {guess[0]:.3g} s loop CPU")
            elif rs and rs[0].get("code", "impactfe") == "impactfe":
                note += "; err_v does not decrease under refinement at any Courant number"
        else:
            note = (f"cheapest run below: {cells_of(first)} cells, "
                    f"C = {num(first, 'courant'):g}, err_v = {fmt(num(first, 'err_v'), '.3g')}"
                    if first else "")
        peer = bool(rs) and rs[0].get("code", "impactfe") != "impactfe"
        run_cell = fmt(c_run, ".3g") or "—"
        if peer and c_run is not None:
            run_cell = f"({run_cell})*"
        table.append([label, fmt(c_loop, ".3g") or "—", run_cell, note])
    lines.append(md_table(["scheme", "loop CPU s", "run CPU s", "note"], table))
    if peers:
        lines.append("\n\\* The peers' `cpu_run_seconds` is their set-up plus time loop "
                     "inside an already running Python process: no process start-up, "
                     "unlike ours. Compare the loop columns.")
    own = list(groups(good))
    fronts = {label: runs.pareto_front(points(rs, "cpu_loop_seconds", "err_v"))
              for label, rs in list(groups(good).items()) + list(groups(ok_rows(peers)).items())}
    text, leader, wins, losses = budget_section({k: f for k, f in fronts.items() if f},
                                                [k for k in own if fronts[k]], "err_v")
    lines.append(text)
    outcome = budget_outcome(leader, wins, losses)
    # Energy at the finest level.
    finest = max(levels)
    table = []
    for label, rs in groups(good).items():
        ers = {num(r, "courant"): num(r, "energy_ratio") for r in rs
               if int(num(r, "cells")) == finest}
        table.append([label] + [fmt(ers.get(c), ".4f") for c in courants])
    lines.append(f"\nEnergy ratio (end / start; exact 1) on {finest} cells per bar:\n")
    lines.append(md_table(["scheme"] + [f"C = {c:g}" for c in courants], table))
    failed = [r for r in rows if r.get("status", "ok") != "ok"]
    if failed:
        lines.append("\nRuns that failed:\n")
        lines.append(md_table(["scheme", "cells", "C", "status"],
                              [[row_label(r), r["cells"], r["courant"], r["status"]]
                               for r in failed]))
    else:
        lines.append("\nNo run failed (all exit codes 0).")
    outcome["failed_runs"] = len(failed)
    return "\n".join(lines), outcome


def plot_scene(name, rows, out, caption):
    sc = SCENES[name]
    grid_rows = [r for r in ok_rows(rows) if r.get("level", "") != ""]
    refs = {r["status"].split(";")[0]: r for r in rows if r.get("level", "") == ""}
    _, paper_mesh, _, _, _ = scene_geometry(name)
    paper = f"{paper_mesh[0]}x{paper_mesh[1]}"
    uncertainty = num(refs.get("reference at 2h", {}), "err_force")
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    for ax, cost_key in zip(axes, ("cpu_loop_seconds", "cpu_run_seconds")):
        for label, rs in groups(grid_rows).items():
            color = color_of(label)
            front = runs.pareto_front(points(rs, cost_key, "err_force"))
            if front:
                ax.plot(*zip(*front), "-o", color=color, ms=4, lw=1.6,
                        label=f"{label} (Pareto front)")
            line = sorted((r for r in rs if num(r, "h_factor") == 1),
                          key=lambda r: num(r, "cells"))
            pts = points(line, cost_key, "err_force")
            if pts:
                ax.plot(*zip(*pts), ":", marker=".", color=color, lw=1, ms=4)
        if uncertainty:
            ax.axhline(uncertainty, color="k", lw=0.8, ls="--", alpha=0.6,
                       label="reference at 2h vs reference")
        log_axes(ax)
        ax.set_xlabel("CPU seconds, " + ("time loop (summary.json)"
                                         if cost_key == "cpu_loop_seconds"
                                         else "whole process (getrusage)"))
        ax.set_ylabel("err_force (L1 in time / reference impulse)")
    axes[0].legend(fontsize=7, loc="lower left")
    ref = refs.get("reference", {})
    fig.suptitle(f"{sc['title']}: error of the total normal force against CPU seconds; "
                 "solid: Pareto front over meshes × steps, dotted: the paper's Courant "
                 f"number on every mesh\nreference {ref.get('mesh')} ({ref.get('cells')} cells), "
                 f"h = {ref.get('time_step')}, {ref.get('scheme')}; " + caption, fontsize=9)
    fig.tight_layout()
    png = os.path.join(out, f"work_precision_{name}.png")
    fig.savefig(png, dpi=110)
    plt.close(fig)

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.8))
    for label, rs in groups(grid_rows).items():
        line = sorted((r for r in rs if r["mesh"] == paper), key=lambda r: num(r, "time_step"))
        pts = points(line, "time_step", "err_force_time")
        if pts:
            axes[0].plot(*zip(*pts), "-o", color=color_of(label), ms=4, label=label)
        for factor, style in ((1, "-o"), (4, "--^")):
            line = sorted((r for r in rs if num(r, "h_factor") == factor),
                          key=lambda r: num(r, "cells"))
            pts = points(line, "dx", "err_force")
            if pts:
                axes[1].plot(*zip(*pts), style, color=color_of(label), ms=4,
                             label=f"{label}, h factor {factor}")
    axes[0].set_xlabel(f"time step h (paper mesh {paper})")
    same_h = next((r["time_step"] for r in rows
                   if r.get("status", "").startswith("same-mesh")), "?")
    axes[0].set_ylabel(f"err_force against the same mesh at h = {same_h}")
    axes[1].set_xlabel("dx = sqrt(area / cells) (h ∝ dx)")
    axes[1].set_ylabel("err_force against the fine reference")
    for ax in axes:
        log_axes(ax)
    axes[0].legend(fontsize=7)
    axes[1].legend(fontsize=6, ncol=2)
    fig.suptitle(f"{sc['title']}: convergence in h on the paper's mesh (left) and under "
                 "mesh and step refinement at fixed Courant number (right)\n" + caption,
                 fontsize=9)
    fig.tight_layout()
    png2 = os.path.join(out, f"convergence_{name}.png")
    fig.savefig(png2, dpi=110)
    plt.close(fig)
    return png, png2


def scene_tables(name, rows):
    grid_rows = [r for r in ok_rows(rows) if r.get("level", "") != ""]
    refs = [r for r in rows if r.get("level", "") == ""]
    _, paper_mesh, h_paper, _, _ = scene_geometry(name)
    paper = f"{paper_mesh[0]}x{paper_mesh[1]}"
    lines = ["Reference runs (scheme of the scene's parameter file):\n",
             md_table(["run", "mesh", "cells", "h", "Courant", "loop CPU s", "run CPU s",
                       "err_force vs reference", "err_impulse", "peak force", "energy ratio",
                       "status"],
                      [[r["status"].split(";")[0], r["mesh"], r["cells"], r["time_step"],
                        r["courant"], r["cpu_loop_seconds"], r["cpu_run_seconds"],
                        r["err_force"], r.get("err_impulse", ""), r["peak_force"],
                        r["energy_ratio"],
                        r["status"]] for r in refs])]
    factors = sorted({num(r, "h_factor") for r in grid_rows})
    same_h = next((r["time_step"] for r in refs
                   if r["status"].startswith("same-mesh")), "?")
    table = []
    for label, rs in groups(grid_rows).items():
        line = [r for r in rs if r["mesh"] == paper]
        pt = slope([num(r, "time_step") for r in line], [num(r, "err_force_time") for r in line])
        entries = []
        for factor in factors:
            line = [r for r in rs if num(r, "h_factor") == factor]
            entries.append(fmt(slope([num(r, "dx") for r in line],
                                     [num(r, "err_force") for r in line]), ".2f"))
        line = [r for r in rs if num(r, "h_factor") == 1]
        pi = slope([num(r, "dx") for r in line], [num(r, "err_impulse") for r in line])
        table.append([label, fmt(pt, ".2f")] + entries + [fmt(pi, ".2f")])
    courant_of = {num(r, "h_factor"): r["courant"] for r in grid_rows}
    lines.append("\nConvergence rates (least-squares slopes of log err_force): in h on "
                 f"the paper's mesh {paper} against the same mesh at h = "
                 f"{same_h} (time error "
                 "alone), and in dx at fixed Courant number (h factor = h / (h_paper "
                 "dx/dx_paper)) against the fine reference (time and space error):\n")
    lines.append(md_table(["scheme", f"in h, mesh {paper}"]
                          + [f"in dx, factor {f:g} (C = {courant_of[f]})" for f in factors]
                          + ["err_impulse in dx, factor 1"],
                          table))
    table = []
    for label, rs in groups(grid_rows).items():
        for r in rs:
            if r["mesh"] == paper and num(r, "h_factor") == 1:
                table.append([label, r["time_step"], r["courant"], r["err_force"],
                              r["err_force_time"], r.get("err_impulse", ""), r["peak_force"],
                              r["energy_ratio"],
                              r["cpu_loop_seconds"], r["cpu_run_seconds"],
                              r["max_penetration"]])
    lines.append(f"\nAt the paper's mesh and step ({paper}, h = {h_paper:g}):\n")
    lines.append(md_table(["scheme", "h", "C", "err_force", "err_force (time)",
                           "err_impulse", "peak force",
                           "energy ratio", "loop CPU s", "run CPU s", "max penetration"],
                          table))
    fronts = {label: runs.pareto_front(points(rs, "cpu_loop_seconds", "err_force"))
              for label, rs in groups(grid_rows).items()}
    text, leader, wins, losses = budget_section({k: f for k, f in fronts.items() if f},
                                                list(fronts), "err_force")
    lines.append(text)
    outcome = budget_outcome(leader, wins, losses)
    failed = [r for r in rows if r.get("level", "") != "" and r.get("status") != "ok"]
    if failed:
        lines.append(f"\nRuns with a non-zero exit code ({len(failed)}; those with "
                     "'check failed' have results and are plotted):\n")
        lines.append(md_table(["scheme", "mesh", "h", "C", "status"],
                              [[row_label(r), r["mesh"], r["time_step"], r["courant"],
                                r["status"]] for r in failed]))
    else:
        lines.append("\nEvery grid run exited with code 0.")
    outcome["failed_runs"] = len(failed)
    return "\n".join(lines), outcome


def write_markdown(out, text):
    path = os.path.join(out, "work_precision.md")
    block = f"{BEGIN_MARK}\n{text}\n{END_MARK}\n"
    if os.path.exists(path):
        old = open(path).read()
        if BEGIN_MARK in old and END_MARK in old:
            head = old.split(BEGIN_MARK)[0]
            tail = old.split(END_MARK, 1)[1].lstrip("\n")
            new = head + block + tail
        else:
            new = old.rstrip("\n") + "\n\n" + block
    else:
        new = ("# Work-precision benchmark\n\n"
               "Made by `/usr/bin/python3 benchmarks/work_precision/run_work_precision.py`"
               " (see benchmarks/work_precision/README.md).\n\n" + block)
    with open(path, "w") as f:
        f.write(new)
    return path


def report(args, caption, run_info):
    parts = [f"Machine and commit: {caption}. {run_info}\n"]
    outcomes = {}
    bars_csv = os.path.join(args.out, "work_precision_two_bars_1d.csv")
    if os.path.exists(bars_csv):
        rows = read_csv(bars_csv)
        peers_csv = os.path.join(args.out, "peers_two_bars_1d.csv")
        peers = []
        if os.path.exists(peers_csv):
            peers = [r for r in read_csv(peers_csv) if r.get("code", "") != "impactfe"]
            print(f"peers: {peers_csv}: {len(peers)} rows, drawn dashed")
            peer_note = (f"Peers from `{os.path.basename(peers_csv)}` "
                         f"({', '.join(sorted({r.get('code', '?') for r in peers}))}) are "
                         "drawn dashed in the work-precision diagram and listed in the "
                         "CPU table.")
        else:
            print(f"peers: {peers_csv} not found: the 1D diagram has no peer lines")
            peer_note = f"No peer results (`{os.path.basename(peers_csv)}` absent)."
        fixed = 0.9 if any(num(r, "courant") == 0.9 for r in rows) else num(rows[0], "courant")
        png, png2 = plot_bars(rows, peers, args.out, caption, fixed)
        text, outcomes["1d"] = bars_tables(rows, peers)
        print("\n== two_bars_1d ==\n" + text + "\n" + peer_note)
        parts.append(f"## 1D two bars\n\n![work-precision]({os.path.basename(png)})\n\n"
                     f"![convergence]({os.path.basename(png2)})\n\n{peer_note}\n\n{text}\n")
    for name in ("bars2d", "cylinder", "plate"):
        path = os.path.join(args.out, SCENES[name]["csv"])
        if not os.path.exists(path):
            continue
        rows = read_csv(path)
        png, png2 = plot_scene(name, rows, args.out, caption)
        text, outcomes[name] = scene_tables(name, rows)
        print(f"\n== {name} ==\n" + text)
        parts.append(f"## {SCENES[name]['title']}\n\n![work-precision]({os.path.basename(png)})"
                     f"\n\n![convergence]({os.path.basename(png2)})\n\n{text}\n")
    md = write_markdown(args.out, "\n".join(parts))
    print(f"\nfigures and tables in {args.out}/ (tables: {md})")
    write_summary(args, caption, outcomes)


def write_summary(args, caption, outcomes):
    """summary.json beside the run files, and the RESULT line: per scene,
    the variant with the most of the BUDGETS budgets at equal loop CPU,
    how many it wins and loses, and by how much at most (relative)."""
    summary = {"program": "run_work_precision", "machine_and_commit": caption,
               "cost": "loop CPU seconds", "scenes": outcomes}
    path = os.path.join(os.path.dirname(args.runs), "summary.json")
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        json.dump(summary, f, indent=1)
    print(f"summary: {path}")
    fields = ["program=run_work_precision", f"budgets={BUDGETS}"]
    for name, o in outcomes.items():
        # the label without spaces, commas or '=' (one token of the line)
        leader = re.sub(r"[^\w.+/-]+", "_", o["leader"])
        fields += [f"{name}_leader={leader}",
                   f"{name}_budgets_won={o['budgets_won']}",
                   f"{name}_budgets_lost={o['budgets_lost']}",
                   f"{name}_largest_loss={o['largest_loss']:.3g}",
                   f"{name}_failed_runs={o['failed_runs']}"]
    print("RESULT " + " ".join(fields))


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default=None)
    parser.add_argument("--runs", default=None,
                        help="folder for the run files (default results/work_precision)")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--only", default="1d,bars2d,cylinder,plate")
    parser.add_argument("--plot-only", action="store_true")
    parser.add_argument("--rescore", action="store_true",
                        help="2D: no runs; the errors of the CSVs' rows computed "
                             "again from the run files in --runs (the CPU columns "
                             "kept), then the figures and tables")
    parser.add_argument("--schemes", default="",
                        help="run only these SCHEMES entries, as <scheme>:<theta> "
                             "(e.g. theta+mr:0.55,modified-theta:0.5); the rows of "
                             "the others in --out are kept")
    parser.add_argument("--extend-only", action="store_true",
                        help="1D: no grid runs, only the extension runs, added to the "
                             "CSV in --out (use with a larger --extend-budget)")
    parser.add_argument("--repeats", type=int, default=None,
                        help="best of this many runs when the loop takes less "
                             "than --repeat-below (default 3, --quick 1)")
    parser.add_argument("--repeat-below", type=float, default=0.2,
                        help="loop CPU seconds below which a run is repeated "
                             "(default 0.2; larger values make the middle of the "
                             "grid less noisy at more run time)")
    parser.add_argument("--extend-budget", type=float, default=None,
                        help="1D: largest predicted loop CPU seconds of one extension "
                             "run (default 120, --quick 0)")
    args = parser.parse_args()
    args.build = os.path.abspath(args.build)
    # Default folders are relative to the repository top, given ones to the
    # current directory.
    if args.out is None:
        args.out = os.path.join(TOP, "results/work_precision_quick" if args.quick else "doc")
    args.out = os.path.abspath(args.out)
    if args.runs is None:
        args.runs = os.path.join(TOP, "results/work_precision"
                                 + ("_quick" if args.quick else "") + "/runs")
    args.runs = os.path.abspath(args.runs)
    if args.repeats is None:
        args.repeats = 1 if args.quick else 3
    if args.extend_budget is None:
        args.extend_budget = 0. if args.quick else 120.
    os.chdir(TOP)  # the parameter files include each other relative to the top
    os.makedirs(args.out, exist_ok=True)
    caption = caption_line(args.build)
    only = set(args.only.split(","))
    start = time.time()
    if args.rescore:
        for name in ("bars2d", "cylinder", "plate"):
            if name in only:
                csv_path = os.path.join(args.out, SCENES[name]["csv"])
                write_csv(csv_path, COLUMNS_2D, rescore_scene(args, name))
    elif not args.plot_only:
        bars_csv = os.path.join(args.out, "work_precision_two_bars_1d.csv")
        if args.extend_only:
            write_csv(bars_csv, COLUMNS_1D, extend_bars(args, read_csv(bars_csv)))
        elif "1d" in only:
            write_csv(bars_csv, COLUMNS_1D,
                      merged_with_kept(args, bars_csv, run_bars(args)))
        for name in ("bars2d", "cylinder", "plate"):
            if name in only and not args.extend_only:
                csv_path = os.path.join(args.out, SCENES[name]["csv"])
                write_csv(csv_path, COLUMNS_2D,
                          merged_with_kept(args, csv_path, run_scene(args, name)))
    wall = time.time() - start
    run_info = (f"Figures drawn {datetime.date.today().isoformat()}"
                + ("" if args.plot_only or args.rescore else
                   "; the last invocation ran "
                   + ("the 1D extension runs" if args.extend_only else
                      f"{', '.join(sorted(only))} "
                      f"{'(quick grid)' if args.quick else '(full grid)'}")
                   + f" in {wall / 60:.1f} min wall")
                + f"; {os.cpu_count()} cores, load average "
                f"{os.getloadavg()[0]:.1f} at the end.")
    report(args, caption, run_info)


if __name__ == "__main__":
    main()
