// Contact states and block principal pivoting on them (2D friction): the
// warm start of the time loop. The LCP forms themselves are in
// contact_problem.cc.
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include "contact_workspace.h"
#include "floating_point_mode.h"
#include "text.h"

namespace impactfe
{
  namespace lcp
  {
    namespace
    {
      bool
      all_zero(const std::vector<double> &v)
      {
        return std::all_of(v.begin(), v.end(), [](const double x) {
          return x == 0.;
        });
      }
    } // namespace



    // @sect3{Contact states and block principal pivoting (2D friction)}
    namespace
    {
      constexpr double eps = std::numeric_limits<double>::epsilon();

      /// V = V_free + W P, row by row (W is row-major).
      void
      local_velocities(const ContactProblem      &p,
                       const std::vector<double> &P,
                       std::vector<double>       &V)
      {
        const std::size_t m = P.size();
        V.resize(m);
        for (std::size_t i = 0; i < m; ++i)
          {
            const double *wi = p.W.row(i);
            double        s  = 0.;
            for (std::size_t j = 0; j < m; ++j)
              s += wi[j] * P[j];
            V[i] = p.free_velocity[i] + s;
          }
      }

      bool
      closed(const ContactState s)
      {
        return s != ContactState::open;
      }

      /**
       * The point (P, V) of given 2D states in the variables of the facet
       * form with k = 2, d_0 = +t, d_1 = -t:
       *   z = (P_N [n_c], beta [2 n_c, contact-major], sigma [n_c]),
       *   M z + q = (V_N + b_N, sigma + V_T, sigma - V_T, mu P_N - beta_0 -
       * beta_1), w the values a complementary basis of these states carries
       * (exact zeros where the state imposes an equation), and the residual w -
       * (M z + q), computed with W only. Returns verify_with_residual().
       */
      Verification
      verify_facet_point(const ContactProblem            &p,
                         const std::vector<ContactState> &states,
                         const std::vector<double>       &P,
                         const std::vector<double>       &V,
                         const double                     tolerance_factor,
                         ContactSolver::Workspace        &ws,
                         std::vector<double>             &z,
                         std::vector<double>             &w)
      {
        const unsigned int nc = p.n_contacts;
        const std::size_t  n  = 4 * static_cast<std::size_t>(nc);
        auto beta = [nc](std::size_t c, std::size_t j) -> std::size_t {
          return nc + 2 * c + j;
        };
        auto sigma = [nc](std::size_t c) -> std::size_t {
          return 3 * std::size_t(nc) + c;
        };

        z.assign(n, 0.);
        w.assign(n, 0.);
        std::vector<double> &q        = ws.q;
        std::vector<double> &residual = ws.residual;
        std::vector<double> &Mzq      = ws.Mz_q;
        q.assign(n, 0.);
        residual.assign(n, 0.);
        Mzq.assign(n, 0.);
        for (unsigned int c = 0; c < nc; ++c)
          {
            const double PN = P[2 * c], PT = P[2 * c + 1], VN = V[2 * c],
                         VT = V[2 * c + 1];
            q[c]            = p.free_velocity[2 * c] + p.gap_term[c];
            q[beta(c, 0)]   = p.free_velocity[2 * c + 1];
            q[beta(c, 1)]   = -p.free_velocity[2 * c + 1];

            z[c]          = PN;
            z[beta(c, 0)] = std::max(PT, 0.);
            z[beta(c, 1)] = std::max(-PT, 0.);
            switch (states[c])
              {
                case ContactState::open:
                case ContactState::slip_positive:
                case ContactState::slip_negative:
                  z[sigma(c)] = std::abs(VT);
                  break;
                case ContactState::stick:
                  z[sigma(c)] = 0.;
                  break;
              }

            Mzq[c]          = VN + p.gap_term[c];
            Mzq[beta(c, 0)] = z[sigma(c)] + VT;
            Mzq[beta(c, 1)] = z[sigma(c)] - VT;
            Mzq[sigma(c)]   = p.mu[c] * PN - z[beta(c, 0)] - z[beta(c, 1)];

            for (const std::size_t i :
                 {std::size_t(c), beta(c, 0), beta(c, 1), sigma(c)})
              w[i] = Mzq[i];
            // the equations of the state: these w are nonbasic, exactly 0
            if (closed(states[c]))
              w[c] = 0.;
            if (states[c] == ContactState::stick)
              {
                w[beta(c, 0)] = 0.;
                w[beta(c, 1)] = 0.;
              }
            for (const std::size_t i :
                 {std::size_t(c), beta(c, 0), beta(c, 1), sigma(c)})
              residual[i] = w[i] - Mzq[i];
          }

        // ||M||_inf of the facet form, row sums taken from W
        double norm_M = 0.;
        for (unsigned int c = 0; c < nc; ++c)
          {
            for (unsigned int r = 0; r < 2; ++r)
              {
                const double *wi  = p.W.row(2 * c + r);
                double        sum = (r == 1 ? 1. : 0.);
                for (unsigned int e = 0; e < nc; ++e)
                  sum += std::abs(wi[2 * e]) + 2. * std::abs(wi[2 * e + 1]);
                norm_M = std::max(norm_M, sum);
              }
            norm_M = std::max(norm_M, p.mu[c] + 2.);
          }
        return verify_with_residual(
          norm_M, q, z, w, residual, tolerance_factor);
      }

