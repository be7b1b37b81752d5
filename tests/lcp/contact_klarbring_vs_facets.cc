// The 2D Klarbring form (size 3 n_c) and the facet form with k = 2
// (d = +t, -t; size 4 n_c) must give the same (P_N, P_T) (spec, "The LCP in
// 3D"). Random SPD Delassus operators W = B B' + 0.5 I for n_c = 1..8
// contacts, random free velocities, gap terms and friction coefficients
// (fixed seed, portable RNG). Both solutions are also checked directly
// against Signorini and Coulomb by verify_contact_solution().
//
// Then a W with a singular tangential block: two contacts whose tangential
// directions act on the same degree of freedom (W = H'H with H = [e1 e3 e2
// e3], W_TT = [1 1; 1 1]). The automatic form must detect it, use the facet
// form with k = 2 and say so, and the impulses must still satisfy the
// contact laws.
#include <impactfe/lcp/contact_problem.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng rng(314159);

  for (unsigned int nc = 1; nc <= 8; ++nc)
    {
      unsigned int n_same = 0, n_ok = 0, n_problems = 0;
      for (unsigned int instance = 0; instance < 10; ++instance)
        {
          const unsigned int m = 2 * nc;
          ContactProblem     p;
          p.n_directions = 2;
          p.n_contacts   = nc;
          DenseMatrix B(m, m);
          for (unsigned int i = 0; i < m; ++i)
            for (unsigned int j = 0; j < m; ++j)
              B(i, j) = rng.uniform(-1., 1.);
          p.W = lcp_test::gram_plus_shift(B);
          p.free_velocity.resize(m);
          for (auto &v : p.free_velocity)
            v = rng.uniform(-1., 1.);
          p.gap_term.resize(nc);
          p.mu.resize(nc);
          for (unsigned int c = 0; c < nc; ++c)
            {
              p.gap_term[c] = rng.uniform(0., 0.2);
              p.mu[c]       = rng.uniform(0.1, 0.5);
            }
          ++n_problems;

          ContactOptions ok, of;
          ok.form                  = FrictionForm::klarbring;
          of.form                  = FrictionForm::facets;
          const ContactSolution sk = solve_contact_problem(p, ok);
          const ContactSolution sf = solve_contact_problem(p, of);
          if (sk.lcp.status != Status::solved ||
              sf.lcp.status != Status::solved)
            continue;
          if (verify_contact_solution(p, sk.P).ok &&
              verify_contact_solution(p, sf.P).ok)
            ++n_ok;
          if (lcp_test::max_diff(sk.P, sf.P) <
              1e-9 * std::max(1., lcp_test::linfty(sk.P)))
            ++n_same;
        }
      dealii::deallog << "n_c = " << nc << ": " << n_problems
                      << " problems, both forms satisfy the contact laws in "
                      << n_ok << ", same (P_N, P_T) in " << n_same << std::endl;
      impactfe_tests::check(n_ok == n_problems && n_same == n_problems,
                            "Klarbring == facets(k=2), n_c = " +
                              std::to_string(nc));
    }

  // singular W_TT
  {
    DenseMatrix H(3, 4, 0.);
    H(0, 0) = 1.; // contact 0, normal
    H(2, 1) = 1.; // contact 0, tangent: DOF 2
    H(1, 2) = 1.; // contact 1, normal
    H(2, 3) = 1.; // contact 1, tangent: DOF 2 as well
    ContactProblem p;
    p.n_directions = 2;
    p.n_contacts   = 2;
    p.W.reinit(4, 4);
    for (unsigned int i = 0; i < 4; ++i)
      for (unsigned int j = 0; j < 4; ++j)
        for (unsigned int k = 0; k < 3; ++k)
          p.W(i, j) += H(k, i) * H(k, j);
    p.free_velocity          = {-1., 2., -1., 2.};
    p.gap_term               = {0., 0.};
    p.mu                     = {0.3, 0.3};
    const ContactSolution s  = solve_contact_problem(p);
    const auto            cv = verify_contact_solution(p, s.P);
    dealii::deallog << "singular W_TT: form " << to_string(s.form)
                    << ", k = " << s.n_facets << ", status "
                    << to_string(s.lcp.status) << ", P = " << lcp_test::str(s.P)
                    << std::endl;
    dealii::deallog << "message mentions the fallback: "
                    << (s.message.find("W_TT is singular") !=
                            std::string::npos ?
                          "yes" :
                          "no")
                    << std::endl;
    // By hand: each normal row is decoupled (W_NN = I), so P_N = (1, 1);
    // the common tangential velocity is 2 + P_T0 + P_T1 and both contacts
    // slide backwards against it with |P_T| = 0.3: P_T = (-0.3, -0.3),
    // V_T = 1.4 > 0.
    impactfe_tests::check(s.form == FrictionForm::facets && s.n_facets == 2 &&
                            s.lcp.status == Status::solved && cv.ok &&
                            lcp_test::max_diff(s.P, {1., -0.3, 1., -0.3}) <
                              1e-12,
                          "singular W_TT handled by the facet form");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
