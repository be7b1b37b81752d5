// solve_contact_problem() with a guess of the contact states: block
// principal pivoting on W in 2D with friction, Lemke's method (warm) when it
// gives up, and the helpers contact_states(), guess_from_states() and
// verify_with_residual().
//
// 1. Three decoupled contacts (W = I, mu = 0.5) with one answer each of
//    open, stick, slip+, slip-: closed form P, and the states found from
//    every one of the 4^4 = 256 guesses of the four states (block pivoting
//    or its fallback), always the same P as cold Lemke.
// 2. 300 random 2D problems (W = B B^T + I/2, random V_free, b_N, mu in
//    [0, 1]): guesses = the states of the cold answer (must be solved by
//    block pivoting in one solve), all open, all stick, random. Every answer
//    must pass verify() and verify_contact_solution(). With such mu and
//    coupling the frictional problem can have several solutions, so P is
//    compared with cold Lemke's only in a second set where it is unique
//    enough in practice: mu in [0, 0.2], W = B B^T / (2 n_c) + I.
//    Then W made non-symmetric (the LU path instead of Cholesky): verified;
//    and CholeskyFactorization against LUFactorization.
// 3. The fallback: max_block_pivoting_iterations = 1 with a wrong guess.
// 4. Frictionless problems: Lemke from the guessed basis, same P as cold.
// 5. guess_from_states() for the three forms; verify_with_residual() equals
//    verify() when given the residual of M.
// No pivot counts or timings are printed.
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/lu.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using impactfe::ContactState;

namespace
{
  std::string
  states_string(const std::vector<ContactState> &states)
  {
    std::string s;
    for (const ContactState c : states)
      s += (s.empty() ? "" : " ") + to_string(c);
    return s;
  }

  std::string
  bools(const std::vector<bool> &v)
  {
    std::string s;
    for (const bool b : v)
      s += b ? '1' : '0';
    return s;
  }

  ContactProblem
  random_problem(lcp_test::Rng     &rng,
                 const unsigned int nc,
                 const double       mu_max              = 1.,
                 const bool         diagonally_dominant = false)
  {
    DenseMatrix  B(2 * nc, 2 * nc);
    const double b = diagonally_dominant ? 1. / std::sqrt(2. * nc) : 1.;
    for (unsigned int i = 0; i < 2 * nc; ++i)
      for (unsigned int j = 0; j < 2 * nc; ++j)
        B(i, j) = b * rng.uniform(-1., 1.);
    ContactProblem p;
    p.n_directions = 2;
    p.n_contacts   = nc;
    p.W = lcp_test::gram_plus_shift(B, diagonally_dominant ? 1. : 0.5);
    p.free_velocity.resize(2 * nc);
    p.gap_term.resize(nc);
    p.mu.resize(nc);
    for (unsigned int i = 0; i < 2 * nc; ++i)
      p.free_velocity[i] = rng.uniform(-1., 1.);
    for (unsigned int c = 0; c < nc; ++c)
      {
        p.gap_term[c] = rng.uniform(-0.5, 0.5);
        p.mu[c]       = rng.uniform(0., mu_max);
      }
    return p;
  }

  const std::vector<ContactState> all_states = {ContactState::open,
                                                ContactState::stick,
                                                ContactState::slip_positive,
                                                ContactState::slip_negative};
} // namespace



