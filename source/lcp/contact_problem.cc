#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/lu.h>

#include "floating_point_mode.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

namespace impactfe
{
  namespace lcp
  {
    std::string
    to_string(const FrictionForm form)
    {
      switch (form)
        {
          case FrictionForm::frictionless:
            return "frictionless";
          case FrictionForm::klarbring:
            return "klarbring";
          case FrictionForm::facets:
            return "facets";
          case FrictionForm::automatic:
            return "automatic";
        }
      return "automatic";
    }






    void
    check_contact_problem(const ContactProblem &p)
    {
      if (p.n_directions < 1 || p.n_directions > 3)
        throw std::invalid_argument("contact problem: n_directions must be 1, 2 or 3");
      const std::size_t m = static_cast<std::size_t>(p.n_contacts) * p.n_directions;
      if (p.W.n_rows() != m || p.W.n_cols() != m)
        throw std::invalid_argument("contact problem: W must be (n_contacts n_directions)^2");
      if (p.free_velocity.size() != m)
        throw std::invalid_argument("contact problem: free_velocity has the wrong size");
      if (p.gap_term.size() != p.n_contacts)
        throw std::invalid_argument("contact problem: gap_term must have n_contacts entries");
      if (p.n_directions > 1 && p.mu.size() != p.n_contacts)
        throw std::invalid_argument("contact problem: mu must have n_contacts entries");
      for (const double v : p.W.data())
        if (!std::isfinite(v))
          throw std::invalid_argument("contact problem: W has a non-finite entry");
      for (const auto *vec : {&p.free_velocity, &p.gap_term, &p.mu})
        for (const double v : *vec)
          if (!std::isfinite(v))
            throw std::invalid_argument("contact problem: non-finite data");
      for (const double v : p.mu)
        if (v < 0.)
          throw std::invalid_argument("contact problem: negative friction coefficient");
    }



    namespace
    {
      bool
      all_zero(const std::vector<double> &v)
      {
        for (const double x : v)
          if (x != 0.)
            return false;
        return true;
      }

      ContactLCP
      assemble_frictionless(const ContactProblem &p)
      {
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        ContactLCP         lcp;
        lcp.form = FrictionForm::frictionless;
        lcp.M.reinit(nc, nc);
        lcp.q.resize(nc);
        for (unsigned int a = 0; a < nc; ++a)
          {
            for (unsigned int b = 0; b < nc; ++b)
              lcp.M(a, b) = p.W(a * dim, b * dim);
            lcp.q[a] = p.free_velocity[a * dim] + p.gap_term[a];
          }
        return lcp;
      }

      std::vector<std::vector<double>>
      facet_directions(const unsigned int dim, const unsigned int k)
      {
        std::vector<std::vector<double>> D;
        if (dim == 2)
          return {{1.}, {-1.}};
        const double pi = std::acos(-1.);
        for (unsigned int j = 0; j < k; ++j)
          {
            const double theta = 2. * pi * j / k;
            D.push_back({std::cos(theta), std::sin(theta)});
          }
        return D;
      }

