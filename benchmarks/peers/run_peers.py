"""Run the peer codes (Siconos, GetFEM) on the 1D two-bar impact and write
doc/peers_two_bars_1d.csv; print the tables of doc/peers.md.

    /usr/bin/python3 benchmarks/peers/run_peers.py [--quick] [--no-extend]
                     [--csv PATH] [--ours SNAPSHOT_DIR] [--tables-only]

Run from the repository top. A peer whose Python module is missing is
skipped with a message (exit code 0): these runs are optional and never
part of ctest.

Grid: cells per bar 10, 20, 40, 80, 160, 320 and Courant numbers
c h/dx = 0.5, 0.9, 2, 4 (h = C dx / c); Siconos at theta = 0.5 and 0.55.
Extension: a curve (code, scheme, theta) whose best err_v is still above
1e-2 gets 640 cells (all Courant numbers), then 1280 cells (C = 0.5, 0.9).

CPU seconds to reach err_v = 1e-2: on the work-precision front of each
curve (the runs that no cheaper run beats in err_v), log(cpu) is
interpolated linearly in log(err_v) between the two front runs around
1e-2. If no run reaches it, the last three front runs are fitted by a
power law and the value is marked as extrapolated.

--tables-only reads the CSV instead of running the peers (and prints the
tables; with --ours, our runs are still made).

--ours SNAPSHOT_DIR also runs our two_bars_1d (SNAPSHOT_DIR/bin, /lib) on
the same grid for comparison (printed only, not written to the CSV; our
CPU = set-up + time loop from summary.json).

When a peer ran (or with --tables-only), ends with results/peers/summary.json (every curve's crossing of 1e-2) and
one line `RESULT program=run_peers ... <code>_<scheme>_<theta>_loop_seconds=...`
(loop CPU seconds to err_v = 1e-2; `none` where no front reaches it).
"""
import csv
import json
import math
import os
import re
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import two_bars_exact as tb  # noqa: E402
import siconos_two_bars  # noqa: E402
import getfem_two_bars  # noqa: E402

COLUMNS = ["code", "scheme", "theta", "cells_per_bar", "time_step",
           "courant", "n_steps", "cpu_run_seconds", "cpu_loop_seconds",
           "err_v", "err_f", "energy_ratio"]
CELLS = (10, 20, 40, 80, 160, 320)
COURANTS = (0.5, 0.9, 2., 4.)
EXTENSION = ((640, COURANTS), (1280, (0.5, 0.9)))
TARGET = 1e-2


def fmt(x):
    return repr(x) if isinstance(x, float) else str(x)


def curve_key(row):
    return (row["code"], row["scheme"], float(row["theta"]))


def front(rows, cpu_key):
    """The work-precision front: sorted by CPU, each run more accurate
    than every cheaper one."""
    pts = sorted((float(r[cpu_key]), float(r["err_v"])) for r in rows)
    out, best = [], math.inf
    for c, e in pts:
        if e < best:
            out.append((c, e))
            best = e
    return out


def cpu_at_target(rows, cpu_key, target=TARGET):
    """(seconds, how): how = 'interpolated', 'reached by the cheapest run'
    or 'extrapolated' (only when the best run is within a factor 2 of the
    target); None with the reason otherwise."""
    pts = front(rows, cpu_key)
    for k, (c, e) in enumerate(pts):
        if e <= target:
            if k == 0:
                return c, "reached by the cheapest run"
            c0, e0 = pts[k - 1]
            s = (math.log(c) - math.log(c0)) / (math.log(e) - math.log(e0))
            return (math.exp(math.log(c0) + s * (math.log(target) - math.log(e0))),
                    "interpolated")
    tail = [(c, e) for c, e in pts if c > 0][-3:]
    if len(tail) < 2 or pts[-1][1] > 2. * target:
        return None, "not reached, not extrapolated"
    xs = [math.log(e) for _, e in tail]
    ys = [math.log(c) for c, _ in tail]
    mx, my = sum(xs) / len(xs), sum(ys) / len(ys)
    sxx = sum((x - mx) ** 2 for x in xs)
    if sxx == 0.:
        return None, "not reached"
    slope = sum((x - mx) * (y - my) for x, y in zip(xs, ys)) / sxx
    if slope >= 0.:
        return None, "not reached (err_v does not decrease with CPU)"
    return math.exp(my + slope * (math.log(target) - mx)), "extrapolated"


