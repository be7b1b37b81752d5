"""The 1D two-bar impact (paper section 6.1.1): data, exact solution, P1
matrices and the error measures of programs/two_bars_1d/two_bars_1d.cc,
reimplemented in Python for the peer benchmarks (Siconos, GetFEM).

The definitions follow two_bars_1d.cc line by line:

* exact solution, piecewise constant in time (t_contact = g0/v0 = 0 here,
  duration 2L/c, c = sqrt(E/rho)):
    bar 1's contact node   v0 for t < t_contact, v0/2 for t < t_contact +
                           duration, 0 afterwards (lab frame);
    contact force          0.5*rho*c*v0*A on [t_contact, t_contact+duration),
                           0 elsewhere;
* time of step i: accumulated as t_{i+1} = t_i + h from t_0 = 0, as
  MultibodySystem does (report.time = current.time + h). With the Courant
  numbers of the grid, the end of the exact contact 2L/c falls on a step end
  in exact arithmetic; the rounding of the accumulated time then decides on
  which side of the jump that step is, so the peers use the same sum;
* err_v = (1/N) sum_{i=1..N} |v_c(t_i) - v_c^ex(t_i)| / (v0/2), with v_c
  the velocity of bar 1's right-end node (lab frame) at the end of step i;
  the initial state t_0 = 0 is not counted; N = ceil(T/h - 1e-9);
* err_f = (1/N) sum_i |F_i - F^ex(t_i)| / (0.5*rho*c*v0*A), F_i the total
  normal contact force of step i, positive in compression; for the
  theta-schemes F_i = P_i / h, P_i the contact impulse of the step;
* energy_ratio = (1/2 v^T M v + 1/2 u^T K u at the end) / (the same at
  t = 0), M and K the consistent P1 mass and stiffness of both bars.

Run as a script it checks itself against our program: it recomputes err_v,
err_f and energy_ratio from history.csv of two_bars_1d runs and compares
them with summary.json (see main() and doc/peers.md). It also runs the
theta-method of /work/shared/spec/schemes.md in numpy on the same P1
matrices (theta_method_reference) and compares with our program's
'theta' scheme, which checks the assembly the peers share.
"""
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np

# Table 1 of the paper and parameter_files/two_bars_1d.prm.
BAR_LENGTH = 0.254          # m
YOUNGS_MODULUS = 0.20684e12  # Pa
DENSITY = 0.78957e4         # kg/m^3
IMPACT_VELOCITY = 5.13588   # m/s
END_TIME = 0.2e-3           # s
PAPER_TIME_STEP = 0.2226e-5  # s
AREA = 6.4516e-4            # m^2 (1 in^2, as in the .prm)
INITIAL_GAP = 0.0           # m


def wave_speed(E=YOUNGS_MODULUS, rho=DENSITY):
    return math.sqrt(E / rho)


def n_steps(end_time, h):
    """TimeSteppingParameters::n_steps()."""
    return int(math.ceil(end_time / h - 1e-9))


def time_step_for_courant(courant, cells_per_bar, L=BAR_LENGTH):
    """h with c h / dx = courant."""
    return courant * (L / cells_per_bar) / wave_speed()


class ExactSolution:
    """two_bars_1d.cc's ExactSolution."""

    def __init__(self, v0=IMPACT_VELOCITY, L=BAR_LENGTH, g0=INITIAL_GAP,
                 E=YOUNGS_MODULUS, rho=DENSITY, area=AREA):
        c = wave_speed(E, rho)
        self.v0 = v0
        self.t_contact = g0 / v0
        self.duration = 2. * L / c
        self.contact_force = 0.5 * rho * c * v0 * area

    def contact_velocity(self, t):
        if t < self.t_contact:
            return self.v0
        return 0.5 * self.v0 if t < self.t_contact + self.duration else 0.

    def target_velocity(self, t):
        return self.v0 - self.contact_velocity(t)

    def normal_force(self, t):
        end = self.t_contact + self.duration
        return self.contact_force if self.t_contact <= t < end else 0.


