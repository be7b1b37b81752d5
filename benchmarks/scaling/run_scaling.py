"""Cost of a time step as the problem grows: runs build/bin/block_scaling
(one process per size) over two sweeps and plots them.

  dofs:     square blocks of n x n cells, n = 16 ... 707 (578 to 10^6 DOFs,
            17 to 708 contact candidates, all touching);
  contacts: thin slabs of nx x 4 cells, nx = 10 ... 2000, with the nodes of
            the top face as candidates too (22 to 4002 candidates, half of
            them never near the plane).

Every run uses Lemke's method on the dense Delassus matrix (the active set
method, and its scaling in contacts, is run_contact_scaling.py's). Writes
scaling.csv, scaling_dofs.png and scaling_contacts.png to --out (default
doc; with --quick results/scaling_quick, so that a quick run does not
overwrite the documented sweep), prints the fitted exponents (least squares
in log-log over the larger half of each sweep), writes
results/scaling[_quick]/summary.json and ends with one RESULT line (the
largest sizes, their seconds per step, and the per-step exponents against
DOFs and against candidates). Run from the repository top:

  /usr/bin/python3 benchmarks/scaling/run_scaling.py [--build build] [--quick]
      [--out DIR]
"""
import argparse
import csv
import io
import json
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
from runs import fit_exponent, machine_and_commit  # noqa: E402

PHASES = [("assembly_seconds", "assembly (once)"),
          ("factorization_seconds", "factorisation (once)"),
          ("delassus_seconds", "Delassus columns (once per candidate)"),
          ("free_per_step", "free velocity, per step"),
          ("lcp_per_step", "LCP, per step"),
          ("update_per_step", "update, per step")]


def run(build, nx, ny, steps, top):
    cmd = [os.path.join(build, "bin", "block_scaling"), "--nx", str(nx),
           "--ny", str(ny), "--steps", str(steps), "--header",
           "--method", "lemke"]
    if top:
        cmd.append("--top-candidates")
    out = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    row = next(csv.DictReader(io.StringIO(out)))
    print(", ".join(f"{k}={row[k]}" for k in
                    ("n_dofs", "n_candidates", "delassus_seconds",
                     "free_per_step", "lcp_per_step", "peak_rss_mb")),
          flush=True)
    return row


def fit(xs, ys):
    """Exponent p of y ~ x^p over the larger half of the points."""
    pts = [(x, y) for x, y in zip(xs, ys) if y > 0]
    return fit_exponent(pts[len(pts) // 2:])


def plot(rows, xkey, xlabel, title, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    xs = [float(r[xkey]) for r in rows]
    fig, ax = plt.subplots(figsize=(7.5, 5))
    exponents = {}
    for key, label in PHASES:
        ys = [float(r[key]) for r in rows]
        p = fit(xs, ys)
        exponents[key] = p
        ax.loglog(xs, ys, "o-", label=f"{label}  ~ {xlabel.split()[0]}^{p:.2f}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("CPU seconds")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title + "\n" + machine_and_commit(), fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return exponents


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--build", default="build")
    parser.add_argument("--quick", action="store_true",
                        help="small sizes only (about a minute)")
    parser.add_argument("--out", default=None,
                        help="folder of the CSV and the figures (default doc, "
                             "with --quick results/scaling_quick)")
    args = parser.parse_args()
    out = args.out or ("results/scaling_quick" if args.quick else "doc")

    if args.quick:
        squares, slabs = [16, 32, 64, 128], [10, 30, 100, 300]
    else:
        squares = [16, 32, 64, 128, 256, 512, 707]
        slabs = [10, 30, 100, 300, 1000, 2000]
    rows = []
    for n in squares:
        r = run(args.build, n, n, 10, False)
        r["sweep"] = "dofs"
        rows.append(r)
    for nx in slabs:
        r = run(args.build, nx, 4, 3, True)
        r["sweep"] = "contacts"
        rows.append(r)

    os.makedirs(out, exist_ok=True)
    keys = ["sweep"] + [k for k in rows[0] if k != "sweep"]
    with open(os.path.join(out, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    dofs = [r for r in rows if r["sweep"] == "dofs"]
    slab = [r for r in rows if r["sweep"] == "contacts"]
    e1 = plot(dofs, "n_dofs", "DOFs",
              "Square block on a plane (n x n Q1 cells, n+1 contacts, mu = 0.3)",
              os.path.join(out, "scaling_dofs.png"))
    e2 = plot(slab, "n_candidates", "n_c (contact candidates)",
              "Slab nx x 4 cells, bottom and top nodes candidates (mu = 0.3)",
              os.path.join(out, "scaling_contacts.png"))
    print("\nfitted exponents (larger half of each sweep)")
    print(f"{'phase':40s} {'vs DOFs':>8s} {'vs n_c':>8s}")
    for key, label in PHASES:
        print(f"{label:40s} {e1[key]:8.2f} {e2[key]:8.2f}")
    print("peak memory [MB]: " + ", ".join(
        f"{r['n_dofs']} DOFs: {float(r['peak_rss_mb']):.0f}" for r in dofs))
    print(f"wrote {out}/scaling.csv, scaling_dofs.png, scaling_contacts.png")

    # The step (free velocity + LCP + update) per sweep, for the summary.
    def step_seconds(r):
        return sum(float(r[k]) for k in
                   ("free_per_step", "lcp_per_step", "update_per_step"))

    step_dofs = fit([float(r["n_dofs"]) for r in dofs], [step_seconds(r) for r in dofs])
    step_nc = fit([float(r["n_candidates"]) for r in slab],
                  [step_seconds(r) for r in slab])
    summary = {"program": "run_scaling", "machine_and_commit": machine_and_commit(),
               "method": "lemke", "exponents_vs_dofs": e1, "exponents_vs_candidates": e2,
               "step_exponent_vs_dofs": step_dofs,
               "step_exponent_vs_candidates": step_nc, "runs": rows}
    folder = "results/scaling_quick" if args.quick else "results/scaling"
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print(f"summary: {folder}/summary.json")
    print(f"RESULT program=run_scaling method=lemke dofs={dofs[-1]['n_dofs']} "
          f"seconds_per_step_largest_square={step_seconds(dofs[-1]):.4g} "
          f"candidates={slab[-1]['n_candidates']} "
          f"seconds_per_step_largest_slab={step_seconds(slab[-1]):.4g} "
          f"step_exponent_vs_dofs={step_dofs:.3f} "
          f"step_exponent_vs_candidates={step_nc:.3f} "
          f"delassus_exponent_vs_candidates={e2['delassus_seconds']:.3f}")


if __name__ == "__main__":
    main()
