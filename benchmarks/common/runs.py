"""Helpers shared by the figure scripts in benchmarks/: run a program on a
parameter file with a few entries changed, and read its CSV outputs.

Run the scripts from the repository top with /usr/bin/python3 (Debian's
python3-matplotlib)."""
import csv
import json
import os
import subprocess
import sys


def run(build, program, base_prm, out_dir, overrides=""):
    """Run build/bin/<program> on <base_prm> (included) plus <overrides>
    (parameter-file text), results in <out_dir>. Returns summary.json."""
    executable = os.path.join(build, "bin", program)
    if not os.path.exists(executable):
        sys.exit(f"{executable} not found: build first (see README.md)")
    os.makedirs(out_dir, exist_ok=True)
    wrapper = os.path.join(out_dir, "run.prm")
    with open(wrapper, "w") as f:
        f.write(f"include {base_prm}\n{overrides}\n"
                "subsection Output\n"
                f"  set Output directory = {out_dir}\n"
                "  set VTU output = false\n  set Plot = false\nend\n")
    subprocess.run([executable, wrapper], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out_dir, "summary.json")) as f:
        return json.load(f)


def read_columns(path):
    """A CSV file as {column: [float, ...]}."""
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def read_shapes(path):
    """shapes.csv as {time: [(x0, y0, x1, y1), ...]}."""
    shapes = {}
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            shapes.setdefault(float(r["time"]), []).append(
                (float(r["x0"]), float(r["y0"]), float(r["x1"]), float(r["y1"])))
    return shapes


def machine_and_commit():
    """One line for captions: the CPU model and the git commit."""
    model = "unknown CPU"
    try:
        for line in open("/proc/cpuinfo"):
            if line.startswith("model name"):
                model = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    try:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"],
                                capture_output=True, text=True).stdout.strip()
    except OSError:
        commit = "?"
    return f"{model}, commit {commit or '?'}"
