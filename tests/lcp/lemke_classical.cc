// Classical LCPs with solutions known in closed form.
//
//  1. Cottle-Pang-Stone (1992), Remark 4.1.14 (also Siconos numerics'
//     lcp_CPS_1.dat): M = [1 1; 1 1], q = (-1, -1); the solution set is
//     {z >= 0 : z_1 + z_2 = 1}.
//  2. A convex QP as an LCP, Siconos numerics' lcp_CPS_4.dat (read there
//     column-major): min 1/2 x'Qx + c'x, x >= 0, x_1 + x_2 + x_3 >= 6 with
//     Q = [11 0 10; 0 11 10; 10 10 21], c = (50, 50, 10). M = [Q -a; a' 0] is
//     copositive-plus. By hand: x_1 = x_2 = a, x_3 = b, stationarity of the
//     x_1 and x_3 rows gives 9a + 11b = 40 and 2a + b = 6, so a = b = 2 and
//     the multiplier is 11a + 10b + 50 = 92: z = (2, 2, 2, 92), w = 0.
//  3. A linear program as an LCP: min x_1 + x_2 s.t. x_1 + 2x_2 >= 2,
//     3x_1 + x_2 >= 3, x >= 0; M = [0 -A'; A 0], q = (c, -b). Optimum at the
//     vertex x = (4/5, 3/5) with duals y = (2/5, 1/5).
//  4. M = [2 1; 1 2], q = (-5, -6): both rows active, z = (4/3, 7/3).
//  5. M = [1 2 0; 0 1 2; 2 0 1] (a P-matrix: minors 1, 1, 9), q = -e: ties at
//     every step; z = (1/3, 1/3, 1/3).
// Each is also checked against complete enumeration (lcp_test::enumerate),
// and the pivot counts against benchmarks/lcp/reference_lemke.py (exact
// rational tableau): 2, 5, 5, 3, 4.
#include <impactfe/lcp/lemke.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using lcp_test::matrix;

namespace
{
  void
  run(const std::string         &name,
      const DenseMatrix         &M,
      const std::vector<double> &q,
      const std::vector<double> &expected,
      const unsigned int         expected_pivots)
  {
    const Result r = solve_lemke(M, q);
    dealii::deallog << name << ": " << to_string(r.status) << " in " << r.pivots
                    << " pivots, z = " << lcp_test::str(r.z) << std::endl;
    bool in_enumeration = false;
    for (const auto &s : lcp_test::enumerate(M, q))
      in_enumeration = in_enumeration || lcp_test::max_diff(s, r.z) < 1e-10;
    impactfe_tests::check(r.status == Status::solved && r.verification.ok &&
                            (expected.empty() ||
                             lcp_test::max_diff(r.z, expected) < 1e-12) &&
                            in_enumeration && r.pivots == expected_pivots,
                          name);
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();

  {
    const DenseMatrix         M = matrix({{1, 1}, {1, 1}});
    const std::vector<double> q = {-1, -1};
    run("CPS remark 4.1.14", M, q, {}, 2);
    const Result r = solve_lemke(M, q);
    impactfe_tests::check(std::abs(r.z[0] + r.z[1] - 1.) < 1e-14,
                          "z_1 + z_2 = 1");
  }
  run("QP (lcp_CPS_4)",
      matrix(
        {{11, 0, 10, -1}, {0, 11, 10, -1}, {10, 10, 21, -1}, {1, 1, 1, 0}}),
      {50, 50, 10, -6},
      {2, 2, 2, 92},
      5);
  run("LP",
      matrix({{0, 0, -1, -3}, {0, 0, -2, -1}, {1, 2, 0, 0}, {3, 1, 0, 0}}),
      {1, 1, -2, -3},
      {0.8, 0.6, 0.4, 0.2},
      5);
  run("2x2 SPD", matrix({{2, 1}, {1, 2}}), {-5, -6}, {4. / 3, 7. / 3}, 3);
  run("cyclic P-matrix",
      matrix({{1, 2, 0}, {0, 1, 2}, {2, 0, 1}}),
      {-1, -1, -1},
      {1. / 3, 1. / 3, 1. / 3},
      4);

  // The trivial case: q >= 0.
  {
    const Result r = solve_lemke(matrix({{-1, 5}, {3, -2}}), {0, 2});
    dealii::deallog << "q >= 0: " << to_string(r.status) << " in " << r.pivots
                    << " pivots, z = " << lcp_test::str(r.z) << std::endl;
    impactfe_tests::check(r.status == Status::solved && r.pivots == 0 &&
                            r.z == std::vector<double>{0, 0},
                          "trivial exit");
  }
  // Scale invariance: M and q scaled by 1e-9 (a Delassus operator in SI units
  // can be that small) give the same z and pivots.
  {
    DenseMatrix M = matrix(
      {{11, 0, 10, -1}, {0, 11, 10, -1}, {10, 10, 21, -1}, {1, 1, 1, 0}});
    std::vector<double> q = {50, 50, 10, -6};
    for (unsigned int i = 0; i < 4; ++i)
      {
        q[i] *= 1e-9;
        for (unsigned int j = 0; j < 4; ++j)
          M(i, j) *= 1e-9;
      }
    const Result r = solve_lemke(M, q);
    impactfe_tests::check(r.status == Status::solved && r.pivots == 5 &&
                            lcp_test::max_diff(r.z, {2, 2, 2, 92}) < 1e-10,
                          "scaled by 1e-9");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
