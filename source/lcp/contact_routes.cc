#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/interior_point.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <sstream>

#include "contact_workspace.h"
#include "floating_point_mode.h"

namespace impactfe
{
  namespace lcp
  {
    namespace
    {
      bool
      frictionless(const ContactProblem &p)
      {
        return p.n_directions == 1 ||
               std::all_of(p.mu.begin(), p.mu.end(), [](double m) {
                 return m == 0.;
               });
      }

      /// The form whose LCP matrix is copositive for a positive semidefinite
      /// W: W_NN itself without friction, the facet form with friction.
      ContactOptions
      copositive_form(const ContactProblem &p, const ContactOptions &options)
      {
        ContactOptions o = options;
        o.form =
          frictionless(p) ? FrictionForm::frictionless : FrictionForm::facets;
        return o;
      }

      /// Lemke on an assembled form; impulses and states if solved.
      ContactSolution
      solve_assembled(const ContactProblem &p,
                      const ContactLCP     &lcp,
                      const Result         &r)
      {
        ContactSolution s;
        s.form     = lcp.form;
        s.n_facets = lcp.n_facets;
        s.lcp      = r;
        if (r.status == Status::solved)
          {
            s.P      = impulses_from_lcp(p, lcp, r.z);
            s.states = contact_states(p, s.P);
          }
        s.message = lcp.message + "; " + r.message;
        return s;
      }

      std::string
      form_name(const ContactLCP &lcp)
      {
        if (lcp.form == FrictionForm::facets)
          return "facet form, k = " + std::to_string(lcp.n_facets);
        return to_string(lcp.form) + " form";
      }

      /**
       * The guess "z_i basic" reduced to a set whose principal block of M is
       * nonsingular: indices are taken greedily in order of decreasing z_i,
       * and one is kept only if the block stays nonsingular (its Schur
       * complement on the kept block, |d - r B^{-1} c|, above 1e-11 max|M|;
       * B^{-1} is updated by bordering, O(g^3) for g guessed indices, used
       * only for g <= max_size). Redundant contacts (W u = 0 for some
       * u != 0) make the block of a regularised or interior solution
       * singular; dropping the dependent columns keeps W P, hence the
       * velocities. With an ill-conditioned kept block a dependent column
       * can pass the test: the result is a guess, which Lemke's method
       * checks.
       */
      std::vector<bool>
      independent_guess(const DenseMatrix         &M,
                        const std::vector<double> &z,
                        const std::size_t          max_size)
      {
        std::vector<std::size_t> candidates;
        for (std::size_t i = 0; i < z.size(); ++i)
          if (z[i] > 0.)
            candidates.push_back(i);
        std::vector<bool> guess(z.size(), false);
        if (candidates.size() > max_size)
          {
            for (const std::size_t i : candidates)
              guess[i] = true;
            return guess;
          }
        std::stable_sort(candidates.begin(),
                         candidates.end(),
                         [&](std::size_t a, std::size_t b) {
                           return z[a] > z[b];
                         });
        const double             tol = 1e-11 * M.max_abs();
        const std::size_t        g   = candidates.size();
        std::vector<std::size_t> kept;
        std::vector<double>      inverse(g * g), u(g), v(g); // stride g
        for (const std::size_t i : candidates)
          {
            const std::size_t k = kept.size();
            std::fill(v.begin(), v.begin() + k, 0.);
            for (std::size_t a = 0; a < k; ++a)
              {
                double       ua = 0.;
                const double ra = M(i, kept[a]);
                for (std::size_t b = 0; b < k; ++b)
                  {
                    ua += inverse[a * g + b] * M(kept[b], i);
                    v[b] += ra * inverse[a * g + b];
                  }
                u[a] = ua;
              }
            double schur = M(i, i);
            for (std::size_t a = 0; a < k; ++a)
              schur -= M(i, kept[a]) * u[a];
            if (!(std::abs(schur) > tol))
              continue;
            for (std::size_t a = 0; a < k; ++a)
              {
                for (std::size_t b = 0; b < k; ++b)
                  inverse[a * g + b] += u[a] * v[b] / schur;
                inverse[a * g + k] = -u[a] / schur;
                inverse[k * g + a] = -v[a] / schur;
              }
            inverse[k * g + k] = 1. / schur;
            kept.push_back(i);
          }
        for (const std::size_t i : kept)
          guess[i] = true;
        return guess;
      }

    } // namespace

