#!/usr/bin/python3
"""Which θ is best on which mesh and step, and how close `Theta rule =
courant` (θ = 1/2 + κ/C) comes to it (issue 16).

Runs modified θ with free flight 4 h (the 2D grid's best fixed-θ variant)
at several fixed θ over the full 2D grid of run_work_precision.py (2D bars,
cylinder, plate: same meshes, steps, references and err_force), then, for
every grid point, prints err_force against θ and the best θ, and for each
κ the error of θ = min(1, 1/2 + κ/C) (interpolated linearly in θ between
the scanned values) over the best scanned error, as mean and max over the
grid points; the same ratios for each fixed θ. Errors only: the runs are
made once (--repeats 1), their CPU times are not used.

usage: /usr/bin/python3 benchmarks/work_precision/theta_scan.py
           [--build build] [--out results/theta_scan]
           [--thetas 0.5,0.51,...] [--kappas 0.01,0.02,...] [--analyse-only]
About 15 min on 2 cores (most of it the three references).
Writes <out>/work_precision_*.csv (the runs), <out>/summary.json, and ends
with a RESULT line: each scene's mean ratio of the rule at the best κ and
of the best fixed θ.
"""
import argparse
import csv
import json
import os
import sys
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
sys.path.insert(0, HERE)
import run_work_precision as wp  # noqa: E402

SCENE_CSV = {name: wp.SCENES[name]["csv"] for name in ("bars2d", "cylinder", "plate")}


def errors_by_point(path):
    """{(cells, h_factor): {theta: err_force}}, {(cells, h_factor): C}."""
    errors, courant = defaultdict(dict), {}
    for r in csv.DictReader(open(path)):
        if r["level"] == "" or r["status"] != "ok":
            continue  # the references, failed runs
        key = (int(r["cells"]), float(r["h_factor"]))
        courant[key] = float(r["courant"])
        errors[key][float(r["theta"])] = float(r["err_force"])
    return errors, courant


def interpolated(errors, theta):
    thetas = sorted(errors)
    if theta <= thetas[0]:
        return errors[thetas[0]]
    if theta >= thetas[-1]:
        return errors[thetas[-1]]
    i = max(j for j, t in enumerate(thetas) if t <= theta)
    a, b = thetas[i], thetas[i + 1]
    return errors[a] + (errors[b] - errors[a]) * (theta - a) / (b - a)


def ratios(errors, theta_of):
    r = [interpolated(e, theta_of(k)) / min(e.values()) for k, e in errors.items()]
    return sum(r) / len(r), max(r)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="build")
    parser.add_argument("--out", default=os.path.join(TOP, "results/theta_scan"))
    parser.add_argument("--thetas", default="0.5,0.51,0.52,0.53,0.55,0.575,0.6,0.65,0.7")
    parser.add_argument("--kappas", default="0.01,0.02,0.025,0.03,0.04,0.05")
    parser.add_argument("--analyse-only", action="store_true",
                        help="no runs: analyse the CSVs in --out")
    args = parser.parse_args()
    out = os.path.abspath(args.out)
    thetas = [float(t) for t in args.thetas.split(",")]
    kappas = [float(k) for k in args.kappas.split(",")]
    if not args.analyse_only:
        wp.SCHEMES = [("modified-theta+ff4", t, f"modified θ, θ = {t}, free flight 4 h")
                      for t in thetas]
        wp.COLORS = ["C%d" % (i % 10) for i in range(len(thetas))]
        sys.argv = [sys.argv[0], "--build", os.path.abspath(args.build), "--out", out,
                    "--runs", os.path.join(out, "runs"), "--repeats", "1",
                    "--only", "bars2d,cylinder,plate"]
        wp.main()

    summary, result = {}, []
    for name, file in SCENE_CSV.items():
        errors, courant = errors_by_point(os.path.join(out, file))
        scanned = sorted({t for e in errors.values() for t in e})
        print(f"\n{name}: err_force by θ (columns), best θ, κ* = (best θ − 1/2) C")
        print(f"{'cells':>6} {'factor':>6} {'C':>6} " + " ".join(f"{t:7.3f}" for t in scanned))
        for key in sorted(errors):
            e = errors[key]
            best = min(e, key=e.get)
            print(f"{key[0]:6d} {key[1]:6g} {courant[key]:6.3f} "
                  + " ".join(f"{e.get(t, float('nan')):7.4f}" for t in scanned)
                  + f"  best {best:.3f}  κ* {(best - 0.5) * courant[key]:.3f}")
        rule = {k: ratios(errors, lambda p, k=k: min(1., 0.5 + k / courant[p]))
                for k in kappas}
        fixed = {t: ratios(errors, lambda p, t=t: t) for t in scanned}
        print("error over the best scanned θ's, mean / max over the grid points:")
        print("  θ = 1/2 + κ/C: " + "  ".join(f"κ {k:g}: {m:.3f}/{x:.3f}"
                                              for k, (m, x) in rule.items()))
        print("  fixed θ:       " + "  ".join(f"{t:g}: {m:.3f}/{x:.3f}"
                                              for t, (m, x) in fixed.items()))
        best_kappa = min(rule, key=lambda k: rule[k][0])
        best_theta = min(fixed, key=lambda t: fixed[t][0])
        summary[name] = {"points": len(errors),
                         "rule": {str(k): {"mean": m, "max": x} for k, (m, x) in rule.items()},
                         "fixed": {str(t): {"mean": m, "max": x} for t, (m, x) in fixed.items()},
                         "best_kappa": best_kappa, "best_fixed_theta": best_theta}
        result += [f"{name}_best_kappa={best_kappa:g}",
                   f"{name}_rule_mean_ratio={rule[best_kappa][0]:.4f}",
                   f"{name}_best_fixed_theta={best_theta:g}",
                   f"{name}_fixed_mean_ratio={fixed[best_theta][0]:.4f}"]
    os.makedirs(out, exist_ok=True)
    with open(os.path.join(out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    print("RESULT " + " ".join(result))


if __name__ == "__main__":
    main()
