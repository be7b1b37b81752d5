#!/usr/bin/env python3
"""ctest driver: run taylor_bar on one process and on two MPI ranks on the
same parameter file and compare what they wrote. Both runs must pass
their own checks (exit code 0). Compared, each against its own scale:

* every column of history.csv (length, footprint radius, the energies,
  the contact dissipation, the normal force, the largest plastic strain)
  to --tolerance of the largest |value| of the serial run's column; the
  Newton iterations and the LCP's rows of every step exactly;
* the deformed cells of cells_final.csv (their corners and plastic
  strain, rows sorted: the ranks write their cells in another order) to
  --tolerance of the bar's length (corners) and of the largest strain;
* the wall impulse and the change of momentum of summary.json.

Prints one line per quantity and exits with 1 if one differs by more."""
import argparse
import csv
import json
import os
import shlex
import shutil
import subprocess
import sys


def run(command, cwd):
    with open(os.path.join(cwd, "log"), "w") as out:
        code = subprocess.call(command, cwd=cwd, stdout=out,
                               stderr=subprocess.STDOUT)
    if code != 0:
        print(f"{' '.join(command)} exited with {code}; its output:")
        print(open(os.path.join(cwd, "log")).read())
        sys.exit(1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--program", required=True)
    ap.add_argument("--prm", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--tolerance", type=float, default=1e-8)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    runs = {"serial": [a.program, a.prm],
            "mpi": shlex.split(a.mpiexec) + [a.program, a.prm]}
    for name, command in runs.items():
        os.makedirs(os.path.join(a.work, name))
        run(command, os.path.join(a.work, name))

    def path(name, file):
        return os.path.join(a.work, name, "results", file)

    failed = False

    def report(quantity, difference, exact=False):
        nonlocal failed
        ok = difference == 0 if exact else difference <= a.tolerance
        failed = failed or not ok
        shown = "equal" if exact and ok else f"{difference:.1e}"
        print(f"{quantity}: {shown} {'OK' if ok else 'FAILED'}")

    serial = list(csv.DictReader(open(path("serial", "history.csv"))))
    mpi = list(csv.DictReader(open(path("mpi", "history.csv"))))
    if len(serial) != len(mpi) or not serial:
        print(f"history.csv: {len(serial)} rows against {len(mpi)}: FAILED")
        return 1
    for name in serial[0]:
        s = [float(r[name]) for r in serial]
        m = [float(r[name]) for r in mpi]
        if name in ("newton_iterations", "lcp_rows"):
            report(name, max(abs(x - y) for x, y in zip(s, m)), exact=True)
            continue
        scale = max(abs(x) for x in s) or 1.
        report(name, max(abs(x - y) for x, y in zip(s, m)) / scale)

    def cells(name):
        # sorted by the corners rounded to 1e-9 m (the rows' order is the
        # ranks'), compared unrounded
        rows = [tuple(float(x) for x in r) for r in
                list(csv.reader(open(path(name, "cells_final.csv"))))[1:]]
        return sorted(rows, key=lambda r: tuple(round(x, 9) for x in r[:8]))
    cs, cm = cells("serial"), cells("mpi")
    if len(cs) != len(cm):
        print(f"cells_final.csv: {len(cs)} cells against {len(cm)}: FAILED")
        return 1
    length = max(max(abs(x) for x in r[:8]) for r in cs)
    alpha = max(r[8] for r in cs) or 1.
    report("cells_final.csv corners",
           max(abs(x - y) for r, q in zip(cs, cm) for x, y in
               zip(r[:8], q[:8])) / length)
    report("cells_final.csv plastic strain",
           max(abs(r[8] - q[8]) for r, q in zip(cs, cm)) / alpha)

    js = json.load(open(path("serial", "summary.json")))
    jm = json.load(open(path("mpi", "summary.json")))
    print(f"ranks: {js['ranks']} and {jm['ranks']}")
    for key in ("wall_impulse", "momentum_change"):
        report(key, abs(js[key] - jm[key]) / abs(js["initial_momentum"]))
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
