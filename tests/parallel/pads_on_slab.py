#!/usr/bin/env python3
"""ctest driver of parallel/pads_on_slab: contact_mpi with Scene = bodies
on pads_on_slab.prm (a slab sliding on a plane under two pads at rest,
each pad's pair with its own friction coefficient, 0.5 and 0.1). Checks

* one rank and two ranks give the same history.csv
  (tools/compare_histories.py, 1e-8);
* Coulomb's law per pair, through the pads' momenta: while the slab
  slides under a pad, each of its closed contacts slides and has P_T =
  mu P_N, so the pad's horizontal momentum is mu times its normal impulse,
  p_x(t) = mu (p_y(t) + m g t) (the normal impulse balances the vertical
  momentum and gravity), at every step to 1e-8 of mu m g T. p is the
  body's M v (history.csv), m = rho A t from the geometry: neither comes
  from the contact impulses. With one coefficient for both pads the check
  fails for one of them;
* the pads did move (p_x > 0.5 of mu m g T at the end) and the slab
  stayed faster than both (its mean velocity above theirs)."""
import csv
import os
import shlex
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import bodies_arguments, write_meshes  # noqa: E402
from serial_vs_mpi import run as run_logged  # noqa: E402

RHO, THICKNESS, G = 1000., 0.01, 9.81
SLAB = ("2", "40", "4", "0", "0.2", "0.02")          # DIM NX NY X0 L H
PADS = {2: (("2", "8", "4", "0.02", "0.04", "0.02", "0.02"), 0.5),
        3: (("2", "8", "4", "0.12", "0.04", "0.02", "0.02"), 0.1)}


def run(command, prm, make_mesh, work):
    os.makedirs(work)
    meshes = {"slab.msh": SLAB}
    meshes.update({f"pad_{b}.msh": args for b, (args, _) in PADS.items()})
    write_meshes(make_mesh, work, meshes)
    shutil.copy(prm, os.path.join(work, "pads_on_slab.prm"))
    run_logged(command + ["pads_on_slab.prm"], work, "log")
    return os.path.join(work, "results", "history.csv")


def main():
    a = bodies_arguments()
    one = run([a.program], a.prm, a.make_mesh,
              os.path.join(a.work, "one_rank"))
    two = run(shlex.split(a.mpiexec) + [a.program], a.prm, a.make_mesh,
              os.path.join(a.work, "two_ranks"))
    ok = subprocess.call([sys.executable, a.compare, one, two]) == 0

    rows = list(csv.DictReader(open(two)))
    end = float(rows[-1]["time"])
    slab_mass = RHO * 0.2 * 0.02 * THICKNESS
    slab_v = float(rows[-1]["body_1_momentum_x"]) / slab_mass
    for b, (args, mu) in PADS.items():
        m = RHO * float(args[4]) * float(args[5]) * THICKNESS
        scale = mu * m * G * end
        worst = max(abs(float(r[f"body_{b}_momentum_x"]) -
                        mu * (float(r[f"body_{b}_momentum_y"]) +
                              m * G * float(r["time"])))
                    for r in rows)
        p_x = float(rows[-1][f"body_{b}_momentum_x"])
        moved = p_x > 0.5 * scale and slab_v > p_x / m
        print(f"pad {b} (mu = {mu}): p_x - mu (p_y + m g t) at most "
              f"{worst / scale:.1e} of mu m g T, bound 1e-8 "
              f"({'OK' if worst <= 1e-8 * scale else 'WRONG'}); p_x(T) = "
              f"{p_x / scale:.4f} mu m g T, pad at {p_x / m:.4f} m/s, slab "
              f"at {slab_v:.4f} m/s ({'OK' if moved else 'WRONG'})")
        ok = ok and worst <= 1e-8 * scale and moved
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
