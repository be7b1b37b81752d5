// A step of the oblique plate (60 x 48 cells, theta-method theta = 0.55
// with mass redistribution, h = 1.67e-6 s; 32 contacts, mu = 0.1) whose W
// spans 23 orders of magnitude (the massless contact nodes' rows grow like
// 1/h^2). Lemke's method in Klarbring's form stops within rounding of a
// secondary ray and its LCP point passes the LCP's verification, but the
// impulses recovered through W_TT^{-1} leave the Coulomb cone by 1.2 % of
// the largest normal impulse, and the re-solve at their contact states
// fails. Until 2026-12-07 ContactSolver returned that point as solved, and
// the plate's run failed its Coulomb check at the end.
//
// Checked here, with the problem file written by 'Dump LCP of step':
// - automatic form: the Klarbring point is rejected and the next route
//   solves; its impulses pass verify_contact_solution() (Signorini,
//   cone, sliding law on P itself) and lie on the cone to round-off;
// - Klarbring's form requested: the step is not solved (no impulses), not
//   answered wrongly.
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/problem_io.h>

#include <algorithm>
#include <cmath>

#include "../tests.h"

using namespace impactfe::lcp;
using dealii::deallog;

namespace
{
  // max over contacts of (|P_T| - mu P_N) / max P_N
  double
  cone_excess(const ContactProblem &p, const std::vector<double> &P)
  {
    double p_max = 0., excess = -1e300;
    for (unsigned int c = 0; c < p.n_contacts; ++c)
      p_max = std::max(p_max, P[2 * c]);
    for (unsigned int c = 0; c < p.n_contacts; ++c)
      excess =
        std::max(excess, (std::abs(P[2 * c + 1]) - p.mu[c] * P[2 * c]) / p_max);
    return excess;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  const ProblemFile file =
    read_problem_file(std::string(IMPACTFE_SOURCE_DIR) +
                      "/tests/lcp/data/klarbring_cone_miss.dat");
  const ContactProblem &p = file.contact;
  deallog << "contacts " << p.n_contacts << ", directions " << p.n_directions
          << ", largest / smallest non-zero |W_ij| > 1e20: " << std::boolalpha
          << ([&] {
               double wmin = 1e300;
               for (std::size_t i = 0; i < p.W.n_rows(); ++i)
                 for (std::size_t j = 0; j < p.W.n_cols(); ++j)
                   if (p.W(i, j) != 0.)
                     wmin = std::min(wmin, std::abs(p.W(i, j)));
               return p.W.max_abs() / wmin > 1e20;
             }())
          << std::endl;

  {
    ContactSolver          solver;
    const ContactSolution &s = solver.solve(p);
    deallog << "automatic: " << to_string(s.lcp.status) << std::endl;
    deallog << "Klarbring point rejected: "
            << (s.message.find("rejected: the Klarbring impulses fail") !=
                std::string::npos)
            << std::endl;
    const ContactVerification v = verify_contact_solution(p, s.P, 1e-10);
    deallog << "verified (Signorini, cone, sliding law to 1e-10): " << v.ok
            << std::endl;
    deallog << "cone excess below 1e-12 of max P_N: "
            << (cone_excess(p, s.P) < 1e-12) << std::endl;
    deallog << "contacts separated / sticking / sliding: " << v.n_separated
            << " / " << v.n_sticking << " / " << v.n_sliding << std::endl;
  }

  {
    ContactOptions options;
    options.form = FrictionForm::klarbring;
    ContactSolver          solver;
    const ContactSolution &s = solver.solve(p, options);
    deallog << "Klarbring form requested: " << to_string(s.lcp.status)
            << ", impulses returned: " << !s.P.empty() << std::endl;
  }
}