      using FactoredSystem = ContactSolver::Workspace::FactoredSystem;

      bool
      same_bits(const std::vector<double> &a, const std::vector<double> &b)
      {
        return a.size() == b.size() &&
               (a.empty() ||
                std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) ==
                  0);
      }

      /**
       * Whether the factors held in @p ws were made from these states, slip
       * factors and W, to the last bit: then they are the factors a new
       * factorisation would give. (Comparing W costs |W| reads, against
       * |S|^3 / 3 flops for the factorisation.)
       */
      bool
      factors_match(const ContactProblem            &p,
                    const std::vector<ContactState> &states,
                    const std::vector<double>       &slip_factor,
                    const ContactSolver::Workspace  &ws)
      {
        return ws.factored_system != FactoredSystem::none &&
               ws.factored_states == states &&
               same_bits(ws.factored_slip_factor, slip_factor) &&
               same_bits(ws.factored_W, p.W.data());
      }

      void
      remember_factors(const ContactProblem            &p,
                       const std::vector<ContactState> &states,
                       const std::vector<double>       &slip_factor,
                       const FactoredSystem             system,
                       ContactSolver::Workspace        &ws)
      {
        ws.factored_system = system;
        ws.factored_states.assign(states.begin(), states.end());
        ws.factored_slip_factor.assign(slip_factor.begin(), slip_factor.end());
        ws.factored_W.assign(p.W.data().begin(), p.W.data().end());
      }

      /// -(V_free + b_N) on normal rows, -V_free on tangential rows.
      double
      right_hand_side(const ContactProblem &p, const unsigned int row)
      {
        return -p.free_velocity[row] -
               (row % 2 == 0 ? p.gap_term[row / 2] : 0.);
      }

