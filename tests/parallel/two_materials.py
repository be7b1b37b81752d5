#!/usr/bin/env python3
"""ctest driver of parallel/two_materials: contact_mpi on one and two ranks
on two_materials.prm (two bars of different materials). Checks

* the two runs' history.csv agree (tools/compare_histories.py, 1e-8);
* the contact force over the middle half of [0, 2 L / c1] (before bar 1's
  reflected wave returns, away from the numerical wave fronts) is the 1D
  plateau A v0 Z1 Z2 / (Z1 + Z2), Z = sqrt(E rho), to 1 %; equal bars would
  give A v0 Z1 / 2, 50 % more, so the second material must be used."""
import argparse
import csv
import math
import os
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import run as run_logged  # noqa: E402


def run(command, cwd):
    os.makedirs(cwd)
    run_logged(command, cwd, "log")
    return os.path.join(cwd, "results", "history.csv")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--program", required=True)
    ap.add_argument("--prm", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--compare", required=True)
    ap.add_argument("--work", required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    one = run([a.program, a.prm], os.path.join(a.work, "one_rank"))
    two = run(shlex.split(a.mpiexec) + [a.program, a.prm],
              os.path.join(a.work, "two_ranks"))
    same = subprocess.call([sys.executable, a.compare, one, two])

    # the data of two_materials.prm
    E1, E2, rho, L, A, v0 = 0.20684e12, 0.5171e11, 0.78957e4, 0.254, \
        0.0254 ** 2, 5.13588
    z1, z2 = math.sqrt(E1 * rho), math.sqrt(E2 * rho)
    plateau = A * v0 * z1 * z2 / (z1 + z2)
    window = 2 * L / math.sqrt(E1 / rho)
    rows = list(csv.DictReader(open(two)))
    forces = [float(r["normal_force"]) for r in rows
              if 0.25 * window < float(r["time"]) <= 0.75 * window]
    mean = sum(forces) / len(forces)
    error = abs(mean / plateau - 1)
    ok = error <= 0.01
    print(f"contact force over [{0.25 * window:.3g}, {0.75 * window:.3g}] s "
          f"({len(forces)} steps): mean {mean:.6g} N, 1D plateau "
          f"{plateau:.6g} N, relative difference {error:.1e} "
          f"({'OK' if ok else 'WRONG'}, bound 1e-2)")
    return 0 if same == 0 and ok else 1


if __name__ == "__main__":
    sys.exit(main())
