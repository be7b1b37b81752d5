"""Peer run: the 1D two-bar impact with GetFEM (Debian's python3-getfem),
mass redistribution + Newmark (beta = 1/4, gamma = 1/2) + GetFEM's basic
contact brick. What is implemented, precisely (see also doc/peers.md):

* GetFEM objects: one 1D mesh holding both bars as two disjoint chains of
  GT_PK(1,1) segments (bar 2 is shifted by 1 m in the reference geometry so
  that GetFEM does not merge the two end points at x = 0; the shift does not
  enter any matrix, the gap is given to the contact brick as data), a
  FEM_PK(1,1) MeshFem, an IM_GAUSS1D(2) MeshIm; the consistent mass
  (asm_mass_matrix, times rho*A) and stiffness (asm_laplacian with
  coefficient E*A) are assembled by GetFEM.
* Mass redistribution (Khenous, Laborde, Renard 2008, in its simplest P1
  form): in the element that carries a contact node, the consistent element
  mass rho*A*dx/6 [[2,1],[1,2]] is replaced by rho*A*dx on the other node
  only, so that the two contact nodes have zero mass and the total mass is
  unchanged (the element's centre of mass moves by dx/2: a P1 element has
  no other node to keep it). Done with Spmat.assign on GetFEM's matrix.
* Time scheme: Newmark beta = 1/4, gamma = 1/2 written in displacements,
  which needs no acceleration at the massless contact nodes:
      (4/h^2 M + K) u^{n+1} = 4/h^2 M u^n + 4/h M v^n - K u^n
                              - B^T r^n - B^T r^{n+1},
      v^{n+1} = 2 (u^{n+1} - u^n)/h - v^n,
  B u = u_1(right end) - u_2(left end), r the contact force (>= 0 in
  compression), Signorini on the displacement at t_{n+1}:
      g0 - B u^{n+1} >= 0  _|_  r^{n+1} >= 0.
  (At a massless node the momentum row is M a = 0 = F - K u - B^T r, which
  is what M a^n stands for above.)
* Contact: each step is a static contact problem solved by GetFEM's model
  solver: an explicit-matrix brick (4/h^2 M + K), an explicit-rhs brick
  (updated each step with set_private_rhs) and add_basic_contact_brick
  (constraint B u <= gap, non-symmetric Alart-Curnier augmented Lagrangian,
  augmentation r = E*A/dx, semi-smooth Newton in Model.solve, warm-started
  from the previous step, GetFEM's default linear solver). The system is
  handed to GetFEM scaled by 1/max diag(4/h^2 M + K) and solved to a
  residual of 1e-14 (see the comment in run(): unscaled, GetFEM accepts a
  wrong-sign multiplier as converged).
* Errors exactly as programs/two_bars_1d (two_bars_exact): v of bar 1's
  right-end node at the step's end, force = r^{n+1} (as our own Newmark
  reports r^{i+1}), step times accumulated t += h, N = ceil(T/h - 1e-9)
  steps; energy 1/2 v.M v + 1/2 u.K u with the scheme's (redistributed)
  M. The contact node has zero mass, so its end-of-step velocity v^{n+1}
  is not a state of the dynamics: the recurrence v^{n+1} = 2 du/h - v^n
  makes it alternate between 0 and v0 around the interface velocity v0/2
  for the whole contact. The CSV therefore has two rows per run: scheme
  'mass-redistribution-newmark' with that v^{n+1} (our definition to the
  letter), and 'mass-redistribution-newmark-mean-velocity' with the
  contact node's velocity taken as (u_c^{n+1} - u_c^n)/h; same run, same
  CPU times, same err_f and energy.

Run from the repository top:
    /usr/bin/python3 benchmarks/peers/getfem_two_bars.py [--quick] [--check]
--check compares the brick's answers with the exact one-node
complementarity solved in closed form on the same matrices.
"""
import os
import sys
import time

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_v, "1")

import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import two_bars_exact as tb  # noqa: E402

try:
    import getfem as gf
except ImportError:
    gf = None

CODE = "getfem"
SCHEME = "mass-redistribution-newmark"
THETA = 0.5          # Newmark gamma = 1/2 (beta = 1/4): the CSV's theta
CELLS = (10, 20, 40, 80, 160, 320)
COURANTS = (0.5, 0.9, 2., 4.)
BAR_2_SHIFT = 1.0    # m, reference geometry only
NOISY = ("noisy",) if os.environ.get("GETFEM_NOISY") else ()


def available():
    return gf is not None


def version():
    try:
        import subprocess
        out = subprocess.run(["dpkg-query", "-W", "-f=${Version}",
                              "python3-getfem"], capture_output=True,
                             text=True).stdout.strip()
        return out or "?"
    except OSError:
        return "?"


def to_scipy(spmat):
    import scipy.sparse as sps
    spmat.to_csc()
    jc, ir = spmat.csc_ind()
    return sps.csc_matrix((spmat.csc_val(), ir, jc), shape=spmat.size())


