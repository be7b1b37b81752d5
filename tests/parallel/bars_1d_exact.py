#!/usr/bin/env python3
"""The exact 1D solution of bars in a row with unilateral contact between
neighbours (no friction, no gravity), by characteristics: an independent
computation for the tests of contact_mpi's Scene = bodies.

Each bar carries the invariants sigma - Z v (along dx/dt = +c) and
sigma + Z v (along -c), Z = rho c, on nodes spaced c dt apart, so that one
step moves every invariant by exactly one node: the update is exact (no
dispersion) for piecewise constant data. At a closed interface between
bar i (right end) and bar j = i + 1 (left end) velocity and stress are
continuous, v = (S_j - R_i) / (Z_i + Z_j); if that stress is a tension the
ends are free (sigma = 0) instead, and the gap grows by (v_j - v_i) dt
until it closes again (closure is resolved to one step, the only error
besides the momenta's trapezoidal sums, both O(dt)).

Used as a module: momenta(bars, end_time, steps_per_unit) returns each
bar's momentum at end_time. Run as a script it prints them for the
materials of tests/parallel/three_materials.prm."""
import argparse
import math
from fractions import Fraction


def momenta(bars, end_time, cells_per_shortest):
    """bars: list of dicts with length, youngs_modulus, density, velocity
    (the bars touch at t = 0); the section cancels out (momenta per unit
    area). The transit times L/c must have rational ratios (up to 1e-12):
    dt is the largest step that divides every transit time into
    cells_per_shortest or more whole cells."""
    transit = [b["length"] / math.sqrt(b["youngs_modulus"] / b["density"])
               for b in bars]
    base = min(transit)
    ratios = [Fraction(t / base).limit_denominator(1000) for t in transit]
    for r, t in zip(ratios, transit):
        assert abs(float(r) * base - t) < 1e-12 * t, \
            "transit times L/c are not in a rational ratio"
    denominator = math.lcm(*(r.denominator for r in ratios))
    dt = base / (denominator * cells_per_shortest)
    cells = [round(t / dt) for t in transit]
    impedance = [math.sqrt(b["youngs_modulus"] * b["density"]) for b in bars]
    n_bars = len(bars)
    # the state on nodes: velocity and stress
    v = [[b["velocity"]] * (n + 1) for b, n in zip(bars, cells)]
    s = [[0.] * (n + 1) for n in cells]
    gap = [0.] * (n_bars - 1)
    n_steps = round(end_time / dt)
    for _ in range(n_steps):
        new_v = [list(x) for x in v]
        new_s = [list(x) for x in s]
        right = []  # R at each bar's right end, S at its left end
        left = []
        for i in range(n_bars):
            z, n = impedance[i], cells[i]
            for k in range(1, n):
                r = s[i][k - 1] - z * v[i][k - 1]
                q = s[i][k + 1] + z * v[i][k + 1]
                new_s[i][k] = 0.5 * (r + q)
                new_v[i][k] = (q - r) / (2. * z)
            right.append(s[i][n - 1] - z * v[i][n - 1])
            left.append(s[i][1] + z * v[i][1])
        # free ends first, then each interface in contact
        for i in range(n_bars):
            z, n = impedance[i], cells[i]
            new_s[i][0], new_v[i][0] = 0., left[i] / z
            new_s[i][n], new_v[i][n] = 0., -right[i] / z
        for i in range(n_bars - 1):
            j = i + 1
            zi, zj = impedance[i], impedance[j]
            v_free_i, v_free_j = -right[i] / zi, left[j] / zj
            if gap[i] + (v_free_j - v_free_i) * dt <= 0.:
                vc = (left[j] - right[i]) / (zi + zj)
                sc = right[i] + zi * vc
                if sc <= 0.:
                    n = cells[i]
                    new_s[i][n], new_v[i][n] = sc, vc
                    new_s[j][0], new_v[j][0] = sc, vc
                    gap[i] = 0.
                    continue
            gap[i] = max(0., gap[i] + (v_free_j - v_free_i) * dt)
        v, s = new_v, new_s
    result = []
    for i, b in enumerate(bars):
        dx = b["length"] / cells[i]
        inner = sum(v[i][1:-1]) + 0.5 * (v[i][0] + v[i][-1])
        result.append(b["density"] * dx * inner)
    return result


def three_materials():
    """The bars of three_materials.prm: steel bar 1 (E, rho) at v0, bar 2
    of E/4 (impedance Z/2), bar 3 of 4 rho (impedance 2 Z), 0.254 m each."""
    e, rho, length, v0 = 0.20684e12, 0.78957e4, 0.254, 5.13588
    return [dict(length=length, youngs_modulus=e, density=rho, velocity=v0),
            dict(length=length, youngs_modulus=e / 4, density=rho,
                 velocity=0.),
            dict(length=length, youngs_modulus=e, density=4 * rho,
                 velocity=0.)]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--end-time", type=float, default=0.4e-3)
    ap.add_argument("--cells", type=int, default=400)
    a = ap.parse_args()
    bars = three_materials()
    p = momenta(bars, a.end_time, a.cells)
    total = bars[0]["density"] * bars[0]["length"] * bars[0]["velocity"]
    print("momentum fractions p_b / (m_1 v0):",
          ", ".join(f"{x / total:.6f}" for x in p),
          f"(sum {sum(p) / total:.9f})")


if __name__ == "__main__":
    main()
