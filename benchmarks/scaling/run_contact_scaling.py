"""Cost of a frictional step against the number of contacts, for the two
contact solvers (issue 14): Lemke's method on the dense Delassus matrix and
the matrix-free active set method (`Contact solver/Method`).

The scene is build/bin/block_scaling's slab of nx x 4 plane-strain Q1 cells
thrown onto a rigid plane with Coulomb friction (mu = 0.3): every one of
the nx + 1 bottom nodes touches, part sticking and part sliding; 20 steps of
theta-Euler, h = 1e-4 s. Two sweeps, one process per run:

  cells of 1 mm (the slab nx mm long): the same Courant number (3.7) and
      the same local dynamics at every n_c, so the cost shows what n_c
      alone does; Lemke's method up to 1001 contacts, the active set method
      up to 30001;
  a slab 1 m long (cells of 1/nx m): the Courant number grows with nx (37
      at 10001 contacts, 110 at 30001) and the contact problem gets harder
      to precondition; the active set method only.
 For each run: seconds per step (CPU of
the time loop, Delassus columns excluded), the once-only Delassus columns,
the active set iterations and GMRES iterations, the fallbacks, the largest
verification violation, and the last step's normal force and final kinetic
energy, which must agree between the methods where both run.

Writes doc/contact_scaling.csv, doc/contact_scaling.png and
results/contact_scaling/summary.json, prints a table and the fitted
exponents, and ends with one RESULT line. Run from the repository top:

  /usr/bin/python3 benchmarks/scaling/run_contact_scaling.py [--build build]
      [--quick]
"""
import argparse
import csv
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
from runs import fit_exponent as fit, machine_and_commit  # noqa: E402