      /**
       * The impulses of given states for a symmetric positive definite W. The
       * unknowns split into those of the sticking contacts, x_S = (P_N, P_T)
       * with the rows S = (N, T) of these contacts, and the normal impulses
       * x_L of the sliding contacts (P_T = slip_factor P_N):
       *   [W_SS  B] [x_S]   [r_S]     B(i, l) = W(S_i, N_l) + s_l W(S_i, T_l),
       *   [C     D] [x_L] = [r_L],    C = W(N_L, S), D likewise.
       * W_SS is a principal block of W: Cholesky, (1/3) |S|^3 flops; then
       * Z_B = W_SS^{-1} B, the Schur complement D - C Z_B (|L| x |L|, LU),
       * z_r = W_SS^{-1} r_S, x_L from r_L - C z_r, and x_S = z_r - Z_B x_L.
       * (Only the upper triangle of W_SS is read.) False if W_SS is not
       * numerically positive definite or the Schur complement is singular: the
       * caller then uses one LU.
       *
       * With @p reuse_factors (factors_match()) the Cholesky factor, Z_B
       * and the Schur complement's LU of the last call are used as they
       * are, and only the right-hand side is solved: about 2 |S|^2 +
       * 4 |S| |L| + 2 |L|^2 flops instead of |S|^3 / 3 + |S|^2 |L| + |L|^3.
       */
      bool
      impulses_by_cholesky(const ContactProblem            &p,
                           const std::vector<ContactState> &states,
                           const std::vector<double>       &slip_factor,
                           const bool                       reuse_factors,
                           ContactSolver::Workspace        &ws,
                           std::vector<double>             &P)
      {
        std::vector<unsigned int> &S = ws.stick_rows;
        std::vector<unsigned int> &L = ws.slip_contacts;
        S.clear();
        L.clear();
        for (unsigned int c = 0; c < p.n_contacts; ++c)
          if (states[c] == ContactState::stick)
            {
              S.push_back(2 * c);
              S.push_back(2 * c + 1);
            }
          else if (closed(states[c]))
            L.push_back(c);
        const std::size_t ns = S.size(), nl = L.size();
        if (ns == 0)
          return false;
        CholeskyFactorization &cholesky = ws.cholesky;
        DenseMatrix           &Z        = ws.Z;
        if (!reuse_factors)
          {
            ws.factored_system = FactoredSystem::none;
            DenseMatrix &Wss   = ws.W_SS;
            Wss.reinit(ns, ns);
            for (std::size_t i = 0; i < ns; ++i)
              {
                const double *wi = p.W.row(S[i]);
                double       *ri = Wss.row(i);
                for (std::size_t j = i; j < ns; ++j)
                  ri[j] = wi[S[j]];
              }
            if (!cholesky.factorize(Wss))
              return false;

            Z.reinit(ns, nl);
            for (std::size_t i = 0; i < ns; ++i)
              {
                const double *wi = p.W.row(S[i]);
                double       *zi = Z.row(i);
                for (std::size_t k = 0; k < nl; ++k)
                  zi[k] = wi[2 * L[k]] + slip_factor[L[k]] * wi[2 * L[k] + 1];
              }
            if (nl > 0)
              {
                cholesky.solve(Z);
                DenseMatrix &Schur = ws.schur;
                Schur.reinit(nl, nl);
                for (std::size_t a = 0; a < nl; ++a)
                  {
                    const double *wa = p.W.row(2 * L[a]);
                    double       *ta = Schur.row(a);
                    for (std::size_t b = 0; b < nl; ++b)
                      ta[b] =
                        wa[2 * L[b]] + slip_factor[L[b]] * wa[2 * L[b] + 1];
                    for (std::size_t i = 0; i < ns; ++i)
                      {
                        const double c = wa[S[i]];
                        if (c == 0.)
                          continue;
                        const double *zi = Z.row(i);
                        for (std::size_t b = 0; b < nl; ++b)
                          ta[b] -= c * zi[b];
                      }
                  }
                if (!ws.schur_lu.factorize(Schur))
                  return false;
              }
            remember_factors(
              p, states, slip_factor, FactoredSystem::cholesky, ws);
          }

        // The right-hand side, solved the same way whether the factors are
        // new or reused, so that reusing them changes no bit.
        DenseMatrix &z_rhs = ws.Z_rhs;
        z_rhs.reinit(ns, 1);
        for (std::size_t i = 0; i < ns; ++i)
          z_rhs(i, 0) = right_hand_side(p, S[i]);
        cholesky.solve(z_rhs);
        std::vector<double> &x_slip = ws.slip_impulses;
        x_slip.assign(nl, 0.);
        for (std::size_t a = 0; a < nl; ++a)
          {
            const double *wa = p.W.row(2 * L[a]);
            x_slip[a]        = right_hand_side(p, 2 * L[a]);
            for (std::size_t i = 0; i < ns; ++i)
              {
                const double c = wa[S[i]];
                if (c == 0.)
                  continue;
                x_slip[a] -= c * z_rhs(i, 0);
              }
          }
        if (nl > 0)
          ws.schur_lu.solve(x_slip);
        for (std::size_t i = 0; i < ns; ++i)
          {
            const double *zi = Z.row(i);
            double        v  = z_rhs(i, 0);
            for (std::size_t k = 0; k < nl; ++k)
              v -= zi[k] * x_slip[k];
            P[S[i]] = v;
          }
        for (std::size_t k = 0; k < nl; ++k)
          {
            P[2 * L[k]]     = x_slip[k];
            P[2 * L[k] + 1] = slip_factor[L[k]] * x_slip[k];
          }
        return true;
      }

