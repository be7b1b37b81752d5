#!/usr/bin/env python3
"""ctest driver: run a serial program and contact_mpi on two ranks on
the same scene, then compare their history.csv with
tools/compare_histories.py (to 1e-8 of each quantity's scale; the
momentum's bound adds the two runs' own impulse balance errors). Both runs
must also pass their own checks (exit code 0). The "serial" program may be
contact_mpi itself, run on one rank without mpiexec; --rename is
passed on to compare_histories.py (the serial bars' column names)."""
import argparse
import csv
import json
import os
import shlex
import shutil
import subprocess
import sys


def write_meshes(make_mesh, work, meshes):
    """Each {file name: make_bar_msh.py's arguments} of @p meshes into
    @p work (the bar and block meshes of the Scene = bodies tests)."""
    for name, args in meshes.items():
        with open(os.path.join(work, name), "w") as out:
            subprocess.check_call([sys.executable, make_mesh,
                                   *(str(x) for x in args)], stdout=out)


def bodies_arguments(prm_options=("--prm",), compare=True, dim=False,
                     extra=()):
    """The parsed command line of the Scene = bodies drivers: --program,
    the parameter files @p prm_options, --make-mesh, --mpiexec, --compare
    (if @p compare), --work (emptied here), --dim (if @p dim) and the
    (option, default) pairs of @p extra."""
    ap = argparse.ArgumentParser()
    for option in ("--program",) + tuple(prm_options) + ("--make-mesh",
                                                         "--mpiexec"):
        ap.add_argument(option, required=True)
    if compare:
        ap.add_argument("--compare", required=True)
    ap.add_argument("--work", required=True)
    if dim:
        ap.add_argument("--dim", type=int, choices=(2, 3), default=2)
    for option, default in extra:
        ap.add_argument(option, default=default)
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    return a


def run(command, cwd, log):
    with open(os.path.join(cwd, log), "w") as out:
        code = subprocess.call(command, cwd=cwd, stdout=out,
                               stderr=subprocess.STDOUT)
    if code != 0:
        print(f"{' '.join(command)} exited with {code}; its output:")
        print(open(os.path.join(cwd, log)).read())
        sys.exit(1)


def read_contact_problem(path):
    """W, q (gap terms folded in) and mu of a frictional-contact file in
    the dense Siconos text format the programs write (Dump LCP of step)."""
    import numpy as np
    tokens = open(path).read().split()
    nd, nc = int(tokens[0]), int(tokens[1])
    assert tokens[2] == "0", f"{path}: not dense storage"
    m = int(tokens[3])
    start = 7
    w = np.array([float(x) for x in tokens[start:start + m * m]])
    w = w.reshape((m, m)).T  # written column by column
    q = np.array([float(x) for x in tokens[start + m * m:start + m * m + m]])
    mu = np.array([float(x) for x in tokens[start + m * m + m:]])
    assert m == nd * nc and len(mu) == nc, f"{path}: sizes"
    return nd, nc, w, q, mu


