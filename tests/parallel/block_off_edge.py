#!/usr/bin/env python3
"""ctest driver of parallel/block_off_edge: contact_mpi with Scene =
bodies and a contact search every step (block_off_edge.prm: a block
sliding off the end of a slab). Checks

* one rank and two ranks give the same history.csv
  (tools/compare_histories.py, 1e-8);
* Coulomb's law while the block lies on the slab (t <= 0.01 s, all its
  contacts sliding): its horizontal momentum loses mu times its normal
  impulse, p_x(t) = p_x(0) - mu (p_y(t) + m g t), to 1e-6 of m v0 at
  every step (p from M v in history.csv, m = rho A t from the geometry).
  Not to round-off: the searches take the frames in the current
  configuration, whose normals the slab's deflection under the block tilts
  (by up to about 1e-5 rad; measured 2e-8 of m v0). A friction coefficient
  wrong by 1 % would show as 1e-4 of m v0;
* the slab's end: from the first step after which the block carries no
  contact force to the end, the block falls freely, p_y(t) = p_y(t_1) -
  m g (t - t_1) and p_x constant, to 1e-8 of m v0 at every step; it has
  left the slab's top (its last rows have no block contact) and did so
  after its centre passed the end (t_1 > 0.015 s: the centre, at 0.07 m,
  reaches 0.1 m at 0.015 s, slowing by mu g). The free fall follows from
  the impulse balance once the block's force is zero; what it adds is that
  the force is zero there, i.e. that the block's candidates are gone. The
  pair is one-sided (the block's nodes against the slab's top): while the
  block tips over the edge the slab's corner is not kept out of the block's
  lower side, which the test does not need;
* the same scene with the pairs of t = 0 ('Contact search interval' = 0)
  is the known wrong answer of small sliding: the block's nodes keep
  their segments, extended past the end, and the slab still carries its
  weight at the end (force on the block within 25 % of m g). That run must
  say so: its log has the warning that nodes slid off the slab's contact
  boundary, by more than 20 % of its length (the block's last node ends
  about 3 cm past the end of the 0.1 m slab), and summary.json's
  largest_slide_off agrees. The driver checks all of it, so that a change
  of either mode shows."""
import csv
import json
import os
import shlex
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import bodies_arguments, write_meshes  # noqa: E402
from serial_vs_mpi import run as run_logged  # noqa: E402

RHO, THICKNESS, G, MU, V0 = 1000., 0.01, 9.81, 0.2, 2.
MASS = RHO * 0.02 * 0.01 * THICKNESS
MESHES = {"slab.msh": (2, 20, 4, 0, 0.1, 0.01),           # DIM NX NY X0 L H
          "block.msh": (2, 4, 4, 0.06, 0.02, 0.01, 0.01)}  # ... Y0


def run(command, prm, make_mesh, work, interval=1):
    os.makedirs(work)
    write_meshes(make_mesh, work, MESHES)
    text = open(prm).read()
    if interval == 0:
        text = text.replace("set Contact search interval = 1",
                            "set Contact search interval = 0").replace(
            "  set Contact search distance = 1e-3\n", "")
    with open(os.path.join(work, "block_off_edge.prm"), "w") as out:
        out.write(text)
    run_logged(command + ["block_off_edge.prm"], work, "log")
    return os.path.join(work, "results", "history.csv")


def rows_of(history):
    return [{k: float(v) for k, v in row.items()}
            for row in csv.DictReader(open(history))]


def main():
    a = bodies_arguments()
    mpi = shlex.split(a.mpiexec) + [a.program]
    one = run([a.program], a.prm, a.make_mesh, os.path.join(a.work, "one"))
    two = run(mpi, a.prm, a.make_mesh, os.path.join(a.work, "two"))
    once = run([a.program], a.prm, a.make_mesh, os.path.join(a.work, "once"),
               interval=0)
    ok = os.system(f"{sys.executable} {a.compare} {one} {two}") == 0

    rows = rows_of(two)
    scale = MASS * V0
    p0 = rows[0]["body_2_momentum_x"]
    coulomb = max(abs(r["body_2_momentum_x"] - p0 +
                      MU * (r["body_2_momentum_y"] + MASS * G * r["time"]))
                  for r in rows if r["time"] <= 0.01 + 1e-12)
    print(f"Coulomb on the slab (t <= 0.01 s): largest |p_x - p_x(0) + mu "
          f"(p_y + m g t)| = {coulomb / scale:.2e} m v0")
    ok = ok and coulomb <= 1e-6 * scale

    # the first row from which the block carries no force to the end
    free = len(rows)
    while free > 0 and rows[free - 1]["body_2_force_x"] == 0. and \
            rows[free - 1]["body_2_force_y"] == 0.:
        free -= 1
    h = rows[1]["time"] - rows[0]["time"]
    left = free < len(rows) - 10
    fall = 0.
    if left:
        start = rows[free]
        for r in rows[free:]:
            fall = max(fall,
                       abs(r["body_2_momentum_y"] - start["body_2_momentum_y"]
                           + MASS * G * (r["time"] - start["time"])),
                       abs(r["body_2_momentum_x"] - start["body_2_momentum_x"]))
    print(f"the block carries no contact force from t = "
          f"{rows[min(free, len(rows) - 1)]['time']:.4f} s on "
          f"({len(rows) - free} steps); free fall: largest difference "
          f"{fall / scale:.2e} m v0")
    ok = ok and left and rows[free]["time"] > 0.015 and fall <= 1e-8 * scale

    floating = rows_of(once)[-1]["body_2_force_y"]
    print(f"with the pairs of t = 0 the slab carries {floating / (MASS * G):.3f}"
          f" m g at the end (the block slides on in the air)")
    ok = ok and abs(floating / (MASS * G) - 1.) <= 0.25
    log = open(os.path.join(a.work, "once", "log")).read()
    summary = json.load(open(os.path.join(a.work, "once", "results",
                                          "summary.json")))
    slide = summary["largest_slide_off"]
    warned = "Warning: nodes slid off the other body's contact boundary" in log
    print(f"and it warns that nodes slid off the slab: {warned}, by "
          f"{slide:.3f} of the slab's length")
    ok = ok and warned and slide > 0.2
    searched = json.load(open(os.path.join(a.work, "two", "results",
                                           "summary.json")))
    ok = ok and searched["contact_searches"] == 299
    print("OK" if ok else "WRONG")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
