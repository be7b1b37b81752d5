#!/usr/bin/python3
"""lcp-solve on the friction-contact problems of Siconos numerics' test
collection (issue 15): every file it can read, text and FCLib HDF5, with
the status, pivots, seconds, Lemke's relative error and the exact-cone
error of each answer; optionally against Siconos' own 2D Lemke.

usage (from the repository top):
    /usr/bin/python3 benchmarks/lcp/siconos_collection.py \
        [--build build] [--data DIR] [--extra FILE ...] [--facets 8] \
        [--cone facets|exact] [--tolerance 1e-10] [--timeout S] [--peer] \
        [--out results/siconos_collection]

--cone exact: lcp-solve --cone exact (the circular cone by facet LCPs
re-aligned with the slip directions, doc/lcp.md "The exact cone"); the
table adds the facet LCPs taken (largest over a file's groups) and whether
the exact-cone error reached --tolerance.

--data: the folder numerics/src/FrictionContact/test/data of a Siconos
source tree. Without it the script downloads Debian's source package of
Siconos 4.4.0 (siconos_4.4.0+dfsg.orig.tar.xz, 19 MB, from
deb.debian.org) into <out>/siconos-4.4.0 once and uses its folder.
--extra: more files, e.g. the granular-flow files
fc2d_granularflowonwall_{00667_00000,02020_00213,07002_00801}.dat of
Siconos' git repository (same folder; not in the 4.4.0 release).
--peer: time Siconos' SICONOS_FRICTION_2D_LEMKE (Debian's python3-siconos)
on the 2D files with compressed-column storage (CPU time, best of 2), and
check its answer the same way (the exact-cone error); with --cone exact,
also Siconos' exact-cone Newton solver SICONOS_FRICTION_3D_NSN_AC on the 3D
text files, to --tolerance on its own error measure (printed in the cone
error column; its iterations in the pivots column).

Files Siconos' readers call friction-contact problems but impactfe does
not solve (global text problems "GFC3D", rolling friction "RFC3D",
"ACinputs") are listed as "not read" with lcp-solve's message.
Writes <out>/runs.csv and <out>/summary.json; ends with one line
`RESULT key=value ...`. Exit code 0 also when problems are unsolved: the
table says so.
"""
import argparse
import csv
import glob
import json
import os
import re
import subprocess
import sys
import tarfile
import time
import urllib.request

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.abspath(os.path.join(HERE, "..", ".."))
DEBIAN_SOURCE = ("http://deb.debian.org/debian/pool/main/s/siconos/"
                 "siconos_4.4.0+dfsg.orig.tar.xz")
DATA_IN_SOURCE = "siconos-4.4.0/numerics/src/FrictionContact/test/data"


def fetch_debian_source(out):
    folder = os.path.join(out, DATA_IN_SOURCE)
    if os.path.isdir(folder):
        return folder
    os.makedirs(out, exist_ok=True)
    archive = os.path.join(out, os.path.basename(DEBIAN_SOURCE))
    if not os.path.exists(archive):
        print("downloading", DEBIAN_SOURCE, flush=True)
        urllib.request.urlretrieve(DEBIAN_SOURCE, archive)
    with tarfile.open(archive) as tar:
        members = [m for m in tar.getmembers()
                   if m.name.startswith(DATA_IN_SOURCE + "/")]
        tar.extractall(out, members=members)
    return folder


def run_ours(binary, path, facets, cone="facets", tolerance=1e-10,
             timeout=None, route="auto"):
    """One lcp-solve run; returns a dict of what it printed."""
    cmd = [binary, "--reference", "--facets", str(facets), "--cone", cone,
           path]
    if cone == "exact":
        cmd[1:1] = ["--route", route, "--tolerance", str(tolerance)]
    t0 = time.time()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        return {"file": os.path.basename(path), "code": "impactfe",
                "wall_s": time.time() - t0, "status": "timeout", "n": "",
                "pivots": "", "relative_error": "", "solve_s": "",
                "exact_cone_error": "", "cone_iterations": "",
                "converged": "", "message": f"stopped after {timeout} s"}
    wall = time.time() - t0
    row = {"file": os.path.basename(path), "code": "impactfe",
           "wall_s": wall, "status": "not read", "n": "", "pivots": "",
           "relative_error": "", "solve_s": "", "exact_cone_error": "",
           "message": "", "cone_iterations": "", "converged": ""}
    lines = p.stdout.split("\n")
    for line in lines:
        f = line.split()
        if len(f) == 6 and f[0] == path:
            row.update(n=f[1], status=f[2], pivots=f[3],
                       relative_error=f[4], solve_s=float(f[5]))
        if len(f) >= 4 and f[0] == "reference" and f[2] == "exact_cone_error":
            row["exact_cone_error"] = f[3]
        if len(f) == 6 and f[0] == "cone" and f[1] == path:
            row["cone_iterations"] = f[3].split("=")[1]
            row["converged"] = f[5].split("=")[1]
    if p.returncode == 2:
        row["message"] = p.stderr.strip().split("\n")[-1][:200]
    elif row["status"] != "solved":
        row["message"] = p.stderr.strip()[:200]
    return row