      ContactLCP
      assemble_facets(const ContactProblem &p, const unsigned int k_requested)
      {
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        const unsigned int k  = (dim == 2 ? 2 : k_requested);
        if (dim == 3 && k < 3)
          throw std::invalid_argument("facet form: need at least 3 facets in 3D");
        ContactLCP lcp;
        lcp.form       = FrictionForm::facets;
        lcp.n_facets   = k;
        lcp.directions = facet_directions(dim, k);
        const auto        &D = lcp.directions;
        const unsigned int n = (k + 2) * nc;
        lcp.M.reinit(n, n);
        lcp.q.assign(n, 0.);
        auto N     = [&](unsigned int c) { return c * dim; };
        auto T     = [&](unsigned int c, unsigned int a) { return c * dim + 1 + a; };
        auto beta  = [&](unsigned int c, unsigned int j) { return nc + c * k + j; };
        auto sigma = [&](unsigned int c) { return nc + nc * k + c; };

        for (unsigned int c = 0; c < nc; ++c)
          {
            lcp.q[c] = p.free_velocity[N(c)] + p.gap_term[c];
            for (unsigned int i = 0; i < k; ++i)
              {
                double s = 0.;
                for (unsigned int a = 0; a + 1 < dim; ++a)
                  s += D[i][a] * p.free_velocity[T(c, a)];
                lcp.q[beta(c, i)] = s;
              }
            for (unsigned int e = 0; e < nc; ++e)
              {
                lcp.M(c, e) = p.W(N(c), N(e));
                for (unsigned int j = 0; j < k; ++j)
                  {
                    double s1 = 0., s2 = 0.;
                    for (unsigned int a = 0; a + 1 < dim; ++a)
                      {
                        s1 += p.W(N(c), T(e, a)) * D[j][a];
                        s2 += D[j][a] * p.W(T(e, a), N(c));
                      }
                    lcp.M(c, beta(e, j)) = s1;
                    lcp.M(beta(e, j), c) = s2;
                  }
                for (unsigned int i = 0; i < k; ++i)
                  for (unsigned int j = 0; j < k; ++j)
                    {
                      double s = 0.;
                      for (unsigned int a = 0; a + 1 < dim; ++a)
                        for (unsigned int b = 0; b + 1 < dim; ++b)
                          s += D[i][a] * p.W(T(c, a), T(e, b)) * D[j][b];
                      lcp.M(beta(c, i), beta(e, j)) = s;
                    }
              }
            for (unsigned int i = 0; i < k; ++i)
              {
                lcp.M(beta(c, i), sigma(c)) = 1.;
                lcp.M(sigma(c), beta(c, i)) = -1.;
              }
            lcp.M(sigma(c), c) = p.mu[c];
          }
        return lcp;
      }

      /// The block (r, s) of W, r, s in {0 (normal), 1 (tangential)}, as a
      /// contiguous n_c x n_c matrix.
      DenseMatrix
      delassus_block(const ContactProblem &p, const unsigned int r, const unsigned int s)
      {
        const unsigned int nc = p.n_contacts;
        DenseMatrix        B(nc, nc);
        for (unsigned int a = 0; a < nc; ++a)
          {
            const double *wa = p.W.row(2 * a + r);
            double       *ba = B.row(a);
            for (unsigned int b = 0; b < nc; ++b)
              ba[b] = wa[2 * b + s];
          }
        return B;
      }

      /// C = A B, rows of C accumulated from rows of B (contiguous loops).
      DenseMatrix
      multiply(const DenseMatrix &A, const DenseMatrix &B)
      {
        const std::size_t n = A.n_rows(), k = A.n_cols(), m = B.n_cols();
        DenseMatrix       C(n, m, 0.);
        for (std::size_t i = 0; i < n; ++i)
          {
            const double *ai = A.row(i);
            double       *ci = C.row(i);
            for (std::size_t l = 0; l < k; ++l)
              {
                const double a = ai[l];
                if (a == 0.)
                  continue;
                const double *bl = B.row(l);
                for (std::size_t j = 0; j < m; ++j)
                  ci[j] += a * bl[j];
              }
          }
        return C;
      }

