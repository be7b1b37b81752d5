// Block pivoting must not accept a point outside the Coulomb cone because
// impulses and velocities are measured on one scale.
//
// Two decoupled contacts, W = 1e6 I (impulses of 1e-7 N s against
// velocities of 0.1 m/s, the proportions of a fine FE mesh), mu = 0.5:
//  - contact 0 is pressed (V_free,N = -0.1) and pushed sideways with
//    V_free,T = -0.051: sticking would need |P_T| = 0.51 P_N, so it slides
//    (V_T < 0, P_T = +mu P_N);
//  - contact 1 is open and moves sideways at 1 m/s.
// From the guess (stick, open), the first block pivoting point sticks with
// |P_T| = 0.51 P_N. In the facet form its cone row is violated by 1e-9 N s,
// below the facet form's tolerance 1e3 eps n (||q|| + ||M|| ||z||), which
// the open contact's sigma = |V_T| = 1 m/s inflates to 4e-6. The point
// must be rejected (verify_contact_solution() measures impulses on their
// own scale) and the answer be the sliding one, as cold Lemke's.
#include <impactfe/lcp/contact_problem.h>

#include "../tests.h"

using namespace impactfe::lcp;
using impactfe::ContactState;

int
main()
{
  impactfe_tests::initlog();

  ContactProblem p;
  p.n_directions = 2;
  p.n_contacts   = 2;
  p.W.reinit(4, 4);
  for (unsigned int i = 0; i < 4; ++i)
    p.W(i, i) = 1e6;
  p.free_velocity = {-0.1, -0.051, 1., 1.};
  p.gap_term      = {0., 0.};
  p.mu            = {0.5, 0.5};

  const ContactSolution cold = solve_contact_problem(p);
  const ContactSolution warm =
    solve_contact_problem(p, {}, {ContactState::stick, ContactState::open});

  for (const auto &[name, s] : {std::make_pair("cold Lemke", &cold),
                                std::make_pair("guess (stick, open)", &warm)})
    {
      const ContactVerification v = verify_contact_solution(p, s->P, 1e-10);
      dealii::deallog << name << ": " << to_string(s->lcp.status) << ", states "
                      << to_string(s->states[0]) << " "
                      << to_string(s->states[1]) << ", P_0 = ("
                      << impactfe_tests::rounded(s->P[0]) << ", "
                      << impactfe_tests::rounded(s->P[1]) << "), P_1 = ("
                      << impactfe_tests::rounded(s->P[2]) << ", "
                      << impactfe_tests::rounded(s->P[3]) << "), |P_T| / P_N = "
                      << impactfe_tests::rounded(std::abs(s->P[1]) / s->P[0])
                      << std::endl;
      impactfe_tests::check(v.ok && v.max_cone_violation <= 1e-10,
                            std::string(name) +
                              ": Coulomb cone and sliding law hold");
    }
  dealii::deallog << "guess (stick, open) solved by: "
                  << to_string(warm.lcp.start_path) << std::endl;
  double difference = 0.;
  for (unsigned int i = 0; i < 4; ++i)
    difference = std::max(difference, std::abs(warm.P[i] - cold.P[i]));
  impactfe_tests::check(difference <= 1e-10 * cold.P[0],
                        "same impulses as cold Lemke");
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