class ErrorAccumulator:
    """The sums of TwoBarsProblem::do_time_step; add() once per step, with
    the step's end time, bar 1's contact-node velocity and the contact
    force."""

    def __init__(self, exact=None):
        self.exact = exact or ExactSolution()
        self.sum_v = 0.
        self.sum_f = 0.
        self.n = 0

    def add(self, t, v_contact, normal_force):
        ex = self.exact
        self.sum_v += abs(v_contact - ex.contact_velocity(t)) / (0.5 * ex.v0)
        self.sum_f += abs(normal_force - ex.normal_force(t)) / ex.contact_force
        self.n += 1

    def err_v(self):
        return self.sum_v / self.n

    def err_f(self):
        return self.sum_f / self.n


def step_times(h, count):
    """t_1 .. t_count accumulated as our program does."""
    t, out = 0., []
    for _ in range(count):
        t = t + h
        out.append(t)
    return out


def p1_bar_matrices(cells, L=BAR_LENGTH, E=YOUNGS_MODULUS, rho=DENSITY,
                    area=AREA):
    """Consistent mass and stiffness of one bar of `cells` equal P1
    elements (dense (n+1) x (n+1) numpy arrays; the problem is small)."""
    dx = L / cells
    me = rho * area * dx / 6. * np.array([[2., 1.], [1., 2.]])
    ke = E * area / dx * np.array([[1., -1.], [-1., 1.]])
    M = np.zeros((cells + 1, cells + 1))
    K = np.zeros((cells + 1, cells + 1))
    for e in range(cells):
        M[e:e + 2, e:e + 2] += me
        K[e:e + 2, e:e + 2] += ke
    return M, K


def total_energy(M, K, u, v):
    return 0.5 * v @ (M @ v) + 0.5 * u @ (K @ u)


def errors_from_history(path, h=None):
    """(err_v, err_f, energy_ratio, n) recomputed from a two_bars_1d
    history.csv. The time of each row is the program's (printed with 10
    digits); with h given, the accumulated time is used instead, which is
    what decides the side of the jump when a step ends on it."""
    with open(path, newline="") as f:
        rows = [{k: float(x) for k, x in r.items()} for r in csv.DictReader(f)]
    acc = ErrorAccumulator()
    times = step_times(h, len(rows) - 1) if h else [r["time"] for r in rows[1:]]
    for t, r in zip(times, rows[1:]):
        acc.add(t, r["contact_velocity"], r["normal_force"])
    e0 = rows[0]["kinetic_energy"] + rows[0]["elastic_energy"]
    e1 = rows[-1]["kinetic_energy"] + rows[-1]["elastic_energy"]
    return acc.err_v(), acc.err_f(), e1 / e0, acc.n


def theta_method_reference(theta, cells, h, end_time=END_TIME):
    """The theta-method of /work/shared/spec/schemes.md (Signorini on
    g^{i+1}, one-row LCP solved in closed form), on the matrices above.
    Returns (err_v, err_f, energy_ratio, n). Only for checking the assembly
    and the error code against our program's 'theta' scheme."""
    M1, K1 = p1_bar_matrices(cells)
    n1 = cells + 1
    Z = np.zeros_like(M1)
    M = np.block([[M1, Z], [Z, M1]])
    K = np.block([[K1, Z], [Z, K1]])
    H = np.zeros(2 * n1)
    H[cells], H[n1] = -1., 1.       # V_N = v2(0) - v1(L); P pushes apart
    u = np.zeros(2 * n1)
    v = np.zeros(2 * n1)
    v[:n1] = IMPACT_VELOCITY
    Mt = M + (h * theta) ** 2 * K
    Mt_inv = np.linalg.inv(Mt)
    MtH = Mt_inv @ H
    W = H @ MtH
    rhs_v = M - h * h * theta * (1 - theta) * K
    g = INITIAL_GAP
    e0 = total_energy(M, K, u, v)
    acc = ErrorAccumulator()
    for t in step_times(h, n_steps(end_time, h)):
        vfree = Mt_inv @ (rhs_v @ v - h * (K @ u))
        vn_old = H @ v
        q = H @ vfree + (1 - theta) / theta * vn_old + g / (h * theta)
        P = max(0., -q / W)
        v_new = vfree + MtH * P
        u = u + h * (theta * v_new + (1 - theta) * v)
        g = g + h * theta * (H @ v_new) + h * (1 - theta) * vn_old
        v = v_new
        acc.add(t, v[cells], P / h)
    return acc.err_v(), acc.err_f(), total_energy(M, K, u, v) / e0, acc.n