    Status
    lcp_feasibility(const DenseMatrix         &M,
                    const std::vector<double> &q,
                    const LemkeOptions        &options);

    namespace
    {
      /**
       * Why a verified LCP solution is not accepted, or "" if it is.
       * - Klarbring form: P_T is recovered through W_TT^{-1}; with an
       *   ill-conditioned W_TT a verified z can give impulses that fail the
       *   contact conditions. They are checked on (P, V) directly, with the
       *   tolerance of block pivoting (exact cone in 2D).
       * - Impulses 1e6 times larger than |q| / |W| (or any point of the
       *   regularised route): verify() measures against ||M|| ||z||, so a
       *   problem that a perturbation of W at the level of rounding makes
       *   solvable (singular W) passes with enormous impulses. Such a point
       *   is accepted only if the form is feasible (lcp_feasibility()).
       */
      std::string
      objection_to(const ContactProblem  &p,
                   const ContactOptions  &options,
                   const ContactSolution &s,
                   const bool             regularised)
      {
        if (s.form == FrictionForm::klarbring)
          {
            std::vector<double> V;
            const std::string   objection =
              internal::klarbring_objection(p, options, s.P, V);
            if (!objection.empty())
              return objection;
          }
        const double normW = p.W.max_abs(),
                     qmax =
                       linfty_norm(p.free_velocity) + linfty_norm(p.gap_term);
        const bool huge =
          linfty_norm(s.P) > 1e6 * (normW > 0. ? qmax / normW : 0.);
        if (regularised || huge)
          {
            ContactOptions   o   = copositive_form(p, options);
            const ContactLCP lcp = assemble_contact_lcp(p, o);
            if (lcp_feasibility(lcp.M, lcp.q, options.lemke) ==
                Status::ray_termination)
              {
                std::ostringstream m;
                m << "impulses up to " << linfty_norm(s.P)
                  << ", but the form is infeasible (feasibility test): a solution only of a problem within "
                     "rounding of this one";
                return m.str();
              }
          }
        return "";
      }
    } // namespace



    Status
    lcp_feasibility(const DenseMatrix         &M,
                    const std::vector<double> &q,
                    const LemkeOptions        &options)
    {
      const std::size_t   n = q.size();
      DenseMatrix         A(2 * n, 2 * n, 0.);
      std::vector<double> b(2 * n, 0.);
      for (std::size_t i = 0; i < n; ++i)
        {
          for (std::size_t j = 0; j < n; ++j)
            {
              A(i, n + j) = -M(j, i);
              A(n + i, j) = M(i, j);
            }
          b[n + i] = q[i];
        }
      const Result r = solve_lemke(A, b, options);
      if (r.status != Status::ray_termination)
        return r.status;
      // A ray proves infeasibility in exact arithmetic; in floating point
      // its x part must be a Farkas certificate: x >= 0, M^T x <= 0,
      // q^T x < 0, each to rounding. Otherwise nothing is proven.
      const double        eps = std::numeric_limits<double>::epsilon();
      std::vector<double> x(r.ray_z.begin() + n, r.ray_z.end());
      double              x_max = 0., qx = 0., q_max = 0.;
      for (std::size_t i = 0; i < n; ++i)
        {
          x_max = std::max(x_max, std::abs(x[i]));
          q_max = std::max(q_max, std::abs(q[i]));
          qx += q[i] * x[i];
        }
      const double tol = options.verification_tolerance_factor * eps *
                         std::max<std::size_t>(n, 1);
      bool certified = x_max > 0. && qx < -tol * q_max * x_max * double(n);
      for (std::size_t i = 0; certified && i < n; ++i)
        {
          double s = 0.;
          for (std::size_t j = 0; j < n; ++j)
            s += M(j, i) * x[j];
          certified =
            x[i] >= -tol * x_max && s <= tol * M.max_abs() * x_max * double(n);
        }
      return certified ? Status::ray_termination : Status::numerical_failure;
    }