class Peer:
    """A code with one or more (theta) configurations; run(theta, cells,
    courant) returns its CSV rows."""

    def __init__(self, name, available, thetas, run):
        self.name, self.available, self.thetas, self.run = \
            name, available, thetas, run


def siconos_rows(theta, cells, courant):
    return [siconos_two_bars.run(theta, cells, courant)]


def getfem_rows(theta, cells, courant):
    return getfem_two_bars.csv_rows(getfem_two_bars.run(cells, courant))


def print_progress(rows):
    for r in rows:
        print(f"  {r['code']:8s} {r['scheme']:42s} theta={r['theta']:<5g}"
              f" cells={r['cells_per_bar']:<5d} C={r['courant']:<4g}"
              f" cpu={r['cpu_run_seconds']:8.3f}s"
              f" err_v={r['err_v']:.4g} err_f={r['err_f']:.4g}"
              f" E/E0={r['energy_ratio']:.6g}", flush=True)


def run_with_extension(run_rows, thetas, cells_list, extend):
    """The grid for each theta, then the extension levels while a curve of
    that theta has not reached the target."""
    rows = []
    for theta in thetas:
        mine = []
        for cells in cells_list:
            for courant in COURANTS:
                new = run_rows(theta, cells, courant)
                print_progress(new)
                mine.extend(new)
        if extend:
            for cells, courants in EXTENSION:
                curves = {}
                for r in mine:
                    curves.setdefault(curve_key(r), []).append(r["err_v"])
                if all(min(e) <= TARGET for e in curves.values()):
                    break
                print(f"  extending to {cells} cells per bar (theta = {theta}):"
                      " a curve has not reached err_v = 1e-2", flush=True)
                for courant in courants:
                    new = run_rows(theta, cells, courant)
                    print_progress(new)
                    mine.extend(new)
        rows.extend(mine)
    return rows


def ours_rows(snapshot, scheme, theta, cells, courant, tmp):
    h = tb.time_step_for_courant(courant, cells)
    d = os.path.join(tmp, f"{scheme}_{theta}_{cells}_{courant}")
    s = tb.run_ours(snapshot, d, scheme, theta, cells, h)
    return [{"code": "impactfe", "scheme": scheme, "theta": theta,
             "cells_per_bar": cells, "time_step": h, "courant": courant,
             "n_steps": int(s["n_steps"]),
             "cpu_run_seconds": s["setup_cpu_seconds"] + s["loop_cpu_seconds"],
             "cpu_loop_seconds": s["loop_cpu_seconds"],
             "err_v": s["err_v"], "err_f": s["err_f"],
             "energy_ratio": s["energy_ratio"]}]


def print_crossings(rows, title):
    """Prints the table of CPU seconds to reach err_v = 1e-2 per curve and
    returns its rows (for summary.json and the RESULT line)."""
    curves = {}
    crossings = []
    for r in rows:
        curves.setdefault(curve_key(r), []).append(r)
    print(f"\n{title}")
    print("| code | scheme | θ | best err_v in the runs | CPU s (whole run) at err_v = 1e-2 | CPU s (time loop) at err_v = 1e-2 |")
    print("|---|---|---|---|---|---|")
    for (code, scheme, theta), rs in curves.items():
        best = min(rs, key=lambda r: r["err_v"])
        cols = []
        seconds = {}
        for key in ("cpu_run_seconds", "cpu_loop_seconds"):
            sec, how = cpu_at_target(rs, key)
            seconds[key] = sec
            cols.append("—, " + how if sec is None else f"{sec:.3g} ({how})")
        print(f"| {code} | {scheme} | {theta:g} | {best['err_v']:.3g} "
              f"({best['cells_per_bar']} cells, C = {best['courant']:g}) | "
              f"{cols[0]} | {cols[1]} |")
        crossings.append({"code": code, "scheme": scheme, "theta": theta,
                          "best_err_v": best["err_v"],
                          "run_seconds_at_1e-2": seconds["cpu_run_seconds"],
                          "loop_seconds_at_1e-2": seconds["cpu_loop_seconds"]})
    return crossings


