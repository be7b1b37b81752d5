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
* the wall impulse and the change of momentum of summary.json;
* with --vtu (VTU output turned on in a copy of the file): the same
  number of outputs in both solution.pvd files, each of the distributed
  run a .pvtu whose pieces, one per rank, exist.

Checks that the runs were made on one and on two ranks (summary.json),
prints one line per quantity and exits with 1 if one differs by more."""
import argparse
import csv
import json
import os
import re
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
    ap.add_argument("--vtu", action="store_true")
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    os.makedirs(a.work)
    prm = a.prm
    if a.vtu:
        prm = os.path.join(a.work, "vtu.prm")
        with open(prm, "w") as out:
            # an override of the included file's entry (a second `set` in
            # one file is refused)
            out.write(f"include {os.path.abspath(a.prm)}\n"
                      "subsection Output\n  set VTU output = true\nend\n")
    runs = {"serial": [a.program, prm],
            "mpi": shlex.split(a.mpiexec) + [a.program, prm]}
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
        # sorted by the cell's centre rounded to 1e-6 of the bar's size
        # (the rows' order is the ranks'), compared unrounded
        rows = [tuple(float(x) for x in r) for r in
                list(csv.reader(open(path(name, "cells_final.csv"))))[1:]]
        size = max(max(abs(x) for x in r[:8]) for r in rows)

        def centre(r):
            return (round(sum(r[0:8:2]) / 4 / size, 6),
                    round(sum(r[1:8:2]) / 4 / size, 6))
        return sorted(rows, key=centre)
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
    ranks_ok = js["ranks"] == 1 and jm["ranks"] == 2
    failed = failed or not ranks_ok
    print(f"ranks: {js['ranks']} and {jm['ranks']} "
          f"{'OK' if ranks_ok else 'FAILED (expected 1 and 2)'}")
    for key in ("wall_impulse", "momentum_change"):
        report(key, abs(js[key] - jm[key]) / abs(js["initial_momentum"]))
    if a.vtu:
        def records(name):
            text = open(path(name, "solution.pvd")).read()
            return re.findall(r'file="([^"]+)"', text)
        serial_files, mpi_files = records("serial"), records("mpi")
        pieces_ok = len(mpi_files) == len(serial_files) > 0
        for pvtu in mpi_files:
            text = open(path("mpi", pvtu)).read()
            pieces = re.findall(r'Source="([^"]+)"', text)
            pieces_ok = pieces_ok and len(pieces) == 2 and all(
                os.path.exists(path("mpi", p)) for p in pieces)
        failed = failed or not pieces_ok
        print(f"VTU: {len(serial_files)} outputs and {len(mpi_files)} "
              f".pvtu of 2 pieces each {'OK' if pieces_ok else 'FAILED'}")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
