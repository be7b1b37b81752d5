#!/usr/bin/env python3
"""Strong scaling of contact_mpi: one and two MPI ranks on the same
block (3D: n x n/2 x n cells, the exact cone; 2D: n x n/2 cells, plane
strain) on a rigid plane, every bottom node sliding, a few time steps
each, for several n, with the direct (MUMPS), the AMG-CG and/or the
substructured solves of M~.

    /usr/bin/python3 benchmarks/parallel/run_strong_scaling.py [--sizes 16 24 32]
        [--dim 3] [--steps 10] [--ranks 1 2]
        [--solvers direct "amg cg" substructured]
        [--build build] [--out doc]

The 10^6-DoF scene of issue 14 is --dim 2 --sizes 1000 (1 003 002 DoFs,
1 001 contacts).

Writes doc/parallel_scaling.csv, doc/parallel_scaling.png (seconds per step
against DoFs, and the speed-up; --name changes the file names),
results/parallel_scaling/summary.json,
prints a table and ends with one RESULT line. The times are wall seconds
of the time loop (contact_mpi's RESULT line), so the machine must
be otherwise idle; the machine and the commit are printed with the
table."""
import argparse
import csv
import json
import os
import platform
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "benchmarks", "common"))
from runs import mpiexec  # noqa: E402

# the parts of the scene's file that both dimensions share
TIME_STEPPING = """subsection Time stepping
  set Scheme    = theta-euler
  set Theta     = 0.55
  set Time step = 5e-4
  set End time  = {end_time}
end
"""
# the block's material in both dimensions (the 2D template adds its plane
# model before the subsection ends)
MATERIAL = """subsection Material
  set Young's modulus = 1e9
  set Density         = 1e3
  set Poisson's ratio = 0.3
"""
PARALLEL_AND_OUTPUT = """subsection Parallel solver
  set Solver = {solver}
end
subsection Output
  set Output directory = {out}
  set VTU output       = false
  set Plot             = false
end
"""

PRM_2D = """set Dimension = 2
subsection Geometry
  set Length                  = 0.1
  set Height                  = {height}
  set Number of cells along x = {n}
  set Number of cells up      = {m}
end
subsection Initial conditions
  set Sliding speed     = 1
  set Sliding direction = 0
end
subsection Obstacle
  set Type                 = plane
  set Point on plane       = 0, 0
  set Normal               = 0, 1
  set Friction coefficient = 0.5
end
{material}  set Plane model     = plane strain
end
{time_stepping}subsection Contact solver
  set Method = active set
end
{parallel_and_output}"""

PRM = """set Dimension = 3
subsection Geometry
  set Length                  = 0.1
  set Height                  = {height}
  set Width                   = 0.1
  set Number of cells along x = {n}
  set Number of cells up      = {m}
  set Number of cells along z = {n}
end
subsection Initial conditions
  set Sliding speed     = 1
  set Sliding direction = 0.3
end
subsection Obstacle
  set Friction coefficient = 0.5
end
{material}end
{time_stepping}subsection Contact solver
  set Method        = active set
  set Friction cone = exact
end
{parallel_and_output}"""