def build(cells):
    """GetFEM mesh, FEM, redistributed mass, stiffness; the DoFs of the
    two contact nodes and the end nodes' neighbours."""
    L = tb.BAR_LENGTH
    dx = L / cells
    mesh = gf.Mesh("empty", 1)
    gt = gf.GeoTrans("GT_PK(1,1)")
    for x0 in (-L, BAR_2_SHIFT):
        x = x0 + dx * np.arange(cells + 1)
        for e in range(cells):
            mesh.add_convex(gt, np.array([[x[e], x[e + 1]]]))
    mf = gf.MeshFem(mesh, 1)
    mf.set_fem(gf.Fem("FEM_PK(1,1)"))
    mim = gf.MeshIm(mesh, gf.Integ("IM_GAUSS1D(2)"))
    nd = mf.nbdof()

    M = gf.asm_mass_matrix(mim, mf)
    M.scale(tb.DENSITY * tb.AREA)
    K = gf.asm_laplacian(mim, mf, mf,
                         np.full(nd, tb.YOUNGS_MODULUS * tb.AREA))

    xdof = mf.basic_dof_nodes()[0]

    def dof_at(x):
        return int(np.argmin(np.abs(xdof - x)))

    contact_1 = dof_at(0.)                 # bar 1, right end
    contact_2 = dof_at(BAR_2_SHIFT)        # bar 2, left end
    inner_1 = dof_at(-dx)
    inner_2 = dof_at(BAR_2_SHIFT + dx)
    me = tb.DENSITY * tb.AREA * dx
    for c, o in ((contact_1, inner_1), (contact_2, inner_2)):
        idx = [c, o]
        # The contact node's only element: its consistent mass
        # me/6 [[2, 1], [1, 2]] out, me on the inner node in; the contact
        # node's row and column are set to exact zeros.
        block = gf.Spmat("copy", M, idx, idx).full()
        block[1, 1] += me - 2. / 6. * me
        block[0, :] = 0.
        block[:, 0] = 0.
        M.assign(idx, idx, block)
    bar_1 = xdof <= 1e-12                 # bar 1 is on [-L, 0]
    return {"mesh": mesh, "mf": mf, "mim": mim, "M": M, "K": K, "nd": nd,
            "contact_1": contact_1, "contact_2": contact_2, "bar_1": bar_1,
            "xdof": xdof}