    double
    scale_to_unit_delassus(const ContactProblem &p, ContactProblem &scaled)
    {
      const double scale = p.W.max_abs();
      if (!(scale > 0.) || (scale >= 0.5 && scale <= 2.))
        return 1.;
      scaled = p;
      for (std::size_t i = 0; i < scaled.W.n_rows(); ++i)
        for (std::size_t j = 0; j < scaled.W.n_cols(); ++j)
          scaled.W(i, j) /= scale;
      for (double &v : scaled.free_velocity)
        v /= scale;
      for (double &b : scaled.gap_term)
        b /= scale;
      return scale;
    }



    RoutedContactSolution
    solve_contact_problem_by_routes(const ContactProblem  &p,
                                    const ContactOptions  &options,
                                    const ContactSolution *first_attempt)
    {
      const internal::FlushSubnormalsScope
        flush_subnormals; // see floating_point_mode.h
      check_contact_problem(p);

      // The LCP forms put W beside blocks of 1 and mu; a W far from unit
      // size (rigid bodies of small mass give 1e-5, a stiff FE mesh 1e3)
      // makes Lemke's pivot test and the feasibility test compare numbers of
      // different scales: seen as false rays (z0 < 0) and a false
      // "infeasible" on LMGC90's PerioBox problem. V = W P + q and V / s =
      // (W / s) P + q / s have the same impulses, so the problem is solved
      // with W scaled to max |W| = 1; only velocities (w, sigma) are scaled.
      if (first_attempt == nullptr)
        {
          ContactProblem scaled;
          const double   scale = scale_to_unit_delassus(p, scaled);
          if (scale != 1.)
            {
              RoutedContactSolution r =
                solve_contact_problem_by_routes(scaled, options);
              std::ostringstream m;
              m << "W and q scaled by 1/" << scale << ": "
                << r.solution.message;
              r.solution.message = m.str();
              return r;
            }
        }

      RoutedContactSolution out;
      unsigned int          total_pivots = 0;

      // Record one route; true if it gave a verified solution.
      auto record = [&](const std::string &kind,
                        const std::string &route,
                        ContactSolution  &&s) {
        RouteAttempt a;
        a.kind    = kind;
        a.route   = route;
        a.status  = s.lcp.status;
        a.pivots  = s.lcp.pivots;
        a.message = s.lcp.message;
        total_pivots += s.lcp.pivots;
        if (s.lcp.status == Status::solved)
          {
            const std::string objection =
              objection_to(p, options, s, kind == "regularised");
            if (!objection.empty())
              {
                a.status      = Status::numerical_failure;
                a.message     = "rejected: " + objection;
                s.lcp.status  = Status::numerical_failure;
                s.lcp.message = a.message;
                s.P.clear();
                s.states.clear();
                s.lcp.z.clear();
                s.lcp.w.clear();
              }
          }
        out.attempts.push_back(a);
        out.solution = std::move(s);
        if (out.solution.lcp.status == Status::solved)
          {
            out.successful_route = static_cast<int>(out.attempts.size()) - 1;
            return true;
          }
        return false;
      };
      auto finish = [&]() {
        std::ostringstream m;
        for (std::size_t i = 0; i < out.attempts.size(); ++i)
          {
            const RouteAttempt &a = out.attempts[i];
            m << (i ? "; " : "") << "route " << i + 1 << " (" << a.route
              << "): " << to_string(a.status);
            if (a.status != Status::infeasible)
              m << " after " << a.pivots
                << (a.pivots == 1 ? " pivot" : " pivots");
            if (a.status != Status::solved && !a.message.empty())
              m << " [" << a.message << "]";
          }
        out.solution.lcp.pivots = total_pivots;
        out.solution.message    = m.str();
        return out;
      };

      // 1. The requested form (or what the caller already tried).
      const ContactLCP first = assemble_contact_lcp(p, options);
      if (first_attempt != nullptr)
        {
          ContactSolution s = *first_attempt;
          s.lcp.message     = s.message;
          if (record("requested", "as requested", std::move(s)))
            return finish();
        }
      else if (record(
                 "requested",
                 form_name(first) +
                   (first.message.find("singular") != std::string::npos ?
                      " (W_TT singular: facets instead of Klarbring)" :
                      ""),
                 solve_assembled(p,
                                 first,
                                 solve_lemke(first.M, first.q, options.lemke))))
        return finish();

      // 2. The copositive form, if that is not what route 1 solved.
      const ContactOptions copositive = copositive_form(p, options);
      const ContactLCP     lcp        = assemble_contact_lcp(p, copositive);
      if (first_attempt != nullptr || lcp.form != first.form ||
          lcp.n_facets != first.n_facets)
        if (record("copositive",
                   form_name(lcp),
                   solve_assembled(p,
                                   lcp,
                                   solve_lemke(lcp.M, lcp.q, options.lemke))))
          return finish();

      // 3. The interior point method on the copositive form: no pivots, so
      //    the degenerate forms of rank-deficient W (redundant contacts) do
      //    not stop it. Where its point misses the verification (a contact
      //    degenerate at the solution keeps both z_i and w_i near sqrt(nu)),
      //    its guess z_i > w_i starts Lemke's method on the form.
      //    A verified point is accurate to the verification's 1e-8 only,
      //    which stops the exact cone's facet re-alignment short: on forms
      //    of at most largest_polished rows Lemke warm-started from it (its
      //    independent basic columns) looks for the exact basic solution,
      //    and where that fails, routes 4 and 5 do before the point is
      //    taken (BoxesStack1 of Siconos' collection: route 4 solves it).
      ContactSolution       verified_interior_point;
      constexpr std::size_t largest_polished = 4000;
      {
        ContactSolution s = solve_facet_form_by_interior_point(p, copositive);
        if (!s.lcp.z.empty() && (s.lcp.status != Status::solved ||
                                 lcp.q.size() <= largest_polished))
          {
            std::vector<double> basic(s.lcp.z.size(), 0.);
            for (std::size_t i = 0; i < basic.size(); ++i)
              if (s.lcp.z[i] > s.lcp.w[i])
                basic[i] = s.lcp.z[i];
            const std::vector<bool> guess =
              independent_guess(lcp.M, basic, largest_polished / 2);
            // routes 1 and 2 were the cold solve
            LemkeOptions warm_only  = options.lemke;
            warm_only.cold_fallback = false;
            ContactSolution warm =
              solve_assembled(p,
                              lcp,
                              solve_lemke_warm(lcp.M, lcp.q, guess, warm_only));
            warm.lcp.message =
              s.message + "; Lemke warm-started from it: " + warm.lcp.message;
            if (s.lcp.status != Status::solved)
              s = std::move(warm);
            else if (warm.lcp.status == Status::solved &&
                     objection_to(p, options, warm, false).empty())
              {
                warm.lcp.pivots += s.lcp.pivots;
                s = std::move(warm);
              }
            else if (objection_to(p, options, s, false).empty())
              {
                RouteAttempt a;
                a.kind   = "interior-point";
                a.route  = form_name(lcp) + ", interior point";
                a.status = Status::solved;
                a.pivots = warm.lcp.pivots;
                a.message =
                  "verified, kept while routes 4 and 5 look for the exact basic solution";
                total_pivots += warm.lcp.pivots;
                out.attempts.push_back(a);
                verified_interior_point = std::move(s);
              }
          }
        if (verified_interior_point.lcp.status != Status::solved &&
            record("interior-point",
                   form_name(lcp) + ", interior point",
                   std::move(s)))
          return finish();
      }
      const auto take_interior_point = [&]() {
        out.successful_route = -1;
        for (std::size_t i = 0; i < out.attempts.size(); ++i)
          if (out.attempts[i].kind == "interior-point")
            out.successful_route = static_cast<int>(i);
        out.solution = std::move(verified_interior_point);
        return finish();
      };

      // 4. A smaller pivot tolerance. The candidate test y_p > tol * eps *
      //     ||a|| * max|B^{-1}| scales with the largest entry of the basis
      //     inverse: near a singular basis (W singular) true positive
      //     entries fall below it and Lemke's method reports a ray that is
      //     not there. Whatever this run returns is verified like any other.
      {
        LemkeOptions o           = options.lemke;
        o.pivot_tolerance_factor = 1e-2 * options.lemke.pivot_tolerance_factor;
        if (record("small-tolerance",
                   form_name(lcp) + ", pivot tolerance / 100",
                   solve_assembled(p, lcp, solve_lemke(lcp.M, lcp.q, o))))
          return finish();
      }

      // 5. Another covering vector: a different path of Lemke's method.
      {
        LemkeOptions o = options.lemke;
        o.covering_vector.resize(lcp.q.size());
        for (std::size_t i = 0; i < lcp.q.size(); ++i)
          o.covering_vector[i] =
            1. + 0.5 * std::sin(1. + static_cast<double>(i));
        if (record("covering",
                   form_name(lcp) + ", covering vector 1 + sin(1 + i) / 2",
                   solve_assembled(p, lcp, solve_lemke(lcp.M, lcp.q, o))))
          return finish();
      }
      if (verified_interior_point.lcp.status == Status::solved)
        return take_interior_point();

      // 6. Regularised: W + eps max|W| I is positive definite (for a W whose
      //    symmetric part is semidefinite up to its asymmetry), so Lemke's
      //    method processes its copositive form; its basis, reduced to
      //    independent columns, starts Lemke on the original form.
      {
        const double tau =
          std::max(p.W.max_abs(), std::numeric_limits<double>::min());
        const std::size_t m         = p.W.n_rows();
        double            asymmetry = 0.;
        for (std::size_t i = 0; i < m; ++i)
          for (std::size_t j = 0; j < i; ++j)
            asymmetry = std::max(asymmetry, std::abs(p.W(i, j) - p.W(j, i)));
        for (const double base : {1e-10, 1e-6})
          {
            const double eps = base + static_cast<double>(m) * asymmetry / tau;
            ContactProblem regularised = p;
            for (std::size_t i = 0; i < m; ++i)
              regularised.W(i, i) += eps * tau;
            const ContactLCP rlcp =
              assemble_contact_lcp(regularised, copositive);
            LemkeOptions o = options.lemke;
            o.pivot_tolerance_factor =
              1e-2 * options.lemke.pivot_tolerance_factor;
            const Result       r = solve_lemke(rlcp.M, rlcp.q, o);
            std::ostringstream name;
            name << form_name(lcp) << " warm-started from W + " << eps
                 << " max|W| I";
            if (r.status != Status::solved)
              {
                ContactSolution s;
                s.lcp         = r;
                s.lcp.message = "the regularised problem: " + r.message;
                record("regularised", name.str(), std::move(s));
                continue;
              }
            const std::vector<bool> guess = independent_guess(lcp.M, r.z, 400);
            ContactSolution         s     = solve_assembled(
              p, lcp, solve_lemke_warm(lcp.M, lcp.q, guess, options.lemke));
            s.lcp.pivots += r.pivots;
            if (record("regularised", name.str(), std::move(s)))
              return finish();
          }
      }

      // No route solved it: is the copositive form feasible at all?
      const Status feasibility = lcp_feasibility(lcp.M, lcp.q, options.lemke);
      if (feasibility == Status::ray_termination)
        {
          ContactSolution s;
          s.form       = lcp.form;
          s.n_facets   = lcp.n_facets;
          s.lcp.status = Status::infeasible;
          s.lcp.message =
            "no z >= 0 with M z + q >= 0 in the " + form_name(lcp) +
            " (ray of Lemke's method on the skew-symmetric LCP of that linear program): "
            "the problem has no solution";
          record("feasibility", "feasibility test", std::move(s));
        }
      else
        {
          RouteAttempt a;
          a.kind   = "feasibility";
          a.route  = "feasibility test";
          a.status = feasibility;
          a.message =
            feasibility == Status::solved ?
              "the " + form_name(lcp) + " is feasible: not proven unsolvable" :
              "undecided";
          out.attempts.push_back(a);
        }
      return finish();
    }



