// The active set (semismooth Newton) solver of lcp/active_set.h against
// Lemke's method, on problems whose W is only used through products:
//
// 1. 50 random 2D frictional problems, 20 to 200 contacts (W = B B^T /
//    (2 n_c) + I, mu in [0, 0.2], where the answer is unique in practice),
//    cold start, Jacobi preconditioner: every answer converged, passes the
//    dense verify_contact_solution(), and equals cold Lemke's (solve_contact_
//    problem) to 1e-8 relative.
// 2. The same with warm starts (the states and impulses of Lemke's answer
//    perturbed): the same answers.
// 3. 50 random frictionless problems (n_directions = 1, W = B B^T + I/2,
//    strongly coupled), 20 to 200 contacts: the same checks.
// 3b, 3c. 50 random 3D problems (20 to 60 contacts, the circular cone),
//    cold and warm, against ExactConeSolver (facet LCPs re-aligned until
//    the circular cone holds to 1e-12): the same checks.
// 3d, 3e. 50 random 3D problems with the polygonal cone of 8 facets, cold
//    and warm, against Lemke's method on the facet LCP (FrictionForm::
//    facets): every answer converged, passes the polygonal cone's
//    verification (verify_contact_velocities() with n_facets = 8) and equals
//    Lemke's P to 1e-8 relative.
//    In 1 to 3e also: the solver's last product W x was with the P it
//    returns (the time loop takes the velocity correction from that
//    product; GMRES computes W P by recurrence, refine() by a product),
//    and its V is q + W P to 1e-12.
// 4. 30 strongly coupled frictional problems (W = B B^T + I/2, mu up to
//    1), where the method may cycle: every answer it accepts passes the
//    dense verification (the ones it does not accept are left to Lemke's
//    method in the time loop), and its last product was with it.
// 5. A solve that cannot converge (1 iteration from a wrong guess) says so.
// 6. verify_contact_velocities() with V = q + W P and ||W||_inf gives
//    verify_contact_solution()'s numbers.
// 7. A contact that must slide, guessed sticking, its stick impulse 5e-7
//    outside the cone, beside an open contact whose W_jj is 1e-4 (so that
//    c |q| = 1e4 is far above the impulses, 1): the answer slides, equals
//    the exact one and passes the verification. (The state-change margin
//    after a tight solve, 1e-10 c |q| = 1e-6, kept the stick state, and
//    the answer failed the verification.)
// 8. A lift-off front: 100 frictionless contacts, W_ij = 0.95^|i-j| (its
//    inverse is tridiagonal), q_i = -0.99 + 0.02 i. From P = 0 the first
//    50 close; the last closed one then pulls (P < 0), opens, and so on,
//    one contact per iteration, until |q| at the end of the closed set
//    exceeds 0.95 * 0.02 / 0.05 = 0.38 (contact 30, q = -0.39): 19
//    contacts open one by one. With 5 iterations allowed, the method goes
//    on while the front moves, and its answer equals Lemke's.
// No iteration counts are printed.
#include <impactfe/lcp/active_set.h>
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/exact_cone.h>

#include <algorithm>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using impactfe::ContactState;

namespace
{
  ContactProblem
  random_problem(lcp_test::Rng     &rng,
                 const unsigned int nc,
                 const unsigned int nd,
                 const double       mu_max,
                 const bool         weakly_coupled)
  {
    const unsigned int m = nd * nc;
    DenseMatrix        B(m, m);
    const double       b = weakly_coupled ? 1. / std::sqrt(2. * nc) : 1.;
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        B(i, j) = b * rng.uniform(-1., 1.);
    ContactProblem p;
    p.n_directions = nd;
    p.n_contacts   = nc;
    p.W            = lcp_test::gram_plus_shift(B, weakly_coupled ? 1. : 0.5);
    p.free_velocity.resize(m);
    p.gap_term.resize(nc);
    p.mu.assign(nc, 0.);
    for (unsigned int i = 0; i < m; ++i)
      p.free_velocity[i] = rng.uniform(-1., 1.);
    for (unsigned int c = 0; c < nc; ++c)
      {
        p.gap_term[c] = rng.uniform(-0.5, 0.5);
        if (nd > 1)
          p.mu[c] = rng.uniform(0., mu_max);
      }
    return p;
  }