      /// Returns false if W_TT is singular. The blocks of W are copied into
      /// contiguous matrices first, so that the O(n_c^3) products run along
      /// rows.
      bool
      assemble_klarbring(const ContactProblem &p, const double tol, ContactLCP &lcp)
      {
        const unsigned int nc = p.n_contacts;
        LUFactorization    lu;
        if (!lu.factorize(delassus_block(p, 1, 1), tol))
          return false;
        const DenseMatrix A    = lu.inverse();
        const DenseMatrix Wnt  = delassus_block(p, 0, 1);
        const DenseMatrix AWtn = multiply(A, delassus_block(p, 1, 0));
        const DenseMatrix WntA = multiply(Wnt, A);
        const DenseMatrix S    = multiply(Wnt, AWtn); // W_NT A W_TN

        std::vector<double> Vt(nc), AVt;
        for (unsigned int b = 0; b < nc; ++b)
          Vt[b] = p.free_velocity[2 * b + 1];
        A.vmult(AVt, Vt);

        lcp.form         = FrictionForm::klarbring;
        lcp.n_facets     = 0;
        lcp.M.reinit(3 * nc, 3 * nc);
        lcp.q.assign(3 * nc, 0.);
        for (unsigned int a = 0; a < nc; ++a)
          {
            const double *wa      = p.W.row(2 * a);
            double       *m0      = lcp.M.row(a);
            double       *m1      = lcp.M.row(nc + a);
            double       *m2      = lcp.M.row(2 * nc + a);
            double        wntavt  = 0.;
            const double *s_a     = S.row(a);
            const double *wnta_a  = WntA.row(a);
            const double *awtn_a  = AWtn.row(a);
            const double *A_a     = A.row(a);
            const double *wnt_a   = Wnt.row(a);
            for (unsigned int b = 0; b < nc; ++b)
              {
                const double mu_ab = (a == b ? p.mu[a] : 0.);
                m0[b]              = wa[2 * b] - s_a[b];
                m0[nc + b]         = wnta_a[b];
                m0[2 * nc + b]     = -wnta_a[b];
                m1[b]              = mu_ab - awtn_a[b];
                m1[nc + b]         = A_a[b];
                m1[2 * nc + b]     = -A_a[b];
                m2[b]              = mu_ab + awtn_a[b];
                m2[nc + b]         = -A_a[b];
                m2[2 * nc + b]     = A_a[b];
                wntavt += wnt_a[b] * AVt[b];
              }
            lcp.q[a]          = p.free_velocity[2 * a] - wntavt + p.gap_term[a];
            lcp.q[nc + a]     = -AVt[a];
            lcp.q[2 * nc + a] = AVt[a];
          }
        lcp.W_TT_inverse = A;
        return true;
      }
    } // namespace



    ContactLCP
    assemble_contact_lcp(const ContactProblem &p, const ContactOptions &options)
    {
      const internal::FlushSubnormalsScope flush_subnormals; // see floating_point_mode.h
      check_contact_problem(p);
      FrictionForm form = options.form;
      std::string  why;
      if (form == FrictionForm::automatic)
        {
          if (p.n_directions == 1 || all_zero(p.mu))
            {
              form = FrictionForm::frictionless;
              why  = (p.n_directions == 1 ? "normal directions only" : "all friction coefficients are 0");
            }
          else if (p.n_directions == 2)
            form = FrictionForm::klarbring;
          else
            form = FrictionForm::facets;
        }
      if (p.n_directions == 1 && form != FrictionForm::frictionless)
        throw std::invalid_argument("contact problem with normal directions only: use the frictionless form");
      if (form == FrictionForm::klarbring && p.n_directions != 2)
        throw std::invalid_argument("the Klarbring form is for 2D contact (n_directions == 2)");

      ContactLCP lcp;
      if (form == FrictionForm::frictionless)
        {
          lcp         = assemble_frictionless(p);
          lcp.message = "frictionless form" + (why.empty() ? std::string() : " (" + why + ")");
        }
      else if (form == FrictionForm::klarbring)
        {
          if (assemble_klarbring(p, options.singularity_tolerance, lcp))
            lcp.message = "Klarbring form";
          else
            {
              lcp = assemble_facets(p, 2);
              lcp.message =
                "W_TT is singular (rank-deficient tangential block): facet form with k = 2 instead of Klarbring";
            }
        }
      else
        {
          lcp = assemble_facets(p, options.n_facets);
          std::ostringstream s;
          s << "facet form, k = " << lcp.n_facets;
          if (p.n_directions == 2 && options.n_facets != 2)
            s << " (in 2D the cone has the two facets +t, -t)";
          lcp.message = s.str();
        }
      return lcp;
    }