def is_2d_csc(path):
    try:
        with open(path) as f:
            head = [next(f).strip() for _ in range(6)]
    except (StopIteration, UnicodeDecodeError, OSError):
        return False
    return head[0] == "2" and head[2] == "2"


def run_peer(path):
    """Siconos' 2D Lemke on a CSC text file, through a child process so
    that a crash of the peer does not end this script."""
    code = r'''
import re, sys, time
import numpy as np
import siconos.numerics as sn
lines = open(sys.argv[1]).read().split("\n")
d, nc = int(lines[0]), int(lines[1])
m = d * nc
W = np.zeros((m, m))
k = 0
while not re.match(r"\s*col 0 :", lines[k]):
    k += 1
col = None
while True:
    mc = re.match(r"\s*col (\d+) :", lines[k])
    me = re.match(r"\s*(\d+) : (\S+)\s*$", lines[k])
    if mc:
        col = int(mc.group(1))
    elif me:
        W[int(me.group(1)), col] = float(me.group(2))
    else:
        break
    k += 1
q = np.array([float(x) for x in lines[k].split()])
mu = np.array([float(x) for x in lines[k + 1].split()])
p = sn.FrictionContactProblem(d, W, q, mu)
best = None
for rep in range(2):
    r = np.zeros(m); u = np.zeros(m)
    so = sn.SolverOptions(sn.SICONOS_FRICTION_2D_LEMKE)
    t0 = time.process_time()
    info = sn.fc2d_driver(p, r, u, so)
    t = time.process_time() - t0
    best = t if best is None else min(best, t)
v = W @ r + q
num = 0.
for c in range(nc):
    rn, rt, un, ut = r[2*c], r[2*c+1], v[2*c], v[2*c+1]
    x0, x1 = rn - (un + mu[c] * abs(ut)), rt - ut
    if abs(x1) <= mu[c] * x0:
        p0, p1 = x0, x1
    elif mu[c] * abs(x1) <= -x0:
        p0, p1 = 0., 0.
    else:
        a = (mu[c] * abs(x1) + x0) / (1 + mu[c] ** 2)
        p0, p1 = a, mu[c] * a * (1 if x1 > 0 else -1)
    num += (rn - p0) ** 2 + (rt - p1) ** 2
den = max(np.linalg.norm(q), np.linalg.norm(r), np.linalg.norm(v))
print("PEER", info, best, (num ** 0.5) / den if den > 0 else num ** 0.5)
'''
    row = {"file": os.path.basename(path), "code": "siconos-lemke",
           "status": "failed", "solve_s": "", "exact_cone_error": ""}
    p = subprocess.run(["/usr/bin/python3", "-c", code, path],
                       capture_output=True, text=True)
    for line in p.stdout.split("\n"):
        f = line.split()
        if f and f[0] == "PEER":
            row.update(status="solved" if f[1] == "0" else "info=" + f[1],
                       solve_s=float(f[2]), exact_cone_error=f[3])
    if p.returncode != 0:
        row["status"] = "error: " + p.stderr.strip().split("\n")[-1][:120]
    return row