      /**
       * Block principal pivoting for 2D friction, from @p states (updated in
       * place). On success P, V, z, w, verification are those of the
       * accepted point. See solve_contact_problem() for the method.
       */
      bool
      block_pivoting_2d(const ContactProblem      &p,
                        const ContactOptions      &options,
                        ContactSolver::Workspace  &ws,
                        std::vector<ContactState> &states,
                        std::vector<double>       &P,
                        std::vector<double>       &V,
                        std::vector<double>       &z,
                        std::vector<double>       &w,
                        Verification              &verification,
                        unsigned int              &iterations,
                        std::string               &why,
                        const unsigned int         max_iterations)
      {
        const unsigned int nc = p.n_contacts;
        const double       tolerance_factor =
          options.lemke.verification_tolerance_factor;
        // The tolerance of verify_facet_point() (see verify_with_residual()),
        // at least 1e-10: a backward-stable solve meets it on any W.
        const double physical_tolerance =
          std::max(tolerance_factor * eps * 4. * std::max(nc, 1u), 1e-10);
        // the states tried so far, one block of n_c after the other
        std::vector<ContactState> &visited = ws.visited_states;
        visited.clear();
        visited.reserve(static_cast<std::size_t>(nc) * max_iterations);
        std::vector<unsigned int> &rows            = ws.rows;
        std::vector<unsigned int> &unknown_column  = ws.unknown_column;
        std::vector<unsigned int> &unknown_contact = ws.unknown_contact;
        std::vector<double>       &rhs             = ws.rhs;
        std::vector<double>       &slip_factor     = ws.slip_factor;
        slip_factor.assign(nc, 0.);
        // at most 2 n_c entries each: reserved once, never grown in a solve
        for (auto *list :
             {&rows, &unknown_column, &unknown_contact, &ws.stick_rows})
          list->reserve(2 * static_cast<std::size_t>(nc));
        ws.slip_contacts.reserve(nc);
        iterations        = 0;
        ws.reused_factors = 0;

        // W symmetric up to rounding (a Delassus operator computed column by
        // column is symmetric only to rounding): the systems are solved by
        // Cholesky on the sticking block (impulses_by_cholesky()); whatever
        // comes out is verified against W itself.
        double max_asymmetry = 0.;
        for (std::size_t i = 0; i < p.W.n_rows(); ++i)
          for (std::size_t j = 0; j < i; ++j)
            max_asymmetry =
              std::max(max_asymmetry, std::abs(p.W(i, j) - p.W(j, i)));
        const bool symmetric = max_asymmetry <= 1e3 * eps * p.W.max_abs();

        for (;;)
          {
            if (iterations >= max_iterations)
              {
                internal::set_text(why,
                                   "no verified point after %u block "
                                   "pivoting solves",
                                   iterations);
                return false;
              }
            for (std::size_t start = 0; start < visited.size(); start += nc)
              if (std::equal(states.begin(),
                             states.end(),
                             visited.begin() + start))
                {
                  why.assign(
                    "block pivoting returned to a set of states it had tried");
                  return false;
                }
            visited.insert(visited.end(), states.begin(), states.end());
            ++iterations;

            // The unknowns: P_N of each closed contact (P_T = slip_factor P_N
            // rides along for sliding ones), P_T of each sticking one. The
            // equations: the normal row of each closed contact, the tangential
            // row of each sticking one. As many equations as unknowns.
            rows.clear();
            unknown_column.clear();
            unknown_contact.clear();
            for (unsigned int c = 0; c < nc; ++c)
              {
                slip_factor[c] =
                  states[c] == ContactState::slip_positive ? -p.mu[c] :
                  states[c] == ContactState::slip_negative ? p.mu[c] :
                                                             0.;
                if (!closed(states[c]))
                  continue;
                rows.push_back(2 * c);
                unknown_column.push_back(2 * c);
                unknown_contact.push_back(c);
                if (states[c] == ContactState::stick)
                  {
                    rows.push_back(2 * c + 1);
                    unknown_column.push_back(2 * c + 1);
                    unknown_contact.push_back(c);
                  }
              }
            const std::size_t m = rows.size();
            P.assign(2 * static_cast<std::size_t>(nc), 0.);
            bool solved = (m == 0);
            // The same states and W as the last factorisation (a time loop
            // whose contacts keep their states): its factors are reused. The
            // path it took is the one a new factorisation would take.
            const bool reuse =
              !solved && factors_match(p, states, slip_factor, ws);
            ws.reused_factors += reuse ? 1 : 0;
            if (!solved && symmetric &&
                (!reuse || ws.factored_system == FactoredSystem::cholesky))
              solved =
                impulses_by_cholesky(p, states, slip_factor, reuse, ws, P);
            if (!solved)
              {
                rhs.resize(m);
                for (std::size_t r = 0; r < m; ++r)
                  rhs[r] = right_hand_side(p, rows[r]);
                LUFactorization &lu = ws.G_lu;
                if (!reuse || ws.factored_system != FactoredSystem::lu)
                  {
                    ws.factored_system = FactoredSystem::none;
                    DenseMatrix &G     = ws.G;
                    G.reinit(m, m);
                    for (std::size_t r = 0; r < m; ++r)
                      {
                        const double *wi = p.W.row(rows[r]);
                        double       *gr = G.row(r);
                        for (std::size_t u = 0; u < m; ++u)
                          {
                            const unsigned int j = unknown_column[u];
                            gr[u]                = (j % 2 == 0) ?
                                                     wi[j] + slip_factor[unknown_contact[u]] *
                                                wi[j + 1] :
                                                     wi[j];
                          }
                      }
                    if (!lu.factorize(G))
                      {
                        why.assign("singular system for the current states");
                        return false;
                      }
                    remember_factors(
                      p, states, slip_factor, FactoredSystem::lu, ws);
                  }
                lu.solve(rhs);
                for (std::size_t u = 0; u < m; ++u)
                  {
                    const unsigned int j = unknown_column[u];
                    P[j]                 = rhs[u];
                    if (j % 2 == 0)
                      P[j + 1] = slip_factor[unknown_contact[u]] * rhs[u];
                  }
              }
            local_velocities(p, P, V);

            // Accept the point only if it passes the facet form's
            // verification and the contact conditions themselves. The facet
            // form's scale s = ||q|| + ||M|| ||z|| mixes impulses (P_N, beta)
            // and velocities (sigma = |V_T| of open and sliding contacts):
            // where |V_T| is large against ||M|| ||P||, its tolerance on the
            // impulse rows grows to the size of the impulses, and points
            // with |P_T| > mu P_N, or sliding against their friction force,
            // passed. verify_contact_solution() measures impulses and
            // velocities on their own scales.
            verification =
              verify_facet_point(p, states, P, V, tolerance_factor, ws, z, w);
            if (verification.ok &&
                internal::verify_contact_solution(
                  p, P, physical_tolerance, ws.verification_velocity)
                  .ok)
              return true;

            // Change the state of every contact that violates its conditions.
            bool changed = false;
            for (unsigned int c = 0; c < nc; ++c)
              {
                const double PN = P[2 * c], PT = P[2 * c + 1],
                             VT        = V[2 * c + 1];
                const ContactState old = states[c];
                if (old == ContactState::open)
                  {
                    if (V[2 * c] + p.gap_term[c] < 0.)
                      states[c] = ContactState::stick;
                  }
                else if (PN < 0.)
                  states[c] = ContactState::open;
                else if (old == ContactState::stick)
                  {
                    if (std::abs(PT) > p.mu[c] * PN)
                      states[c] = PT < 0. ? ContactState::slip_positive :
                                            ContactState::slip_negative;
                  }
                else if ((old == ContactState::slip_positive && VT < 0.) ||
                         (old == ContactState::slip_negative && VT > 0.))
                  states[c] = ContactState::stick;
                changed = changed || (states[c] != old);
              }
            if (!changed)
              {
                internal::set_text(
                  why,
                  "the point of the current states satisfies every sign "
                  "condition but fails verification (relative error %f)",
                  verification.relative_error);
                return false;
              }
          }
      }
    } // namespace



