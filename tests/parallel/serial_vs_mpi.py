#!/usr/bin/env python3
"""ctest driver: run a serial program and contact_mpi on two ranks on
the same scene, then compare their history.csv with
tools/compare_histories.py (to 1e-8 of each quantity's scale; the
momentum's bound adds the two runs' own impulse balance errors). Both runs
must also pass their own checks (exit code 0). The "serial" program may be
contact_mpi itself, run on one rank without mpiexec; --rename is
passed on to compare_histories.py (the serial bars' column names)."""
import argparse
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
    a = ap.parse_args()
    shutil.rmtree(a.work, ignore_errors=True)
    for sub in ("serial", "mpi"):
        os.makedirs(os.path.join(a.work, sub))
    run([a.serial, a.serial_prm], os.path.join(a.work, "serial"), "log")
    parallel_prm = a.parallel_prm
    if a.copy_parallel_prm:
        parallel_prm = os.path.join(a.work, "mpi", "parallel.prm")
        shutil.copyfile(a.parallel_prm, parallel_prm)
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
    return subprocess.call([sys.executable, a.compare,
                            os.path.join(a.work, "serial/results/history.csv"),
                            os.path.join(a.work, "mpi/results/history.csv"),
                            "--allowance", str(e_serial + e_mpi)] +
                           [f"--rename={r}" for r in a.rename])


if __name__ == "__main__":
    sys.exit(main())
