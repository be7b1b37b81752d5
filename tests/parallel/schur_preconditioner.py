#!/usr/bin/env python3
"""ctest driver of parallel/schur_preconditioner: contact_mpi on the thin
slab of schur_preconditioner.prm (121 exact-cone contacts, all sliding)
with the substructured solver's three ways of making the contact
problem's products and preconditioner:

* dense: S_C formed, preconditioner H^T S_C H (one rank);
* sparse, Schur complement: S_C applied by solves with M~ pinned on the
  contact DoFs (one rank and two);
* sparse, contact block: H^T M~ H (one rank).

Checks: every run passes its own checks (exit code 0); the four
history.csv agree (tools/compare_histories.py, 1e-8); the pinned-solve
preconditioner is the dense one: its products W x (summary.json) are
those of the dense run to 10 % (the same operator, so the same GMRES
iterations up to round-off), and the contact block's are at least three
times as many (why the Schur complement is the default in 3D with
friction)."""
import argparse
import json
import os
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import run as run_logged  # noqa: E402

VARIANTS = {"dense": ("dense", None),
            "schur": ("sparse", "Schur complement"),
            "block": ("sparse", "contact block")}


def run(command, prm, work, variant):
    os.makedirs(work)
    operator, preconditioner = VARIANTS[variant]
    text = open(prm).read() + ("subsection Parallel solver\n"
                               "  set Solver           = substructured\n"
                               f"  set Contact operator = {operator}\n")
    if preconditioner:
        text += f"  set Contact preconditioner = {preconditioner}\n"
    with open(os.path.join(work, "slab.prm"), "w") as f:
        f.write(text + "end\n")
    run_logged(command + ["slab.prm"], work, "log")
    summary = json.load(open(os.path.join(work, "results", "summary.json")))
    return os.path.join(work, "results", "history.csv"), summary


def main():
    ap = argparse.ArgumentParser()
    for option in ("--program", "--prm", "--mpiexec", "--compare",
                   "--work"):
        ap.add_argument(option, required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    runs = {name: run([a.program], a.prm, os.path.join(a.work, name), name)
            for name in VARIANTS}
    runs["schur, 2 ranks"] = run(shlex.split(a.mpiexec) + [a.program],
                                 a.prm, os.path.join(a.work, "schur_2"),
                                 "schur")
    ok = True
    for name, (history, summary) in runs.items():
        expected = ("dense", "") if name == "dense" else (
            "sparse", "contact block" if name == "block" else
            "Schur complement")
        used = (summary["contact_operator"],
                summary["contact_preconditioner"])
        good = used == expected
        print(f"{name}: contact operator {used[0]}, preconditioner "
              f"'{used[1]}' ({'OK' if good else 'WRONG'})")
        ok = ok and good
        if name != "dense":
            same = subprocess.call([sys.executable, a.compare,
                                    runs["dense"][0], history]) == 0
            ok = ok and same
    products = {name: s["products"] for name, (_, s) in runs.items()}
    close = abs(products["schur"] - products["dense"]) <= \
        0.1 * products["dense"]
    weaker = products["block"] >= 3 * products["schur"]
    print("products W x of the pinned-solve preconditioner within 10 % of "
          f"the dense run's: {'OK' if close else 'WRONG'}")
    print("the contact block's products at least three times as many: "
          f"{'OK' if weaker else 'WRONG'}")
    return 0 if ok and close and weaker else 1


if __name__ == "__main__":
    sys.exit(main())