    // The other routes on W scaled to max |W| = 1, as for a cold routed
    // solve (the impulses of the failed attempt do not depend on the
    // scale, so it is recorded against the scaled problem as it is).
    ContactSolution
    continue_with_other_routes(const ContactProblem  &p,
                               const ContactOptions  &options,
                               const ContactSolution &failed)
    {
      ContactProblem scaled;
      const double   scale = scale_to_unit_delassus(p, scaled);
      if (scale == 1.)
        return solve_contact_problem_by_routes(p, options, &failed).solution;
      ContactSolution s =
        solve_contact_problem_by_routes(scaled, options, &failed).solution;
      std::ostringstream m;
      m << "W and q scaled by 1/" << scale << ": " << s.message;
      s.message = m.str();
      return s;
    }



    namespace
    {
      /// The groups of the contacts @p contacts (sorted) of @p p that W
      /// does not couple, counting only W's entries among them.
      std::vector<std::vector<unsigned int>>
      groups_among(const ContactProblem            &p,
                   const std::vector<unsigned int> &contacts)
      {
        const unsigned int        d = p.n_directions;
        const std::size_t         n = contacts.size();
        std::vector<unsigned int> parent(n);
        std::iota(parent.begin(), parent.end(), 0u);
        const auto root = [&](unsigned int a) {
          while (parent[a] != a)
            a = parent[a] = parent[parent[a]];
          return a;
        };
        for (std::size_t a = 0; a < n; ++a)
          for (unsigned int i = 0; i < d; ++i)
            {
              const double *row = p.W.row(std::size_t(contacts[a]) * d + i);
              for (std::size_t b = 0; b < n; ++b)
                for (unsigned int j = 0; j < d; ++j)
                  if (row[std::size_t(contacts[b]) * d + j] != 0.)
                    parent[root(a)] = root(b);
            }
        std::vector<std::vector<unsigned int>> groups;
        std::vector<int>                       group_of_root(n, -1);
        for (std::size_t a = 0; a < n; ++a)
          {
            const unsigned int r = root(a);
            if (group_of_root[r] < 0)
              {
                group_of_root[r] = int(groups.size());
                groups.emplace_back();
              }
            groups[group_of_root[r]].push_back(contacts[a]);
          }
        return groups;
      }
    } // namespace