    std::vector<double>
    impulses_from_lcp(const ContactProblem &p, const ContactLCP &lcp, const std::vector<double> &z)
    {
      const unsigned int  nc = p.n_contacts, dim = p.n_directions;
      std::vector<double> P(static_cast<std::size_t>(nc) * dim, 0.);
      if (z.size() != lcp.q.size())
        throw std::invalid_argument("impulses_from_lcp: z has the wrong size");
      for (unsigned int c = 0; c < nc; ++c)
        P[c * dim] = z[c];
      if (lcp.form == FrictionForm::klarbring)
        {
          // P_T = A (lambda1 - lambda2 - V_free,T - W_TN P_N)
          std::vector<double> r(nc);
          for (unsigned int a = 0; a < nc; ++a)
            {
              double s = z[nc + a] - z[2 * nc + a] - p.free_velocity[2 * a + 1];
              for (unsigned int b = 0; b < nc; ++b)
                s -= p.W(2 * a + 1, 2 * b) * z[b];
              r[a] = s;
            }
          for (unsigned int a = 0; a < nc; ++a)
            {
              double s = 0.;
              for (unsigned int b = 0; b < nc; ++b)
                s += lcp.W_TT_inverse(a, b) * r[b];
              P[2 * a + 1] = s;
            }
        }
      else if (lcp.form == FrictionForm::facets)
        {
          const unsigned int k = lcp.n_facets;
          for (unsigned int c = 0; c < nc; ++c)
            for (unsigned int j = 0; j < k; ++j)
              for (unsigned int a = 0; a + 1 < dim; ++a)
                P[c * dim + 1 + a] += lcp.directions[j][a] * z[nc + c * k + j];
        }
      return P;
    }



    ContactSolution
    solve_contact_problem(const ContactProblem &p, const ContactOptions &options, const std::vector<bool> *guess)
    {
      const internal::FlushSubnormalsScope flush_subnormals; // see floating_point_mode.h
      const ContactLCP lcp = assemble_contact_lcp(p, options);
      ContactSolution  s;
      s.form     = lcp.form;
      s.n_facets = lcp.n_facets;
      if (guess != nullptr && guess->size() == lcp.q.size())
        s.lcp = solve_lemke_warm(lcp.M, lcp.q, *guess, options.lemke);
      else
        s.lcp = solve_lemke(lcp.M, lcp.q, options.lemke);
      std::string warm_note;
      if (guess != nullptr && guess->size() != lcp.q.size())
        warm_note = "; guess ignored (wrong size for this form)";
      if (s.lcp.status == Status::solved)
        {
          s.P      = impulses_from_lcp(p, lcp, s.lcp.z);
          s.states = contact_states(p, s.P);
        }
      s.message = lcp.message + "; " + s.lcp.message + warm_note;
      // automatic: never stop at the first failure (contact_routes.h)
      if (options.form == FrictionForm::automatic && s.lcp.status != Status::solved)
        return continue_with_other_routes(p, options, s);
      return s;
    }



    ContactVerification
    verify_contact_solution(const ContactProblem &p, const std::vector<double> &P, const double tol)
    {
      check_contact_problem(p);
      const unsigned int nc = p.n_contacts, dim = p.n_directions;
      if (P.size() != static_cast<std::size_t>(nc) * dim)
        throw std::invalid_argument("verify_contact_solution: P has the wrong size");
      std::vector<double> V;
      p.W.vmult(V, P);
      double pmax = 0., vfree = 0., bmax = 0.;
      for (std::size_t i = 0; i < P.size(); ++i)
        {
          V[i] += p.free_velocity[i];
          pmax  = std::max(pmax, std::abs(P[i]));
          vfree = std::max(vfree, std::abs(p.free_velocity[i]));
        }
      for (const double b : p.gap_term)
        bmax = std::max(bmax, std::abs(b));
      const double normW = p.W.linfty_norm();
      const double sV    = vfree + bmax + normW * pmax;
      // impulse scale: ||P||, or the impulse that the free velocities call
      // for when P is (nearly) zero
      const double sP = std::max(pmax, normW > 0. ? (vfree + bmax) / normW : 0.);
      auto rel = [](const double v, const double s) { return s > 0. ? v / s : (v > 0. ? v * 1e300 : 0.); };

      ContactVerification r;
      for (unsigned int c = 0; c < nc; ++c)
        {
          const double PN = P[c * dim];
          const double wN = V[c * dim] + p.gap_term[c];
          r.max_signorini_violation =
            std::max({r.max_signorini_violation, rel(-PN, sP), rel(-wN, sV), rel(std::abs(PN * wN), sP * sV)});
          if (dim == 1)
            {
              if (PN <= tol * sP)
                ++r.n_separated;
              else
                ++r.n_sticking;
              continue;
            }
          double PT2 = 0., VT2 = 0.;
          for (unsigned int a = 1; a < dim; ++a)
            {
              PT2 += P[c * dim + a] * P[c * dim + a];
              VT2 += V[c * dim + a] * V[c * dim + a];
            }
          const double PT = std::sqrt(PT2), VT = std::sqrt(VT2);
          r.max_cone_violation = std::max(r.max_cone_violation, rel(PT - p.mu[c] * PN, sP));
          if (PN <= tol * sP)
            ++r.n_separated;
          else if (VT <= tol * sV)
            ++r.n_sticking;
          else
            {
              ++r.n_sliding;
              double dev2 = 0.;
              for (unsigned int a = 1; a < dim; ++a)
                {
                  const double e = P[c * dim + a] + p.mu[c] * PN * V[c * dim + a] / VT;
                  dev2 += e * e;
                }
              r.max_sliding_violation = std::max(r.max_sliding_violation, rel(std::sqrt(dev2), sP));
            }
        }
      r.ok = r.max_signorini_violation <= tol && r.max_cone_violation <= tol && r.max_sliding_violation <= tol;
      return r;
    }



