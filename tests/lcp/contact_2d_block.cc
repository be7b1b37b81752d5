// One block on a plane in 2D (one contact, local directions [N, T]), solved
// in the Klarbring form and in the facet form (k = 2); all expected values
// are closed-form and computed below from the formulas, not pasted.
//
// Decoupled W = I (a unit point mass), V_free = (-1, v_T), mu = 0.5:
//   P_N = 1; stick (P_T = -v_T, V_T = 0) iff |v_T| <= mu P_N = 0.5, else slide
//   with P_T = -mu P_N sign(v_T) and V_T = v_T + P_T.
// Gap term b_N = 0.3: w_N = V_N + 0.3, so P_N = 0.7 and V_N = -0.3.
// Coupled W = [2 0.5; 0.5 1], V_free,N = -1: stick needs W P = -V_free with
//   |P_T| <= mu P_N; sliding with V_T > 0 gives P_T = -mu P_N and
//   V_N = 0 => P_N = 1 / (2 - 0.5 mu); with V_T < 0, P_N = 1 / (2 + 0.5 mu).
#include <impactfe/lcp/contact_problem.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

namespace
{
  ContactProblem
  block(const double w_nn,
        const double w_nt,
        const double w_tt,
        const double vn,
        const double vt,
        const double bn,
        const double mu)
  {
    ContactProblem p;
    p.n_directions  = 2;
    p.n_contacts    = 1;
    p.W             = lcp_test::matrix({{w_nn, w_nt}, {w_nt, w_tt}});
    p.free_velocity = {vn, vt};
    p.gap_term      = {bn};
    p.mu            = {mu};
    return p;
  }

  void
  run(const std::string         &name,
      const ContactProblem      &p,
      const std::vector<double> &expected_P,
      const std::string         &expected_state)
  {
    for (const FrictionForm form :
         {FrictionForm::klarbring, FrictionForm::facets})
      {
        ContactOptions o;
        o.form                   = form;
        const ContactSolution s  = solve_contact_problem(p, o);
        const auto            cv = verify_contact_solution(p, s.P);
        std::vector<double>   V;
        p.W.vmult(V, s.P);
        for (unsigned int i = 0; i < 2; ++i)
          V[i] += p.free_velocity[i];
        const std::string state = cv.n_sliding  ? "slide" :
                                  cv.n_sticking ? "stick" :
                                                  "separated";
        dealii::deallog << name << " [" << to_string(s.form)
                        << "]: P = " << lcp_test::str(s.P)
                        << ", V = " << lcp_test::str(V) << ", " << state
                        << std::endl;
        impactfe_tests::check(s.lcp.status == Status::solved && cv.ok &&
                                lcp_test::max_diff(s.P, expected_P) < 1e-12 &&
                                state == expected_state,
                              name + " " + to_string(form));
      }
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  const double mu = 0.5;
  run("W=I, v_T=0.2 (below mu)",
      block(1, 0, 1, -1, 0.2, 0, mu),
      {1, -0.2},
      "stick");
  run("W=I, v_T=2 (above mu)", block(1, 0, 1, -1, 2, 0, mu), {1, -mu}, "slide");
  run("W=I, v_T=-2", block(1, 0, 1, -1, -2, 0, mu), {1, mu}, "slide");
  run("W=I, v_T=0.5 (= mu P_N)",
      block(1, 0, 1, -1, 0.5, 0, mu),
      {1, -0.5},
      "stick");
  run("W=I, separating", block(1, 0, 1, 1, 2, 0, mu), {0, 0}, "separated");
  run("W=I, gap term 0.3",
      block(1, 0, 1, -1, 0.2, 0.3, mu),
      {0.7, -0.2},
      "stick");

  // coupled, mu = 1, v_T = 0.1: the stick solution W^{-1}(1, -0.1) = (0.6,
  // -0.4)
  run("coupled, mu=1, stick",
      block(2, 0.5, 1, -1, 0.1, 0, 1.),
      {0.6, -0.4},
      "stick");
  // coupled, mu = 0.3: sliding forward and backward
  {
    const double m  = 0.3;
    const double pf = 1. / (2. - 0.5 * m);
    run("coupled, mu=0.3, v_T=0.1",
        block(2, 0.5, 1, -1, 0.1, 0, m),
        {pf, -m * pf},
        "slide");
    const double pb = 1. / (2. + 0.5 * m);
    run("coupled, mu=0.3, v_T=-0.5",
        block(2, 0.5, 1, -1, -0.5, 0, m),
        {pb, m * pb},
        "slide");
  }

  // automatic: mu = 0 gives the frictionless form (normal block only)
  {
    const ContactSolution s =
      solve_contact_problem(block(2, 0.5, 1, -1, 0.1, 0, 0.));
    dealii::deallog << "mu = 0, automatic: " << to_string(s.form)
                    << ", n = " << s.lcp.z.size()
                    << ", P = " << lcp_test::str(s.P) << std::endl;
    impactfe_tests::check(s.form == FrictionForm::frictionless &&
                            s.lcp.z.size() == 1 &&
                            lcp_test::max_diff(s.P, {0.5, 0.}) < 1e-14,
                          "frictionless when mu == 0");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
