#!/usr/bin/python3
"""Work-precision of the 2D scenes with a cost that does not depend on the
machine's load: the instructions of the time steps, counted by callgrind.

usage (from anywhere; the script works from the repository top):
    /usr/bin/python3 benchmarks/work_precision/count_instructions.py \
        [--build build] [--out doc] [--only cylinder,plate,bars2d] [--jobs 2]
        [--schemes modified-theta+courant+ff4:0.025,...] [--plot-only]

Why: on this 2-core shared machine two variants that do the same work at a
grid point (the same steps, free-flight steps and Lemke pivots) differed in
their loop CPU seconds by factors 0.7-1.5, best of 3 or of 8, so the budget
counts of run_work_precision.py between such variants follow the noise
(doc/work_precision.md). callgrind counts the instructions executed, the same
number on every run of the same binary and input whatever else the machine
does; instructions are not seconds (cache misses and branch mispredictions
cost more than an add), so this is a second measure beside the CPU seconds,
not a replacement.

What is counted: each grid run of <out>/<scene csv> (the rows of
run_work_precision.py, same mesh, step and scheme) is run again under
    valgrind --tool=callgrind --instr-atstart=no --collect-atstart=no
and the program (ContactScene::run) switches instrumentation on around its
time loop and collection on around each do_time_step() call, so the count is
that of the time steps alone, without set-up and output (as the
cpu_loop_seconds column, which takes the output's share off). Every run's
n_steps must equal the CSV row's, else the script stops; a peak force that
differs from the row's is recorded (peak_force_drift): under valgrind the
BLAS may pick other kernels, whose last bits differ, and a chaotic run
(Newmark) then follows another path.

Writes <out>/work_precision_<scene>_instructions.csv, the figure
<out>/work_precision_<scene>_instructions.png, and prints per scene the
budget table twice: with run_work_precision.py's log-log interpolation along
each scheme's Pareto front, and with the error of the best run that fits
the budget (no interpolation: a user with a budget can only pick a run that
exists). Several runs go at once (--jobs): counts do not depend on it.
"""
import argparse
import concurrent.futures
import datetime
import json
import math
import os
import re
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
sys.path.insert(0, HERE)
import runs  # noqa: E402
import run_work_precision as wp  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

VALGRIND = ["valgrind", "--tool=callgrind", "--instr-atstart=no",
            "--collect-atstart=no", "--callgrind-out-file=/dev/null"]
# The pair whose loop CPU differed by 0.7-1.5 at equal work (the Courant
# rule and fixed theta = 0.55, both with free flight 4 h).
EQUAL_WORK = [("modified-theta+courant+ff4", "0.025"), ("modified-theta+ff4", "0.55")]
COLUMNS = ["scheme", "theta", "level", "mesh", "time_step", "n_steps",
           "loop_instructions", "cpu_loop_seconds", "err_force", "peak_force_drift"]


def instructions_of(out_dir):
    with open(os.path.join(out_dir, "stdout.txt")) as f:
        m = re.search(r"Collected : (\d+)", f.read())
    return int(m.group(1)) if m else None


def grid_cases(args, name):
    """(row, out_dir, overrides) for each grid row of the scene's CSV whose
    scheme is selected; h recomputed from the grid as run_scene() does."""
    sc = wp.SCENES[name]
    prm, paper_mesh, h_paper, area, _ = wp.scene_geometry(name)
    dx_of = lambda mesh: math.sqrt(area / sc["cells"](mesh))  # noqa: E731
    wanted = None
    if args.schemes:
        wanted = {tuple(s.split(":")) for s in args.schemes.split(",")}
    cases = []
    for row in wp.read_csv(os.path.join(args.out, sc["csv"])):
        if row["level"] == "" or row["code"] != "impactfe" or row["status"] != "ok":
            continue
        if wanted is not None and (row["scheme"], row["theta"]) not in wanted:
            continue
        mesh = tuple(int(n) for n in row["mesh"].split("x"))
        factor = float(row["h_factor"])
        h = h_paper * factor * dx_of(mesh) / dx_of(paper_mesh)
        if abs(h / float(row["time_step"]) - 1) > 1e-5:
            sys.exit(f"{name}: cannot recompute the step of row {row}")
        theta = None if row["theta"] == "" else float(row["theta"])
        out = os.path.join(args.runs, name,
                           f"{row['scheme']}_{row['theta']}_{row['mesh']}_{row['h_factor']}")
        cases.append((row, out, wp.mesh_overrides(name, mesh) + sc["extra"]
                      + wp.time_stepping_overrides(row["scheme"], theta, h)))
    return prm, cases


