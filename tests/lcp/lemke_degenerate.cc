// Degenerate LCPs: ties in the minimum-ratio test, zeros in q. Integer data,
// so ties are exact and the lexicographic rule (Cottle-Pang-Stone 1992,
// Section 4.9) decides every step.
//
// The cases, their exact solutions and the pivot counts come from
// benchmarks/lcp/degenerate_cases.py, which runs the independent exact
// rational tableau implementation benchmarks/lcp/reference_lemke.py (same
// rules: lexicographic minimum ratio, z0 preferred on ties) and complete
// enumeration. The matrices are L L' + K - K' + I (positive definite, hence
// P: one solution each).
#include <impactfe/lcp/lemke.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using lcp_test::matrix;

namespace
{
  struct Case
  {
    std::vector<std::vector<double>> M;
    std::vector<double>              q;
    std::vector<double>              z;
    unsigned int                     pivots;
  };
} // namespace

int
main()
{
  impactfe_tests::initlog();
  const std::vector<Case> cases = {
    {{{2, 1, 2}, {1, 4, 1}, {0, 3, 3}},
     {-1, -2, 0},
     {2. / 7, 3. / 7, 0. / 1},
     3}, // solved, 1 solution(s) by enumeration
    {{{3, 4, -3}, {0, 4, -3}, {-1, -3, 4}},
     {0, -1, 0},
     {0. / 1, 4. / 7, 3. / 7},
     3}, // solved, 1 solution(s) by enumeration
    {{{4, -2, 1, 0}, {0, 5, 2, -4}, {-1, 0, 4, 0}, {2, -4, -2, 5}},
     {1, -1, -2, 0},
     {0. / 1, 4. / 9, 1. / 2, 5. / 9},
     4}, // solved, 1 solution(s) by enumeration
    {{{2, -2, -1, -2}, {2, 3, -1, -1}, {-1, -1, 4, 1}, {2, -1, -1, 3}},
     {-1, 0, 1, 1},
     {1. / 2, 0. / 1, 0. / 1, 0. / 1},
     2}, // solved, 1 solution(s) by enumeration
    {{{5, -1, 0, -1, 1},
      {-1, 4, 3, -1, 0},
      {0, 1, 4, 1, 1},
      {1, -1, -1, 4, 3},
      {-1, -4, -1, 1, 4}},
     {-1, 1, -1, -2, 0},
     {26. / 89, 0. / 1, 12. / 89, 41. / 89, 0. / 1},
     4}, // solved, 1 solution(s) by enumeration
    {{{4, -2, -1, 2, -1},
      {-2, 4, -1, -1, 1},
      {1, -1, 5, 1, 0},
      {0, -1, -1, 6, 0},
      {-1, 1, -2, 4, 3}},
     {-2, -1, 0, 0, -1},
     {151. / 183, 38. / 61, 0. / 1, 19. / 183, 16. / 61},
     5}, // solved, 1 solution(s) by enumeration
    {{{3, 0, 1, 3, -1, 0},
      {-2, 3, 1, 1, 3, 0},
      {-3, 1, 5, -4, -1, 2},
      {1, -3, 0, 5, 1, 0},
      {-1, 1, -1, 1, 6, -3},
      {2, 0, 0, -2, 1, 6}},
     {-1, -2, -1, -2, -1, 0},
     {0. / 1,
      437. / 3277,
      1710. / 3277,
      1433. / 3277,
      700. / 3277,
      361. / 3277},
     6}, // solved, 1 solution(s) by enumeration
    {{{5, 0, -2, 0, 1, 2},
      {0, 5, -2, 2, 0, -3},
      {-2, -2, 5, 1, 1, 0},
      {0, -2, -1, 5, 0, 1},
      {-1, -4, 3, 4, 4, 3},
      {2, -1, 0, 3, -1, 7}},
     {1, -1, 0, 1, 0, 0},
     {0. / 1, 134. / 503, 37. / 503, 0. / 1, 83. / 503, 31. / 503},
     5}, // solved, 1 solution(s) by enumeration
    {{{8, -3, 4, -3, 2, -4, 0, -2},
      {-5, 7, -2, 0, -2, 0, 1, 5},
      {4, -4, 8, -2, -1, -1, 1, -2},
      {-1, 2, -2, 8, -2, -2, -2, 5},
      {2, 0, -1, 0, 7, 0, 0, -3},
      {0, -2, -1, 0, 2, 7, 5, -1},
      {-2, -1, -1, -2, 2, 5, 6, -2},
      {-2, 1, -2, 3, -1, -3, -2, 6}},
     {-1, -1, 0, 1, -1, 0, -1, 0},
     {8085. / 46009,
      8207. / 46009,
      1238. / 46009,
      0. / 1,
      7395. / 46009,
      0. / 1,
      11771. / 46009,
      6896. / 46009},
     7}, // solved, 1 solution(s) by enumeration
    {{{6, 0, -2, 1, 4, 1, 5, 1},
      {2, 7, 1, -1, 3, -2, 2, 1},
      {-2, 1, 6, 4, -1, 0, -2, -1},
      {-3, -3, 0, 6, 1, 2, -2, -1},
      {0, -1, 3, -1, 8, -2, 4, -4},
      {-1, 2, 0, 0, -4, 5, -3, 5},
      {3, 2, -2, -2, 4, 1, 6, -3},
      {-1, 1, -1, 1, -8, 3, -1, 8}},
     {-2, 0, -1, 0, 1, -1, -1, 0},
     {690. / 2383,
      0. / 1,
      1155. / 4766,
      164. / 2383,
      0. / 1,
      722. / 2383,
      179. / 2383,
      0. / 1},
     6}, // solved, 1 solution(s) by enumeration
    // all ratios tie at every step; the solution set is {z >= 0: sum z = 1}
    {{{1, 1, 1}, {1, 1, 1}, {1, 1, 1}}, {-1, -1, -1}, {0, 0, 1}, 2},
    {{{1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}, {1, 1, 1, 1}},
     {-1, -1, -1, -1},
     {0, 0, 0, 1},
     2},
    // q with a zero: a degenerate basis on the path
    {{{2, 1, 0}, {1, 2, 1}, {0, 1, 2}}, {-1, 0, -1}, {0.5, 0, 0.5}, 3},
  };

  unsigned int index = 0;
  for (const Case &c : cases)
    {
      const DenseMatrix M    = matrix(c.M);
      const Result      r    = solve_lemke(M, c.q);
      const std::string name = "case " + std::to_string(index++) +
                               " (n=" + std::to_string(c.q.size()) + ")";
      dealii::deallog << name << ": " << to_string(r.status) << " in "
                      << r.pivots << " pivots, z = " << lcp_test::str(r.z)
                      << std::endl;
      impactfe_tests::check(r.status == Status::solved && r.verification.ok &&
                              r.pivots == c.pivots &&
                              lcp_test::max_diff(r.z, c.z) < 1e-12,
                            name + " matches the exact reference");
      // warm start from the empty guess and from the full guess: same z
      const Result w0 =
        solve_lemke_warm(M, c.q, std::vector<bool>(c.q.size(), false));
      const Result w1 =
        solve_lemke_warm(M, c.q, std::vector<bool>(c.q.size(), true));
      impactfe_tests::check(w0.status == Status::solved &&
                              w1.status == Status::solved &&
                              lcp_test::max_diff(w0.z, c.z) < 1e-12 &&
                              (lcp_test::max_diff(w1.z, c.z) < 1e-12 ||
                               w1.verification.ok),
                            name + " warm starts");
    }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
