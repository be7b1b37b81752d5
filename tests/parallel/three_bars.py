#!/usr/bin/env python3
"""ctest driver of parallel/three_bars and three_bars_3d: contact_mpi with
Scene = bodies on three_bars.prm or three_bars_3d.prm (--dim 3: three
equal bars in a row, bar 1 thrown at the others). Checks

* one rank and two ranks give the same history.csv
  (tools/compare_histories.py, 1e-8), 20 cells along each bar;
* the bars' mean velocities at the end against the 1D solution (bar 1
  and bar 2 at rest, bar 3 at v0: the pulse of length 2L that bar 1 makes
  passes through bar 2 into bar 3, which leaves at 3L/c): within 5 % of
  v0 with 20 cells, and closer with 40 cells (the same Courant number);
* the total momentum stays m v0 (each run checks its impulse balance)."""
import argparse
import csv
import os
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import run as run_logged  # noqa: E402

V0, L, H, STEP = 5.13588, 0.254, 0.0254, 0.2226e-5


def run(command, prm, dim, cells, make_mesh, work):
    """Meshes of `cells` along each bar (4 across in 2D, 2 x 2 in 3D) and
    the step for the same Courant number, then the run; returns its
    history.csv."""
    os.makedirs(work)
    across = "4" if dim == 2 else "2"
    for bar in range(3):
        with open(os.path.join(work, f"bar_{bar + 1}.msh"), "w") as out:
            subprocess.check_call(
                [sys.executable, make_mesh, str(dim), str(cells), across,
                 str((bar - 1) * L), str(L), str(H)], stdout=out)
    text = open(prm).read().replace(
        "set Time step = 0.2226e-5", f"set Time step = {STEP * 20 / cells}")
    with open(os.path.join(work, "three_bars.prm"), "w") as out:
        out.write(text)
    run_logged(command + ["three_bars.prm"], work, "log")
    return os.path.join(work, "results", "history.csv")


def final_velocities(history):
    rows = list(csv.DictReader(open(history)))
    mass = float(rows[0]["body_1_momentum_x"]) / V0
    return [float(rows[-1][f"body_{b}_momentum_x"]) / mass
            for b in (1, 2, 3)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--program", required=True)
    ap.add_argument("--prm", required=True)
    ap.add_argument("--make-mesh", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--compare", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--dim", type=int, choices=(2, 3), default=2)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    mpi = shlex.split(a.mpiexec) + [a.program]
    one = run([a.program], a.prm, a.dim, 20, a.make_mesh,
              os.path.join(a.work, "one_rank"))
    two = run(mpi, a.prm, a.dim, 20, a.make_mesh,
              os.path.join(a.work, "two_ranks"))
    fine = run(mpi, a.prm, a.dim, 40, a.make_mesh,
               os.path.join(a.work, "two_ranks_40"))
    same = subprocess.call([sys.executable, a.compare, one, two])

    exact = [0., 0., V0]
    ok = same == 0
    errors = []
    for cells, history in ((20, two), (40, fine)):
        v = final_velocities(history)
        error = max(abs(x - e) for x, e in zip(v, exact)) / V0
        errors.append(error)
        print(f"{cells} cells per bar: final velocities "
              f"{', '.join(f'{x:.4g}' for x in v)} m/s against 0, 0, {V0}: "
              f"largest difference {error:.3f} v0")
    ok = ok and errors[0] <= 0.05 and errors[1] < errors[0]
    print(f"within 5 % of v0 with 20 cells, closer with 40: "
          f"{'OK' if errors[0] <= 0.05 and errors[1] < errors[0] else 'WRONG'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
