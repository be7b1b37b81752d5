#!/usr/bin/python3
"""The k-facet study of the 3D oblique plate (issue 12): how much the
answer of the polygonal Coulomb cone depends on the direction of sliding,
against the exact (circular) cone.

The scene of parameter_files/oblique_plate_3d.prm is turned about the
plane's normal by phi (entry `Turn about the normal`); the contact frames
are not, so the slip direction meets the k facets at another angle. For
each k in 4, 8, 16, 32 and each phi of a set covering one sector of k = 8 (phi = 0 and turns off
the positions where a vertex or an edge's middle faces the slip direction), the
run's impulse (normal, along the plate, across it) and final velocity, in
the plate's own frame, are compared with the exact cone's at phi = 0. The
exact cone is run at every phi too: its spread over phi is the measure of
its direction independence.

Errors, relative to the exact cone's friction impulse |I_T| (for the
impulses) or to |v_end| (for the velocity), maximum over phi:
  err_impulse  = max |I(k, phi) - I_exact| / |I_T,exact|
  err_across   = max |I_across(k, phi)| / |I_T,exact|
  err_velocity = max |v_end(k, phi) - v_end,exact| / |v_end,exact|

usage (from the repository top, after building):
    /usr/bin/python3 benchmarks/oblique_plate_3d/run_cone_study.py \
        [--build build] [--out doc] [--turns 9]
Writes <out>/oblique_plate_3d_cones.png, <out>/oblique_plate_3d_cones.csv,
results/oblique_plate_3d_cones/summary.json and ends with a RESULT line.
"""
import argparse
import csv
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(__file__), "..", "common"))
import runs  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402,F401

PRM = "parameter_files/oblique_plate_3d.prm"
FACETS = [4, 8, 16, 32]


def one_run(build, work, cone, k, phi):
    overrides = ("subsection Geometry\n"
                 f"  set Turn about the normal = {phi!r}\nend\n"
                 "subsection Contact solver\n"
                 f"  set Friction cone = {cone}\n"
                 f"  set Number of facets = {k}\nend\n")
    out = os.path.join(work, f"{cone}_{k}_{phi:.6f}")
    s = runs.run(build, "oblique_plate_3d", PRM, out, overrides)
    return {"cone": cone, "k": k, "phi": phi,
            "impulse_normal": s["impulse_normal"],
            "impulse_along": s["impulse_along"],
            "impulse_across": s["impulse_across"],
            "v_along": s["final_velocity_along"],
            "v_normal": s["final_velocity_normal"],
            "v_across": s["final_velocity_across"],
            "loop_seconds": s["loop_cpu_seconds"]}


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default="build")
    ap.add_argument("--out", default="doc")
    ap.add_argument("--turns", type=int, default=9,
                    help="turns phi in [0, pi/4] (one sector of k = 8)")
    a = ap.parse_args()
    # phi = 0 and turns off the symmetric positions of every k (a vertex or
    # the middle of an edge on the slip direction gives no impulse across
    # the plate by symmetry, and would hide the polygon's error).
    turns = [0.] + [math.pi / 4 * (i + 0.3) / (a.turns - 1)
                    for i in range(a.turns - 1)]
    work = tempfile.mkdtemp(prefix="cones_")
    rows = []
    for phi in turns:
        rows.append(one_run(a.build, work, "exact", 8, phi))
        for k in FACETS:
            rows.append(one_run(a.build, work, "facets", k, phi))
    ref = rows[0]
    friction = math.hypot(ref["impulse_along"], ref["impulse_across"])
    speed = math.sqrt(ref["v_along"] ** 2 + ref["v_normal"] ** 2 +
                      ref["v_across"] ** 2)

    def errors(r):
        di = math.sqrt((r["impulse_normal"] - ref["impulse_normal"]) ** 2 +
                       (r["impulse_along"] - ref["impulse_along"]) ** 2 +
                       (r["impulse_across"] - ref["impulse_across"]) ** 2)
        dv = math.sqrt((r["v_along"] - ref["v_along"]) ** 2 +
                       (r["v_normal"] - ref["v_normal"]) ** 2 +
                       (r["v_across"] - ref["v_across"]) ** 2)
        return di / friction, abs(r["impulse_across"]) / friction, dv / speed

    for r in rows:
        r["err_impulse"], r["err_across"], r["err_velocity"] = errors(r)
    table = {}
    for label, sel in [("exact", lambda r: r["cone"] == "exact")] + [
            (f"k = {k}", lambda r, k=k: r["cone"] == "facets" and r["k"] == k)
            for k in FACETS]:
        sub = [r for r in rows if sel(r)]
        table[label] = {key: max(r[key] for r in sub)
                        for key in ("err_impulse", "err_across",
                                    "err_velocity")}
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "oblique_plate_3d_cones.csv"), "w",
              newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    print(f"{'cone':8s} {'err_impulse':>12s} {'err_across':>12s} "
          f"{'err_velocity':>12s}   (max over {len(turns)} turns in [0, pi/4])")
    for label, e in table.items():
        print(f"{label:8s} {e['err_impulse']:12.3e} {e['err_across']:12.3e} "
              f"{e['err_velocity']:12.3e}")

    fig, ax = plt.subplots(1, 2, figsize=(11, 4.2))
    for k in FACETS:
        sub = [r for r in rows if r["cone"] == "facets" and r["k"] == k]
        ax[0].plot([r["phi"] for r in sub], [r["err_impulse"] for r in sub],
                   "o-", label=f"{k} facets")
    sub = [r for r in rows if r["cone"] == "exact"]
    ax[0].plot([r["phi"] for r in sub],
               [max(r["err_impulse"], 1e-16) for r in sub], "k*-",
               label="exact cone")
    ax[0].set_yscale("log")
    ax[0].set_xlabel("turn of the scene about the normal, phi [rad]")
    ax[0].set_ylabel("|I - I_exact(phi = 0)| / |I_T|")
    ax[0].legend()
    ax[0].grid(True, which="both", alpha=0.3)
    ks = FACETS
    for key, label in [("err_impulse", "impulse"),
                       ("err_across", "impulse across the plate"),
                       ("err_velocity", "final velocity")]:
        ax[1].loglog(ks, [table[f"k = {k}"][key] for k in ks], "o-",
                     label=label)
    ax[1].loglog(ks, [table["k = 4"]["err_impulse"] * (4 / k) ** 2
                      for k in ks], "k:", label="slope -2")
    ax[1].set_xlabel("facets k")
    ax[1].set_ylabel("max over phi of the error")
    ax[1].xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
    ax[1].set_xticks(ks)
    ax[1].set_xticklabels([str(k) for k in ks])
    ax[1].legend()
    ax[1].grid(True, which="both", alpha=0.3)
    fig.suptitle("3D oblique plate: polygonal against exact Coulomb cone\n" +
                 runs.machine_and_commit(), fontsize=9)
    fig.tight_layout()
    png = os.path.join(a.out, "oblique_plate_3d_cones.png")
    fig.savefig(png, dpi=120)

    res = os.path.join("results", "oblique_plate_3d_cones")
    os.makedirs(res, exist_ok=True)
    with open(os.path.join(res, "summary.json"), "w") as f:
        json.dump({"turns": turns, "errors": table, "runs": rows}, f, indent=1)
    print(f"figure: {png}")
    print("RESULT turns=%d exact_spread=%.3g " % (len(turns),
                                                  table["exact"]["err_impulse"])
          + " ".join(f"k{k}_err_impulse={table[f'k = {k}']['err_impulse']:.3g}"
                     for k in FACETS))


if __name__ == "__main__":
    main()
