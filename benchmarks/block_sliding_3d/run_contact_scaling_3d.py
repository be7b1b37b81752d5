#!/usr/bin/python3
"""Cost of a frictional 3D step against the number of contacts (issue 14):
a thin slab of n x 1 x n Q1 cells (0.1 m x 2 mm x 0.1 m, the material and
loads of parameter_files/block_sliding_3d.prm) sliding at 1 m/s on a rigid
plane, mu = 0.5, every one of its (n + 1)^2 bottom nodes a sliding contact,
with the exact circular cone and with the polygonal cone of 8 facets. The
active set method solves every step, W x by sparse solve pairs with M~
(`Dense Schur complement = false`, the same kind of product at every size;
the dense complement would need 7 GB at 10^4 contacts). 20 steps of
theta-Euler, h = 5e-4 s (5 until 2026-11-29: a longer run shows what
fronts and warm starts cost over time; --steps to change).

For each run: CPU seconds per step (the program's cost breakdown: free
velocity + contact problem + update), Newton and GMRES iterations per
step, refinements, fallbacks, the largest verification violation and the
run's Coulomb check. Fits the exponent of the cost per step in n_c from
10^3 to 3.10^4 contacts, writes doc/contact_scaling_3d.{csv,png} and
results/contact_scaling_3d/summary.json, prints a table and ends with one
RESULT line. Not a test: timings depend on the machine. Run from the
repository top:

  /usr/bin/python3 benchmarks/block_sliding_3d/run_contact_scaling_3d.py
      [--build build] [--out doc] [--quick]
"""
import argparse
import csv
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

sys.path.insert(0, os.path.dirname(__file__))
import run_performance  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

PRM = "parameter_files/block_sliding_3d.prm"
STEPS = 20
FIELDS = ["cells_per_edge", "cone", "dofs", "contacts", "steps",
          "seconds_per_step", "free_velocity_per_step", "lcp_per_step",
          "newton_iterations_per_step", "gmres_iterations_per_step",
          "refinements", "fallbacks", "largest_violation", "coulomb_excess",
          "wrong_slip_count", "returncode"]


def overrides(n, cone, steps=STEPS):
    return run_performance.overrides(n, steps, False, cone, height=0.002,
                                     cells_up=1)


def measure(build, n, cone, steps=STEPS):
    out_dir = os.path.join("results", "contact_scaling_3d", f"n{n}_{cone}")
    r = runs.run_measured(build, "block_sliding_3d", os.path.abspath(PRM),
                          out_dir, overrides(n, cone, steps))
    s = r["summary"]
    if s is None:
        sys.exit(f"n = {n}, {cone}: block_sliding_3d failed: {r['message']}")
    cost, lcp, checks = s["cost"], s["lcp"], s["checks"]
    row = {"cells_per_edge": n, "cone": cone if cone == "exact" else "8 facets",
           "dofs": 3 * s["nodes"], "contacts": s["contact_candidates"],
           "steps": s["n_steps"],
           "seconds_per_step": cost["free_velocity_per_step"] +
           cost["lcp_per_step"] + cost["update_per_step"],
           "free_velocity_per_step": cost["free_velocity_per_step"],
           "lcp_per_step": cost["lcp_per_step"],
           "newton_iterations_per_step":
           lcp["active_set_iterations"] / s["n_steps"],
           "gmres_iterations_per_step":
           lcp["active_set_gmres_iterations"] / s["n_steps"],
           "refinements": lcp["active_set_refinements"],
           "fallbacks": lcp["active_set_fallbacks"],
           "largest_violation": lcp["active_set_largest_violation"],
           "coulomb_excess": checks["coulomb_excess"],
           "wrong_slip_count": checks.get("wrong_slip_count", 0),
           "returncode": r["returncode"]}
    print({k: row[k] for k in FIELDS}, flush=True)
    if r["returncode"] != 0:
        sys.exit(f"n = {n}, {cone}: a check of the run failed: {r['message']}")
    return row


def exponent(rows, cone, lo=1e3):
    return runs.fit_exponent([(r["contacts"], r["seconds_per_step"])
                              for r in rows
                              if r["cone"] == cone and r["contacts"] >= lo])


