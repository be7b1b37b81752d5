#!/usr/bin/env python3
"""A chain of N bars (Newton's cradle in 2D) on contact_mpi, Scene =
bodies: how the error against the exact 1D answer and the cost per step
grow with the number of bodies.

The bars are the paper's (0.254 x 0.0254 m, plane stress, 0.0254 m thick)
with nu = 0, so that the 2D bars are 1D bars; they touch, and bar 1 moves
at v0 = 5.13588 m/s. With `--materials alternating` every second bar is
of E/4 (impedance Z/2), so that each interface reflects. The run lasts
until the pulse has left the chain, (N + 2) L/c (equal bars) or (2 N + 4)
L/c (alternating). The exact answer is the characteristics solution of
tests/parallel/bars_1d_exact.py (for equal bars: all at rest but the last,
which leaves at v0). The error is the largest |p_b - p_b,exact| over the
bars, relative to m_1 v0; the energy ratio is the run's.

    /usr/bin/python3 benchmarks/bar_chain/run_bar_chain.py [--bars 4 8 16 32 64]
        [--cells 20] [--ranks 1 2] [--materials equal|alternating]
        [--build build] [--out doc]

Writes doc/bar_chain[_alternating].csv and .png (error and wall seconds
per step against N), results/bar_chain/summary.json, prints a table with
the machine and the commit, one RESULT line per run and a last RESULT
line for the whole sweep."""
import argparse
import csv
import json
import os
import platform
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests", "parallel"))
import bars_1d_exact  # noqa: E402

E, RHO, L, H, V0 = 0.20684e12, 0.78957e4, 0.254, 0.0254, 5.13588
STEP_20 = 0.2226e-5  # the step of 20 cells along a bar (Courant 1.42)

PRM = """set Dimension = 2
set Scene     = bodies
subsection Geometry
  set Thickness = 0.0254
end
subsection Bodies
  set Mesh files         = {files}
  set Initial velocities = {velocities}
  set Contact pairs      = {pairs}
  set Young's moduli     = {moduli}
end
subsection Loads
  set Gravity = 0
end
subsection Material
  set Young's modulus = {e}
  set Density         = {rho}
  set Poisson's ratio = 0
  set Plane model     = plane stress
end
subsection Discretization
  set Mass redistribution = true
end
subsection Time stepping
  set Scheme    = theta
  set Theta     = 0.51
  set Time step = {step}
  set End time  = {end}
end
subsection Output
  set Output directory       = results
  set VTU output             = false
  set Print performance data = true
end
"""


def moduli(n, materials):
    return [E / 4 if materials == "alternating" and b % 2 == 1 else E
            for b in range(n)]