    // @sect3{Contact states and block principal pivoting (2D friction)}
    namespace
    {
      constexpr double eps = std::numeric_limits<double>::epsilon();

      double
      linfty(const std::vector<double> &v)
      {
        double m = 0.;
        for (const double x : v)
          m = std::max(m, std::abs(x));
        return m;
      }

      /// V = V_free + W P, row by row (W is row-major).
      void
      local_velocities(const ContactProblem &p, const std::vector<double> &P, std::vector<double> &V)
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

      /// The LCP form a state guess is solved in when block pivoting is not
      /// used (or fails): the form solve_contact_problem() would choose.
      FrictionForm
      resolved_form(const ContactProblem &p, const FrictionForm requested)
      {
        if (requested != FrictionForm::automatic)
          return requested;
        if (p.n_directions == 1 || all_zero(p.mu))
          return FrictionForm::frictionless;
        return p.n_directions == 2 ? FrictionForm::klarbring : FrictionForm::facets;
      }

      /**
       * The point (P, V) of given 2D states in the variables of the facet
       * form with k = 2, d_0 = +t, d_1 = -t:
       *   z = (P_N [n_c], beta [2 n_c, contact-major], sigma [n_c]),
       *   M z + q = (V_N + b_N, sigma + V_T, sigma - V_T, mu P_N - beta_0 - beta_1),
       * w the values a complementary basis of these states carries (exact
       * zeros where the state imposes an equation), and the residual
       * w - (M z + q), computed with W only. Returns verify_with_residual().
       */
      Verification
      verify_facet_point(const ContactProblem            &p,
                         const std::vector<ContactState> &states,
                         const std::vector<double>       &P,
                         const std::vector<double>       &V,
                         const double                     tolerance_factor,
                         std::vector<double>             &z,
                         std::vector<double>             &w)
      {
        const unsigned int nc = p.n_contacts;
        const std::size_t  n  = 4 * static_cast<std::size_t>(nc);
        auto beta  = [nc](std::size_t c, std::size_t j) -> std::size_t { return nc + 2 * c + j; };
        auto sigma = [nc](std::size_t c) -> std::size_t { return 3 * std::size_t(nc) + c; };

        z.assign(n, 0.);
        w.assign(n, 0.);
        std::vector<double> q(n, 0.), residual(n, 0.), Mzq(n, 0.);
        for (unsigned int c = 0; c < nc; ++c)
          {
            const double PN = P[2 * c], PT = P[2 * c + 1], VN = V[2 * c], VT = V[2 * c + 1];
            q[c]          = p.free_velocity[2 * c] + p.gap_term[c];
            q[beta(c, 0)] = p.free_velocity[2 * c + 1];
            q[beta(c, 1)] = -p.free_velocity[2 * c + 1];

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

            for (const std::size_t i : {std::size_t(c), beta(c, 0), beta(c, 1), sigma(c)})
              w[i] = Mzq[i];
            // the equations of the state: these w are nonbasic, exactly 0
            if (closed(states[c]))
              w[c] = 0.;
            if (states[c] == ContactState::stick)
              {
                w[beta(c, 0)] = 0.;
                w[beta(c, 1)] = 0.;
              }
            for (const std::size_t i : {std::size_t(c), beta(c, 0), beta(c, 1), sigma(c)})
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
        return verify_with_residual(norm_M, q, z, w, residual, tolerance_factor);
      }

      /// -(V_free + b_N) on normal rows, -V_free on tangential rows.
      double
      right_hand_side(const ContactProblem &p, const unsigned int row)
      {
        return -p.free_velocity[row] - (row % 2 == 0 ? p.gap_term[row / 2] : 0.);
      }

      /**
       * The impulses of given states for a symmetric positive definite W. The
       * unknowns split into those of the sticking contacts, x_S = (P_N, P_T)
       * with the rows S = (N, T) of these contacts, and the normal impulses
       * x_L of the sliding contacts (P_T = slip_factor P_N):
       *   [W_SS  B] [x_S]   [r_S]     B(i, l) = W(S_i, N_l) + s_l W(S_i, T_l),
       *   [C     D] [x_L] = [r_L],    C = W(N_L, S), D likewise.
       * W_SS is a principal block of W: Cholesky, (1/3) |S|^3 flops; then
       * Z = W_SS^{-1} [B r_S], the Schur complement D - C Z_B (|L| x |L|, LU)
       * for x_L, and x_S = Z_r - Z_B x_L. (Only the upper triangle of W_SS is
       * read.) False if W_SS is not numerically positive definite or the
       * Schur complement is singular: the caller then uses one LU.
       */
      bool
      impulses_by_cholesky(const ContactProblem            &p,
                           const std::vector<ContactState> &states,
                           const std::vector<double>       &slip_factor,
                           std::vector<double>             &P)
      {
        std::vector<unsigned int> S, L;
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

        DenseMatrix Wss(ns, ns);
        for (std::size_t i = 0; i < ns; ++i)
          {
            const double *wi = p.W.row(S[i]);
            double       *ri = Wss.row(i);
            for (std::size_t j = i; j < ns; ++j)
              ri[j] = wi[S[j]];
          }
        CholeskyFactorization cholesky;
        if (!cholesky.factorize(Wss))
          return false;

        DenseMatrix Z(ns, nl + 1);
        for (std::size_t i = 0; i < ns; ++i)
          {
            const double *wi = p.W.row(S[i]);
            double       *zi = Z.row(i);
            for (std::size_t k = 0; k < nl; ++k)
              zi[k] = wi[2 * L[k]] + slip_factor[L[k]] * wi[2 * L[k] + 1];
            zi[nl] = right_hand_side(p, S[i]);
          }
        cholesky.solve(Z);

        std::vector<double> x_slip(nl);
        if (nl > 0)
          {
            DenseMatrix Schur(nl, nl);
            for (std::size_t a = 0; a < nl; ++a)
              {
                const double *wa = p.W.row(2 * L[a]);
                double       *ta = Schur.row(a);
                for (std::size_t b = 0; b < nl; ++b)
                  ta[b] = wa[2 * L[b]] + slip_factor[L[b]] * wa[2 * L[b] + 1];
                x_slip[a] = right_hand_side(p, 2 * L[a]);
                for (std::size_t i = 0; i < ns; ++i)
                  {
                    const double c = wa[S[i]];
                    if (c == 0.)
                      continue;
                    const double *zi = Z.row(i);
                    for (std::size_t b = 0; b < nl; ++b)
                      ta[b] -= c * zi[b];
                    x_slip[a] -= c * zi[nl];
                  }
              }
            LUFactorization lu;
            if (!lu.factorize(Schur))
              return false;
            lu.solve(x_slip);
          }
        for (std::size_t i = 0; i < ns; ++i)
          {
            const double *zi = Z.row(i);
            double        v  = zi[nl];
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
                        std::vector<ContactState> &states,
                        std::vector<double>       &P,
                        std::vector<double>       &V,
                        std::vector<double>       &z,
                        std::vector<double>       &w,
                        Verification              &verification,
                        unsigned int              &iterations,
                        std::string               &why)
      {
        const unsigned int nc = p.n_contacts;
        const double       tolerance_factor = options.lemke.verification_tolerance_factor;
        // The tolerance of verify_facet_point() (see verify_with_residual()),
        // at least 1e-10: a backward-stable solve meets it on any W.
        const double physical_tolerance =
          std::max(tolerance_factor * eps * 4. * std::max(nc, 1u), 1e-10);
        std::set<std::vector<ContactState>> visited;
        std::vector<unsigned int>          rows, unknown_column, unknown_contact;
        std::vector<double>                rhs, slip_factor(nc, 0.);
        iterations = 0;

        // W symmetric up to rounding (a Delassus operator computed column by
        // column is symmetric only to rounding): the systems are solved by
        // Cholesky on the sticking block (impulses_by_cholesky()); whatever
        // comes out is verified against W itself.
        double max_asymmetry = 0.;
        for (std::size_t i = 0; i < p.W.n_rows(); ++i)
          for (std::size_t j = 0; j < i; ++j)
            max_asymmetry = std::max(max_asymmetry, std::abs(p.W(i, j) - p.W(j, i)));
        const bool symmetric = max_asymmetry <= 1e3 * eps * p.W.max_abs();

        for (;;)
          {
            if (iterations >= options.max_block_pivoting_iterations)
              {
                why = "no verified point after " + std::to_string(iterations) + " block pivoting solves";
                return false;
              }
            if (!visited.insert(states).second)
              {
                why = "block pivoting returned to a set of states it had tried";
                return false;
              }
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
                slip_factor[c] = states[c] == ContactState::slip_positive ? -p.mu[c] :
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
            if (!solved && symmetric)
              solved = impulses_by_cholesky(p, states, slip_factor, P);
            if (!solved)
              {
                DenseMatrix G(m, m);
                rhs.resize(m);
                for (std::size_t r = 0; r < m; ++r)
                  {
                    const double *wi = p.W.row(rows[r]);
                    double       *gr = G.row(r);
                    for (std::size_t u = 0; u < m; ++u)
                      {
                        const unsigned int j = unknown_column[u];
                        gr[u] = (j % 2 == 0) ? wi[j] + slip_factor[unknown_contact[u]] * wi[j + 1] : wi[j];
                      }
                    rhs[r] = right_hand_side(p, rows[r]);
                  }
                LUFactorization lu;
                if (!lu.factorize(G))
                  {
                    why = "singular system for the current states";
                    return false;
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
            verification = verify_facet_point(p, states, P, V, tolerance_factor, z, w);
            if (verification.ok &&
                verify_contact_solution(p, P, physical_tolerance).ok)
              return true;

            // Change the state of every contact that violates its conditions.
            bool changed = false;
            for (unsigned int c = 0; c < nc; ++c)
              {
                const double       PN = P[2 * c], PT = P[2 * c + 1], VT = V[2 * c + 1];
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
                      states[c] = PT < 0. ? ContactState::slip_positive : ContactState::slip_negative;
                  }
                else if ((old == ContactState::slip_positive && VT < 0.) ||
                         (old == ContactState::slip_negative && VT > 0.))
                  states[c] = ContactState::stick;
                changed = changed || (states[c] != old);
              }
            if (!changed)
              {
                why = "the point of the current states satisfies every sign condition but fails "
                      "verification (relative error " + std::to_string(verification.relative_error) + ")";
                return false;
              }
          }
      }
    } // namespace



    std::vector<ContactState>
    contact_states(const ContactProblem &p, const std::vector<double> &P, const double tol)
    {
      check_contact_problem(p);
      const unsigned int nc = p.n_contacts, dim = p.n_directions;
      if (P.size() != static_cast<std::size_t>(nc) * dim)
        throw std::invalid_argument("contact_states: P has the wrong size");
      std::vector<double> V;
      local_velocities(p, P, V);
      double bmax = 0.;
      for (const double b : p.gap_term)
        bmax = std::max(bmax, std::abs(b));
      const double normW = p.W.linfty_norm(), pmax = linfty(P), vfree = linfty(p.free_velocity);
      const double sV = vfree + bmax + normW * pmax;
      const double sP = std::max(pmax, normW > 0. ? (vfree + bmax) / normW : 0.);
      const bool   frictional_2d = (dim == 2 && !all_zero(p.mu));

      std::vector<ContactState> states(nc, ContactState::open);
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
      return states;
    }



    std::vector<bool>
    guess_from_states(const ContactLCP &lcp, const std::vector<ContactState> &states)
    {
      const std::size_t nc = states.size();
      std::vector<bool> guess(lcp.q.size(), false);
      const std::size_t per_contact =
        lcp.form == FrictionForm::frictionless ? 1 :
        lcp.form == FrictionForm::klarbring    ? 3 :
                                                 lcp.n_facets + 2;
      if (lcp.q.size() != per_contact * nc)
        throw std::invalid_argument("guess_from_states: one state per contact expected");
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
              guess[nc + k * nc + c] = slip_pos || slip_neg || states[c] == ContactState::open;
              if (k == 2 && lcp.directions.size() == 2)
                {
                  // P_T = -mu P_N along V_T: facet d_1 = -t for V_T > 0
                  guess[nc + c * k + 1] = slip_pos;
                  guess[nc + c * k + 0] = slip_neg;
                }
            }
        }
      return guess;
    }