int
main()
{
  impactfe_tests::initlog();
  using impactfe_tests::check;

  // 1. Decoupled contacts, W = I, mu = 0.5, V_free,N = -1 except the open one:
  //    contact 0: V_free = (+1, 2): open, P = 0;
  //    contact 1: V_free = (-1, 0.2): stick, P = (1, -0.2);
  //    contact 2: V_free = (-1, 2): slip+, P = (1, -0.5), V_T = 1.5;
  //    contact 3: V_free = (-1, -2): slip-, P = (1, 0.5), V_T = -1.5.
  {
    ContactProblem p;
    p.n_directions = 2;
    p.n_contacts   = 4;
    p.W            = DenseMatrix(8, 8, 0.);
    for (unsigned int i = 0; i < 8; ++i)
      p.W(i, i) = 1.;
    p.free_velocity                    = {1., 2., -1., 0.2, -1., 2., -1., -2.};
    p.gap_term                         = {0., 0., 0., 0.};
    p.mu                               = {0.5, 0.5, 0.5, 0.5};
    const std::vector<double> expected = {0., 0., 1., -0.2, 1., -0.5, 1., 0.5};

    const ContactSolution cold = solve_contact_problem(p);
    dealii::deallog << "decoupled, cold: P = " << lcp_test::str(cold.P)
                    << ", states = " << states_string(cold.states) << std::endl;
    check(cold.lcp.status == Status::solved &&
            lcp_test::max_diff(cold.P, expected) < 1e-14,
          "decoupled, cold Lemke");
    dealii::deallog << "contact_states(P) = "
                    << states_string(contact_states(p, cold.P)) << std::endl;

    unsigned int n_ok = 0, n_block = 0, n_exact_states = 0;
    for (unsigned int code = 0; code < 256; ++code)
      {
        std::vector<ContactState> guess(4);
        for (unsigned int c = 0; c < 4; ++c)
          guess[c] = all_states[(code >> (2 * c)) & 3];
        const ContactSolution s = solve_contact_problem(p, {}, guess);
        n_ok += (s.lcp.status == Status::solved && s.lcp.verification.ok &&
                 lcp_test::max_diff(s.P, expected) < 1e-14);
        n_block += (s.lcp.start_path == StartPath::block_pivoting);
        n_exact_states += (s.states == cold.states);
      }
    dealii::deallog << "decoupled, 256 guesses: " << n_ok
                    << " solved with the expected P, " << n_block
                    << " by block pivoting, " << n_exact_states
                    << " with the states of the answer" << std::endl;
    check(n_ok == 256 && n_block == 256 && n_exact_states == 256,
          "decoupled, every guess");

    const ContactSolution exact = solve_contact_problem(p, {}, cold.states);
    dealii::deallog << "decoupled, exact guess: "
                    << to_string(exact.lcp.start_path) << ", "
                    << exact.block_pivoting_iterations << " solve, form "
                    << to_string(exact.form) << " (k = " << exact.n_facets
                    << "), z = " << lcp_test::str(exact.lcp.z) << std::endl;
    dealii::deallog << "  w = " << lcp_test::str(exact.lcp.w) << std::endl;
  }

  // 2. Random problems: every answer verified; P == cold P where unique.
  for (const bool compare : {false, true})
    {
      lcp_test::Rng rng(compare ? 777 : 20261121);
      unsigned int  n_problems = 0, n_ok = 0, n_exact_one_solve = 0;
      for (unsigned int trial = 0; trial < 300; ++trial)
        {
          const ContactProblem p =
            compare ? random_problem(rng, 1 + rng.integer(25), 0.2, true) :
                      random_problem(rng, 1 + rng.integer(25));
          const ContactSolution cold = solve_contact_problem(p);
          if (cold.lcp.status != Status::solved)
            {
              dealii::deallog << "trial " << trial
                              << ": cold Lemke failed: " << cold.message
                              << std::endl;
              continue;
            }
          ++n_problems;
          std::vector<ContactState> random_guess(p.n_contacts);
          for (ContactState &s : random_guess)
            s = all_states[rng.integer(4)];
          const std::vector<std::vector<ContactState>> guesses = {
            cold.states,
            std::vector<ContactState>(p.n_contacts, ContactState::open),
            std::vector<ContactState>(p.n_contacts, ContactState::stick),
            random_guess};
          bool all = true;
          for (unsigned int g = 0; g < guesses.size(); ++g)
            {
              const ContactSolution s =
                solve_contact_problem(p, {}, guesses[g]);
              if (g == 0)
                n_exact_one_solve +=
                  (s.lcp.start_path == StartPath::block_pivoting &&
                   s.block_pivoting_iterations == 1);
              const bool ok =
                s.lcp.status == Status::solved && s.lcp.verification.ok &&
                verify_contact_solution(p, s.P).ok &&
                (!compare ||
                 lcp_test::relative_difference(p, s.P, cold.P) <= 1e-9);
              if (!ok)
                dealii::deallog << "trial " << trial << ", guess " << g << ": "
                                << s.message << std::endl;
              all = all && ok;
            }
          n_ok += all;
        }
      const std::string name =
        compare ? "random, mu <= 0.2, W diagonally dominant: P == cold P" :
                  "random, mu <= 1: verified";
      dealii::deallog
        << name << ": " << n_ok << " of " << n_problems
        << " problems from all 4 guesses; the answer's states in one block pivoting solve: "
        << n_exact_one_solve << std::endl;
      check(n_problems == 300 && n_ok == n_problems &&
              n_exact_one_solve == n_problems,
            name);
    }

  // 2b. W not symmetric (W + 0.01 K, K skew): one LU per block pivoting
  //     solve instead of Cholesky; every answer verified.
  {
    lcp_test::Rng rng(99);
    unsigned int  n_ok = 0;
    for (unsigned int trial = 0; trial < 100; ++trial)
      {
        ContactProblem    p = random_problem(rng, 1 + rng.integer(20), 0.5);
        const std::size_t m = p.W.n_rows();
        for (std::size_t i = 0; i < m; ++i)
          for (std::size_t j = 0; j < i; ++j)
            {
              const double k = 0.01 * rng.uniform(-1., 1.);
              p.W(i, j) += k;
              p.W(j, i) -= k;
            }
        std::vector<ContactState> guess(p.n_contacts);
        for (ContactState &s : guess)
          s = all_states[rng.integer(4)];
        const ContactSolution s = solve_contact_problem(p, {}, guess);
        n_ok += (s.lcp.status == Status::solved && s.lcp.verification.ok &&
                 verify_contact_solution(p, s.P).ok);
      }
    check(n_ok == 100, "non-symmetric W: 100 problems verified");
  }

  // 2c. CholeskyFactorization::solve against LUFactorization::solve.
  {
    lcp_test::Rng rng(4);
    DenseMatrix   B(60, 60);
    for (unsigned int i = 0; i < 60; ++i)
      for (unsigned int j = 0; j < 60; ++j)
        B(i, j) = rng.uniform(-1., 1.);
    const DenseMatrix A = lcp_test::gram_plus_shift(B, 0.1);
    DenseMatrix       X(60, 3);
    for (unsigned int i = 0; i < 60; ++i)
      for (unsigned int c = 0; c < 3; ++c)
        X(i, c) = rng.uniform(-1., 1.);
    const DenseMatrix     R = X;
    CholeskyFactorization cholesky;
    LUFactorization       lu;
    const bool            factorised = cholesky.factorize(A) && lu.factorize(A);
    cholesky.solve(X);
    double difference = 0., size = 0.;
    for (unsigned int c = 0; c < 3; ++c)
      {
        std::vector<double> x(60);
        for (unsigned int i = 0; i < 60; ++i)
          x[i] = R(i, c);
        lu.solve(x);
        for (unsigned int i = 0; i < 60; ++i)
          {
            difference = std::max(difference, std::abs(x[i] - X(i, c)));
            size       = std::max(size, std::abs(x[i]));
          }
      }
    DenseMatrix not_definite = A;
    not_definite(7, 7)       = -1.;
    check(factorised && difference <= 1e-10 * size &&
            !CholeskyFactorization().factorize(not_definite),
          "Cholesky == LU on an SPD matrix; indefinite matrix refused");
  }

  // 3. The fallback: one solve allowed, the guess "all open" is wrong.
  {
    lcp_test::Rng         rng(5);
    const ContactProblem  p    = random_problem(rng, 8);
    const ContactSolution cold = solve_contact_problem(p);
    ContactOptions        o;
    o.max_block_pivoting_iterations = 1;
    const ContactSolution s =
      solve_contact_problem(p,
                            o,
                            std::vector<ContactState>(8, ContactState::open));
    dealii::deallog << "fallback: path " << to_string(s.lcp.start_path)
                    << ", form " << to_string(s.form)
                    << ", block pivoting solves " << s.block_pivoting_iterations
                    << std::endl;
    check(s.lcp.status == Status::solved &&
            s.lcp.start_path != StartPath::block_pivoting &&
            s.form == FrictionForm::klarbring &&
            lcp_test::relative_difference(p, s.P, cold.P) <= 1e-9 &&
            s.message.find("block pivoting gave up") != std::string::npos,
          "fallback to Lemke");
  }

  // 4. Frictionless: states map to the normal impulses.
  {
    lcp_test::Rng rng(11);
    unsigned int  n_ok = 0;
    for (unsigned int trial = 0; trial < 50; ++trial)
      {
        ContactProblem p = random_problem(rng, 1 + rng.integer(20));
        for (double &m : p.mu)
          m = 0.;
        const ContactSolution     cold = solve_contact_problem(p);
        std::vector<ContactState> guess(p.n_contacts);
        for (ContactState &s : guess)
          s = all_states[rng.integer(2)];
        const ContactSolution s = solve_contact_problem(p, {}, guess);
        const ContactSolution e = solve_contact_problem(p, {}, cold.states);
        n_ok += (s.lcp.status == Status::solved &&
                 s.form == FrictionForm::frictionless &&
                 lcp_test::relative_difference(p, s.P, cold.P) <= 1e-9 &&
                 e.lcp.pivots == 0 &&
                 lcp_test::relative_difference(p, e.P, cold.P) <= 1e-9);
      }
    check(n_ok == 50, "frictionless, warm from states == cold");
  }

  // 5. guess_from_states() and verify_with_residual().
  {
    ContactProblem p;
    p.n_directions = 2;
    p.n_contacts   = 4;
    p.W            = DenseMatrix(8, 8, 0.);
    for (unsigned int i = 0; i < 8; ++i)
      p.W(i, i) = 2.;
    p.free_velocity                        = {0., 0., 0., 0., 0., 0., 0., 0.};
    p.gap_term                             = {0., 0., 0., 0.};
    p.mu                                   = {0.5, 0.5, 0.5, 0.5};
    const std::vector<ContactState> states = all_states;
    for (const FrictionForm form : {FrictionForm::frictionless,
                                    FrictionForm::klarbring,
                                    FrictionForm::facets})
      {
        ContactOptions o;
        o.form               = form;
        const ContactLCP lcp = assemble_contact_lcp(p, o);
        dealii::deallog << "guess_from_states(" << states_string(states)
                        << ") [" << to_string(form)
                        << "] = " << bools(guess_from_states(lcp, states))
                        << std::endl;
      }

    lcp_test::Rng       rng(3);
    DenseMatrix         M(6, 6);
    std::vector<double> q(6), z(6), w(6), residual(6);
    for (unsigned int i = 0; i < 6; ++i)
      {
        q[i] = rng.uniform(-1., 1.);
        z[i] = rng.uniform(0., 1.);
        w[i] = rng.uniform(0., 1.);
        for (unsigned int j = 0; j < 6; ++j)
          M(i, j) = rng.uniform(-1., 1.);
      }
    for (unsigned int i = 0; i < 6; ++i)
      {
        residual[i] = w[i] - q[i];
        for (unsigned int j = 0; j < 6; ++j)
          residual[i] -= M(i, j) * z[j];
      }
    const Verification a = verify(M, q, z, w);
    const Verification b =
      verify_with_residual(M.linfty_norm(), q, z, w, residual);
    check(a.ok == b.ok && a.residual == b.residual &&
            a.relative_error == b.relative_error &&
            a.max_complementarity == b.max_complementarity &&
            a.min_z == b.min_z && a.min_w == b.min_w,
          "verify_with_residual == verify");
  }

  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