def run(cells, courant, end_time=tb.END_TIME, check=False):
    """One run; returns the CSV row (and, with check, the largest
    difference from the closed-form one-node complementarity)."""
    h = tb.time_step_for_courant(courant, cells)
    n_steps = tb.n_steps(end_time, h)
    dx = tb.BAR_LENGTH / cells

    cpu_start = time.process_time()
    fe = build(cells)
    nd, c1, c2 = fe["nd"], fe["contact_1"], fe["contact_2"]
    M_s, K_s = to_scipy(fe["M"]), to_scipy(fe["K"])
    A = gf.Spmat("copy", fe["M"])
    A.scale(4. / h ** 2)
    A = gf.Spmat("add", A, fe["K"])
    # GetFEM's Newton measures one residual: the momentum rows in N and
    # the Alart-Curnier contact row divided by r, i.e. in metres (the gap,
    # or lambda/r when the multiplier has the wrong sign). In SI units the
    # momentum rows' rounding floor (~1e-8 N) is far above a meaningful gap
    # tolerance, and a wrong-sign multiplier of 4e4 N reads as 3e-6 "m" and
    # passes as converged. So the system handed to GetFEM is scaled by
    # s = 1/max diag(A): unknowns stay in metres, forces are s*N, r is
    # s*E*A/dx = O(1), and max_res = 1e-14 bounds both rows.
    s = 1. / to_scipy(A).diagonal().max()
    A_model = gf.Spmat("copy", A)
    A_model.scale(s)
    B = np.zeros(nd)
    B[c1], B[c2] = 1., -1.
    BN = gf.Spmat("empty", 1, nd)
    BN.add([0], [c1, c2], np.array([[1., -1.]]))

    md = gf.Model("real")
    md.add_fem_variable("u", fe["mf"])
    md.add_explicit_matrix("u", "u", A_model, 1, 1)
    rhs_brick = md.add_explicit_rhs("u", np.zeros(nd))
    md.add_variable("lambda_n", 1)
    md.add_initialized_data("r", [s * tb.YOUNGS_MODULUS * tb.AREA / dx])
    md.add_initialized_data("gap", [tb.INITIAL_GAP])
    md.add_basic_contact_brick("u", "lambda_n", "r", BN, "gap")

    u = np.zeros(nd)
    v = np.where(fe["bar_1"], tb.IMPACT_VELOCITY, 0.)
    r_old = 0.
    e0 = tb.total_energy(M_s, K_s, u, v)
    acc = tb.ErrorAccumulator()
    acc_mean = tb.ErrorAccumulator()     # v_c = (u_c^{n+1} - u_c^n) / h
    worst_check = 0.
    if check:
        import scipy.sparse.linalg as spla
        A_s = to_scipy(A)
        lu = spla.splu(A_s.tocsc())
        AiB = lu.solve(B)
        BAiB = B @ AiB
    times = tb.step_times(h, n_steps)
    iterations = 0
    loop_start = time.process_time()
    for t in times:
        b = M_s @ (4. / h ** 2 * u + 4. / h * v) - K_s @ u - r_old * B
        md.set_private_rhs(rhs_brick, s * b)
        # Default linear solver ('auto'): 'lsolver', 'superlu' crashes
        # (segmentation fault) in python3-getfem 5.4.2 on Debian bookworm.
        nbit, converged = md.solve("max_res", 1e-14, "max_iter", 100,
                                   *NOISY)
        if not converged:
            raise RuntimeError(f"GetFEM contact step at t = {t} did not "
                               f"converge in {nbit} iterations")
        iterations += nbit
        u_new = md.variable("u")
        # GetFEM's multiplier is the reaction on B u <= gap: -r.
        r_new = -md.variable("lambda_n")[0] / s
        if check:
            u_free = lu.solve(b)
            g_free = tb.INITIAL_GAP - B @ u_free
            r_ref = max(0., -g_free / BAiB)
            u_ref = u_free - r_ref * AiB
            scale_u = max(1e-30, np.abs(u_ref).max())
            worst_check = max(worst_check,
                              abs(r_new - r_ref) / (0.5 * tb.ExactSolution().contact_force),
                              np.abs(u_new - u_ref).max() / scale_u)
        v_mean_c = (u_new[c1] - u[c1]) / h
        v = 2. / h * (u_new - u) - v
        u = u_new
        r_old = r_new
        acc.add(t, v[c1], r_new)
        acc_mean.add(t, v_mean_c, r_new)
    loop_end = time.process_time()
    e1 = tb.total_energy(M_s, K_s, u, v)
    cpu_end = time.process_time()
    row = {"code": CODE, "scheme": SCHEME, "theta": THETA,
           "cells_per_bar": cells, "time_step": h, "courant": courant,
           "n_steps": n_steps, "cpu_run_seconds": cpu_end - cpu_start,
           "cpu_loop_seconds": loop_end - loop_start,
           "err_v": acc.err_v(), "err_f": acc.err_f(),
           "energy_ratio": e1 / e0,
           "err_v_mean_velocity": acc_mean.err_v()}
    if check:
        row["check"] = worst_check
        row["newton_iterations"] = iterations
    return row


def csv_rows(row):
    """Two CSV rows per run: the scheme's own end-of-step velocity of the
    (massless) contact node, and the same run with the contact node's
    velocity taken as its mean over the step (u_c^{n+1} - u_c^n)/h; see
    doc/peers.md. Everything else (CPU, err_f, energy) is the same run."""
    strict = {k: x for k, x in row.items() if k in CSV_KEYS}
    mean = dict(strict)
    mean["scheme"] = SCHEME + "-mean-velocity"
    mean["err_v"] = row["err_v_mean_velocity"]
    return [strict, mean]


CSV_KEYS = ("code", "scheme", "theta", "cells_per_bar", "time_step",
            "courant", "n_steps", "cpu_run_seconds", "cpu_loop_seconds",
            "err_v", "err_f", "energy_ratio")


def run_grid(cells_list=CELLS, courants=COURANTS, progress=None):
    """All runs of the grid, as CSV rows (two per run, see csv_rows)."""
    rows = []
    for cells in cells_list:
        for courant in courants:
            row = run(cells, courant)
            rows.extend(csv_rows(row))
            if progress:
                progress(row)
    return rows


def print_row(row):
    extra = ""
    if "check" in row:
        extra = (f" | vs closed form {row['check']:.1e},"
                 f" {row['newton_iterations']} Newton its")
    print(f"{row['code']:8s} cells={row['cells_per_bar']:<5d}"
          f" C={row['courant']:<4g} steps={row['n_steps']:<6d}"
          f" cpu={row['cpu_run_seconds']:.3f}s loop={row['cpu_loop_seconds']:.3f}s"
          f" err_v={row['err_v']:.4g} (mean v: {row['err_v_mean_velocity']:.4g})"
          f" err_f={row['err_f']:.4g}"
          f" E/E0={row['energy_ratio']:.6g}{extra}", flush=True)


def main():
    if not available():
        print("skipped: python3-getfem not installed")
        return 0
    print(f"GetFEM {version()} (python3-getfem)")
    cells_list = (10, 20) if "--quick" in sys.argv else CELLS
    if "--check" in sys.argv:
        for cells in cells_list:
            for courant in COURANTS:
                print_row(run(cells, courant, check=True))
    else:
        run_grid(cells_list, progress=print_row)
    return 0


if __name__ == "__main__":
    sys.exit(main())