def write_summary(crossings, csv_path):
    """results/peers/summary.json and the RESULT line: each curve's loop CPU
    seconds to err_v = 1e-2 (none: not reached on its grid)."""
    os.makedirs("results/peers", exist_ok=True)
    with open("results/peers/summary.json", "w") as f:
        json.dump({"program": "run_peers", "csv": csv_path,
                   "target_err_v": 1e-2, "curves": crossings}, f, indent=1)
    print("\nsummary: results/peers/summary.json")
    fields = ["program=run_peers", "target_err_v=0.01", f"curves={len(crossings)}"]
    for c in crossings:
        key = re.sub(r"[^\w.-]+", "_", f"{c['code']}_{c['scheme']}_{c['theta']:g}")
        sec = c["loop_seconds_at_1e-2"]
        fields.append(f"{key}_loop_seconds={'none' if sec is None else f'{sec:.3g}'}")
    print("RESULT " + " ".join(fields))


def print_table(rows):
    print("\n| code | scheme | θ | cells | C | steps | CPU run s | CPU loop s | err_v | err_f | E_end/E_0 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['code']} | {r['scheme']} | {r['theta']:g} | "
              f"{r['cells_per_bar']} | {r['courant']:g} | {r['n_steps']} | "
              f"{r['cpu_run_seconds']:.3g} | {r['cpu_loop_seconds']:.3g} | "
              f"{r['err_v']:.4g} | {r['err_f']:.4g} | "
              f"{r['energy_ratio']:.5g} |")


def read_rows(path):
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            for k in ("theta", "time_step", "courant", "cpu_run_seconds",
                      "cpu_loop_seconds", "err_v", "err_f", "energy_ratio"):
                r[k] = float(r[k])
            for k in ("cells_per_bar", "n_steps"):
                r[k] = int(r[k])
            rows.append(r)
    return rows


def main():
    args = sys.argv[1:]
    quick = "--quick" in args
    extend = "--no-extend" not in args and not quick
    csv_path = "doc/peers_two_bars_1d.csv"
    if "--csv" in args:
        csv_path = args[args.index("--csv") + 1]
    snapshot = args[args.index("--ours") + 1] if "--ours" in args else None
    cells_list = (10, 20) if quick else CELLS

    peers = [Peer("siconos", siconos_two_bars.available(),
                  siconos_two_bars.THETAS, siconos_rows),
             Peer("getfem", getfem_two_bars.available(),
                  (getfem_two_bars.THETA,), getfem_rows)]
    rows = []
    if "--tables-only" in args:
        peers = []
        rows = read_rows(csv_path)
    for peer in peers:
        if not peer.available:
            print(f"skipped: python3-{peer.name} not installed")
            continue
        version = (siconos_two_bars if peer.name == "siconos"
                   else getfem_two_bars).version()
        print(f"{peer.name} {version}", flush=True)
        rows.extend(run_with_extension(peer.run, peer.thetas, cells_list,
                                       extend))
    if not rows:
        print("no peer available: nothing written")
        return 0

    if "--tables-only" not in args:
        os.makedirs(os.path.dirname(csv_path) or ".", exist_ok=True)
        with open(csv_path, "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(COLUMNS)
            for r in rows:
                w.writerow([fmt(r[c]) for c in COLUMNS])
        print(f"\nwrote {csv_path} ({len(rows)} rows)")
    print_table(rows)
    crossings = print_crossings(rows, "Peers: CPU seconds to reach err_v = 1e-2")

    if snapshot:
        ours = []
        with tempfile.TemporaryDirectory(prefix="peers_ours_") as tmp:
            for scheme, theta in (("theta", 0.5), ("theta", 0.55),
                                  ("modified-theta", 0.55),
                                  ("theta-euler", 0.55)):
                ours.extend(run_with_extension(
                    lambda th, n, c, s=scheme: ours_rows(snapshot, s, th, n,
                                                         c, tmp),
                    (theta,), cells_list, extend))
        crossings += print_crossings(ours, f"Ours ({snapshot}): CPU seconds "
                                           "to reach err_v = 1e-2")
    write_summary(crossings, csv_path)
    return 0


if __name__ == "__main__":
    sys.exit(main())