    namespace internal
    {
      void
      contact_states(const ContactProblem      &p,
                     const std::vector<double> &P,
                     const double               tol,
                     std::vector<double>       &V,
                     std::vector<ContactState> &states)
      {
        check_contact_problem(p);
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        if (P.size() != static_cast<std::size_t>(nc) * dim)
          throw std::invalid_argument("contact_states: P has the wrong size");
        local_velocities(p, P, V);
        double bmax = 0.;
        for (const double b : p.gap_term)
          bmax = std::max(bmax, std::abs(b));
        const double normW = p.W.linfty_norm(), pmax = linfty_norm(P),
                     vfree = linfty_norm(p.free_velocity);
        const double sV    = vfree + bmax + normW * pmax;
        const double sP =
          std::max(pmax, normW > 0. ? (vfree + bmax) / normW : 0.);
        const bool frictional_2d = (dim == 2 && !all_zero(p.mu));

        states.assign(nc, ContactState::open);
        for (unsigned int c = 0; c < nc; ++c)
          {
            if (P[c * dim] <= tol * sP)
              continue;
            states[c] = ContactState::stick;
            if (frictional_2d)
              {
                const double VT = V[c * dim + 1];
                if (VT > tol * sV)
                  states[c] = ContactState::slip_positive;
                else if (VT < -tol * sV)
                  states[c] = ContactState::slip_negative;
              }
          }
      }



