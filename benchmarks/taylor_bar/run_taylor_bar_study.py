#!/usr/bin/python3
"""The Taylor bar (issue 13, the paper's section 6.4): taylor_bar on three
meshes (time step halved with the cell size), plain Q1 against F-bar,
Coulomb friction and a bilateral wall, and the 3D quarter model on two
meshes (the check of the axisymmetric one), against the published range of finite-element
results (final length 21.42-21.7 mm, footprint radius 7.0-7.1 mm, largest
equivalent plastic strain near 3, as collected in issue 13).

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/taylor_bar/run_taylor_bar_study.py \
        [--build build] [--out doc] [--quick]
Writes <out>/taylor_bar.png (the paper's Fig. 10: initial mesh and final
shape coloured by the equivalent plastic strain), <out>/taylor_bar.csv,
results/taylor_bar_study/summary.json, and ends with a RESULT line.
"""
import argparse
import csv
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.collections import PolyCollection  # noqa: E402

PRM = "parameter_files/taylor_bar.prm"
PUBLISHED = {"final_length_mm": (21.42, 21.7),
             "footprint_radius_mm": (7.0, 7.1)}
# name, radial cells, axial cells, time step, F-bar, mu, bilateral contact,
# model
CASES = [("mesh 5x50", 5, 50, 2e-7, True, 0., False, "axisymmetric"),
         ("mesh 10x100", 10, 100, 1e-7, True, 0., False, "axisymmetric"),
         ("mesh 20x200", 20, 200, 5e-8, True, 0., False, "axisymmetric"),
         ("plain Q1 10x100", 10, 100, 1e-7, False, 0., False, "axisymmetric"),
         ("mu 0.1 10x100", 10, 100, 1e-7, True, 0.1, False, "axisymmetric"),
         ("mu 1 10x100", 10, 100, 1e-7, True, 1.0, False, "axisymmetric"),
         ("bilateral 10x100", 10, 100, 1e-7, True, 0., True, "axisymmetric"),
         ("3D quarter 4x50", 4, 50, 2e-7, True, 0., False, "3d"),
         ("3D quarter 8x100", 8, 100, 1e-7, True, 0., False, "3d")]
KEYS = ["final_length_mm", "footprint_radius_mm", "contact_radius_mm",
        "max_equivalent_plastic_strain", "energy_balance_relative_error",
        "newton_iterations_per_step", "newton_quadratic_fraction",
        "max_contact_violation", "n_dofs", "cpu_seconds"]


def overrides(nr, nz, h, fbar, mu, bilateral, model):
    return (f"subsection Geometry\n  set Model = {model}\n"
            f"  set Radial cells = {nr}\n"
            f"  set Axial cells = {nz}\nend\n"
            f"subsection Time\n  set Time step = {h}\nend\n"
            f"subsection Discretisation\n  set F-bar = {'true' if fbar else 'false'}\nend\n"
            f"subsection Contact\n  set Friction coefficient = {mu}\n"
            f"  set Bilateral contact = {'true' if bilateral else 'false'}\nend\n")


def read_cells(path):
    polygons, alpha = [], []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            polygons.append([(1e3 * float(r[f"r{i}"]), 1e3 * float(r[f"z{i}"]))
                             for i in range(4)])
            alpha.append(float(r["alpha"]))
    return polygons, alpha


def figure(results, out):
    fig, axes = plt.subplots(1, 4, figsize=(14, 6), sharey=True)
    for ax, (title, name) in zip(axes, [("initial mesh (10x100)", "mesh 10x100"),
                                        ("t = 80 us, F-bar, frictionless", "mesh 20x200"),
                                        ("t = 80 us, plain Q1 (locks)", "plain Q1 10x100"),
                                        ("t = 80 us, 3D quarter 8x100,\nsection y = 0",
                                         "3D quarter 8x100")]):
        kind = "cells_initial.csv" if title.startswith("initial") else "cells_final.csv"
        polygons, alpha = read_cells(os.path.join(results[name]["dir"], kind))
        mirrored = [[(-r, z) for r, z in p] for p in polygons]
        collection = PolyCollection(polygons + mirrored, array=alpha + alpha,
                                    cmap="jet", edgecolors="k", linewidths=0.1)
        collection.set_clim(0., 3.5)
        ax.add_collection(collection)
        ax.set_xlim(-8, 8)
        ax.set_ylim(-0.5, 33)
        ax.set_aspect("equal")
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("r [mm]")
    axes[0].set_ylabel("z [mm]")
    fig.colorbar(collection, ax=axes, label="equivalent plastic strain",
                 shrink=0.7)
    fig.suptitle("Taylor bar (copper, 227 m/s): impactfe taylor_bar\n"
                 + runs.machine_and_commit(), fontsize=9)
    fig.savefig(os.path.join(out, "taylor_bar.png"), dpi=130)


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default="doc")
    parser.add_argument("--quick", action="store_true",
                        help="only the two coarse meshes (a check of the script)")
    args = parser.parse_args()
    cases = CASES[:2] if args.quick else CASES
    results = {}
    for name, nr, nz, h, fbar, mu, bilateral, model in cases:
        directory = os.path.join("results", "taylor_bar_study",
                                 name.replace(" ", "_"))
        summary = runs.run(args.build, "taylor_bar", os.path.abspath(PRM),
                           directory,
                           overrides(nr, nz, h, fbar, mu, bilateral, model))
        results[name] = {k: summary[k] for k in KEYS}
        results[name]["dir"] = directory
        print(f"{name:18s} " + " ".join(f"{k}={summary[k]:.4g}" for k in KEYS),
              flush=True)
    with open(os.path.join(args.out, "taylor_bar.csv"), "w") as f:
        f.write("case," + ",".join(KEYS) + "\n")
        for name, r in results.items():
            f.write(name + "," + ",".join(f"{r[k]:.6g}" for k in KEYS) + "\n")
    if not args.quick:
        figure(results, args.out)
    finest = results[cases[-1 if args.quick else 2][0]]
    summary = {"cases": {n: {k: r[k] for k in KEYS} for n, r in results.items()},
               "published_range": PUBLISHED,
               "machine": runs.machine_and_commit()}
    os.makedirs("results/taylor_bar_study", exist_ok=True)
    with open("results/taylor_bar_study/summary.json", "w") as f:
        json.dump(summary, f, indent=2)
    print(f"RESULT benchmark=taylor_bar final_length_mm={finest['final_length_mm']:.4g} "
          f"footprint_radius_mm={finest['footprint_radius_mm']:.4g} "
          f"max_equivalent_plastic_strain={finest['max_equivalent_plastic_strain']:.4g} "
          f"energy_balance_relative_error={finest['energy_balance_relative_error']:.3g}")


if __name__ == "__main__":
    main()
