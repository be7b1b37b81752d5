#!/usr/bin/env python3
"""Generate the degenerate integer LCPs of tests/lcp/lemke_degenerate.cc and
print their exact solutions and Lemke pivot counts from reference_lemke.py
(exact rational arithmetic, lexicographic rule, z0 preferred on ties)."""
import random
import reference_lemke as ref

random.seed(7)
cases = []
for n in (3, 4, 5, 6, 8):
    for rep in range(2):
        L = [[random.randint(-1, 1) for _ in range(n)] for _ in range(n)]
        K = [[random.randint(-1, 1) for _ in range(n)] for _ in range(n)]
        M = [[sum(L[i][k] * L[j][k] for k in range(n)) + K[i][j] - K[j][i] + (1 if i == j else 0)
              for j in range(n)] for i in range(n)]
        q = [random.choice([-2, -1, -1, 0, 0, 1]) for _ in range(n)]
        cases.append((M, q))
for M, q in cases:
    st, z, piv = ref.lemke(M, q)
    sols = ref.enumerate_solutions(M, q)
    print("{%s, {%s}, {%s}, %d},  // %s, %d solution(s) by enumeration" % (
        "{" + ", ".join("{" + ", ".join(map(str, r)) + "}" for r in M) + "}",
        ", ".join(map(str, q)),
        ", ".join("%d. / %d" % (v.numerator, v.denominator) for v in z),
        piv, st, len(sols)))