      double
      cone_equation_miss(const ContactProblem &p, const ContactSolution &s)
      {
        if (p.n_directions != 2 || all_zero(p.mu) || s.P.empty())
          return 0.;
        const double p_max = linfty_norm(s.P);
        double       miss  = 0.;
        for (unsigned int c = 0; c < p.n_contacts; ++c)
          {
            const double excess =
              std::abs(s.P[2 * c + 1]) - p.mu[c] * s.P[2 * c];
            const bool sliding = s.states[c] == ContactState::slip_positive ||
                                 s.states[c] == ContactState::slip_negative;
            miss = std::max(miss, sliding ? std::abs(excess) : excess);
          }
        return p_max > 0. ? miss / p_max : 0.;
      }



      bool
      polish_2d_impulses(const ContactProblem     &p,
                         const ContactOptions     &options,
                         ContactSolver::Workspace &ws,
                         ContactSolution          &s)
      {
        if (p.n_directions != 2 || all_zero(p.mu) ||
            s.lcp.status != Status::solved || s.states.size() != p.n_contacts)
          return false;
        // Only where Lemke's P misses the cone's equations by more than
        // round-off: the re-solve costs about as much as Lemke on these
        // sizes, and most answers need none.
        if (cone_equation_miss(p, s) <= 1e-12)
          return false;
        ws.states.assign(s.states.begin(), s.states.end());
        Verification verification;
        unsigned int iterations = 0;
        if (!block_pivoting_2d(p,
                               options,
                               ws,
                               ws.states,
                               ws.P,
                               ws.velocity,
                               ws.z,
                               ws.w,
                               verification,
                               iterations,
                               ws.why_not_block_pivoting,
                               1))
          return false;
        s.P.swap(ws.P); // keeps both capacities: no allocation
        return true;
      }



      void
      guess_from_states(const ContactLCP                &lcp,
                        const std::vector<ContactState> &states,
                        std::vector<bool>               &guess)
      {
        const std::size_t nc = states.size();
        guess.assign(lcp.q.size(), false);
        const std::size_t per_contact =
          lcp.form == FrictionForm::frictionless ? 1 :
          lcp.form == FrictionForm::klarbring    ? 3 :
                                                   lcp.n_facets + 2;
        if (lcp.q.size() != per_contact * nc)
          throw std::invalid_argument(
            "guess_from_states: one state per contact expected");
        for (std::size_t c = 0; c < nc; ++c)
          {
            guess[c]            = closed(states[c]);
            const bool slip_pos = states[c] == ContactState::slip_positive;
            const bool slip_neg = states[c] == ContactState::slip_negative;
            if (lcp.form == FrictionForm::klarbring)
              {
                guess[nc + c]     = slip_pos;
                guess[2 * nc + c] = slip_neg;
              }
            else if (lcp.form == FrictionForm::facets)
              {
                const std::size_t k = lcp.n_facets;
                guess[nc + k * nc + c] =
                  slip_pos || slip_neg || states[c] == ContactState::open;
                if (k == 2 && lcp.directions.size() == 2)
                  {
                    // P_T = -mu P_N along V_T: facet d_1 = -t for V_T > 0
                    guess[nc + c * k + 1] = slip_pos;
                    guess[nc + c * k + 0] = slip_neg;
                  }
              }
          }
      }
    } // namespace internal



