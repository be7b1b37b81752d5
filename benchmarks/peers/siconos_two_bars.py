"""Peer run: the 1D two-bar impact with Siconos (Debian's python3-siconos).

What is modelled (see doc/peers.md):
* each bar is a Siconos LagrangianLinearTIDS (M dv/dt + K q = 0) whose
  consistent P1 mass and stiffness are assembled here in numpy
  (two_bars_exact.p1_bar_matrices); bar 1 starts at v0, bar 2 at rest;
* one Interaction links the two bars: a LagrangianLinearTIR y = C q with
  C = [0 .. 0 -1 | 1 0 .. 0] (bar 2's left-end displacement minus bar 1's
  right-end displacement: the gap, initial gap 0) and a NewtonImpactNSL
  with e = 0;
* MoreauJeanOSI(theta) + TimeStepping + an LCP one-step problem solved by
  Siconos' Lemke (SICONOS_LCP_LEMKE). Siconos' Moreau-Jean is the same
  theta-method for the dynamics and the displacement as ours
  (q^{k+1} = q^k + h(theta v^{k+1} + (1-theta) v^k)); the contact law is
  Siconos' own: the contact is put in the LCP when y + h/2 ydot <= 0
  (MoreauJeanOSI's default activation) and then
  0 <= ydot^{k+1} + e ydot^k  _|_  p^{k+1} >= 0 at the velocity level;
* errors exactly as programs/two_bars_1d (two_bars_exact.ErrorAccumulator):
  bar 1's right-end velocity, force = impulse / h (Interaction.lambda_(1)
  is the impulse of the step), step times accumulated t += h, N =
  ceil(T/h - 1e-9) steps (driven by us, not by Siconos' event manager).

Run from the repository top:
    /usr/bin/python3 benchmarks/peers/siconos_two_bars.py [--quick|--check]
prints the table; benchmarks/peers/run_peers.py writes the CSV. --check
compares Siconos with the same scheme written out in numpy
(velocity_level_reference): what Siconos computes, to rounding.
"""
import os
import sys
import time

# One thread for BLAS/LAPACK, as our program runs on one: process_time()
# would add the CPU of helper threads.
for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import two_bars_exact as tb  # noqa: E402

try:
    import siconos.kernel as sk
    import siconos.numerics as sn
except ImportError:
    sk = None

CODE = "siconos"
SCHEME = "moreau-jean"
THETAS = (0.5, 0.55)
CELLS = (10, 20, 40, 80, 160, 320)
COURANTS = (0.5, 0.9, 2., 4.)


def available():
    return sk is not None


def version():
    try:
        import subprocess
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}",
                              "python3-siconos"], capture_output=True,
                             text=True).stdout.strip()
        return out or "?"
    except OSError:
        return "?"


# Matrix storage handed to Siconos. The Python binding takes numpy arrays
# as dense matrices (scipy.sparse is refused: "ValueError: expected
# matrix"); a Siconos SimpleMatrix with SPARSE storage can be set with
# setMassPtr/setKPtr. Measured per step (theta = 0.5, c h/dx = 4): 80 cells
# dense 0.3 ms / sparse 1.1 ms, 320 cells 3.7 / 4.8 ms, 640 cells 29 / 16
# ms. So: dense up to 320 cells per bar, sparse above (the finer runs of
# the extended grid). Same results to rounding (checked).
SPARSE_FROM_CELLS = 640


def siconos_matrix(A, sparse):
    if not sparse:
        return A
    m = sk.SimpleMatrix(A.shape[0], A.shape[1], sk.SPARSE,
                        int(np.count_nonzero(A)))
    for i, j in zip(*np.nonzero(A)):
        m.setValue(int(i), int(j), float(A[i, j]))
    return m


def run(theta, cells, courant, end_time=tb.END_TIME):
    """One run; returns the CSV row as a dict."""
    h = tb.time_step_for_courant(courant, cells)
    n_steps = tb.n_steps(end_time, h)
    n1 = cells + 1

    cpu_start = time.process_time()
    M, K = tb.p1_bar_matrices(cells)
    sparse = cells >= SPARSE_FROM_CELLS
    bars = []
    for v_init in (tb.IMPACT_VELOCITY, 0.):
        ds = sk.LagrangianLinearTIDS(np.zeros(n1), np.full(n1, v_init), M)
        if sparse:
            ds.setMassPtr(siconos_matrix(M, True))
        ds.setKPtr(siconos_matrix(K, sparse))
        bars.append(ds)
    C = np.zeros((1, 2 * n1))
    C[0, cells] = -1.   # bar 1, right end
    C[0, n1] = 1.       # bar 2, left end
    relation = sk.LagrangianLinearTIR(C)
    law = sk.NewtonImpactNSL(0.)
    contact = sk.Interaction(law, relation)

    # Siconos' own horizon is left open (2 steps beyond T): we drive exactly
    # the same number of steps as our program.
    nsds = sk.NonSmoothDynamicalSystem(0., end_time + 2. * h)
    for ds in bars:
        nsds.insertDynamicalSystem(ds)
    nsds.link(contact, bars[0], bars[1])
    osi = sk.MoreauJeanOSI(theta)
    lcp = sk.LCP(sn.SICONOS_LCP_LEMKE)
    sim = sk.TimeStepping(nsds, sk.TimeDiscretisation(0., h), osi, lcp)

    e0 = sum(tb.total_energy(M, K, ds.q(), ds.velocity()) for ds in bars)
    acc = tb.ErrorAccumulator()
    times = tb.step_times(h, n_steps)
    loop_start = time.process_time()
    for t in times:
        sim.computeOneStep()
        v_c = bars[0].velocity()[cells]
        impulse = contact.lambda_(1)[0]
        acc.add(t, v_c, impulse / h)
        sim.nextStep()
    loop_end = time.process_time()
    e1 = sum(tb.total_energy(M, K, ds.q(), ds.velocity()) for ds in bars)
    cpu_end = time.process_time()
    return {"code": CODE, "scheme": SCHEME, "theta": theta,
            "cells_per_bar": cells, "time_step": h, "courant": courant,
            "n_steps": n_steps, "cpu_run_seconds": cpu_end - cpu_start,
            "cpu_loop_seconds": loop_end - loop_start,
            "err_v": acc.err_v(), "err_f": acc.err_f(),
            "energy_ratio": e1 / e0}