def run_ours(snapshot, out_dir, scheme, theta, cells, h):
    """Run our two_bars_1d (the snapshot build) on the default .prm with a
    few entries changed, from the repository top; returns summary.json."""
    os.makedirs(out_dir, exist_ok=True)
    prm = os.path.join(out_dir, "run.prm")
    with open(prm, "w") as f:
        f.write("include parameter_files/two_bars_1d.prm\n"
                "subsection Geometry\n"
                f"  set Number of cells per bar = {cells}\nend\n"
                "subsection Time stepping\n"
                f"  set Scheme = {scheme}\n  set Theta = {theta!r}\n"
                f"  set Time step = {h!r}\nend\n"
                "subsection Output\n"
                f"  set Output directory = {out_dir}\n"
                "  set VTU output = false\n  set Plot = false\nend\n")
    env = dict(os.environ)
    env["LD_LIBRARY_PATH"] = os.path.join(snapshot, "lib")
    subprocess.run([os.path.join(snapshot, "bin", "two_bars_1d"), prm],
                   check=True, stdout=subprocess.DEVNULL, env=env)
    with open(os.path.join(out_dir, "summary.json")) as f:
        return json.load(f)


def main():
    """Self-check against our program (run from the repository top):
        /usr/bin/python3 benchmarks/peers/two_bars_exact.py [snapshot dir]
    The snapshot directory holds bin/two_bars_1d and lib/ (default
    /work/snap; build/ works too with its lib path)."""
    snapshot = sys.argv[1] if len(sys.argv) > 1 else "/work/snap"
    cases = [("theta-euler", 0.55, 20, PAPER_TIME_STEP)]
    for scheme in ("theta", "theta-euler", "modified-theta", "newmark"):
        for theta in (0.5, 0.55):
            for cells, courant in ((10, 0.5), (20, 0.9), (40, 2.), (80, 4.)):
                if scheme == "newmark" and theta != 0.5:
                    continue
                cases.append((scheme, theta, cells,
                              time_step_for_courant(courant, cells)))
    worst = 0.
    worst_ref = 0.
    with tempfile.TemporaryDirectory(prefix="peers_check_") as tmp:
        print(f"{'scheme':15s} {'theta':>5s} {'cells':>5s} {'c h/dx':>6s} "
              f"{'quantity':12s} {'summary.json':>14s} {'history.csv':>14s} "
              f"{'rel. diff':>9s}  numpy theta-method")
        for k, (scheme, theta, cells, h) in enumerate(cases):
            d = os.path.join(tmp, f"case{k}")
            s = run_ours(snapshot, d, scheme, theta, cells, h)
            mine = errors_from_history(os.path.join(d, "history.csv"), h)
            assert mine[3] == s["n_steps"], (mine[3], s["n_steps"])
            ref = (theta_method_reference(theta, cells, h)
                   if scheme == "theta" else None)
            courant = wave_speed() * h / (BAR_LENGTH / cells)
            for j, name in enumerate(("err_v", "err_f", "energy_ratio")):
                rel = abs(mine[j] - s[name]) / abs(s[name])
                worst = max(worst, rel)
                extra = ""
                if ref is not None:
                    rr = abs(ref[j] - s[name]) / abs(s[name])
                    worst_ref = max(worst_ref, rr)
                    extra = f"{ref[j]:.10g} ({rr:.1e})"
                print(f"{scheme:15s} {theta:5.2f} {cells:5d} {courant:6.3f} "
                      f"{name:12s} {s[name]:14.10g} {mine[j]:14.10g} "
                      f"{rel:9.1e}  {extra}")
    print(f"largest relative difference, history.csv vs summary.json: "
          f"{worst:.2e}")
    print(f"largest relative difference, numpy theta-method vs ours: "
          f"{worst_ref:.2e}")
    return 0 if worst < 1e-6 and worst_ref < 1e-6 else 1


if __name__ == "__main__":
    sys.exit(main())