    std::vector<ContactState>
    contact_states(const ContactProblem      &p,
                   const std::vector<double> &P,
                   const double               tol)
    {
      std::vector<double>       V;
      std::vector<ContactState> states;
      internal::contact_states(p, P, tol, V, states);
      return states;
    }



    std::vector<bool>
    guess_from_states(const ContactLCP                &lcp,
                      const std::vector<ContactState> &states)
    {
      std::vector<bool> guess;
      internal::guess_from_states(lcp, states, guess);
      return guess;
    }



    const ContactSolution &
    ContactSolver::solve(const ContactProblem            &p,
                         const ContactOptions            &options,
                         const std::vector<ContactState> &state_guess)
    {
      const internal::FlushSubnormalsScope
        flush_subnormals; // see floating_point_mode.h
      check_contact_problem(p);
      if (state_guess.size() != p.n_contacts)
        throw std::invalid_argument(
          "solve_contact_problem: one guessed state per contact expected");
      const FrictionForm form = internal::resolved_form(p, options.form);
      Workspace         &ws   = *workspace;
      ContactSolution   &s    = ws.solution;

      std::string &why_not_block_pivoting = ws.why_not_block_pivoting;
      why_not_block_pivoting.clear();
      unsigned int iterations = 0;
      if (p.n_directions == 2 && form != FrictionForm::frictionless)
        {
          s.states.assign(state_guess.begin(), state_guess.end());
          Verification verification;
          if (block_pivoting_2d(p,
                                options,
                                ws,
                                s.states,
                                s.P,
                                ws.velocity,
                                s.lcp.z,
                                s.lcp.w,
                                verification,
                                iterations,
                                why_not_block_pivoting,
                                options.max_block_pivoting_iterations))
            {
              s.form                          = FrictionForm::facets;
              s.n_facets                      = 2;
              s.block_pivoting_iterations     = iterations;
              s.block_pivoting_reused_factors = ws.reused_factors;
              s.lcp.status                    = Status::solved;
              s.lcp.pivots                    = 0;
              s.lcp.refactorisations          = 0;
              s.lcp.driving_variable          = -1;
              s.lcp.verification              = verification;
              s.lcp.start_path                = StartPath::block_pivoting;
              internal::set_text(
                s.lcp.message,
                "block pivoting on the contact states: verified in the facet "
                "form (k = 2) after %u %s",
                iterations,
                iterations == 1 ? "solve" : "solves");
              s.message.assign(s.lcp.message);
              return s;
            }
        }

      // Lemke's method in the requested form, warm-started from the guess.
      ContactLCP &lcp = ws.lcp;
      internal::assemble_contact_lcp(p, options, ws, lcp);
      internal::guess_from_states(lcp, state_guess, ws.guess);
      s.form                          = lcp.form;
      s.n_facets                      = lcp.n_facets;
      s.block_pivoting_iterations     = iterations;
      s.block_pivoting_reused_factors = iterations > 0 ? ws.reused_factors : 0;
      s.P.clear();
      s.states.clear();
      s.lcp = ws.lemke.solve_warm(lcp.M, lcp.q, ws.guess, options.lemke);
      s.message.clear();
      if (!why_not_block_pivoting.empty())
        {
          s.message.assign("block pivoting gave up (");
          s.message.append(why_not_block_pivoting);
          s.message.append("); ");
        }
      internal::finish_lemke_route(p, options, ws, s);
      return s;
    }



    ContactSolution
    solve_contact_problem(const ContactProblem            &p,
                          const ContactOptions            &options,
                          const std::vector<ContactState> &state_guess)
    {
      ContactSolver solver;
      return solver.solve(p, options, state_guess);
    }
  } // namespace lcp
} // namespace impactfe