def run_peer_3d(path, tolerance):
    """Siconos' exact-cone Newton solver (SICONOS_FRICTION_3D_NSN_AC,
    Alart-Curnier's function) on a 3D text file, to the same tolerance on
    its own error measure (sqrt(sum_c |r_c - P_K(r_c - u~_c)|^2) / |q|), at
    most 1000 iterations; CPU time, best of 2, in a child process."""
    code = r'''
import sys, time
import numpy as np
import siconos.numerics as sn
p = sn.frictionContact_newFromFile(sys.argv[1])
m = p.dimension * p.numberOfContacts
best = None
for rep in range(2):
    r = np.zeros(m); u = np.zeros(m)
    so = sn.SolverOptions(sn.SICONOS_FRICTION_3D_NSN_AC)
    so.iparam[sn.SICONOS_IPARAM_MAX_ITER] = 1000
    so.dparam[sn.SICONOS_DPARAM_TOL] = float(sys.argv[2])
    t0 = time.process_time()
    info = sn.fc3d_driver(p, r, u, so)
    t = time.process_time() - t0
    best = t if best is None else min(best, t)
print("PEER", info, best, so.dparam[sn.SICONOS_DPARAM_RESIDU],
      so.iparam[sn.SICONOS_IPARAM_ITER_DONE])
'''
    row = {"file": os.path.basename(path), "code": "siconos-nsn-ac",
           "status": "failed", "solve_s": "", "exact_cone_error": "",
           "iterations": ""}
    try:
        p = subprocess.run(["/usr/bin/python3", "-c", code, path,
                            str(tolerance)],
                           capture_output=True, text=True, timeout=600)
    except subprocess.TimeoutExpired:
        row["status"] = "timeout"
        return row
    for line in p.stdout.split("\n"):
        f = line.split()
        if f and f[0] == "PEER":
            row.update(status="solved" if f[1] == "0" else "info=" + f[1],
                       solve_s=float(f[2]), exact_cone_error=f[3],
                       iterations=f[4])
    if p.returncode != 0:
        row["status"] = "error: " + p.stderr.strip().split("\n")[-1][:120]
    return row


def is_3d_text(path):
    try:
        with open(path) as f:
            return next(f).strip() == "3" and not path.endswith(".hdf5")
    except (StopIteration, UnicodeDecodeError, OSError):
        return False