def run_chain(program, n, cells, ranks, materials, work):
    os.makedirs(work, exist_ok=True)
    make_mesh = os.path.join(ROOT, "tests", "two_bars_2d", "make_bar_msh.py")
    files = []
    for b in range(n):
        name = f"bar_{b + 1}.msh"
        with open(os.path.join(work, name), "w") as out:
            subprocess.check_call([sys.executable, make_mesh, "2", str(cells),
                                   "4", str(b * L), str(L), str(H)],
                                  stdout=out)
        files.append(name)
    c = (E / RHO) ** 0.5
    end = (n + 2) * L / c if materials == "equal" else (2 * n + 4) * L / c
    e_list = moduli(n, materials)
    text = PRM.format(
        files=", ".join(files),
        velocities="; ".join([f"{V0}, 0"] + ["0, 0"] * (n - 1)),
        pairs=", ".join(f"{b}:1 against {b + 1}:0" for b in range(1, n)),
        moduli=", ".join(f"{x:.17g}" for x in e_list),
        e=E, rho=RHO, step=STEP_20 * 20 / cells, end=f"{end:.9g}")
    with open(os.path.join(work, "chain.prm"), "w") as out:
        out.write(text)
    command = [program, "chain.prm"]
    if ranks > 1:
        command = ["mpirun", "-np", str(ranks), "--oversubscribe"] + command
    env = dict(os.environ, OMP_NUM_THREADS="1",
               OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    log = subprocess.run(command, cwd=work, env=env, capture_output=True,
                         text=True)
    if log.returncode != 0:
        sys.exit(f"{' '.join(command)} in {work} failed:\n{log.stdout}"
                 f"\n{log.stderr}")
    summary = json.load(open(os.path.join(work, "results", "summary.json")))
    rows = list(csv.DictReader(open(os.path.join(work, "results",
                                                 "history.csv"))))
    total = float(rows[0]["body_1_momentum_x"])
    p = [float(rows[-1][f"body_{b + 1}_momentum_x"]) / total
         for b in range(n)]
    bars = [dict(length=L, youngs_modulus=e, density=RHO,
                 velocity=V0 if b == 0 else 0.)
            for b, e in enumerate(e_list)]
    exact = [x / (RHO * L * V0)
             for x in bars_1d_exact.momenta(bars, float(rows[-1]["time"]),
                                            100)]
    error = max(abs(a - b) for a, b in zip(p, exact))
    return dict(bars=n, cells_per_bar=cells, ranks=ranks, materials=materials,
                dofs=summary["dofs"], contacts=summary["contact_candidates"],
                steps=summary["steps_taken"],
                seconds_per_step=summary["loop_wall_seconds"] /
                summary["steps_taken"],
                momentum_error=error, energy_ratio=summary["energy_ratio"],
                fallbacks=summary["fallbacks"],
                largest_violation=summary["largest_violation"],
                checks_passed=summary["checks_passed"])


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--bars", type=int, nargs="+", default=[4, 8, 16, 32, 64])
    ap.add_argument("--cells", type=int, default=20)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--materials", choices=("equal", "alternating"),
                    default="equal")
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "doc"))
    a = ap.parse_args()
    program = os.path.join(a.build, "bin", "contact_mpi")
    suffix = "" if a.materials == "equal" else "_alternating"
    results = []
    for n in a.bars:
        for ranks in a.ranks:
            work = os.path.join(ROOT, "results", "bar_chain",
                                f"{a.materials}_{n}_bars_{ranks}_ranks")
            r = run_chain(program, n, a.cells, ranks, a.materials, work)
            results.append(r)
            print(f"RESULT bodies={n} contacts={r['contacts']} "
                  f"dofs={r['dofs']} ranks={ranks} "
                  f"seconds_per_step={r['seconds_per_step']:.6g} "
                  f"momentum_error={r['momentum_error']:.4g} "
                  f"energy_ratio={r['energy_ratio']:.6g} "
                  f"fallbacks={r['fallbacks']}", flush=True)

    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short",
                             "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    cpu = next((line.split(":", 1)[1].strip()
                for line in open("/proc/cpuinfo")
                if line.startswith("model name")), platform.processor())
    print(f"\nMachine: {cpu}, {os.cpu_count()} cores; commit {commit}; "
          f"materials {a.materials}, {a.cells} cells along each bar, "
          f"theta-method 0.51 with mass redistribution\n")
    print("| bars | ranks | DoFs | contacts | steps | wall s/step | "
          "momentum error (m_1 v0) | energy ratio | fallbacks | checks |")
    print("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|")
    for r in results:
        print(f"| {r['bars']} | {r['ranks']} | {r['dofs']} | "
              f"{r['contacts']} | {r['steps']} | "
              f"{r['seconds_per_step']:.3g} | {r['momentum_error']:.4f} | "
              f"{r['energy_ratio']:.4f} | {r['fallbacks']} | "
              f"{r['checks_passed']} |")
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, f"bar_chain{suffix}.csv"), "w",
              newline="") as out:
        writer = csv.DictWriter(out, fieldnames=list(results[0]))
        writer.writeheader()
        writer.writerows(results)
    summary_dir = os.path.join(ROOT, "results", "bar_chain")
    os.makedirs(summary_dir, exist_ok=True)
    with open(os.path.join(summary_dir, f"summary{suffix}.json"), "w") as out:
        json.dump(dict(machine=cpu, commit=commit, runs=results), out,
                  indent=1)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
    for ranks in a.ranks:
        rs = [r for r in results if r["ranks"] == ranks]
        right.loglog([r["bars"] for r in rs],
                     [r["seconds_per_step"] for r in rs], "o-",
                     label=f"{ranks} rank{'s' if ranks > 1 else ''}")
    rs = [r for r in results if r["ranks"] == a.ranks[0]]
    left.loglog([r["bars"] for r in rs], [r["momentum_error"] for r in rs],
                "o-")
    left.set_xlabel("bars N")
    left.set_ylabel("largest |p_b - p_b,exact| / (m_1 v0)")
    left.set_title(f"error at the end ({a.materials} bars)")
    right.set_xlabel("bars N")
    right.set_ylabel("wall seconds per step")
    right.set_title("cost per step")
    right.legend()
    for axis in (left, right):
        axis.grid(True, which="both", alpha=0.3)
    fig.suptitle(f"Chain of N bars, contact_mpi (commit {commit})")
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, f"bar_chain{suffix}.png"), dpi=100)
    worst = max(r["momentum_error"] for r in results)
    print(f"RESULT program=bar_chain materials={a.materials} "
          f"runs={len(results)} largest_bars={max(a.bars)} "
          f"largest_momentum_error={worst:.4g} "
          f"fallbacks={sum(r['fallbacks'] for r in results)}")


if __name__ == "__main__":
    main()
