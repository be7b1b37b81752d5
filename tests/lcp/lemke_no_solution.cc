// LCPs without solution, and one that Lemke cannot solve: ray termination
// must be reported, with no z.
//
//  1. M = [0 -1; 1 0] (skew: copositive-plus), q = (-1, -1): w_1 = -z_2 - 1 < 0
//     for every z >= 0, so the LCP is infeasible. For copositive-plus M, ray
//     termination proves infeasibility (Cottle-Pang-Stone 1992, Thm 4.4.13).
//  2. M = [1 -1; -1 1] (PSD), q = (-1, -1): w_1 + w_2 = -2 < 0, infeasible.
//  3. M = [-1 2; 2 -1], q = (-1, -1) has the solution z = (1, 1) (w = 0), but M
//     is not copositive-plus and Lemke stops on a ray at once.
// The ray pivot counts (3, 2, 1) and driving variables (w_2 -> 1, z_1 -> 2,
// z_2 -> 3) agree with benchmarks/lcp/reference_lemke.py. By hand for 3: the
// first ratios q_i/d_i tie at -1, the lexicographic rule picks row 2, so z0
// enters and w_2 leaves; then z_2 must enter, and with B = [e_1, -e] its
// updated column B^{-1} (-2, 1) = (-3, -1) has no positive entry.
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
      const unsigned int         expected_pivots,
      const int                  expected_driving_variable)
  {
    const Result r = solve_lemke(M, q);
    dealii::deallog << name << ": " << to_string(r.status) << " after "
                    << r.pivots << " pivots, driving variable "
                    << r.driving_variable << std::endl;
    impactfe_tests::check(r.status == Status::ray_termination && r.z.empty() &&
                            r.w.empty() && !r.verification.ok &&
                            r.pivots == expected_pivots &&
                            r.driving_variable == expected_driving_variable &&
                            !r.message.empty(),
                          name);
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  run("skew, infeasible", matrix({{0, -1}, {1, 0}}), {-1, -1}, 3, 1);
  run("PSD, infeasible", matrix({{1, -1}, {-1, 1}}), {-1, -1}, 2, 2);
  run("not copositive-plus, solvable",
      matrix({{-1, 2}, {2, -1}}),
      {-1, -1},
      1,
      3);
  impactfe_tests::check(
    lcp_test::enumerate(matrix({{0, -1}, {1, 0}}), {-1, -1}).empty() &&
      lcp_test::enumerate(matrix({{1, -1}, {-1, 1}}), {-1, -1}).empty() &&
      lcp_test::enumerate(matrix({{-1, 2}, {2, -1}}), {-1, -1}).size() == 1,
    "enumeration agrees: none, none, one solution");

  // Invalid input is an exception, not a status.
  bool thrown = false;
  try
    {
      LemkeOptions o;
      o.covering_vector = {1., 0.};
      solve_lemke(matrix({{1, 0}, {0, 1}}), {-1, -1}, o);
    }
  catch (const std::invalid_argument &)
    {
      thrown = true;
    }
  impactfe_tests::check(thrown, "non-positive covering vector rejected");
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
