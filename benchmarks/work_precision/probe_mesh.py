#!/usr/bin/python3
"""Runs of some variants on one mesh outside a 2D scene's grid, scored as
the grid's runs are: what a scheme reaches past the grid's finest mesh.

usage (from anywhere; the script works from the repository top):
    /usr/bin/python3 benchmarks/work_precision/probe_mesh.py plate 60x48 \
        modified-theta+courant+ff4:0.025:4 theta+mr:0.55:2 ... \
        [--build build] [--runs results/work_precision/runs] [--repeats 3]

Each variant is <scheme>:<theta>:<factor>, spelt as the SCHEMES entries of
run_work_precision.py (for "+courant" the "theta" is kappa); the step is
h_paper * factor * dx / dx_paper, as in the grid. err_force is the grid's
(step_force(), l1_force_difference() over the reference's impulse) against
the reference run that run_work_precision.py left in
<runs>/<scene>/reference, so run the grid of that scene first. loop CPU is
the best of --repeats runs.

Why: the budgets of equal cost at the dear end of the grid compare each
scheme's runs on the finest mesh only, where a scheme whose best step is
large stops being cheaper long before the grid's dearest run; a mesh one
level finer shows what it would reach there (doc/work_precision.md, "Finer
references for the cylinder and the plate").

Prints a table, writes <runs>/<scene>/probe_<mesh>/summary.json, and ends
with one line `RESULT program=probe_mesh scene=... mesh=... <label>_err_force=...
<label>_loop_cpu=... ...` (labels: scheme_theta_factor).
"""
import argparse
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, os.path.join(HERE, "..", "common"))
sys.path.insert(0, HERE)
import runs  # noqa: E402
import run_work_precision as wp  # noqa: E402


def parse_variant(text):
    try:
        scheme, theta, factor = text.split(":")
        return scheme, float(theta), float(factor)
    except ValueError:
        sys.exit(f"variant '{text}': write <scheme>:<theta>:<factor>, "
                 "e.g. modified-theta+courant+ff4:0.025:4")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("scene", choices=["bars2d", "cylinder", "plate"])
    parser.add_argument("mesh", help="e.g. 60x48 (the scene's two mesh entries)")
    parser.add_argument("variants", nargs="+")
    parser.add_argument("--build", default="build")
    parser.add_argument("--runs", default=os.path.join(TOP, "results/work_precision/runs"))
    parser.add_argument("--repeats", type=int, default=3)
    args = parser.parse_args()
    args.build, args.runs = os.path.abspath(args.build), os.path.abspath(args.runs)
    os.chdir(TOP)  # the parameter files include each other relative to the top
    try:
        mesh = tuple(int(n) for n in args.mesh.split("x"))
        if len(mesh) != 2 or min(mesh) < 1:
            raise ValueError
    except ValueError:
        sys.exit(f"mesh '{args.mesh}': write two positive cell counts as NxM")
    variants = [parse_variant(v) for v in args.variants]

    sc = wp.SCENES[args.scene]
    prm, paper_mesh, h_paper, area, c_p = wp.scene_geometry(args.scene)
    end_time = float(wp.prm_value(prm, "End time"))
    dx_of = lambda m: math.sqrt(area / sc["cells"](m))  # noqa: E731
    ref_dir = os.path.join(args.runs, args.scene, "reference")
    if not os.path.exists(os.path.join(ref_dir, "history.csv")):
        sys.exit(f"no reference run in {ref_dir}: run run_work_precision.py "
                 f"--only {args.scene} first")
    reference = wp.read_force(ref_dir)
    norm = wp.reference_impulse(reference)
    with open(os.path.join(ref_dir, "summary.json")) as f:
        ref_summary = json.load(f)

    base = os.path.join(args.runs, args.scene, f"probe_{args.mesh}")
    rows = []
    for scheme, theta, factor in variants:
        h = h_paper * factor * dx_of(mesh) / dx_of(paper_mesh)
        out = os.path.join(base, f"{scheme}_{theta}_{factor:g}")
        loop = None
        for _ in range(max(1, args.repeats)):
            result = runs.run_measured(args.build, sc["program"], prm, out,
                                       wp.mesh_overrides(args.scene, mesh) + sc["extra"]
                                       + wp.time_stepping_overrides(scheme, theta, h))
            if result["summary"] is None or result["returncode"] != 0:
                sys.exit(f"{scheme}:{theta}:{factor:g} on {args.mesh} failed: "
                         f"{wp.status_of(result)}")
            seconds = result["summary"]["loop_cpu_seconds"]
            loop = seconds if loop is None else min(loop, seconds)
        err = wp.l1_force_difference(wp.step_force(out, scheme), reference, end_time) / norm
        rows.append({"scheme": scheme, "theta": theta, "factor": factor, "time_step": h,
                     "courant": c_p * h / dx_of(mesh), "err_force": err,
                     "loop_cpu_seconds": loop, "n_steps": result["summary"]["n_steps"],
                     "energy_ratio": result["summary"].get("energy_ratio")})

    print(f"{args.scene}, mesh {args.mesh} ({sc['cells'](mesh)} cells); reference "
          f"{ref_summary.get('n_steps')} steps in {ref_dir}; {wp.caption_line(args.build)}")
    print(wp.md_table(["scheme", "θ (κ)", "factor", "h", "C", "err_force",
                       "loop CPU s (best of %d)" % args.repeats],
                      [[r["scheme"], r["theta"], f"{r['factor']:g}", f"{r['time_step']:.4g}",
                        f"{r['courant']:.3g}", f"{r['err_force']:.4g}",
                        f"{r['loop_cpu_seconds']:.4g}"] for r in rows]))
    os.makedirs(base, exist_ok=True)
    with open(os.path.join(base, "summary.json"), "w") as f:
        json.dump({"scene": args.scene, "mesh": args.mesh, "reference": ref_dir,
                   "caption": wp.caption_line(args.build), "runs": rows}, f, indent=1)
    label = lambda r: f"{r['scheme']}_{r['theta']:g}_{r['factor']:g}"  # noqa: E731
    print("RESULT program=probe_mesh scene=%s mesh=%s " % (args.scene, args.mesh)
          + " ".join(f"{label(r)}_err_force={r['err_force']:.4g} "
                     f"{label(r)}_loop_cpu={r['loop_cpu_seconds']:.4g}" for r in rows))


if __name__ == "__main__":
    main()