def check_dumped_step(a, step):
    """The contact problem of step @p step that both runs wrote (`Dump LCP
    of step`): the same problem up to the order of the candidates (the
    eigenvalues of W, the sorted q and mu, to 1e-8 of their scales), and
    lcp-solve's answer of the distributed run's file gives the normal
    impulse of that step in its history.csv. Returns an error or None."""
    import numpy as np
    name = f"lcp_step_{step}.dat"
    problems = [read_contact_problem(os.path.join(a.work, sub, "results",
                                                  name))
                for sub in ("serial", "mpi")]
    (nd, nc, w_s, q_s, mu_s), (nd_m, nc_m, w_m, q_m, mu_m) = problems
    print(f"{name}: {nc} contacts of {nd} directions (serial), {nc_m} of "
          f"{nd_m} (two ranks)")
    if (nd, nc) != (nd_m, nc_m) or nc == 0:
        return "the dumped problems differ in size, or are empty"
    scale_w = np.abs(w_s).max()
    ew = np.abs(np.linalg.eigvalsh(w_s) - np.linalg.eigvalsh(w_m)).max()
    eq = np.abs(np.sort(q_s) - np.sort(q_m)).max() / np.abs(q_s).max()
    emu = np.abs(np.sort(mu_s) - np.sort(mu_m)).max()
    print(f"eigenvalues of W: {ew / scale_w:.1e} of max|W|; sorted q: "
          f"{eq:.1e} of max|q|; mu: {emu:.1e}")
    if ew > 1e-8 * scale_w or eq > 1e-8 or emu > 1e-12:
        return "the two runs dumped different problems"
    out = subprocess.run([a.lcp_solve, "--solution",
                          os.path.join(a.work, "mpi", "results", name)],
                         capture_output=True, text=True)
    lines = out.stdout.split("\n")
    if out.returncode != 0 or " solved " not in lines[0]:
        return f"lcp-solve did not solve the dumped file: {out.stdout}"
    p = np.array([float(x) for x in lines[1].split()[1:]])
    normal_impulse = p[::nd].sum()
    with open(os.path.join(a.work, "mpi", "results", "history.csv")) as f:
        rows = list(csv.DictReader(f))
    with open(os.path.join(a.work, "mpi", "results", "summary.json")) as f:
        h = json.load(f)["time_step"]
    row = min(rows, key=lambda r: abs(float(r["time"]) - step * h))
    force = float(row["normal_force"])
    error = abs(normal_impulse / h - force) / abs(force)
    print(f"step {step}: sum of lcp-solve's normal impulses / h = "
          f"{normal_impulse / h:.10g}, the run's normal_force {force:.10g} "
          f"(relative difference {error:.1e})")
    if error > 1e-8:
        return "the dumped problem's answer is not the step's impulse"
    return None


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--serial", required=True)
    ap.add_argument("--serial-prm", required=True)
    ap.add_argument("--parallel", required=True)
    ap.add_argument("--parallel-prm", required=True)
    ap.add_argument("--mpiexec", required=True)
    ap.add_argument("--compare", required=True)
    ap.add_argument("--work", required=True)
    ap.add_argument("--rename", action="append", default=[])
    ap.add_argument("--expect-theta", type=float,
                    help="theta both runs' summary.json must give (to 5e-5; "
                         "Theta rule = courant, worked out by hand)")
    ap.add_argument("--copy-parallel-prm", action="store_true",
                    help="run a copy of --parallel-prm in the work directory "
                         "(its mesh files are the serial run's output)")
    ap.add_argument("--dump-step", type=int,
                    help="both runs write the contact problem of this step "
                         "(Dump LCP of step), checked by check_dumped_step()")
    ap.add_argument("--lcp-solve", help="lcp-solve, for --dump-step")
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    for sub in ("serial", "mpi"):
        os.makedirs(os.path.join(a.work, sub))
    serial_prm, parallel_prm = a.serial_prm, a.parallel_prm
    if a.copy_parallel_prm:
        parallel_prm = os.path.join(a.work, "mpi", "parallel.prm")
        shutil.copyfile(a.parallel_prm, parallel_prm)
    if a.dump_step:
        # the run files included, the dump set after them (an override)
        for sub, prm in (("serial", serial_prm), ("mpi", parallel_prm)):
            wrapper = os.path.join(a.work, sub, "dump.prm")
            with open(wrapper, "w") as out:
                out.write(f"include {os.path.abspath(prm)}\n"
                          "subsection Contact solver\n"
                          f"  set Dump LCP of step = {a.dump_step}\nend\n")
            if sub == "serial":
                serial_prm = wrapper
            else:
                parallel_prm = wrapper
    run([a.serial, serial_prm], os.path.join(a.work, "serial"), "log")
    run(shlex.split(a.mpiexec) + [a.parallel, parallel_prm],
        os.path.join(a.work, "mpi"), "log")
    # each run's own impulse balance error bounds its momentum's round-off
    serial = json.load(open(os.path.join(a.work, "serial/results/summary.json")))
    mpi = json.load(open(os.path.join(a.work, "mpi/results/summary.json")))
    e_serial = serial.get("checks", serial)["impulse_balance_error"]
    e_mpi = mpi["impulse_balance_error"]
    print(f"impulse balance errors: serial {e_serial:.2e}, two ranks {e_mpi:.2e}")
    # the same theta (Theta rule = courant: from each run's own mesh)
    if "theta" in serial and "theta" in mpi:
        print(f"theta: serial {serial['theta']:.12g}, two ranks "
              f"{mpi['theta']:.12g}")
        if abs(serial["theta"] - mpi["theta"]) > 1e-12:
            print("the runs' theta differ")
            return 1
    if a.expect_theta is not None:
        for name, summary in (("serial", serial), ("two ranks", mpi)):
            if abs(summary.get("theta", float("nan")) - a.expect_theta) > 5e-5:
                print(f"{name}: theta = {summary.get('theta')}, expected "
                      f"{a.expect_theta}")
                return 1
    if a.dump_step:
        error = check_dumped_step(a, a.dump_step)
        if error:
            print(error)
            return 1
    return subprocess.call([sys.executable, a.compare,
                            os.path.join(a.work, "serial/results/history.csv"),
                            os.path.join(a.work, "mpi/results/history.csv"),
                            "--allowance", str(e_serial + e_mpi)] +
                           [f"--rename={r}" for r in a.rename])


if __name__ == "__main__":
    sys.exit(main())
