#!/usr/bin/env python3
"""ctest driver of parallel/stack_search: contact_mpi with Scene = bodies
on three blocks stacked on a plane, the pairs named one by one
(stack_search_explicit.prm) and found by the contact search
(stack_search_all.prm: 'all:2 against all:3' within 1e-9 m); with
--dim 3 the same blocks extruded along z (node-to-face). Checks

* the search finds the named pairs: the same number of candidates, and
  the same history.csv to the last printed digit (the same candidates in
  the same order make the same run);
* the search run on two ranks gives the one-rank history
  (tools/compare_histories.py, 1e-8);
* a search within 0.05 m (more than a block's height) finds more
  candidates, on the outer sides only, and gives the same history to
  1e-8: the far candidates never touch. (Paired with the inner side, a
  block's lower nodes would start 0.04 m inside the block two above and
  be pushed out: 2.5e5 times the initial energy before the search kept to
  the outer sides);
* the upper blocks were dragged (their momentum along x grows), so that
  the pairs between blocks carried impulses."""
import csv
import filecmp
import os
import re
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import bodies_arguments, write_meshes  # noqa: E402
from serial_vs_mpi import run as run_logged  # noqa: E402

BLOCKS = {"block_1.msh": ("2", "10", "2", "0", "0.1", "0.02", "0"),
          "block_2.msh": ("2", "8", "2", "0.01", "0.08", "0.02", "0.02"),
          "block_3.msh": ("2", "6", "2", "0.02", "0.06", "0.02", "0.04")}


def run(command, prm, make_mesh, work, dim):
    """The meshes and the run (in 3D the blocks' sections extruded along z
    over their height, node-to-face); its history.csv and its candidate
    count."""
    os.makedirs(work)
    write_meshes(make_mesh, work,
                 {name: (dim,) + args[1:] for name, args in BLOCKS.items()})
    text = open(prm).read()
    if dim == 3:
        for old, new in (("set Dimension = 2", "set Dimension = 3"),
                         ("1, 0; 0, 0; 0, 0", "1, 0, 0; 0, 0, 0; 0, 0, 0"),
                         ("Point on plane       = 0, 0",
                          "Point on plane       = 0, 0, 0"),
                         ("Normal               = 0, 1",
                          "Normal               = 0, 1, 0"),
                         ("  set Thickness = 0.01\n", "")):
            assert old in text, old
            text = text.replace(old, new)
    with open(os.path.join(work, "stack.prm"), "w") as out:
        out.write(text)
    run_logged(command + ["stack.prm"], work, "log")
    log = open(os.path.join(work, "log")).read()
    found = re.search(r"(\d+) contact candidates", log)
    return (os.path.join(work, "results", "history.csv"),
            int(found.group(1)) if found else -1)


def main():
    a = bodies_arguments(("--explicit", "--search"), dim=True)
    named, n_named = run([a.program], a.explicit, a.make_mesh,
                         os.path.join(a.work, "named"), a.dim)
    found, n_found = run([a.program], a.search, a.make_mesh,
                         os.path.join(a.work, "search"), a.dim)
    two, _ = run(shlex.split(a.mpiexec) + [a.program], a.search, a.make_mesh,
                 os.path.join(a.work, "search_two_ranks"), a.dim)
    # a search distance larger than a block: pairs with the farther blocks
    # too, only on the outer sides (no block starts inside another)
    wide_prm = os.path.join(a.work, "wide.prm")
    with open(wide_prm, "w") as out:
        out.write(open(a.search).read().replace(
            "set Contact search distance = 1e-9",
            "set Contact search distance = 0.05"))
    wide, n_wide = run([a.program], wide_prm, a.make_mesh,
                       os.path.join(a.work, "search_wide"), a.dim)
    same = n_named == n_found and n_named > 0 and \
        filecmp.cmp(named, found, shallow=False)
    print(f"named pairs: {n_named} candidates; search: {n_found}; "
          f"history.csv identical: {'OK' if same else 'WRONG'}")
    ok = same and subprocess.call([sys.executable, a.compare, found, two]) == 0
    far = n_wide > n_named
    print(f"search within 0.05 m: {n_wide} candidates (the far ones never "
          f"touch): {'OK' if far else 'WRONG'}")
    ok = ok and far and \
        subprocess.call([sys.executable, a.compare, named, wide]) == 0
    rows = list(csv.DictReader(open(found)))
    dragged = all(float(rows[-1][f"body_{b}_momentum_x"]) > 0.
                  for b in (2, 3))
    print(f"blocks 2 and 3 dragged along x: {'OK' if dragged else 'WRONG'}")
    return 0 if ok and dragged else 1


if __name__ == "__main__":
    sys.exit(main())
