#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "contact_workspace.h"
#include "floating_point_mode.h"
#include "text.h"

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
        throw std::invalid_argument(
          "contact problem: n_directions must be 1, 2 or 3");
      const std::size_t m =
        static_cast<std::size_t>(p.n_contacts) * p.n_directions;
      if (p.W.n_rows() != m || p.W.n_cols() != m)
        throw std::invalid_argument(
          "contact problem: W must be (n_contacts n_directions)^2");
      if (p.free_velocity.size() != m)
        throw std::invalid_argument(
          "contact problem: free_velocity has the wrong size");
      if (p.gap_term.size() != p.n_contacts)
        throw std::invalid_argument(
          "contact problem: gap_term must have n_contacts entries");
      if (p.n_directions > 1 && p.mu.size() != p.n_contacts)
        throw std::invalid_argument(
          "contact problem: mu must have n_contacts entries");
      for (const double v : p.W.data())
        if (!std::isfinite(v))
          throw std::invalid_argument(
            "contact problem: W has a non-finite entry");
      for (const auto *vec : {&p.free_velocity, &p.gap_term, &p.mu})
        for (const double v : *vec)
          if (!std::isfinite(v))
            throw std::invalid_argument("contact problem: non-finite data");
      for (const double v : p.mu)
        if (v < 0.)
          throw std::invalid_argument(
            "contact problem: negative friction coefficient");
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

      void
      assemble_frictionless(const ContactProblem &p, ContactLCP &lcp)
      {
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        lcp.form     = FrictionForm::frictionless;
        lcp.n_facets = 0;
        lcp.M.reinit(nc, nc);
        lcp.q.resize(nc);
        for (unsigned int a = 0; a < nc; ++a)
          {
            for (unsigned int b = 0; b < nc; ++b)
              lcp.M(a, b) = p.W(a * dim, b * dim);
            lcp.q[a] = p.free_velocity[a * dim] + p.gap_term[a];
          }
      }

      void
      assemble_facets(const ContactProblem &p,
                      const unsigned int    k_requested,
                      ContactLCP           &lcp)
      {
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        const unsigned int k = (dim == 2 ? 2 : k_requested);
        if (dim == 3 && k < 3)
          throw std::invalid_argument(
            "facet form: need at least 3 facets in 3D");
        lcp.form     = FrictionForm::facets;
        lcp.n_facets = k;
        internal::facet_directions(dim, k, lcp.directions);
        const auto        &D = lcp.directions;
        const unsigned int n = (k + 2) * nc;
        lcp.M.reinit(n, n);
        lcp.q.assign(n, 0.);
        auto N = [&](unsigned int c) { return c * dim; };
        auto T = [&](unsigned int c, unsigned int a) {
          return c * dim + 1 + a;
        };
        auto beta = [&](unsigned int c, unsigned int j) {
          return nc + c * k + j;
        };
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
      }

      /// The block (r, s) of W, r, s in {0 (normal), 1 (tangential)}, as a
      /// contiguous n_c x n_c matrix @p B.
      void
      delassus_block(const ContactProblem &p,
                     const unsigned int    r,
                     const unsigned int    s,
                     DenseMatrix          &B)
      {
        const unsigned int nc = p.n_contacts;
        B.reinit(nc, nc);
        for (unsigned int a = 0; a < nc; ++a)
          {
            const double *wa = p.W.row(2 * a + r);
            double       *ba = B.row(a);
            for (unsigned int b = 0; b < nc; ++b)
              ba[b] = wa[2 * b + s];
          }
      }

      /// C = A B, rows of C accumulated from rows of B (contiguous loops).
      void
      multiply(const DenseMatrix &A, const DenseMatrix &B, DenseMatrix &C)
      {
        const std::size_t n = A.n_rows(), k = A.n_cols(), m = B.n_cols();
        C.reinit(n, m, 0.);
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
      }

      /// Returns false if W_TT is singular. The blocks of W are copied into
      /// contiguous matrices first, so that the O(n_c^3) products run along
      /// rows. A = W_TT^{-1} is stored in lcp.W_TT_inverse.
      bool
      assemble_klarbring(const ContactProblem     &p,
                         const double              tol,
                         ContactSolver::Workspace &ws,
                         ContactLCP               &lcp)
      {
        const unsigned int nc = p.n_contacts;
        delassus_block(p, 1, 1, ws.W_TT);
        if (!ws.W_TT_lu.factorize(ws.W_TT, tol))
          return false;
        DenseMatrix &A = lcp.W_TT_inverse;
        ws.W_TT_lu.inverse(A);
        const DenseMatrix &Wnt = ws.W_NT;
        delassus_block(p, 0, 1, ws.W_NT);
        delassus_block(p, 1, 0, ws.W_TN);
        multiply(A, ws.W_TN, ws.AW_TN);
        multiply(Wnt, A, ws.W_NT_A);
        multiply(Wnt, ws.AW_TN, ws.W_NT_AW_TN);
        const DenseMatrix &AWtn = ws.AW_TN;
        const DenseMatrix &WntA = ws.W_NT_A;
        const DenseMatrix &S    = ws.W_NT_AW_TN; // W_NT A W_TN

        std::vector<double> &Vt  = ws.V_T;
        std::vector<double> &AVt = ws.AV_T;
        Vt.resize(nc);
        for (unsigned int b = 0; b < nc; ++b)
          Vt[b] = p.free_velocity[2 * b + 1];
        A.vmult(AVt, Vt);

        lcp.form     = FrictionForm::klarbring;
        lcp.n_facets = 0;
        lcp.M.reinit(3 * nc, 3 * nc);
        lcp.q.assign(3 * nc, 0.);
        for (unsigned int a = 0; a < nc; ++a)
          {
            const double *wa     = p.W.row(2 * a);
            double       *m0     = lcp.M.row(a);
            double       *m1     = lcp.M.row(nc + a);
            double       *m2     = lcp.M.row(2 * nc + a);
            double        wntavt = 0.;
            const double *s_a    = S.row(a);
            const double *wnta_a = WntA.row(a);
            const double *awtn_a = AWtn.row(a);
            const double *A_a    = A.row(a);
            const double *wnt_a  = Wnt.row(a);
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
        return true;
      }
    } // namespace



    namespace internal
    {
      void
      facet_directions(const unsigned int                dim,
                       const unsigned int                k,
                       std::vector<std::vector<double>> &D)
      {
        D.resize(dim == 2 ? 2 : k);
        if (dim == 2)
          {
            D[0].assign(1, 1.);
            D[1].assign(1, -1.);
            return;
          }
        const double pi = std::acos(-1.);
        for (unsigned int j = 0; j < k; ++j)
          {
            const double theta = 2. * pi * j / k;
            D[j].resize(2);
            D[j][0] = std::cos(theta);
            D[j][1] = std::sin(theta);
          }
      }



      FrictionForm
      resolved_form(const ContactProblem &p, const FrictionForm requested)
      {
        if (requested != FrictionForm::automatic)
          return requested;
        if (p.n_directions == 1 || all_zero(p.mu))
          return FrictionForm::frictionless;
        return p.n_directions == 2 ? FrictionForm::klarbring :
                                     FrictionForm::facets;
      }



      void
      assemble_contact_lcp(const ContactProblem     &p,
                           const ContactOptions     &options,
                           ContactSolver::Workspace &ws,
                           ContactLCP               &lcp)
      {
        const internal::FlushSubnormalsScope
          flush_subnormals; // see floating_point_mode.h
        check_contact_problem(p);
        const FrictionForm form = resolved_form(p, options.form);
        if (p.n_directions == 1 && form != FrictionForm::frictionless)
          throw std::invalid_argument(
            "contact problem with normal directions only: use the frictionless form");
        if (form == FrictionForm::klarbring && p.n_directions != 2)
          throw std::invalid_argument(
            "the Klarbring form is for 2D contact (n_directions == 2)");

        // (directions is left as it is outside the facet form, where it is
        // not read: its vectors are reused by the next facet form)
        lcp.W_TT_inverse.reinit(0, 0);
        if (form == FrictionForm::frictionless)
          {
            assemble_frictionless(p, lcp);
            lcp.message.assign("frictionless form");
            if (options.form == FrictionForm::automatic)
              lcp.message.append(p.n_directions == 1 ?
                                   " (normal directions only)" :
                                   " (all friction coefficients are 0)");
          }
        else if (form == FrictionForm::klarbring)
          {
            if (assemble_klarbring(p, options.singularity_tolerance, ws, lcp))
              lcp.message.assign("Klarbring form");
            else
              {
                lcp.W_TT_inverse.reinit(0, 0);
                assemble_facets(p, 2, lcp);
                lcp.message.assign(
                  "W_TT is singular (rank-deficient tangential block): facet form with k = 2 instead of Klarbring");
              }
          }
        else
          {
            assemble_facets(p, options.n_facets, lcp);
            internal::set_text(lcp.message, "facet form, k = %u", lcp.n_facets);
            if (p.n_directions == 2 && options.n_facets != 2)
              lcp.message.append(" (in 2D the cone has the two facets +t, -t)");
          }
      }



      void
      impulses_from_lcp(const ContactProblem      &p,
                        const ContactLCP          &lcp,
                        const std::vector<double> &z,
                        std::vector<double>       &r,
                        std::vector<double>       &P)
      {
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        if (z.size() != lcp.q.size())
          throw std::invalid_argument(
            "impulses_from_lcp: z has the wrong size");
        P.assign(static_cast<std::size_t>(nc) * dim, 0.);
        for (unsigned int c = 0; c < nc; ++c)
          P[c * dim] = z[c];
        if (lcp.form == FrictionForm::klarbring)
          {
            // P_T = A (lambda1 - lambda2 - V_free,T - W_TN P_N)
            r.resize(nc);
            for (unsigned int a = 0; a < nc; ++a)
              {
                double s =
                  z[nc + a] - z[2 * nc + a] - p.free_velocity[2 * a + 1];
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
                  P[c * dim + 1 + a] +=
                    lcp.directions[j][a] * z[nc + c * k + j];
          }
      }



      ContactVerification
      verify_contact_solution(const ContactProblem      &p,
                              const std::vector<double> &P,
                              const double               tol,
                              std::vector<double>       &V)
      {
        check_contact_problem(p);
        const unsigned int nc = p.n_contacts, dim = p.n_directions;
        if (P.size() != static_cast<std::size_t>(nc) * dim)
          throw std::invalid_argument(
            "verify_contact_solution: P has the wrong size");
        p.W.vmult(V, P);
        for (std::size_t i = 0; i < P.size(); ++i)
          V[i] += p.free_velocity[i];
        return verify_contact_velocities(
          dim, p.free_velocity, p.gap_term, p.mu, P, V, p.W.linfty_norm(), tol);
      }



      std::string
      klarbring_objection(const ContactProblem      &p,
                          const ContactOptions      &options,
                          const std::vector<double> &P,
                          std::vector<double>       &V)
      {
        const double tol =
          std::max(options.lemke.verification_tolerance_factor *
                     std::numeric_limits<double>::epsilon() * 4. *
                     std::max(p.n_contacts, 1u),
                   1e-10);
        const ContactVerification v = verify_contact_solution(p, P, tol, V);
        if (v.ok)
          return "";
        std::ostringstream m;
        m << "the Klarbring impulses fail the contact conditions (Signorini "
          << v.max_signorini_violation << ", cone " << v.max_cone_violation
          << ", sliding " << v.max_sliding_violation
          << "): W_TT^{-1} ill-conditioned";
        return m.str();
      }



      void
      finish_lemke_route(const ContactProblem     &p,
                         const ContactOptions     &options,
                         ContactSolver::Workspace &ws,
                         ContactSolution          &s)
      {
        if (s.lcp.status == Status::solved)
          {
            impulses_from_lcp(p, ws.lcp, s.lcp.z, ws.tangential_residual, s.P);
            contact_states(p, s.P, 1e-8, ws.velocity, s.states);
          }
        const bool polished = polish_2d_impulses(p, options, ws, s);
        s.message.append(ws.lcp.message);
        s.message.append("; ");
        s.message.append(s.lcp.message);
        if (polished)
          s.message.append("; impulses solved again at these contact states "
                           "(one block pivoting solve, verified)");
        // Lemke's "solved" is a verdict on the form's LCP. When P misses the
        // cone's equations and the re-solve at its states did not replace
        // it, P itself is checked, as the other routes check theirs.
        else if (s.lcp.status == Status::solved &&
                 s.form == FrictionForm::klarbring &&
                 cone_equation_miss(p, s) > 1e-12)
          {
            const std::string objection =
              klarbring_objection(p, options, s.P, ws.velocity);
            if (!objection.empty())
              {
                s.lcp.status = Status::numerical_failure;
                s.message.append("; rejected: ");
                s.message.append(objection);
                s.P.clear();
                s.states.clear();
              }
          }
        // automatic: never stop at the first failure (contact_routes.h)
        if (options.form == FrictionForm::automatic &&
            s.lcp.status != Status::solved)
          s = continue_with_other_routes(p, options, s);
      }
    } // namespace internal



    ContactLCP
    assemble_contact_lcp(const ContactProblem &p, const ContactOptions &options)
    {
      ContactSolver::Workspace ws;
      ContactLCP               lcp;
      internal::assemble_contact_lcp(p, options, ws, lcp);
      return lcp;
    }



    std::vector<double>
    impulses_from_lcp(const ContactProblem      &p,
                      const ContactLCP          &lcp,
                      const std::vector<double> &z)
    {
      std::vector<double> r, P;
      internal::impulses_from_lcp(p, lcp, z, r, P);
      return P;
    }



    ContactVerification
    verify_contact_solution(const ContactProblem      &p,
                            const std::vector<double> &P,
                            const double               tol)
    {
      std::vector<double> V;
      return internal::verify_contact_solution(p, P, tol, V);
    }



    ContactVerification
    verify_contact_velocities(const unsigned int         dim,
                              const std::vector<double> &free_velocity,
                              const std::vector<double> &gap_term,
                              const std::vector<double> &mu,
                              const std::vector<double> &P,
                              const std::vector<double> &V,
                              const double               norm_W,
                              const double               tol,
                              const unsigned int         n_facets)
    {
      const std::size_t nc = gap_term.size();
      if (P.size() != nc * dim || V.size() != nc * dim ||
          free_velocity.size() != nc * dim || (dim > 1 && mu.size() != nc))
        throw std::invalid_argument(
          "verify_contact_velocities: inconsistent sizes");
      double pmax = 0., vfree = 0., bmax = 0.;
      for (std::size_t i = 0; i < P.size(); ++i)
        {
          pmax  = std::max(pmax, std::abs(P[i]));
          vfree = std::max(vfree, std::abs(free_velocity[i]));
        }
      for (const double b : gap_term)
        bmax = std::max(bmax, std::abs(b));
      const double normW = norm_W;
      const double sV    = vfree + bmax + normW * pmax;
      // impulse scale: ||P||, or the impulse that the free velocities call
      // for when P is (nearly) zero
      const double sP =
        std::max(pmax, normW > 0. ? (vfree + bmax) / normW : 0.);
      auto rel = [](const double v, const double s) {
        return s > 0. ? v / s : (v > 0. ? v * 1e300 : 0.);
      };

      ContactVerification r;
      for (unsigned int c = 0; c < nc; ++c)
        {
          const double PN = P[c * dim];
          const double wN = V[c * dim] + gap_term[c];
          r.max_signorini_violation =
            std::max({r.max_signorini_violation,
                      rel(-PN, sP),
                      rel(-wN, sV),
                      rel(std::abs(PN * wN), sP * sV)});
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
          // the polygon of the facet form: its edges' outward normals at
          // (2 j + 1) pi / k, its support function max_j (-V_T . d_j)
          const bool   polygon     = dim == 3 && n_facets > 0;
          const double pi          = std::acos(-1.);
          double       cone_excess = PT - mu[c] * PN, support = -1e300;
          if (polygon)
            {
              cone_excess = -1e300;
              for (unsigned int j = 0; j < n_facets; ++j)
                {
                  const double a = 2. * pi * j / n_facets,
                               e = a + pi / n_facets;
                  cone_excess    = std::max(cone_excess,
                                         std::cos(e) * P[c * dim + 1] +
                                           std::sin(e) * P[c * dim + 2]);
                  support        = std::max(support,
                                     -std::cos(a) * V[c * dim + 1] -
                                       std::sin(a) * V[c * dim + 2]);
                }
              cone_excess -= mu[c] * PN * std::cos(pi / n_facets);
            }
          r.max_cone_violation =
            std::max(r.max_cone_violation, rel(cone_excess, sP));
          if (PN <= tol * sP)
            ++r.n_separated;
          else if (VT <= tol * sV)
            ++r.n_sticking;
          else
            {
              ++r.n_sliding;
              // circular: |P_T + mu P_N V_T/|V_T||; polygon: the
              // dissipation missing to its maximum over the polygon
              double deviation = 0.;
              if (polygon)
                deviation = (mu[c] * std::max(PN, 0.) * support +
                             V[c * dim + 1] * P[c * dim + 1] +
                             V[c * dim + 2] * P[c * dim + 2]) /
                            VT;
              else
                {
                  for (unsigned int a = 1; a < dim; ++a)
                    {
                      const double e =
                        P[c * dim + a] + mu[c] * PN * V[c * dim + a] / VT;
                      deviation += e * e;
                    }
                  deviation = std::sqrt(deviation);
                }
              r.max_sliding_violation =
                std::max(r.max_sliding_violation, rel(deviation, sP));
            }
        }
      r.ok = r.max_signorini_violation <= tol && r.max_cone_violation <= tol &&
             r.max_sliding_violation <= tol;
      return r;
    }



    double
    exact_cone_error(const ContactProblem &p, const std::vector<double> &P)
    {
      const unsigned int  d = p.n_directions;
      const std::size_t   m = std::size_t(d) * p.n_contacts;
      std::vector<double> q = p.free_velocity, u;
      if (P.size() != m || q.size() != m)
        throw std::invalid_argument("exact_cone_error: inconsistent sizes");
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        q[c * d] += p.gap_term[c];
      p.W.vmult(u, P);
      for (std::size_t k = 0; k < m; ++k)
        u[k] += q[k];
      return exact_cone_error(d, q, u, P, p.mu);
    }



    double
    exact_cone_error(const unsigned int         d,
                     const std::vector<double> &q,
                     const std::vector<double> &u,
                     const std::vector<double> &P,
                     const std::vector<double> &mu_of_contact)
    {
      const std::size_t m = P.size();
      if (d < 1 || d > 3 || m % d != 0 || q.size() != m || u.size() != m ||
          (d > 1 && mu_of_contact.size() < m / d))
        throw std::invalid_argument("exact_cone_error: inconsistent sizes");
      const unsigned int n_contacts = m / d;
      double             q2 = 0., P2 = 0., u2 = 0., e2 = 0.;
      for (std::size_t k = 0; k < m; ++k)
        {
          q2 += q[k] * q[k];
          P2 += P[k] * P[k];
          u2 += u[k] * u[k];
        }
      for (unsigned int c = 0; c < n_contacts; ++c)
        {
          const double *Pc = &P[c * d], *uc = &u[c * d];
          const double  mu = d > 1 ? mu_of_contact[c] : 0.;
          double        uT = 0.;
          for (unsigned int j = 1; j < d; ++j)
            uT += uc[j] * uc[j];
          uT = std::sqrt(uT);
          // x = P - u~, then its projection on the cone
          double x[3] = {Pc[0] - (uc[0] + mu * uT), 0., 0.}, xT = 0.;
          for (unsigned int j = 1; j < d; ++j)
            {
              x[j] = Pc[j] - uc[j];
              xT += x[j] * x[j];
            }
          xT             = std::sqrt(xT);
          double proj[3] = {0., 0., 0.};
          if (xT <= mu * x[0]) // inside the cone
            std::copy(x, x + d, proj);
          else if (mu * xT <= -x[0]) // inside the polar cone
            ;
          else // onto the cone's surface
            {
              const double a = (mu * xT + x[0]) / (1. + mu * mu);
              proj[0]        = a;
              for (unsigned int j = 1; j < d; ++j)
                proj[j] = xT > 0. ? mu * a * x[j] / xT : 0.;
            }
          for (unsigned int j = 0; j < d; ++j)
            e2 += (Pc[j] - proj[j]) * (Pc[j] - proj[j]);
        }
      const double scale = std::sqrt(std::max({q2, P2, u2}));
      return scale > 0. ? std::sqrt(e2) / scale : std::sqrt(e2);
    }



    // @sect3{ContactSolver: the solves of a run, with storage kept}
    ContactSolver::ContactSolver()
      : workspace(std::make_unique<Workspace>())
    {}

    ContactSolver::~ContactSolver() = default;

    ContactSolver::ContactSolver(ContactSolver &&) noexcept = default;

    ContactSolver &
    ContactSolver::operator=(ContactSolver &&) noexcept = default;



    const ContactSolution &
    ContactSolver::solution() const
    {
      return workspace->solution;
    }



    std::size_t
    ContactSolver::memory_consumption() const
    {
      return workspace->memory_consumption();
    }



    const ContactSolution &
    ContactSolver::solve(const ContactProblem    &p,
                         const ContactOptions    &options,
                         const std::vector<bool> *guess)
    {
      const internal::FlushSubnormalsScope
                       flush_subnormals; // see floating_point_mode.h
      Workspace       &ws  = *workspace;
      ContactLCP      &lcp = ws.lcp;
      ContactSolution &s   = ws.solution;
      internal::assemble_contact_lcp(p, options, ws, lcp);
      s.form                          = lcp.form;
      s.n_facets                      = lcp.n_facets;
      s.block_pivoting_iterations     = 0;
      s.block_pivoting_reused_factors = 0;
      s.P.clear();
      s.states.clear();
      const bool use_guess = guess != nullptr && guess->size() == lcp.q.size();
      const Result &result =
        use_guess ? ws.lemke.solve_warm(lcp.M, lcp.q, *guess, options.lemke) :
                    ws.lemke.solve(lcp.M, lcp.q, options.lemke);
      s.lcp = result;
      s.message.clear();
      if (guess != nullptr && !use_guess)
        s.message.assign("guess ignored (wrong size for this form); ");
      internal::finish_lemke_route(p, options, ws, s);
      return s;
    }



    ContactSolution
    solve_contact_problem(const ContactProblem    &p,
                          const ContactOptions    &options,
                          const std::vector<bool> *guess)
    {
      ContactSolver solver;
      return solver.solve(p, options, guess);
    }
  } // namespace lcp
} // namespace impactfe
