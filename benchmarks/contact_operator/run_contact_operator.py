#!/usr/bin/env python3
"""contact_mpi with many contacts: the substructured solver's dense and
sparse contact operators (`Parallel solver/Contact operator`) and MUMPS
(`Solver = direct`), on a block sliding over a slab that lies on a rigid
plane, with a contact search every step (Scene = bodies, 2D).

    /usr/bin/python3 benchmarks/contact_operator/run_contact_operator.py
        [--sizes 250 500 1000 2000 4000 8000 16000] [--steps 5]
        [--dense-max 1000] [--direct-max 4000] [--ranks 1 2]
        [--build build] [--out doc]

The scene (block_on_slab.prm.in, README.md): a slab 1 m x 0.01 m of
n x 2 cells on the plane (mu = 0.5), a block 0.5 m x 0.005 m of
(n/2 + 1) x 2 cells on it sliding at 1 m/s (mu = 0.3 between them),
gravity, plane strain, theta = 0.55, h = 1e-4 s. The candidates are every
node of the slab's lower side against the plane and every node of the
block's lower side against the slab's upper side: about 1.5 n; the
contact DoFs (every node of the three named sides) about 5 n.

Every run must pass its own checks (exit code 0: verification of every
contact problem, impulse balance). The runs of one size must also agree:
every column of history.csv against the sparse operator's one-rank run, to
1e-8 of the column's scale (largest_difference). The memory is the peak
resident set of one-rank runs (GNU time).

Writes doc/contact_operator.csv and doc/contact_operator.png (set-up and
per-step wall seconds against contacts), results/contact_operator/
summary.json, prints a table with the machine and the commit, and ends
with one RESULT line."""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "benchmarks", "common"))
from runs import (fit_exponent, machine_and_commit, mpiexec,  # noqa: E402
                  result_checks)

MAKE_MESH = os.path.join(ROOT, "tests", "two_bars_2d", "make_bar_msh.py")


def write_scene(out, n, steps, solver, operator):
    """The meshes and the parameter file of size n in @p out."""
    os.makedirs(out, exist_ok=True)
    for name, args in (("slab.msh", (2, n, 2, 0, 1, 0.01)),
                       ("block.msh", (2, n // 2 + 1, 2, 0.1, 0.5, 0.005,
                                      0.01))):
        with open(os.path.join(out, name), "w") as f:
            subprocess.check_call([sys.executable, MAKE_MESH,
                                   *(str(x) for x in args)], stdout=f)
    template = open(os.path.join(HERE, "block_on_slab.prm.in")).read()
    prm = os.path.join(out, "block_on_slab.prm")
    with open(prm, "w") as f:
        f.write(template.format(end_time=steps * 1e-4 * (1 + 1e-9),
                                solver=solver, operator=operator, out=out))
    return prm


def run_contact_mpi(build, prm, out, ranks, what):
    """contact_mpi on @p prm in @p out on @p ranks ranks (one rank under GNU
    time); stops the script with its output if it fails. Returns its
    RESULT line's values, summary.json and, on one rank, the peak resident
    set in GiB (nan on several)."""
    time_file = os.path.join(out, "time.txt")
    command = (mpiexec(ranks) if ranks > 1 else
               ["/usr/bin/time", "-f", "%M", "-o", time_file])
    proc = subprocess.run(command + [os.path.join(build, "bin",
                                                  "contact_mpi"), prm],
                          capture_output=True, text=True, cwd=out)
    if proc.returncode != 0:
        sys.exit(f"contact_mpi failed ({what}, {ranks} ranks):\n"
                 + proc.stdout[-2000:] + proc.stderr[-2000:])
    line = [l for l in proc.stdout.splitlines()
            if l.startswith("RESULT ")][-1]
    values = dict(kv.split("=", 1) for kv in line.split()[1:])
    summary = json.load(open(os.path.join(out, "summary.json")))
    peak = (float(open(time_file).read().split()[-1]) / 2**20
            if ranks == 1 else float("nan"))
    return values, summary, peak


