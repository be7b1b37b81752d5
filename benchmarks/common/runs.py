"""Helpers shared by the figure scripts in benchmarks/: run a program on a
parameter file with a few entries changed, and read its CSV outputs.

Run the scripts from the repository top with /usr/bin/python3 (Debian's
python3-matplotlib)."""
import csv
import json
import math
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


def mpiexec(ranks):
    """The command prefix that runs a program on @p ranks MPI ranks (none
    for one rank); Open MPI is told to run as root, oversubscribe the
    cores and bind each rank to one."""
    if ranks == 1:
        return []
    cmd = ["mpiexec", "-np", str(ranks)]
    version = subprocess.run(["mpiexec", "--version"], capture_output=True,
                             text=True).stdout
    if "Open MPI" in version or "OpenRTE" in version:
        cmd += ["--allow-run-as-root", "--oversubscribe", "--bind-to", "core"]
    return cmd


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


# ---------------------------------------------------------------------------
# Timed runs for the work-precision benchmark (benchmarks/work_precision/).

def program_environment(build):
    """The environment to run <build>/bin/<program> in: os.environ, plus
    LD_LIBRARY_PATH=<build>/lib when that folder exists (so that a copy of a
    build, e.g. a snapshot, uses its own libimpactfe.so and not the one its
    RUNPATH names)."""
    env = dict(os.environ)
    lib = os.path.join(os.path.abspath(build), "lib")
    if os.path.isdir(lib):
        old = env.get("LD_LIBRARY_PATH")
        env["LD_LIBRARY_PATH"] = lib + (":" + old if old else "")
    return env


def run_measured(build, program, base_prm, out_dir, overrides="",
                 remove=("contact_nodes.csv",), prefix=()):
    """Run <build>/bin/<program> like run(), but do not stop on failure and
    measure the CPU seconds (user + system) of the child process with
    resource.getrusage(RUSAGE_CHILDREN) around it. Files named in <remove>
    are deleted afterwards (they can be large). <prefix> is put before the
    command (e.g. valgrind and its options).

    Returns {"summary": dict or None, "cpu_run_seconds": float,
    "returncode": int, "message": the exception text or "", "out_dir": ...}.
    The 2D programs exit with 1 when one of their built-in checks fails but
    still write summary.json and history.csv: the summary is returned then
    too, and the caller decides."""
    import resource
    executable = os.path.join(build, "bin", program)
    if not os.path.exists(executable):
        sys.exit(f"{executable} not found: build first (see README.md)")
    os.makedirs(out_dir, exist_ok=True)
    summary_file = os.path.join(out_dir, "summary.json")
    if os.path.exists(summary_file):
        os.remove(summary_file)
    wrapper = os.path.join(out_dir, "run.prm")
    with open(wrapper, "w") as f:
        f.write(f"include {base_prm}\n{overrides}\n"
                "subsection Output\n"
                f"  set Output directory = {out_dir}\n"
                "  set VTU output = false\n  set Plot = false\n"
                "  set Shape snapshot times =\nend\n")
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    proc = subprocess.run([*prefix, executable, wrapper], env=program_environment(build),
                          stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    with open(os.path.join(out_dir, "stdout.txt"), "w") as f:
        f.write(proc.stdout + proc.stderr)
    message = ""
    if proc.returncode != 0:
        text = proc.stderr.strip() or proc.stdout.strip()
        lines = [l.strip() for l in text.splitlines()
                 if l.strip() and not set(l.strip()) <= set("-")]
        if "Exception on processing:" in lines:
            lines = lines[lines.index("Exception on processing:") + 1:]
        message = " ".join(l for l in lines if l != "Aborting!")
        failed_checks = [l.strip() for l in proc.stdout.splitlines() if "FAILED" in l]
        if failed_checks:
            message = "; ".join(failed_checks) + " (" + message + ")"
        message = message[:300]
    for name in remove:
        path = os.path.join(out_dir, name)
        if os.path.exists(path):
            os.remove(path)
    summary = None
    if os.path.exists(summary_file):
        with open(summary_file) as f:
            summary = json.load(f)
    return {"summary": summary, "cpu_run_seconds": cpu,
            "returncode": proc.returncode, "message": message, "out_dir": out_dir}


def pareto_front(points):
    """The lower-left envelope of (cost, error) pairs: sorted by cost, the
    points whose error is below that of every cheaper point."""
    front = []
    for cost, error in sorted(points):
        if not front or error < front[-1][1]:
            front.append((cost, error))
    return front


def fit_exponent(points):
    """Least-squares exponent p of y ~ x^p over the (x, y) points with
    y > 0 (nan with fewer than two)."""
    pts = [(math.log(x), math.log(y)) for x, y in points if y > 0]
    if len(pts) < 2:
        return float("nan")
    mx = sum(p[0] for p in pts) / len(pts)
    my = sum(p[1] for p in pts) / len(pts)
    sxx = sum((p[0] - mx) ** 2 for p in pts)
    return sum((p[0] - mx) * (p[1] - my) for p in pts) / sxx


def result_checks(rows):
    """The end of a contact benchmark's RESULT line: the largest
    difference between runs of one size, the largest verification
    violation and the number of fallbacks over @p rows (dicts with
    largest_difference, largest_violation and fallbacks)."""
    return (f"largest_difference="
            f"{max(r['largest_difference'] for r in rows):.2g} "
            f"lcp_relative_error="
            f"{max(r['largest_violation'] for r in rows):.2g} "
            f"fallbacks={sum(r['fallbacks'] for r in rows)}")