    std::vector<std::vector<unsigned int>>
    independent_contact_groups(const ContactProblem &p)
    {
      std::vector<unsigned int> all(p.n_contacts);
      std::iota(all.begin(), all.end(), 0u);
      return groups_among(p, all);
    }



    void
    restrict_contact_problem(const ContactProblem            &p,
                             const std::vector<unsigned int> &contacts,
                             ContactProblem                  &sub)
    {
      const unsigned int d = p.n_directions;
      const std::size_t  m = std::size_t(d) * contacts.size();
      sub.n_directions     = d;
      sub.n_contacts       = static_cast<unsigned int>(contacts.size());
      sub.W.reinit(m, m);
      sub.free_velocity.resize(m);
      sub.gap_term.resize(contacts.size());
      sub.mu.resize(contacts.size());
      for (std::size_t a = 0; a < contacts.size(); ++a)
        {
          sub.gap_term[a] = p.gap_term[contacts[a]];
          sub.mu[a]       = p.mu[contacts[a]];
          for (unsigned int i = 0; i < d; ++i)
            {
              sub.free_velocity[a * d + i] =
                p.free_velocity[contacts[a] * d + i];
              const double *row = p.W.row(std::size_t(contacts[a]) * d + i);
              for (std::size_t b = 0; b < contacts.size(); ++b)
                for (unsigned int j = 0; j < d; ++j)
                  sub.W(a * d + i, b * d + j) = row[contacts[b] * d + j];
            }
        }
    }