  /// The products with W, a Jacobi preconditioner and c = 1 / W_jj.
  struct DenseOperators
  {
    explicit DenseOperators(const ContactProblem &p)
      : penalty(p.W.n_rows())
    {
      for (unsigned int i = 0; i < penalty.size(); ++i)
        penalty[i] = 1. / p.W(i, i);
      // records the impulses of its last product, as the time loop's W
      // keeps that product's by-products
      product = [&p, this](const std::vector<double> &x,
                           std::vector<double>       &y) {
        last_product_P = x;
        p.W.vmult(y, x);
      };
      jacobi = [this](const std::vector<double> &x, std::vector<double> &y) {
        y.resize(x.size());
        for (unsigned int i = 0; i < x.size(); ++i)
          y[i] = penalty[i] * x[i];
      };
    }
    /// solver.solve() of @p p with these operators.
    const ActiveSetReport &
    solve(ActiveSetSolver                 &solver,
          const ContactProblem            &p,
          const std::vector<ContactState> &state_guess   = {},
          const std::vector<double>       &impulse_guess = {},
          const ActiveSetOptions          &options       = {}) const
    {
      return solver.solve(product,
                          jacobi,
                          penalty,
                          p.n_directions,
                          p.free_velocity,
                          p.gap_term,
                          p.mu,
                          state_guess,
                          impulse_guess,
                          options);
    }
    std::vector<double>         penalty;
    DelassusProduct             product, jacobi;
    mutable std::vector<double> last_product_P;
  };

  /// Whether the solver's last product was with its answer P (none is
  /// needed if P = 0) and its V is q + W P to 1e-12.
  bool
  answer_is_last_product(const ContactProblem  &p,
                         const ActiveSetSolver &solver,
                         const DenseOperators  &ops)
  {
    const std::vector<double> &P = solver.impulses();
    std::vector<double>        V;
    p.W.vmult(V, P);
    double v_error = 0., v_scale = 0.;
    for (unsigned int i = 0; i < V.size(); ++i)
      {
        V[i] += p.free_velocity[i];
        v_error = std::max(v_error, std::abs(V[i] - solver.velocities()[i]));
        v_scale = std::max(v_scale, std::abs(V[i]));
      }
    const bool no_impulse =
      std::all_of(P.begin(), P.end(), [](const double v) { return v == 0.; });
    return (no_impulse || ops.last_product_P == P) &&
           v_error <= 1e-12 * v_scale;
  }