def plot(rows, path):
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for cone, marker in (("exact", "o"), ("8 facets", "^")):
        sel = [r for r in rows if r["cone"] == cone]
        x = [r["contacts"] for r in sel]
        ax.loglog(x, [r["seconds_per_step"] for r in sel], marker + "-",
                  label=f"{cone} cone (exponent {exponent(rows, cone):.2f})")
        ax.loglog(x, [r["free_velocity_per_step"] for r in sel],
                  marker + ":", color="grey",
                  label="free velocity (one solve pair)" if cone == "exact"
                  else None)
    ax.axhline(1.0, color="grey", lw=0.8)
    ax.set_xlabel("frictional contacts (all sliding)")
    ax.set_ylabel("CPU seconds per step")
    ax.legend(fontsize=8)
    fig.suptitle("Thin slab n x 1 x n sliding on a plane, mu = 0.5, active "
                 f"set method, sparse products, {rows[0]['steps']} steps\n" +
                 runs.machine_and_commit(),
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=130)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    parser.add_argument("--quick", action="store_true")
    parser.add_argument("--steps", type=int, default=STEPS,
                        help="time steps per run (doc/'s table: 20)")
    args = parser.parse_args()

    sizes = [10, 31, 56] if args.quick else [10, 31, 56, 100, 173]
    rows = [measure(args.build, n, cone, args.steps)
            for n in sizes for cone in ("exact", "facets")]

    os.makedirs(args.out, exist_ok=True)
    with open(os.path.join(args.out, "contact_scaling_3d.csv"), "w",
              newline="") as f:
        writer = csv.DictWriter(f, fieldnames=FIELDS)
        writer.writeheader()
        writer.writerows(rows)
    plot(rows, os.path.join(args.out, "contact_scaling_3d.png"))

    print(f"{'n':>4} {'cone':>8} {'DoFs':>7} {'contacts':>8} {'s/step':>8} "
          f"{'free':>7} {'newton':>6} {'gmres':>6} {'refine':>6} "
          f"{'fallb':>5} {'coulomb':>8}")
    for r in rows:
        print(f"{r['cells_per_edge']:>4} {r['cone']:>8} {r['dofs']:>7} "
              f"{r['contacts']:>8} {r['seconds_per_step']:>8.3f} "
              f"{r['free_velocity_per_step']:>7.3f} "
              f"{r['newton_iterations_per_step']:>6.1f} "
              f"{r['gmres_iterations_per_step']:>6.1f} {r['refinements']:>6} "
              f"{r['fallbacks']:>5} {r['coulomb_excess']:>8.1e}")
    exponents = {cone: exponent(rows, cone) for cone in ("exact", "8 facets")}
    largest = max(rows, key=lambda r: (r["contacts"], r["cone"] == "exact"))
    near_1e4 = {r["cone"]: r for r in rows if r["cells_per_edge"] == 100}
    summary_dir = os.path.join("results", "contact_scaling_3d")
    with open(os.path.join(summary_dir, "summary.json"), "w") as f:
        json.dump({"machine": runs.machine_and_commit(), "runs": rows,
                   "exponents_from_1e3": exponents}, f, indent=1)
    print(f"RESULT contacts={largest['contacts']} dofs={largest['dofs']} "
          f"ranks=1 seconds_per_step={largest['seconds_per_step']:.3g} "
          f"cone=exact exponent_exact={exponents['exact']:.2f} "
          f"exponent_facets8={exponents['8 facets']:.2f} "
          + (f"seconds_per_step_1e4_exact="
             f"{near_1e4['exact']['seconds_per_step']:.3g} "
             f"seconds_per_step_1e4_facets8="
             f"{near_1e4['8 facets']['seconds_per_step']:.3g} "
             if len(near_1e4) == 2 else "")
          + f"lcp_relative_error={max(r['largest_violation'] for r in rows):.2g} "
          f"fallbacks={sum(r['fallbacks'] for r in rows)}")


if __name__ == "__main__":
    main()