    GroupedContactSolution
    solve_contact_problem_by_groups(const ContactProblem &p,
                                    const ContactOptions &options)
    {
      check_contact_problem(p);
      const unsigned int d = p.n_directions, n = p.n_contacts;
      const double       tol = options.lemke.verification_tolerance_factor *
                         std::numeric_limits<double>::epsilon() *
                         std::max(n, 1u);
      GroupedContactSolution out;
      ContactSolution       &s = out.solution;

      // In a group of more than large_group contacts only those that
      // approach without impulse (V_free,N + b_N < 0) start as candidates;
      // one that the impulses push in (V_N + b_N < 0 with P = 0) joins them
      // and the candidates are solved again. Contacts left out have P = 0
      // and V_N + b_N >= 0: open, which satisfies every condition, so the
      // answer is the whole problem's. Smaller groups are solved whole, in
      // one round (their LCPs are cheap; rounds would cost more).
      // In 3D a large group is first tried whole by the interior point
      // method (interior_point.h), where its dense matrix of the order of W
      // is affordable: the facet form is (k + 2) n_c rows against that
      // method's 3 n_c, its cost does not depend on pivots, and the
      // candidates' subproblems of the rounds can be harder than the whole
      // (KaplasTower at 8 facets: a round of 507 of its 570 contacts defeats
      // both methods, the whole takes 8 interior point iterations). Its
      // answer is verified to 1e-8; in 2D (granular files) the rounds keep
      // Lemke's exact basic solutions.
      constexpr std::size_t large_group = 500, largest_dense = 6000;
      std::vector<char>     candidate(n, true);
      const auto            all_groups = independent_contact_groups(p);
      // Groups already solved, by their contacts: a group whose contacts
      // did not change between rounds keeps its answer.
      struct SolvedGroup
      {
        ContactSolution solution;
        bool            first_route = false;
      };
      std::map<std::vector<unsigned int>, SolvedGroup> solved;
      std::vector<unsigned int>                        C;
      ContactProblem                                   group;
      for (const auto &g : all_groups)
        if (g.size() > large_group)
          {
            if (d == 3 && std::size_t(d) * g.size() <= largest_dense)
              {
                restrict_contact_problem(p, g, group);
                ContactSolution whole = solve_facet_form_by_interior_point(
                  group, copositive_form(group, options));
                if (whole.lcp.status == Status::solved)
                  {
                    solved.emplace(g, SolvedGroup{std::move(whole), true});
                    continue;
                  }
              }
            for (const unsigned int c : g)
              candidate[c] = p.free_velocity[c * d] + p.gap_term[c] < 0.;
          }
      std::vector<ContactState> guess, last_states;
      unsigned int              total_pivots = 0, n_first_route = 0;
      for (;;)
        {
          ++out.candidate_rounds;
          C.clear();
          for (unsigned int c = 0; c < n; ++c)
            if (candidate[c])
              C.push_back(c);
          s = ContactSolution();
          s.P.assign(std::size_t(d) * n, 0.);
          s.states.assign(n, ContactState::open);
          s.lcp.status                      = Status::solved;
          s.lcp.verification.ok             = true;
          s.lcp.verification.relative_error = 0.;
          s.form                            = FrictionForm::frictionless;
          // with every contact a candidate the groups are the whole
          // problem's, found above
          std::vector<std::vector<unsigned int>> among;
          if (C.size() < n)
            among = groups_among(p, C);
          const auto &groups = C.size() < n ? among : all_groups;
          out.n_candidates   = static_cast<unsigned int>(C.size());
          out.n_groups       = static_cast<unsigned int>(groups.size());
          out.largest_group  = 0;
          n_first_route      = 0;
          for (std::size_t k = 0; k < groups.size(); ++k)
            {
              const std::vector<unsigned int> &g = groups[k];
              out.largest_group                  = std::max(out.largest_group,
                                           static_cast<unsigned int>(g.size()));
              const std::vector<unsigned int> &contacts = g;
              auto                             known    = solved.find(contacts);
              if (known == solved.end())
                {
                  restrict_contact_problem(p, contacts, group);
                  // first round: cold, by the routes; later rounds start
                  // from the last round's states (new candidates, pushed
                  // in: stick), and fall back on the routes
                  RoutedContactSolution r;
                  if (out.candidate_rounds == 1)
                    r = solve_contact_problem_by_routes(group, options);
                  else
                    {
                      guess.resize(contacts.size());
                      for (std::size_t a = 0; a < contacts.size(); ++a)
                        guess[a] =
                          last_states[contacts[a]] == ContactState::open ?
                            ContactState::stick :
                            last_states[contacts[a]];
                      r.solution = solve_contact_problem(group, options, guess);
                      r.successful_route =
                        r.solution.lcp.status == Status::solved ? 0 : -1;
                    }
                  total_pivots += r.solution.lcp.pivots;
                  if (r.solution.lcp.status != Status::solved)
                    {
                      std::ostringstream m;
                      m << "group " << k + 1 << " of " << groups.size() << " ("
                        << g.size() << " contacts, the first is contact "
                        << contacts[0] << "): " << r.solution.message;
                      s.lcp.status  = r.solution.lcp.status;
                      s.lcp.pivots  = total_pivots;
                      s.lcp.message = m.str();
                      s.message     = s.lcp.message;
                      s.P.clear();
                      s.states.clear();
                      s.lcp.z.clear();
                      s.lcp.verification.ok = false;
                      return out;
                    }
                  known = solved
                            .emplace(contacts,
                                     SolvedGroup{std::move(r.solution),
                                                 r.successful_route == 0})
                            .first;
                }
              const ContactSolution &r = known->second.solution;
              n_first_route += known->second.first_route;
              if (r.form != FrictionForm::frictionless)
                {
                  s.form     = r.form;
                  s.n_facets = std::max(s.n_facets, r.n_facets);
                }
              s.lcp.verification.ok =
                s.lcp.verification.ok && r.lcp.verification.ok;
              s.lcp.verification.relative_error =
                std::max(s.lcp.verification.relative_error,
                         r.lcp.verification.relative_error);
              s.lcp.z.insert(s.lcp.z.end(), r.lcp.z.begin(), r.lcp.z.end());
              for (std::size_t a = 0; a < contacts.size(); ++a)
                {
                  s.states[contacts[a]] = r.states[a];
                  for (unsigned int i = 0; i < d; ++i)
                    s.P[contacts[a] * d + i] = r.P[a * d + i];
                }
            }
          s.lcp.pivots = total_pivots;
          last_states  = s.states;

          // the contacts left out must not penetrate: V_N = (W P)_N + q_N
          // with P nonzero on the candidates' rows only
          const double scale = linfty_norm(p.free_velocity) +
                               linfty_norm(p.gap_term) +
                               p.W.max_abs() * linfty_norm(s.P);
          bool added = false;
          for (unsigned int c = 0; c < n && C.size() < n; ++c)
            if (!candidate[c])
              {
                const double *row = p.W.row(std::size_t(c) * d);
                double        VN  = p.free_velocity[c * d] + p.gap_term[c];
                for (const unsigned int b : C)
                  for (unsigned int j = 0; j < d; ++j)
                    VN += row[b * d + j] * s.P[b * d + j];
                if (VN < -tol * scale)
                  candidate[c] = added = true;
              }
          if (!added)
            break;
        }
      std::ostringstream m;
      m << out.n_candidates << " of " << n
        << " contacts could touch (candidates after " << out.candidate_rounds
        << (out.candidate_rounds == 1 ? " round" : " rounds") << "), in "
        << out.n_groups << " independent groups (largest " << out.largest_group
        << " contacts) solved separately; " << n_first_route
        << " by their first route, " << out.n_groups - n_first_route
        << " by a later one";
      s.lcp.message = m.str();
      s.message     = s.lcp.message;
      return out;
    }


    Result
    solve_lcp(const DenseMatrix         &M,
              const std::vector<double> &q,
              const bool                 warm,
              const LemkeOptions        &options)
    {
      Result r;
      if (warm)
        {
          std::vector<bool> guess(q.size());
          for (std::size_t i = 0; i < q.size(); ++i)
            guess[i] = q[i] < 0.;
          r = solve_lemke_warm(M, q, guess, options);
        }
      else
        r = solve_lemke(M, q, options);
      if (r.status == Status::ray_termination &&
          lcp_feasibility(M, q, options) == Status::ray_termination)
        {
          r.status = Status::infeasible;
          r.message += "; no z >= 0 with M z + q >= 0 (Lemke's ray on the LCP "
                       "of that linear program): the LCP has no solution";
        }
      return r;
    }
  } // namespace lcp
} // namespace impactfe