    ContactSolution
    solve_contact_problem(const ContactProblem            &p,
                          const ContactOptions            &options,
                          const std::vector<ContactState> &state_guess)
    {
      const internal::FlushSubnormalsScope flush_subnormals; // see floating_point_mode.h
      check_contact_problem(p);
      if (state_guess.size() != p.n_contacts)
        throw std::invalid_argument("solve_contact_problem: one guessed state per contact expected");
      const FrictionForm form = resolved_form(p, options.form);

      std::string why_not_block_pivoting;
      unsigned int iterations = 0;
      if (p.n_directions == 2 && form != FrictionForm::frictionless)
        {
          std::vector<ContactState> states = state_guess;
          std::vector<double>       P, V, z, w;
          Verification              verification;
          if (block_pivoting_2d(p, options, states, P, V, z, w, verification, iterations,
                                why_not_block_pivoting))
            {
              ContactSolution s;
              s.form                      = FrictionForm::facets;
              s.n_facets                  = 2;
              s.P                         = std::move(P);
              s.states                    = std::move(states);
              s.block_pivoting_iterations = iterations;
              s.lcp.status                = Status::solved;
              s.lcp.z                     = std::move(z);
              s.lcp.w                     = std::move(w);
              s.lcp.verification          = verification;
              s.lcp.start_path            = StartPath::block_pivoting;
              std::ostringstream m;
              m << "block pivoting on the contact states: verified in the facet form (k = 2) after "
                << iterations << (iterations == 1 ? " solve" : " solves");
              s.lcp.message = m.str();
              s.message     = s.lcp.message;
              return s;
            }
        }

      // Lemke's method in the requested form, warm-started from the guess.
      const ContactLCP        lcp   = assemble_contact_lcp(p, options);
      const std::vector<bool> guess = guess_from_states(lcp, state_guess);
      ContactSolution         s;
      s.form                      = lcp.form;
      s.n_facets                  = lcp.n_facets;
      s.block_pivoting_iterations = iterations;
      s.lcp                       = solve_lemke_warm(lcp.M, lcp.q, guess, options.lemke);
      if (s.lcp.status == Status::solved)
        {
          s.P      = impulses_from_lcp(p, lcp, s.lcp.z);
          s.states = contact_states(p, s.P);
        }
      s.message = lcp.message + "; " + s.lcp.message;
      if (!why_not_block_pivoting.empty())
        s.message = "block pivoting gave up (" + why_not_block_pivoting + "); " + s.message;
      // automatic: never stop at the first failure (contact_routes.h)
      if (options.form == FrictionForm::automatic && s.lcp.status != Status::solved)
        return continue_with_other_routes(p, options, s);
      return s;
    }
  } // namespace lcp
} // namespace impactfe