def with_csv_errors(args, name, rows):
    """<rows> with err_force and cpu_loop_seconds taken again from the
    scene's CSV (run_work_precision.py, which may have rescored its errors
    since the counts were made); a count whose row is gone or whose step
    count differs stops the script."""
    csv_rows = {(r["scheme"], r["theta"], r["mesh"], r["time_step"]): r
                for r in wp.read_csv(os.path.join(args.out, wp.SCENES[name]["csv"]))
                if r["level"] != "" and r["code"] == "impactfe" and r["status"] == "ok"}
    for row in rows:
        key = (row["scheme"], row["theta"], row["mesh"], row["time_step"])
        source = csv_rows.get(key)
        if source is None or source["n_steps"] != row["n_steps"]:
            sys.exit(f"{name}: the count of {key} has no row with its step count "
                     f"in {wp.SCENES[name]['csv']}: count it again")
        row["err_force"] = source["err_force"]
        row["cpu_loop_seconds"] = source["cpu_loop_seconds"]
    return rows


def count_scene(args, name):
    prm, cases = grid_cases(args, name)
    program = wp.SCENES[name]["program"]

    def one(case):
        row, out, overrides = case
        result = runs.run_measured(args.build, program, prm, out, overrides,
                                   prefix=VALGRIND)
        s = result["summary"]
        if s is None:
            sys.exit(f"{name}: run {out} failed: {result['message']}")
        if int(s["n_steps"]) != int(row["n_steps"]):
            sys.exit(f"{name}: run {out} makes {s['n_steps']} steps, its CSV row "
                     f"{row['n_steps']}: rerun run_work_precision.py with this build first")
        # Under valgrind the last bits of a result can differ (the BLAS picks
        # its kernels from the CPU valgrind reports); a chaotic run (Newmark)
        # then drifts apart. Such runs are marked, not dropped.
        drift = abs(float(s["peak_normal_force"]) / float(row["peak_force"]) - 1)
        n = instructions_of(out)
        if n is None:
            sys.exit(f"{name}: no callgrind count in {out}/stdout.txt")
        wp.progress(f"{name} {row['scheme']:28s} θ={row['theta']:6s} {row['mesh']:>5s} "
                    f"h={row['time_step']:<10s} {n / 1e6:10.1f} M instructions")
        return {"scheme": row["scheme"], "theta": row["theta"], "level": row["level"],
                "mesh": row["mesh"], "time_step": row["time_step"],
                "n_steps": row["n_steps"], "loop_instructions": n,
                "cpu_loop_seconds": row["cpu_loop_seconds"], "err_force": row["err_force"],
                "peak_force_drift": wp.fmt(drift, ".2g")}

    # The dearest first, so that the two jobs end together.
    cases.sort(key=lambda c: -float(c[0]["cpu_loop_seconds"] or 0))
    with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        rows = list(pool.map(one, cases))
    return sorted(rows, key=lambda r: (r["scheme"], r["theta"], int(r["level"]),
                                       -float(r["time_step"])))


def error_within_budget(points, budget):
    """The smallest error of the runs that cost at most <budget>; None if
    none does. points: the Pareto front [(cost, err)] (any point set gives
    the same answer)."""
    fitting = [e for c, e in points if c <= budget]
    return min(fitting) if fitting else None


