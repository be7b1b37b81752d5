#!/usr/bin/env python3
"""Independent reference for the LCP tests: a textbook *tableau* Lemke method
in exact rational arithmetic (fractions.Fraction), with the lexicographic
minimum-ratio rule and z0 preferred to leave on ties, plus complete
enumeration of complementary bases.

It shares no code with source/lcp/lemke.cc (which keeps an explicit, rank-one
updated basis inverse in floating point); the tests in tests/lcp/ compare the
pivot counts and solutions of the C++ solver with the numbers this script
prints.

Usage: python3 reference_lemke.py murty N...   (pivot counts on Murty's LCP)
"""
from fractions import Fraction as F
import itertools
import sys


def lemke(M, q, d=None, max_pivots=100000):
    """Return (status, z, pivots); on a ray, z is replaced by the index of the
    variable that cannot enter (i: w_i, n + i: z_i). Tableau rows: x_B = rhs - T * (nonbasic),
    kept as the full tableau [I | -M | -d | q] multiplied by B^{-1}."""
    n = len(q)
    d = d or [F(1)] * n
    if all(v >= 0 for v in q):
        return "solved", [F(0)] * n, 0
    # columns: 0..n-1 w, n..2n-1 z, 2n z0; last column rhs
    T = []
    for i in range(n):
        row = [F(0)] * (2 * n + 2)
        row[i] = F(1)
        for j in range(n):
            row[n + j] = -F(M[i][j])
        row[2 * n] = -F(d[i])
        row[2 * n + 1] = F(q[i])
        T.append(row)
    basic = list(range(n))

    def do_pivot(r, e):
        pv = T[r][e]
        T[r] = [v / pv for v in T[r]]
        for i in range(n):
            if i != r and T[i][e] != 0:
                f = T[i][e]
                T[i] = [a - f * b for a, b in zip(T[i], T[r])]
        basic[r] = e

    def lexkey(i, div):
        # (rhs, B^{-1} row) / div ; B^{-1} sits in the w columns 0..n-1
        return [T[i][2 * n + 1] / div] + [T[i][c] / div for c in range(n)]

    # first pivot: z0 enters, row with lexico-min (q_i, e_i)/d_i
    cand = list(range(n))
    r = min(cand, key=lambda i: lexkey(i, d[i]))
    do_pivot(r, 2 * n)
    pivots = 1
    leaving = r  # w_r left
    while True:
        e = leaving + n if leaving < n else leaving - n
        col = [T[i][e] for i in range(n)]
        cand = [i for i in range(n) if col[i] > 0]
        if not cand:
            return "ray", e, pivots
        ratios = {i: T[i][2 * n + 1] / col[i] for i in cand}
        tmin = min(ratios.values())
        ties = [i for i in cand if ratios[i] == tmin]
        z0row = [i for i in ties if basic[i] == 2 * n]
        if z0row:
            r = z0row[0]
        else:
            r = min(ties, key=lambda i: lexkey(i, col[i]))
        leaving = basic[r]
        do_pivot(r, e)
        pivots += 1
        if leaving == 2 * n:
            z = [F(0)] * n
            for i in range(n):
                if n <= basic[i] < 2 * n:
                    z[basic[i] - n] = T[i][2 * n + 1]
            return "solved", z, pivots
        if pivots > max_pivots:
            return "cap", None, pivots


def solve_linear(A, b):
    n = len(b)
    A = [list(map(F, row)) + [F(v)] for row, v in zip(A, b)]
    for k in range(n):
        p = next((i for i in range(k, n) if A[i][k] != 0), None)
        if p is None:
            return None
        A[k], A[p] = A[p], A[k]
        for i in range(n):
            if i != k and A[i][k] != 0:
                f = A[i][k] / A[k][k]
                A[i] = [a - f * c for a, c in zip(A[i], A[k])]
    return [A[i][n] / A[i][i] for i in range(n)]


def enumerate_solutions(M, q):
    """All solutions of LCP(q, M) on nonsingular complementary bases."""
    n = len(q)
    sols = []
    for mask in itertools.product([0, 1], repeat=n):
        act = [i for i in range(n) if mask[i]]
        z = [F(0)] * n
        if act:
            sub = solve_linear([[M[i][j] for j in act] for i in act], [-q[i] for i in act])
            if sub is None:
                continue
            for k, i in enumerate(act):
                z[i] = sub[k]
        w = [sum(F(M[i][j]) * z[j] for j in range(n)) + q[i] for i in range(n)]
        if all(v >= 0 for v in z) and all(v >= 0 for v in w):
            if z not in sols:
                sols.append(z)
    return sols


def murty(n):
    """Murty's LCP: M lower triangular, 1 on the diagonal, 2 below; q = -e."""
    M = [[1 if i == j else (2 if j < i else 0) for j in range(n)] for i in range(n)]
    q = [-1] * n
    return M, q


if __name__ == "__main__":
    if len(sys.argv) > 2 and sys.argv[1] == "murty":
        for a in sys.argv[2:]:
            n = int(a)
            M, q = murty(n)
            st, z, piv = lemke(M, q)
            print(n, st, piv, [str(v) for v in z] if z else None)
    else:
        print(__doc__)