def run(build, work, n, ranks, steps, solver, dim):
    m = max(1, n // 2)
    out = os.path.join(work, f"{dim}d_n{n}_r{ranks}_{solver.replace(' ', '_')}")
    os.makedirs(out, exist_ok=True)
    prm = os.path.join(out, "block.prm")
    with open(prm, "w") as f:
        common = {"material": MATERIAL,
                  "time_stepping": TIME_STEPPING.format(
                      end_time=steps * 5e-4 * (1 + 1e-9)),
                  "parallel_and_output": PARALLEL_AND_OUTPUT.format(
                      solver=solver, out=out)}
        f.write((PRM if dim == 3 else PRM_2D).format(
            n=n, m=m, height=0.1 * m / n, **common))
    proc = subprocess.run(mpiexec(ranks) + [os.path.join(build, "bin",
                                                         "contact_mpi"),
                                            prm],
                          capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"contact_mpi failed (n = {n}, {ranks} ranks):\n"
                 + proc.stdout[-2000:] + proc.stderr[-2000:])
    line = [l for l in proc.stdout.splitlines() if l.startswith("RESULT ")][-1]
    values = dict(kv.split("=", 1) for kv in line.split()[1:])
    summary = json.load(open(os.path.join(out, "summary.json")))
    return {"solver": solver, "dim": dim, "n": n, "ranks": ranks,
            "dofs": int(values["dofs"]),
            "contacts": int(values["contacts"]),
            "seconds_per_step": float(values["seconds_per_step"]),
            "setup_seconds": summary["setup_wall_seconds"],
            "products_per_step": summary["products"] / summary["n_steps"],
            "solve_fraction": summary["solve_wall_seconds"] / summary["loop_wall_seconds"],
            "cg_per_product": summary["cg_iterations"] / max(1, summary["products"] + summary["n_steps"]),
            "fallbacks": int(values["fallbacks"]),
            "largest_violation": float(values["largest_violation"])}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", type=int, nargs="+", default=[16, 24, 32])
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--steps", type=int, default=10)
    ap.add_argument("--dim", type=int, choices=[2, 3], default=3)
    ap.add_argument("--solvers", nargs="+", default=["direct"],
                    help="Parallel solver/Solver: direct, 'amg cg', "
                    "substructured")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "doc"))
    ap.add_argument("--name", default="parallel_scaling",
                    help="the CSV and PNG file names in --out")
    ap.add_argument("--work", default=os.path.join(ROOT, "results",
                                                   "parallel_scaling"))
    a = ap.parse_args()
    rows = [run(a.build, a.work, n, r, a.steps, s, a.dim) for s in a.solvers
            for n in a.sizes for r in a.ranks]
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short",
                             "HEAD"], capture_output=True, text=True).stdout.strip()
    cpu = ""
    if os.path.exists("/proc/cpuinfo"):
        m = re.search(r"model name\s*:\s*(.*)", open("/proc/cpuinfo").read())
        cpu = m.group(1) if m else ""
    print(f"contact_mpi strong scaling, commit {commit}, {cpu}, "
          f"{os.cpu_count()} cores, {platform.node()}")
    print(f"{'solver':>13} {'n':>4} {'DoFs':>8} {'contacts':>8} {'ranks':>5} {'set-up s':>8} {'s/step':>9} "
          f"{'W x/step':>8} {'CG/solve':>8} {'solves':>6} {'speed-up':>8}")
    base = {}
    for r in rows:
        if r["ranks"] == min(a.ranks):
            base[(r["solver"], r["n"])] = r["seconds_per_step"]
        r["speedup"] = base[(r["solver"], r["n"])] / r["seconds_per_step"]
        print(f"{r['solver']:>13} {r['n']:>4} {r['dofs']:>8} {r['contacts']:>8} {r['ranks']:>5} "
              f"{r['setup_seconds']:>8.2f} {r['seconds_per_step']:>9.4f} {r['products_per_step']:>8.1f} "
              f"{r['cg_per_product']:>8.2f} {r['solve_fraction']:>6.0%} "
              f"{r['speedup']:>8.2f}")
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, a.name + ".csv"), "w") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
        for solver in a.solvers:
            for ranks in a.ranks:
                rr = [r for r in rows
                      if r["ranks"] == ranks and r["solver"] == solver]
                label = f"{solver}, {ranks} rank{'s' if ranks > 1 else ''}"
                ax1.loglog([r["dofs"] for r in rr],
                           [r["seconds_per_step"] for r in rr], "o-",
                           label=label)
                if ranks != min(a.ranks):
                    ax2.semilogx([r["dofs"] for r in rr],
                                 [r["speedup"] for r in rr], "o-", label=label)
        ax1.set_xlabel("DoFs")
        ax1.set_ylabel("wall seconds per step")
        ax1.legend()
        ax1.set_title("contact_mpi, exact cone, (n+1)^2 contacts"
                      if a.dim == 3 else
                      "contact_mpi, 2D, n+1 contacts")
        ax2.set_xlabel("DoFs")
        ax2.set_ylabel("speed-up over 1 rank")
        ax2.axhline(1.6, color="grey", ls=":", label="issue 14's 1.6")
        ax2.legend()
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, a.name + ".png"), dpi=120)
    except ImportError:
        print("matplotlib not found: no plot")
    largest = max(a.sizes)
    big = {r["ranks"]: r for r in rows
           if r["n"] == largest and r["solver"] == a.solvers[0]}
    summary = {"commit": commit, "cpu": cpu, "rows": rows}
    os.makedirs(a.work, exist_ok=True)
    with open(os.path.join(a.work, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    top = max(a.ranks)
    print(f"RESULT program=run_strong_scaling dim={a.dim} "
          f"solver={a.solvers[0].replace(' ', '_')} "
          f"contacts={big[top]['contacts']} "
          f"dofs={big[top]['dofs']} ranks={top} "
          f"seconds_per_step={big[top]['seconds_per_step']:.4g} "
          f"speedup={big[top]['speedup']:.3g} "
          f"fallbacks={sum(r['fallbacks'] for r in rows)} "
          f"largest_violation={max(r['largest_violation'] for r in rows):.2g}")


if __name__ == "__main__":
    main()