def run(build, work, n, ranks, steps, variant):
    solver, operator = (("direct", "automatic") if variant == "direct" else
                        ("substructured", variant))
    out = os.path.join(work, f"n{n}_r{ranks}_{variant}")
    prm = write_scene(out, n, steps, solver, operator)
    values, summary, peak = run_contact_mpi(build, prm, out, ranks,
                                            f"n = {n}, {variant}")
    return {"variant": variant, "n": n, "ranks": ranks,
            "dofs": int(values["dofs"]),
            "contacts": int(values["contacts"]),
            "setup_seconds": summary["setup_wall_seconds"],
            "seconds_per_step": float(values["seconds_per_step"]),
            "products_per_step": summary["products"] / summary["n_steps"],
            "search_seconds_per_step":
                summary["contact_search_wall_seconds"] / summary["n_steps"],
            "peak_gib": peak,
            "fallbacks": int(values["fallbacks"]),
            "largest_violation": float(values["largest_violation"]),
            "history": os.path.join(out, "history.csv")}


def largest_difference(path, reference):
    """The largest difference of a history.csv column from the reference
    run's, relative to the largest value there of the vector the column
    is a component of (x, y, z), or of the column itself; the energies'
    relative to the largest kinetic plus the largest elastic energy (the
    elastic energy alone is 1e-5 of it on the 2D slab, and its last
    digits are round-off of the sum over the ranks)."""
    def columns(p):
        with open(p, newline="") as f:
            rows = list(csv.DictReader(f))
        return {k: [float(r[k]) for r in rows] for k in rows[0]}
    a, b = columns(path), columns(reference)

    def group(key):
        # a vector's components share its scale (a component that stays
        # near zero, as the vertical momentum of a sliding body, is
        # compared against the vector's size), and so do the energies
        if key in ("kinetic_energy", "elastic_energy"):
            return "energy"
        return key[:-2] if key[-2:] in ("_x", "_y", "_z") else key
    scales = {}
    for key, ref in b.items():
        g = group(key)
        scales[g] = scales.get(g, 0.) + (max(abs(x) for x in ref)
                                         if g == "energy" else 0.)
        if g != "energy":
            scales[g] = max(scales[g], max(abs(x) for x in ref))
    worst = 0.
    for key, ref in b.items():
        scale = scales[group(key)]
        if scale == 0. or key not in a or len(a[key]) != len(ref):
            continue
        worst = max(worst, max(abs(x - y) for x, y in zip(a[key], ref))
                    / scale)
    return worst


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--sizes", type=int, nargs="+",
                    default=[250, 500, 1000, 2000, 4000, 8000, 16000])
    ap.add_argument("--steps", type=int, default=5)
    ap.add_argument("--ranks", type=int, nargs="+", default=[1, 2],
                    help="ranks of the sparse operator's runs (the others "
                    "run on one)")
    ap.add_argument("--dense-max", type=int, default=1000,
                    help="largest n for the dense operator (its set-up "
                    "grows like n^3, its memory like n^2: at n = 2000 it "
                    "would need 4.9 GiB, beyond the 4 GiB it may take)")
    ap.add_argument("--direct-max", type=int, default=4000)
    ap.add_argument("--build", default=os.path.join(ROOT, "build"))
    ap.add_argument("--out", default=os.path.join(ROOT, "doc"))
    ap.add_argument("--work", default=os.path.join(ROOT, "results",
                                                   "contact_operator"))
    a = ap.parse_args()

    rows = []
    for n in a.sizes:
        for ranks in a.ranks:
            rows.append(run(a.build, a.work, n, ranks, a.steps, "sparse"))
        if n <= a.dense_max:
            rows.append(run(a.build, a.work, n, 1, a.steps, "dense"))
        if n <= a.direct_max:
            rows.append(run(a.build, a.work, n, 1, a.steps, "direct"))
        reference = [r for r in rows if r["n"] == n][0]["history"]
        for r in rows:
            if r["n"] == n:
                r["largest_difference"] = largest_difference(r["history"],
                                                             reference)
        r = rows[-1]
        print(f"  n = {n}: done ({r['contacts']} contacts)", flush=True)

    print(f"contact_mpi, block on a slab with a search every step, "
          f"{a.steps} steps; {machine_and_commit()}")
    print(f"{'operator':>8} {'n':>6} {'DoFs':>7} {'contacts':>8} "
          f"{'ranks':>5} {'set-up s':>9} {'s/step':>8} {'W x/step':>8} "
          f"{'search s':>8} {'peak GiB':>8} {'max diff':>9} {'violation':>9}")
    for r in rows:
        print(f"{r['variant']:>8} {r['n']:>6} {r['dofs']:>7} "
              f"{r['contacts']:>8} {r['ranks']:>5} {r['setup_seconds']:>9.3f} "
              f"{r['seconds_per_step']:>8.4f} {r['products_per_step']:>8.1f} "
              f"{r['search_seconds_per_step']:>8.4f} {r['peak_gib']:>8.3f} "
              f"{r['largest_difference']:>9.1e} "
              f"{r['largest_violation']:>9.1e}")
    exponents = {}
    for variant in ("sparse", "dense", "direct"):
        pts = [(r["contacts"], r["seconds_per_step"]) for r in rows
               if r["variant"] == variant and r["ranks"] == 1]
        exponents[variant] = fit_exponent(pts[len(pts) // 2:])
    print("growth exponents of s/step over the larger half of each sweep "
          "(one rank): " + ", ".join(f"{k} {v:.2f}" for k, v in
                                     exponents.items()))

    os.makedirs(a.out, exist_ok=True)
    fields = [k for k in rows[0] if k != "history"]
    with open(os.path.join(a.out, "contact_operator.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, fieldnames=fields, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(10, 4))
        for variant in ("sparse", "dense", "direct"):
            for ranks in sorted({r["ranks"] for r in rows}):
                rr = [r for r in rows
                      if r["variant"] == variant and r["ranks"] == ranks]
                if not rr:
                    continue
                label = (("MUMPS" if variant == "direct" else
                          f"substructured, {variant}") +
                         f", {ranks} rank{'s' if ranks > 1 else ''}")
                ax1.loglog([r["contacts"] for r in rr],
                           [r["seconds_per_step"] for r in rr], "o-",
                           label=label)
                ax2.loglog([r["contacts"] for r in rr],
                           [r["setup_seconds"] for r in rr], "o-",
                           label=label)
        ax1.set_xlabel("contact candidates")
        ax1.set_ylabel("wall seconds per step")
        ax1.set_title("block on a slab, search every step")
        ax1.legend(fontsize=8)
        ax2.set_xlabel("contact candidates")
        ax2.set_ylabel("wall seconds of the set-up")
        ax2.legend(fontsize=8)
        fig.suptitle(machine_and_commit(), fontsize=8)
        fig.tight_layout()
        fig.savefig(os.path.join(a.out, "contact_operator.png"), dpi=120)
    except ImportError:
        print("matplotlib not found: no plot")

    os.makedirs(a.work, exist_ok=True)
    with open(os.path.join(a.work, "summary.json"), "w") as f:
        json.dump({"machine": machine_and_commit(), "rows": rows,
                   "exponents": exponents}, f, indent=2)
    largest = max(a.sizes)
    big = [r for r in rows if r["n"] == largest and r["variant"] == "sparse"]
    top = max(big, key=lambda r: r["ranks"])
    one = min(big, key=lambda r: r["ranks"])
    print(f"RESULT program=run_contact_operator contacts={top['contacts']} "
          f"dofs={top['dofs']} ranks={top['ranks']} "
          f"seconds_per_step={top['seconds_per_step']:.4g} "
          f"speedup={one['seconds_per_step'] / top['seconds_per_step']:.3g} "
          f"exponent_sparse={exponents['sparse']:.3g} "
          + result_checks(rows))
    return 0 if all(r["largest_difference"] <= 1e-8 for r in rows) else 1


if __name__ == "__main__":
    sys.exit(main())