def plot_against_peer(rows, path):
    """Solve seconds of lcp-solve --cone exact against Siconos' NSN_AC, per
    3D text file both ran (log-log; open markers: the peer did not reach
    the tolerance within its 1000 iterations)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    ours = {r["file"]: r for r in rows if r["code"] == "impactfe"}
    pairs = [(ours[r["file"]], r) for r in rows
             if r["code"] == "siconos-nsn-ac" and r["solve_s"] != ""
             and r["file"] in ours and ours[r["file"]]["solve_s"] != ""]
    if not pairs:
        return
    fig, ax = plt.subplots(figsize=(6, 5))
    for o, p in pairs:
        ok = p["status"] == "solved"
        ax.loglog(p["solve_s"], o["solve_s"], "o", color="C0",
                  mfc="C0" if ok else "none")
        if float(p["solve_s"]) > 0.1 or float(o["solve_s"]) > 0.1:
            ax.annotate(o["file"].split("-i")[0].split(".")[0],
                        (p["solve_s"], o["solve_s"]), fontsize=7,
                        xytext=(3, 3), textcoords="offset points")
    lo = min(min(float(o["solve_s"]), float(p["solve_s"])) for o, p in pairs)
    hi = max(max(float(o["solve_s"]), float(p["solve_s"])) for o, p in pairs)
    ax.loglog([lo, hi], [lo, hi], "k--", lw=0.8, label="equal time")
    ax.set_xlabel("Siconos NSN_AC seconds (CPU; open: not converged)")
    ax.set_ylabel("lcp-solve --cone exact seconds")
    ax.set_title("Exact cone to 1e-10, Siconos' test collection (3D)")
    ax.legend(loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def main():
    ap = argparse.ArgumentParser(description=__doc__,
                                 formatter_class=argparse.RawTextHelpFormatter)
    ap.add_argument("--build", default=os.path.join(TOP, "build"))
    ap.add_argument("--data")
    ap.add_argument("--extra", nargs="*", default=[])
    ap.add_argument("--facets", type=int, default=8)
    ap.add_argument("--cone", choices=["facets", "exact"], default="facets")
    ap.add_argument("--tolerance", type=float, default=1e-10)
    ap.add_argument("--route", choices=["auto", "facets", "interior-point"],
                    default="auto",
                    help="with --cone exact: lcp-solve's --route")
    ap.add_argument("--timeout", type=float, default=None,
                    help="seconds one lcp-solve run may take (status "
                         "'timeout' after that)")
    ap.add_argument("--peer", action="store_true")
    ap.add_argument("--out",
                    default=os.path.join(TOP, "results", "siconos_collection"))
    a = ap.parse_args()
    binary = os.path.join(a.build, "bin", "lcp-solve")
    if not os.path.exists(binary):
        sys.exit("no " + binary + ": build the project first")
    data = a.data or fetch_debian_source(a.out)
    files = sorted(glob.glob(os.path.join(data, "*.dat")) +
                   glob.glob(os.path.join(data, "*.hdf5"))) + a.extra
    os.makedirs(a.out, exist_ok=True)

    rows = []
    print("%-42s %6s %-16s %7s %10s %10s %10s %5s" %
          ("file", "n", "status", "pivots", "rel.err", "solve s", "cone err",
           "LCPs"))
    for path in files:
        r = run_ours(binary, path, a.facets, a.cone, a.tolerance, a.timeout,
                     a.route)
        rows.append(r)
        print("%-42s %6s %-16s %7s %10s %10s %10s %5s%s" % (
            r["file"][:42], r["n"], r["status"], r["pivots"],
            r["relative_error"],
            "%.3g" % r["solve_s"] if r["solve_s"] != "" else "",
            r["exact_cone_error"],
            r["cone_iterations"] + ("" if r["converged"] != "no" else "!"),
            ("  " + r["message"][:60]) if r["status"] != "solved" else ""),
            flush=True)
        if a.peer and a.cone == "exact" and is_3d_text(path) and \
                r["status"] != "not read":
            pr = run_peer_3d(path, a.tolerance)
            rows.append(pr)
            print("%-42s %6s %-16s %7s %10s %10s %10s" % (
                "  siconos NSN_AC", "", pr["status"][:16], pr["iterations"],
                "", "%.3g" % pr["solve_s"] if pr["solve_s"] != "" else "",
                pr["exact_cone_error"]), flush=True)
        if a.peer and is_2d_csc(path):
            pr = run_peer(path)
            rows.append(pr)
            print("%-42s %6s %-16s %7s %10s %10s %10s" % (
                "  siconos 2D Lemke", "", pr["status"][:16], "", "",
                "%.3g" % pr["solve_s"] if pr["solve_s"] != "" else "",
                pr["exact_cone_error"]), flush=True)

    ours = [r for r in rows if r["code"] == "impactfe"]
    read = [r for r in ours if r["status"] != "not read"]
    solved = [r for r in read if r["status"] == "solved"]
    with open(os.path.join(a.out, "runs.csv"), "w", newline="") as f:
        keys = sorted({k for r in rows for k in r})
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)
    commit = subprocess.run(["git", "-C", TOP, "rev-parse", "--short", "HEAD"],
                            capture_output=True, text=True).stdout.strip()
    cpu = ""
    try:
        cpu = re.search(r"model name\s*:\s*(.*)",
                        open("/proc/cpuinfo").read()).group(1)
    except (OSError, AttributeError):
        pass
    converged = [r for r in solved if r["converged"] == "yes"]
    cone_errors = [float(r["exact_cone_error"]) for r in solved
                   if r["exact_cone_error"] not in ("", "-")]
    summary = {"commit": commit, "cpu": cpu, "facets": a.facets,
               "cone": a.cone, "route": a.route, "tolerance": a.tolerance,
               "converged": len(converged),
               "files": len(ours), "read": len(read), "solved": len(solved),
               "unsolved": [r["file"] for r in read if r["status"] != "solved"],
               "not_read": [r["file"] for r in ours if r["status"] == "not read"],
               "runs": rows}
    with open(os.path.join(a.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    if a.peer and a.cone == "exact":
        plot_against_peer(rows, os.path.join(a.out, "exact_cone_vs_nsn.png"))
    slowest = max((r["solve_s"] for r in solved), default=0.)
    print("RESULT files=%d read=%d solved=%d unsolved=%d facets=%d cone=%s "
          "route=%s converged=%d max_cone_error=%.3g "
          "slowest_solve_seconds=%.3g" %
          (len(ours), len(read), len(solved), len(read) - len(solved),
           a.facets, a.cone, a.route if a.cone == "exact" else "-",
           len(converged) if a.cone == "exact" else 0,
           max(cone_errors, default=0.), slowest))


if __name__ == "__main__":
    main()
