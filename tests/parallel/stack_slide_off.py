#!/usr/bin/env python3
"""ctest driver of parallel/stack_slide_off: the measure of small sliding,
ContactSet::largest_slide_off() in the serial programs and
DistributedContact::largest_slide_off() in contact_mpi, against the
bodies' motion. The stack of two equal blocks (0.1 m long), the lower one
launched at 1 m/s under the upper (serial block_on_plane with Body 2,
tests/parallel/serial_vs_mpi_stack_serial.prm; contact_mpi on
parameter_files/block_stack_mpi.prm): the lower block slides d(t) under
the upper one, so the end nodes of one block pass the other's end by d(t),
and the largest slide off the other block's contact boundary is max_t
d(t) / 0.1 m. d(t) comes from history.csv alone: theta-Euler moves every
node, hence the mean, by h v^{n+1}, so d(t_n) = sum_k h (v_lower^k -
v_upper^k) with v = p / m and m = rho A t from the geometry. Checks, for
each program:

* summary.json's largest_slide_off equals max d / 0.1 m to 1e-3 (the
  blocks' deformation moves the end nodes by far less);
* the log warns (the slide is above 1 % of the length)."""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys

RHO, THICKNESS, LENGTH, STEP = 1000., 0.01, 0.1, 2e-4
MASS = {"lower": RHO * LENGTH * 0.02 * THICKNESS,
        "upper": RHO * LENGTH * 0.05 * THICKNESS}


def run(command, prm, work):
    """The run in @p work, on the parameter file where it is (its meshes
    are beside it)."""
    os.makedirs(work)
    with open(os.path.join(work, "log"), "w") as out:
        code = subprocess.call(command + [os.path.abspath(prm)], cwd=work,
                               stdout=out, stderr=subprocess.STDOUT)
    if code != 0:
        print(open(os.path.join(work, "log")).read())
        sys.exit(f"{' '.join(command)} exited with {code}")


def largest_relative_slide(history, lower, upper):
    d = largest = 0.
    for row in csv.DictReader(open(history)):
        v_lower = float(row[lower]) / MASS["lower"]
        v_upper = float(row[upper]) / MASS["upper"]
        if float(row["time"]) > 0.:
            d += STEP * (v_lower - v_upper)
        largest = max(largest, abs(d))
    return largest / LENGTH


def check(name, work, results, lower, upper):
    slide = json.load(open(os.path.join(results, "summary.json")))
    slide = slide.get("checks", slide)["largest_slide_off"]
    expected = largest_relative_slide(os.path.join(results, "history.csv"),
                                      lower, upper)
    warned = "Warning: nodes slid off" in open(os.path.join(work,
                                                            "log")).read()
    ok = abs(slide - expected) <= 1e-3 and warned
    print(f"{name}: largest slide off {slide:.5f} of the length, from the "
          f"momenta {expected:.5f}; warned: {warned}: "
          f"{'OK' if ok else 'WRONG'}")
    return ok


def main():
    ap = argparse.ArgumentParser()
    for option in ("--serial", "--serial-prm", "--parallel", "--parallel-prm",
                   "--work"):
        ap.add_argument(option, required=True)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    run([a.serial], a.serial_prm, os.path.join(a.work, "serial"))
    mpi_work = os.path.join(a.work, "mpi")
    run([a.parallel], a.parallel_prm, mpi_work)
    serial = os.path.join(a.work, "serial")
    ok = check("block_on_plane", serial, os.path.join(serial, "results"),
               "block_momentum_x", "block_2_momentum_x")
    ok &= check("contact_mpi", mpi_work,
                os.path.join(mpi_work, "results", "block_stack_mpi"),
                "body_2_momentum_x", "body_1_momentum_x")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