def velocity_level_reference(theta, cells, courant, end_time=tb.END_TIME):
    """What MoreauJeanOSI + NewtonImpactNSL(e = 0) + LCP compute, written
    out in numpy on the same matrices (our reading of Siconos 4.4's
    MoreauJeanOSI: W = M + h^2 theta^2 K, free velocity, activation
    y + h/2 ydot <= 0 at the step's start, 0 <= ydot^{k+1} _|_ p >= 0, the
    one-row LCP in closed form). Returns (err_v, err_f, energy_ratio)."""
    h = tb.time_step_for_courant(courant, cells)
    M1, K1 = tb.p1_bar_matrices(cells)
    n1 = cells + 1
    Z = np.zeros_like(M1)
    M = np.block([[M1, Z], [Z, M1]])
    K = np.block([[K1, Z], [Z, K1]])
    C = np.zeros(2 * n1)
    C[cells], C[n1] = -1., 1.
    q = np.zeros(2 * n1)
    v = np.zeros(2 * n1)
    v[:n1] = tb.IMPACT_VELOCITY
    W_inv = np.linalg.inv(M + (h * theta) ** 2 * K)
    WC = W_inv @ C
    delassus = C @ WC
    e0 = tb.total_energy(M, K, q, v)
    acc = tb.ErrorAccumulator()
    for t in tb.step_times(h, tb.n_steps(end_time, h)):
        v_free = v - W_inv @ (h * (K @ q) + h * h * theta * (K @ v))
        p = 0.
        if C @ q + 0.5 * h * (C @ v) <= 0.:
            p = max(0., -(C @ v_free) / delassus)
        v_new = v_free + WC * p
        q = q + h * (theta * v_new + (1. - theta) * v)
        v = v_new
        acc.add(t, v[cells], p / h)
    return acc.err_v(), acc.err_f(), tb.total_energy(M, K, q, v) / e0


def check():
    """Siconos against velocity_level_reference on a few runs."""
    worst = 0.
    for theta in THETAS:
        for cells, courant in ((10, 0.5), (20, 0.9), (40, 2.), (80, 4.)):
            row = run(theta, cells, courant)
            ref = velocity_level_reference(theta, cells, courant)
            diffs = [abs(row[k] - r) / abs(r) for k, r in
                     zip(("err_v", "err_f", "energy_ratio"), ref)]
            worst = max(worst, max(diffs))
            print(f"theta={theta} cells={cells} C={courant}: Siconos "
                  f"err_v={row['err_v']:.10g} err_f={row['err_f']:.10g} "
                  f"E/E0={row['energy_ratio']:.10g}; numpy "
                  f"{ref[0]:.10g} {ref[1]:.10g} {ref[2]:.10g}")
    print(f"largest relative difference: {worst:.1e}")
    return 0 if worst < 1e-9 else 1


def run_grid(thetas=THETAS, cells_list=CELLS, courants=COURANTS,
             progress=None):
    rows = []
    for theta in thetas:
        for cells in cells_list:
            for courant in courants:
                row = run(theta, cells, courant)
                rows.append(row)
                if progress:
                    progress(row)
    return rows


def print_row(row):
    print(f"{row['code']:8s} theta={row['theta']:<5g} cells={row['cells_per_bar']:<5d}"
          f" C={row['courant']:<4g} steps={row['n_steps']:<6d}"
          f" cpu={row['cpu_run_seconds']:.3f}s loop={row['cpu_loop_seconds']:.3f}s"
          f" err_v={row['err_v']:.4g} err_f={row['err_f']:.4g}"
          f" E/E0={row['energy_ratio']:.4g}", flush=True)


def main():
    if not available():
        print("skipped: python3-siconos not installed")
        return 0
    print(f"Siconos {version()} (python3-siconos)")
    if "--check" in sys.argv:
        return check()
    if "--quick" in sys.argv:
        run_grid(cells_list=(10, 20), progress=print_row)
    else:
        run_grid(progress=print_row)
    return 0


if __name__ == "__main__":
    sys.exit(main())