  /// Cases 1 to 3: @p n problems, each solved by the active set method
  /// (cold, or warm from Lemke's perturbed answer) and compared with Lemke.
  void
  compare_with_lemke(const std::string  &title,
                     const unsigned int  nd,
                     const double        mu_max,
                     const bool          weakly_coupled,
                     const bool          warm,
                     const std::uint64_t seed,
                     const unsigned int  max_contacts = 200,
                     const unsigned int  n_facets     = 0)
  {
    lcp_test::Rng   rng(seed);
    ActiveSetSolver solver;
    unsigned int    converged = 0, verified = 0, agree = 0, lemke_solved = 0,
                 last_product     = 0;
    const unsigned int n_problems = 50;
    for (unsigned int k = 0; k < n_problems; ++k)
      {
        const unsigned int   nc = 20 + rng.integer(max_contacts - 19);
        const ContactProblem p =
          random_problem(rng, nc, nd, mu_max, weakly_coupled);
        // the reference: Lemke's method; in 3D on facet LCPs re-aligned
        // until the circular cone holds (ExactConeSolver)
        ExactConeOptions cone;
        cone.tolerance = 1e-12;
        ExactConeSolver exact;
        ContactOptions  facets;
        facets.form     = FrictionForm::facets;
        facets.n_facets = n_facets;
        const ContactSolution lemke =
          n_facets > 0 ? solve_contact_problem(p, facets) :
          nd == 3      ? exact.solve(p, ContactOptions(), cone) :
                         solve_contact_problem(p);
        if (lemke.lcp.status != Status::solved)
          continue;
        ++lemke_solved;
        std::vector<ContactState> state_guess;
        std::vector<double>       impulse_guess;
        if (warm)
          {
            state_guess   = lemke.states;
            impulse_guess = lemke.P;
            for (unsigned int c = 0; c < nc; c += 7) // a few wrong states
              state_guess[c] = ContactState::open;
            for (double &v : impulse_guess)
              v *= 1. + 0.1 * rng.uniform(-1., 1.);
          }
        const DenseOperators ops(p);
        ActiveSetOptions     options;
        options.n_facets = n_facets;
        const ActiveSetReport &report =
          ops.solve(solver, p, state_guess, impulse_guess, options);
        if (!report.converged)
          {
            dealii::deallog << "  not converged (" << nc
                            << " contacts): " << report.message << std::endl;
            continue;
          }
        ++converged;
        std::vector<double> V;
        p.W.vmult(V, solver.impulses());
        for (unsigned int i = 0; i < V.size(); ++i)
          V[i] += p.free_velocity[i];
        if (verify_contact_velocities(nd,
                                      p.free_velocity,
                                      p.gap_term,
                                      p.mu,
                                      solver.impulses(),
                                      V,
                                      p.W.linfty_norm(),
                                      1e-8,
                                      n_facets)
              .ok)
          ++verified;
        if (lcp_test::relative_difference(p, solver.impulses(), lemke.P) <=
            1e-8)
          ++agree;
        // the solver's last product was with its answer (the time loop
        // uses that product's by-products), and its V is q + W P of it
        if (answer_is_last_product(p, solver, ops))
          ++last_product;
      }
    dealii::deallog << title << ": Lemke solved " << lemke_solved << " of "
                    << n_problems << "; active set converged " << converged
                    << ", verified " << verified
                    << ", equal to Lemke's P (1e-8) " << agree
                    << ", last product W P with that P " << last_product
                    << std::endl;
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  using impactfe_tests::check;
  auto &log = dealii::deallog;

  compare_with_lemke("1. 2D, mu <= 0.2, cold", 2, 0.2, true, false, 11);
  compare_with_lemke("2. 2D, mu <= 0.2, warm", 2, 0.2, true, true, 11);
  compare_with_lemke("3. frictionless, coupled", 1, 0., false, false, 12);
  compare_with_lemke(
    "3b. 3D, circular cone, mu <= 0.2, cold", 3, 0.2, true, false, 16, 60);
  compare_with_lemke(
    "3c. 3D, circular cone, mu <= 0.2, warm", 3, 0.2, true, true, 16, 60);
  compare_with_lemke(
    "3d. 3D, 8 facets, mu <= 0.2, cold", 3, 0.2, true, false, 17, 60, 8);
  compare_with_lemke(
    "3e. 3D, 8 facets, mu <= 0.2, warm", 3, 0.2, true, true, 17, 60, 8);

  // 4. Strongly coupled, large mu: what is accepted is verified.
  {
    lcp_test::Rng   rng(13);
    ActiveSetSolver solver;
    bool            all_verified = true;
    for (unsigned int k = 0; k < 30; ++k)
      {
        const ContactProblem p =
          random_problem(rng, 20 + rng.integer(61), 2, 1., false);
        const DenseOperators ops(p);
        if (ops.solve(solver, p).converged)
          all_verified = all_verified &&
                         verify_contact_solution(p, solver.impulses()).ok &&
                         answer_is_last_product(p, solver, ops);
      }
    check(all_verified,
          "4. coupled, mu <= 1: every accepted answer verified, its last "
          "product W P with that P");
  }

  // 5. No convergence is reported, not hidden.
  {
    lcp_test::Rng        rng(14);
    const ContactProblem p = random_problem(rng, 40, 2, 0.2, true);
    const DenseOperators ops(p);
    ActiveSetOptions     options;
    options.max_iterations       = 1;
    options.max_front_iterations = 0;
    ActiveSetSolver        solver;
    const ActiveSetReport &report =
      ops.solve(solver,
                p,
                std::vector<ContactState>(40, ContactState::slip_positive),
                {},
                options);
    check(!report.converged,
          "5. one iteration from a wrong guess: not converged");
    log << "   message: " << report.message << std::endl;
  }

  // 6. The matrix-free verification equals the dense one.
  {
    lcp_test::Rng         rng(15);
    const ContactProblem  p = random_problem(rng, 30, 2, 0.5, true);
    const ContactSolution s = solve_contact_problem(p);
    std::vector<double>   V;
    p.W.vmult(V, s.P);
    for (unsigned int i = 0; i < V.size(); ++i)
      V[i] += p.free_velocity[i];
    const ContactVerification dense = verify_contact_solution(p, s.P);
    const ContactVerification free  = verify_contact_velocities(
      2, p.free_velocity, p.gap_term, p.mu, s.P, V, p.W.linfty_norm());
    check(dense.ok == free.ok &&
            dense.max_signorini_violation == free.max_signorini_violation &&
            dense.max_cone_violation == free.max_cone_violation &&
            dense.n_sliding == free.n_sliding &&
            dense.n_sticking == free.n_sticking,
          "6. verify_contact_velocities() = verify_contact_solution()");
  }

  // 7. A state change below c |q| but above the verification's tolerance.
  {
    ContactProblem p;
    p.n_directions = 2;
    p.n_contacts   = 2;
    p.W            = DenseMatrix(4, 4);
    p.W(0, 0) = p.W(1, 1) = 1e-4;
    p.W(2, 2) = p.W(3, 3) = 1.;
    p.free_velocity       = {1., 0., -1., -0.5 * (1. + 1e-6)};
    p.gap_term            = {0., 0.};
    p.mu                  = {0.5, 0.5};
    const DenseOperators   ops(p);
    ActiveSetSolver        solver;
    const ActiveSetReport &report =
      ops.solve(solver, p, {ContactState::open, ContactState::stick});
    // exact: contact 1 open; contact 2 closed (P_N = 1) and sliding with
    // V_T = -5e-7 < 0, so P_T = mu P_N = 0.5
    const std::vector<double> exact = {0., 0., 1., 0.5};
    double                    error = 0.;
    for (unsigned int i = 0; i < 4; ++i)
      error = std::max(error, std::abs(solver.impulses()[i] - exact[i]));
    check(report.converged && is_sliding(solver.states()[1]) && error < 1e-12 &&
            verify_contact_solution(p, solver.impulses()).ok,
          "7. a slip 5e-7 outside the cone, c |q| = 1e4 times the "
          "impulses: slides, exact (1e-12), verified");
  }

  // 8. A front that needs more iterations than max_iterations.
  {
    const unsigned int n = 100;
    ContactProblem     p;
    p.n_directions = 1;
    p.n_contacts   = n;
    p.W            = DenseMatrix(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        p.W(i, j) = std::pow(0.95, std::abs(int(i) - int(j)));
    p.free_velocity.resize(n);
    for (unsigned int i = 0; i < n; ++i)
      p.free_velocity[i] = -0.99 + 0.02 * i;
    p.gap_term.assign(n, 0.);
    const DenseOperators ops(p);
    ActiveSetOptions     options;
    options.max_iterations = 5;
    ActiveSetSolver        solver;
    const ActiveSetReport &report = ops.solve(solver, p, {}, {}, options);
    const ContactSolution  lemke  = solve_contact_problem(p);
    double                 error = 0., scale = 0.;
    unsigned int           closed = 0;
    for (unsigned int i = 0; i < n; ++i)
      {
        error = std::max(error, std::abs(solver.impulses()[i] - lemke.P[i]));
        scale = std::max(scale, std::abs(lemke.P[i]));
        closed += lemke.P[i] > 0. ? 1 : 0;
      }
    check(report.converged && report.iterations > options.max_iterations &&
            error < 1e-10 * scale,
          "8. a lift-off front past max_iterations = 5: converged, equal "
          "to Lemke's P (1e-10)");
    log << "   closed contacts: " << closed << " of " << n << std::endl;
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