def report_scene(args, name, rows):
    labeled = {}
    for r in rows:
        labeled.setdefault(wp.row_label(r), []).append(r)
    order = [lab for _, _, lab in wp.SCHEMES]
    labeled = dict(sorted(labeled.items(), key=lambda kv: order.index(kv[0])
                          if kv[0] in order else len(order)))
    fronts = {lab: runs.pareto_front([(float(r["loop_instructions"]), float(r["err_force"]))
                                      for r in rs]) for lab, rs in labeled.items()}
    lines = [f"\n### {wp.SCENES[name]['title']}: instructions of the time loop\n"]
    stats = {"runs": len(rows)}
    for key, error_of, how in (
            ("interpolated", wp.error_at_cost,
             "every scheme's error interpolated log-log along its Pareto front"),
            ("within_budget", error_within_budget,
             "every scheme's best run that fits the budget (no interpolation)")):
        text, stats[f"leader_{key}"], stats[f"leader_wins_{key}"], _ = wp.budget_section(
            fronts, list(fronts), "err_force", error_of, cost="instructions",
            cost_header="10⁶ instructions", cost_scale=1e6, how=how)
        lines.append(text)
    # Two variants that do the same work at every point: their instruction
    # ratio against their CPU-second ratio.
    pair = [{(r["mesh"], r["time_step"]): r for r in rows
             if (r["scheme"], r["theta"]) == key} for key in EQUAL_WORK]
    common = sorted(set(pair[0]) & set(pair[1]))
    if common:
        ri = [float(pair[0][k]["loop_instructions"]) / float(pair[1][k]["loop_instructions"])
              for k in common]
        rc = [float(pair[0][k]["cpu_loop_seconds"]) / float(pair[1][k]["cpu_loop_seconds"])
              for k in common]
        same = sum(pair[0][k]["n_steps"] == pair[1][k]["n_steps"] for k in common)
        stats.update(equal_work_instruction_ratio=[min(ri), max(ri)],
                     equal_work_cpu_ratio=[min(rc), max(rc)])
        lines.append(f"\n{wp.scheme_label(EQUAL_WORK[0][0], float(EQUAL_WORK[0][1]))} "
                     f"against {wp.scheme_label(EQUAL_WORK[1][0], float(EQUAL_WORK[1][1]))} "
                     f"at the same {len(common)} grid points ({same} with the same number of "
                     f"steps): instruction ratio {min(ri):.3f}–{max(ri):.3f}, loop CPU ratio "
                     f"of the CSV {min(rc):.2f}–{max(rc):.2f}.")
    drifted = [r for r in rows if float(r["peak_force_drift"]) > 1e-5]
    lines.append(f"\nRuns whose peak force under valgrind differs from the CSV's by more "
                 f"than 1e-5 (relative; the CSV keeps 6 digits): {len(drifted)} of {len(rows)}"
                 + ("" if not drifted else ": " + ", ".join(
                     f"{r['scheme']} θ={r['theta']} {r['mesh']} h={r['time_step']} "
                     f"({r['peak_force_drift']})" for r in drifted)) + ".")
    # Instructions per CPU second: how far the two costs agree.
    rates = sorted(float(r["loop_instructions"]) / float(r["cpu_loop_seconds"])
                   for r in rows if float(r["cpu_loop_seconds"] or 0) > 0)
    if rates:
        lines.append(f"\nInstructions per loop CPU second of the CSV's runs: "
                     f"{rates[0] / 1e9:.2f}–{rates[-1] / 1e9:.2f}·10⁹ (median "
                     f"{rates[len(rates) // 2] / 1e9:.2f}·10⁹).")
    fig, ax = plt.subplots(figsize=(7, 5))
    for lab, rs in labeled.items():
        pts = sorted((float(r["loop_instructions"]), float(r["err_force"])) for r in rs)
        ax.plot([p[0] for p in pts], [p[1] for p in pts], "o", ms=3,
                color=wp.color_of(lab), alpha=0.5)
        f = fronts[lab]
        ax.plot([p[0] for p in f], [p[1] for p in f], "-", color=wp.color_of(lab), label=lab)
    wp.log_axes(ax)
    ax.set_xlabel("instructions of the time loop (callgrind)")
    ax.set_ylabel("err_force (relative L1 against the reference)")
    ax.set_title(f"{wp.SCENES[name]['title']}: error against instructions", fontsize=10)
    ax.legend(fontsize=6)
    fig.text(0.01, 0.005, wp.caption_line(args.build), fontsize=6)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    png = os.path.join(args.out, f"work_precision_{name}_instructions.png")
    fig.savefig(png, dpi=120)
    plt.close(fig)
    return "\n".join(lines), stats


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default=os.path.join(TOP, "doc"))
    parser.add_argument("--runs", default=os.path.join(TOP, "results/work_precision/callgrind"))
    parser.add_argument("--only", default="cylinder,plate,bars2d")
    parser.add_argument("--schemes", default="",
                        help="count only these <scheme>:<theta> rows (the CSV's "
                             "spelling); the others' counts in --out are kept")
    parser.add_argument("--jobs", type=int, default=2)
    parser.add_argument("--plot-only", action="store_true",
                        help="no runs: tables and figures from the instruction CSVs, "
                             "their errors taken again from the scenes' CSVs")
    args = parser.parse_args()
    args.build, args.out, args.runs = (os.path.abspath(p) for p in
                                       (args.build, args.out, args.runs))
    os.chdir(TOP)
    texts, stats = [], {}
    for name in args.only.split(","):
        if name not in wp.SCENES:
            sys.exit(f"--only: unknown scene '{name}' ({', '.join(wp.SCENES)})")
        path = os.path.join(args.out, f"work_precision_{name}_instructions.csv")
        if args.plot_only:
            rows = with_csv_errors(args, name, wp.read_csv(path))
            wp.write_csv(path, COLUMNS, rows)
        else:
            rows = count_scene(args, name)
            if args.schemes and os.path.exists(path):
                new = {(r["scheme"], r["theta"]) for r in rows}
                rows = with_csv_errors(args, name, [r for r in wp.read_csv(path)
                                                    if (r["scheme"], r["theta"]) not in new]) + rows
            wp.write_csv(path, COLUMNS, rows)
        text, stats[name] = report_scene(args, name, rows)
        print(text)
        texts.append(text + f"\n\n![{name}](work_precision_{name}_instructions.png)\n")
    md = os.path.join(args.out, "work_precision_instructions.md")
    made = ("Made by `/usr/bin/python3 benchmarks/work_precision/count_instructions.py"
            f" --only {args.only}`; {wp.caption_line(args.build)}.")
    if args.plot_only:
        # The counts are the CSVs' own: keep the line that says where they
        # were made, and say when the tables were redrawn.
        counted = made
        if os.path.exists(md):
            with open(md) as f:
                for line in f:
                    if line.startswith("Made by"):
                        counted = line.split(" What it counts")[0].strip()
                    elif line.startswith("Counts: "):
                        counted = line[len("Counts: "):].split(" Tables redrawn")[0].strip()
        made = (f"Counts: {counted} Tables redrawn with `--plot-only` on "
                f"{datetime.date.today().isoformat()}, the errors taken again from "
                "the scenes' CSVs.")
    with open(md, "w") as f:
        f.write("# Work–precision in instructions (generated)\n\n" + made
                + " What it counts and why: the script's docstring and "
                "doc/work_precision.md, \"Instructions instead of seconds\".\n"
                + "\n".join(texts))
    os.makedirs(args.runs, exist_ok=True)
    with open(os.path.join(args.runs, "summary.json"), "w") as f:
        json.dump(stats, f, indent=1)
    print("RESULT " + " ".join(
        f"{n}_runs={st['runs']} {n}_leader_wins_interpolated={st['leader_wins_interpolated']}"
        f" {n}_leader_wins_within_budget={st['leader_wins_within_budget']}"
        for n, st in stats.items()))

if __name__ == "__main__":
    main()
