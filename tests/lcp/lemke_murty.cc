// Murty's exponential example for Lemke's method.
//
// M(n) is lower triangular with 1 on the diagonal and 2 below it, q = -e,
// covering vector d = e. [K.G. Murty, "Computational complexity of
// complementary pivot methods", Math. Programming Study 7 (1978) 61-73; also
// K.G. Murty, "Linear Complementarity, Linear and Nonlinear Programming",
// Heldermann 1988, Chapter 6.] The unique solution is z = e_1 (M is a
// P-matrix) and Lemke's method visits 2^n bases: counted as we count pivots
// (every basis exchange, the entry of z0 included) that is exactly 2^n pivots,
// i.e. 2^n - 1 pivots after the initial one. All q_i/d_i tie at the first
// step, so the lexicographic rule is exercised from the start.
//
// Independent check: benchmarks/lcp/reference_lemke.py (exact rational
// tableau Lemke, no shared code) prints 2^n pivots for n = 1..10.
#include <impactfe/lcp/lemke.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

int
main()
{
  impactfe_tests::initlog();

  for (unsigned int n = 1; n <= 12; ++n)
    {
      DenseMatrix M(n, n, 0.);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j <= i; ++j)
          M(i, j) = (i == j ? 1. : 2.);
      const std::vector<double> q(n, -1.);

      LemkeOptions options;
      options.max_pivots = 1u << 14;
      const Result r     = solve_lemke(M, q, options);

      std::vector<double> expected(n, 0.);
      expected[0] = 1.;
      dealii::deallog << "n = " << n << ": status " << to_string(r.status)
                      << ", pivots " << r.pivots << " (2^n = " << (1u << n)
                      << ")" << std::endl;
      impactfe_tests::check(r.status == Status::solved &&
                              r.pivots == (1u << n) &&
                              lcp_test::max_diff(r.z, expected) < 1e-12 &&
                              r.verification.ok,
                            "murty n=" + std::to_string(n));
    }

  // With the default cap (50 (n+1) pivots) n = 12 must stop on the cap, and
  // leave no solution behind.
  {
    const unsigned int n = 12;
    DenseMatrix        M(n, n, 0.);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j <= i; ++j)
        M(i, j) = (i == j ? 1. : 2.);
    const Result r = solve_lemke(M, std::vector<double>(n, -1.));
    dealii::deallog << "n = 12, default cap: status " << to_string(r.status)
                    << ", pivots " << r.pivots << std::endl;
    impactfe_tests::check(r.status == Status::pivot_limit &&
                            r.pivots == 50 * 13 && r.z.empty() && r.w.empty() &&
                            !r.verification.ok,
                          "pivot cap reported, no solution returned");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
