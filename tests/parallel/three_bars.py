#!/usr/bin/env python3
"""ctest driver of parallel/three_bars, three_bars_3d and three_materials:
contact_mpi with Scene = bodies on three bars in a row touching, bar 1
thrown at the others (three_bars.prm, three_bars_3d.prm with --dim 3:
equal bars; three_materials.prm: each bar of its own material, from
subsection Bodies' lists). Checks

* one rank and two ranks give the same history.csv
  (tools/compare_histories.py, 1e-8), 20 cells along each bar;
* each bar's momentum at the end against the exact 1D solution by
  characteristics (bars_1d_exact.py, an independent computation; for
  equal bars it is bars 1 and 2 at rest and bar 3 at v0: the pulse of
  length 2L that bar 1 makes passes through bar 2 into bar 3, which leaves
  at 3L/c), as fractions of m_1 v0: within 5 % with 20 cells, and closer
  with 40 cells (the same Courant number);
* the total momentum stays m_1 v0 (each run checks its impulse balance).
"""
import csv
import os
import shlex
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from serial_vs_mpi import bodies_arguments, write_meshes  # noqa: E402
from serial_vs_mpi import run as run_logged  # noqa: E402

import bars_1d_exact  # noqa: E402

V0, L, H, STEP = 5.13588, 0.254, 0.0254, 0.2226e-5


def exact_fractions(prm):
    """Each bar's momentum at the end time as a fraction of m_1 v0, by
    bars_1d_exact.momenta on the bars of `prm` (subsection Material, the
    per-body lists of subsection Bodies, the end time)."""
    values = {}
    section = ""
    for line in open(prm):
        words = line.split()
        if words[:1] == ["subsection"]:
            section = " ".join(words[1:])
        elif words[:1] == ["set"] and "=" in line:
            key, value = line.split("=", 1)
            values[(section, key.strip()[3:].strip())] = value.strip()

    def per_body(entry, material_entry):
        listed = values.get(("Bodies", entry), "")
        if listed:
            return [float(x) for x in listed.split(",")]
        return [float(values[("Material", material_entry)])] * 3

    moduli = per_body("Young's moduli", "Young's modulus")
    densities = per_body("Densities", "Density")
    bars = [dict(length=L, youngs_modulus=e, density=rho,
                 velocity=V0 if b == 0 else 0.)
            for b, (e, rho) in enumerate(zip(moduli, densities))]
    end = float(values[("Time stepping", "End time")])
    p = bars_1d_exact.momenta(bars, end, 200)
    return [x / (densities[0] * L * V0) for x in p]


def run(command, prm, dim, cells, make_mesh, work):
    """Meshes of `cells` along each bar (4 across in 2D, 2 x 2 in 3D) and
    the step for the same Courant number, then the run; returns its
    history.csv."""
    os.makedirs(work)
    across = 4 if dim == 2 else 2
    write_meshes(make_mesh, work,
                 {f"bar_{bar + 1}.msh": (dim, cells, across, (bar - 1) * L,
                                         L, H) for bar in range(3)})
    text = open(prm).read().replace(
        "set Time step = 0.2226e-5", f"set Time step = {STEP * 20 / cells}")
    with open(os.path.join(work, "three_bars.prm"), "w") as out:
        out.write(text)
    run_logged(command + ["three_bars.prm"], work, "log")
    return os.path.join(work, "results", "history.csv")


def final_fractions(history):
    """Each bar's momentum at the end as a fraction of m_1 v0."""
    rows = list(csv.DictReader(open(history)))
    total = float(rows[0]["body_1_momentum_x"])
    return [float(rows[-1][f"body_{b}_momentum_x"]) / total
            for b in (1, 2, 3)]


def main():
    a = bodies_arguments(dim=True)
    mpi = shlex.split(a.mpiexec) + [a.program]
    one = run([a.program], a.prm, a.dim, 20, a.make_mesh,
              os.path.join(a.work, "one_rank"))
    two = run(mpi, a.prm, a.dim, 20, a.make_mesh,
              os.path.join(a.work, "two_ranks"))
    fine = run(mpi, a.prm, a.dim, 40, a.make_mesh,
               os.path.join(a.work, "two_ranks_40"))
    same = subprocess.call([sys.executable, a.compare, one, two])

    exact = exact_fractions(a.prm)
    ok = same == 0
    errors = []
    for cells, history in ((20, two), (40, fine)):
        p = final_fractions(history)
        error = max(abs(x - e) for x, e in zip(p, exact))
        errors.append(error)
        print(f"{cells} cells per bar: momenta at the end "
              f"{', '.join(f'{x:.4f}' for x in p)} m_1 v0 against the "
              f"exact {', '.join(f'{x:.4f}' for x in exact)}: largest "
              f"difference {error:.3f} m_1 v0")
    ok = ok and errors[0] <= 0.05 and errors[1] < errors[0]
    print(f"within 5 % of m_1 v0 with 20 cells, closer with 40: "
          f"{'OK' if errors[0] <= 0.05 and errors[1] < errors[0] else 'WRONG'}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