def run(build, nx, method, sweep, steps=20):
    cmd = [os.path.join(build, "bin", "block_scaling"), "--nx", str(nx),
           "--ny", "4", "--steps", str(steps), "--method", method]
    if sweep == "cell 1 mm":
        cmd += ["--cell-size", "1e-3"]
    out = subprocess.run(cmd, check=True, capture_output=True,
                         text=True).stdout
    line = [l for l in out.splitlines() if l.startswith("RESULT ")][-1]
    row = dict(kv.split("=", 1) for kv in line.split()[1:])
    row["nx"] = str(nx)
    row["sweep"] = sweep
    print(f"{sweep:10s} {method:10s} contacts={row['contacts']:>6s} "
          f"s/step={float(row['seconds_per_step']):9.4f} "
          f"delassus={float(row['delassus_seconds']):7.2f} s "
          f"iterations={row['active_set_iterations']:>3s} "
          f"gmres={row['gmres_iterations']:>5s} "
          f"fallbacks={row['fallbacks']}", flush=True)
    return row


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default="build")
    parser.add_argument("--quick", action="store_true",
                        help="up to 3001 contacts (about 20 s)")
    parser.add_argument("--steps", type=int, default=20,
                        help="time steps per run (20 since 2026-11-29; the "
                        "3-step runs of before missed the fronts of longer "
                        "runs, doc/lcp.md 'Longer runs')")
    args = parser.parse_args()

    active_sizes = [100, 300, 1000, 3000] + ([] if args.quick else
                                             [10000, 30000])
    lemke_sizes = [100, 300] + ([] if args.quick else [1000])
    rows = [run(args.build, nx, "lemke", "cell 1 mm", args.steps)
            for nx in lemke_sizes]
    rows += [run(args.build, nx, "active-set", "cell 1 mm", args.steps)
             for nx in active_sizes]
    rows += [run(args.build, nx, "active-set", "width 1 m", args.steps)
             for nx in active_sizes if nx > 1000]

    # Where both ran, the answers must agree (the scene's last normal force
    # and kinetic energy, to 1e-8 relative).
    agreement = 0.
    for r in rows:
        if r["method"] != "lemke":
            continue
        a = next(x for x in rows if x["method"] == "active-set" and
                 x["nx"] == r["nx"] and x["sweep"] == r["sweep"])
        for key in ("last_normal_force", "last_kinetic_energy"):
            ref = abs(float(r[key])) or 1.
            agreement = max(agreement,
                            abs(float(a[key]) - float(r[key])) / ref)

    os.makedirs("doc", exist_ok=True)
    keys = ["sweep", "method", "nx", "contacts", "dofs", "seconds_per_step",
            "delassus_seconds", "active_set_solves", "active_set_iterations",
            "gmres_iterations", "fallbacks", "lcp_relative_error",
            "floor_seconds_per_step", "last_normal_force",
            "last_kinetic_energy"]
    with open("doc/contact_scaling.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)

    def series(method, sweep):
        return [(float(r["contacts"]), float(r["seconds_per_step"]))
                for r in rows if r["method"] == method and
                (r["sweep"] == sweep or (sweep == "width 1 m" and
                                         r["nx"] == "1000"))]

    lemke = series("lemke", "cell 1 mm")
    active = series("active-set", "cell 1 mm")
    active_1m = series("active-set", "width 1 m")
    p_lemke = fit(lemke[-2:])
    p_active = fit([p for p in active if p[0] >= 1000])
    p_active_1m = fit(active_1m)

    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.5, 5))
    ax.loglog(*zip(*lemke), "s-",
              label=f"Lemke, dense W (last two points ~ n_c^{p_lemke:.2f})")
    ax.loglog(*zip(*active), "o-",
              label=f"active set, matrix-free (n_c >= 1e3: ~ n_c^{p_active:.2f})")
    if len(active_1m) > 1:
        ax.loglog(*zip(*active_1m), "o--",
                  label="active set, slab 1 m long (Courant number ~ n_c): "
                  f"~ n_c^{p_active_1m:.2f}")
    floor = [(float(r["contacts"]), float(r["floor_seconds_per_step"]))
             for r in rows
             if r["method"] == "active-set" and r["sweep"] == "cell 1 mm"]
    ax.loglog(*zip(*floor), ":", color="grey",
              label="floor: F~, a solve pair with M~, the update")
    ax.axhline(1., color="red", lw=0.8, ls="--", label="1 s per step")
    ax.set_xlabel("frictional contacts n_c (all touching)")
    ax.set_ylabel("CPU seconds per step")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title("Slab nx x 4 Q1 cells (1 mm unless said) on a plane, "
                 f"mu = 0.3, theta-Euler, {args.steps} steps\n" +
                 machine_and_commit(), fontsize=9)
    fig.tight_layout()
    fig.savefig("doc/contact_scaling.png", dpi=110)
    plt.close(fig)

    largest = [r for r in rows if r["method"] == "active-set" and
               r["sweep"] == "cell 1 mm"][-1]
    fallbacks = sum(int(r["fallbacks"]) for r in rows)
    violation = max(float(r.get("lcp_relative_error", 0.)) for r in rows)
    summary = {
        "machine_and_commit": machine_and_commit(),
        "runs": rows,
        "lemke_exponent_last_two": p_lemke,
        "active_set_exponent_from_1e3": p_active,
        "active_set_exponent_slab_1m": p_active_1m,
        "largest_relative_difference_between_methods": agreement,
        "fallbacks": fallbacks,
        "largest_verification_violation": violation,
    }
    os.makedirs("results/contact_scaling", exist_ok=True)
    with open("results/contact_scaling/summary.json", "w") as f:
        json.dump(summary, f, indent=1)
    print(f"\nexponent of the active set method from 1e3 contacts on: "
          f"{p_active:.2f} (cells of 1 mm), {p_active_1m:.2f} (slab 1 m "
          f"long); Lemke (last two points): {p_lemke:.2f}")
    print(f"largest relative difference between the methods: {agreement:.1e}")
    print("wrote doc/contact_scaling.csv, doc/contact_scaling.png, "
          "results/contact_scaling/summary.json")
    print(f"RESULT contacts={largest['contacts']} dofs={largest['dofs']} "
          f"ranks=1 seconds_per_step={largest['seconds_per_step']} "
          f"lcp_relative_error={violation:.3g} fallbacks={fallbacks} "
          f"exponent={p_active:.3f} methods_agree={agreement:.3g}")


if __name__ == "__main__":
    main()
