// Warm starts give the same answers as cold solves.
//
// A sequence of 2D contact problems (block-tridiagonal SPD W = B B' + 0.5 I,
// 12 contacts, free velocities drifting from step to step) solved in the
// frictionless and in the Klarbring form, cold and warm (guess: z_i > 0 of
// the previous step). Solutions must agree and satisfy the contact laws.
// Deterministic paths: the exact active set as guess needs no pivot
// (guess-solved); a guess with a singular principal block (both lambda1 and
// lambda2 of one contact in the Klarbring form, whose block [A -A; -A A] is
// singular) must fall back to cold Lemke and say so.
#include <impactfe/lcp/contact_problem.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng      rng(4242);
  const unsigned int nc = 12, m = 2 * nc;

  DenseMatrix B(m, m, 0.);
  for (unsigned int c = 0; c < nc; ++c)
    for (unsigned int a = 0; a < 2; ++a)
      for (unsigned int b = 0; b < 2; ++b)
        {
          B(2 * c + a, 2 * c + b) =
            (a == b ? 1. : 0.) + 0.3 * rng.uniform(-0.5, 0.5);
          if (c > 0)
            B(2 * c + a, 2 * (c - 1) + b) = 0.5 * rng.uniform(-0.5, 0.5);
        }
  ContactProblem p;
  p.n_directions = 2;
  p.n_contacts   = nc;
  p.W            = lcp_test::gram_plus_shift(B);
  p.free_velocity.assign(m, 0.);
  p.gap_term.assign(nc, 0.);
  p.mu.assign(nc, 0.3);

  for (const FrictionForm form :
       {FrictionForm::frictionless, FrictionForm::klarbring})
    {
      ContactOptions o;
      o.form = form;
      std::vector<bool> guess;
      unsigned int      n_same = 0, n_steps = 0, n_laws = 0;
      for (unsigned int step = 0; step < 40; ++step)
        {
          for (unsigned int c = 0; c < nc; ++c)
            {
              p.free_velocity[2 * c] = -0.2 + std::sin(0.37 * c + 0.05 * step);
              p.free_velocity[2 * c + 1] =
                0.5 * std::cos(0.23 * c + 0.07 * step);
            }
          const ContactSolution cold = solve_contact_problem(p, o);
          const ContactSolution warm =
            solve_contact_problem(p, o, guess.empty() ? nullptr : &guess);
          ++n_steps;
          if (cold.lcp.status == Status::solved &&
              warm.lcp.status == Status::solved &&
              lcp_test::max_diff(cold.P, warm.P) <
                1e-10 * std::max(1., lcp_test::linfty(cold.P)))
            ++n_same;
          if (warm.lcp.status == Status::solved &&
              (form == FrictionForm::frictionless ||
               verify_contact_solution(p, warm.P).ok))
            ++n_laws;
          guess.assign(warm.lcp.z.size(), false);
          for (std::size_t i = 0; i < warm.lcp.z.size(); ++i)
            guess[i] = warm.lcp.z[i] > 0.;
        }
      dealii::deallog << to_string(form) << ": " << n_steps
                      << " steps, warm == cold in " << n_same
                      << ", contact laws hold in " << n_laws << std::endl;
      impactfe_tests::check(n_same == n_steps && n_laws == n_steps,
                            to_string(form) + " warm == cold");
    }

  // exact guess: no pivot
  {
    ContactOptions o;
    o.form                  = FrictionForm::klarbring;
    const ContactSolution c = solve_contact_problem(p, o);
    std::vector<bool>     g(c.lcp.z.size());
    for (std::size_t i = 0; i < g.size(); ++i)
      g[i] = c.lcp.z[i] > 0.;
    const ContactSolution w = solve_contact_problem(p, o, &g);
    dealii::deallog << "exact guess: path " << to_string(w.lcp.start_path)
                    << ", " << w.lcp.pivots << " pivots" << std::endl;
    impactfe_tests::check(w.lcp.start_path == StartPath::guess_solved &&
                            w.lcp.pivots == 0 &&
                            lcp_test::max_diff(w.P, c.P) < 1e-10,
                          "exact guess accepted without pivoting");
    // singular guess: lambda1 and lambda2 of contact 0 both guessed positive
    std::vector<bool> bad(3 * nc, false);
    bad[nc] = bad[2 * nc]   = true;
    const ContactSolution f = solve_contact_problem(p, o, &bad);
    dealii::deallog << "singular guess: path " << to_string(f.lcp.start_path)
                    << std::endl;
    impactfe_tests::check(f.lcp.start_path == StartPath::guess_fallback_cold &&
                            f.lcp.status == Status::solved &&
                            lcp_test::max_diff(f.P, c.P) < 1e-10 &&
                            f.message.find("singular") != std::string::npos,
                          "singular guess falls back to cold Lemke");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
