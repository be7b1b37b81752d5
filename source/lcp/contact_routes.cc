#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

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
       * nonsingular: indices are taken greedily in order of decreasing z_i
       * (relative to the largest z of the same kind of variable), and one is
       * kept only if the block stays nonsingular. Redundant contacts (W u = 0
       * for some u != 0) make the block of a regularised solution singular;
       * dropping the dependent columns keeps W P, hence the velocities.
       * O(g^4) for g guessed indices: only used for g <= max_size.
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
        std::vector<std::size_t> kept;
        for (const std::size_t i : candidates)
          {
            kept.push_back(i);
            DenseMatrix block(kept.size(), kept.size());
            for (std::size_t a = 0; a < kept.size(); ++a)
              for (std::size_t b = 0; b < kept.size(); ++b)
                block(a, b) = M(kept[a], kept[b]);
            LUFactorization lu;
            if (!lu.factorize(block, 1e-11))
              kept.pop_back();
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
            const double tol =
              std::max(options.lemke.verification_tolerance_factor *
                         std::numeric_limits<double>::epsilon() * 4. *
                         std::max(p.n_contacts, 1u),
                       1e-10);
            const ContactVerification v = verify_contact_solution(p, s.P, tol);
            if (!v.ok)
              {
                std::ostringstream m;
                m << "the Klarbring impulses fail the contact conditions (Signorini "
                  << v.max_signorini_violation << ", cone "
                  << v.max_cone_violation << ", sliding "
                  << v.max_sliding_violation << "): W_TT^{-1} ill-conditioned";
                return m.str();
              }
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
          certified = x[i] >= -tol * x_max &&
                      s <= tol * M.max_abs() * x_max * double(n);
        }
      return certified ? Status::ray_termination : Status::numerical_failure;
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
          const double scale = p.W.max_abs();
          if (scale > 0. && (scale < 0.5 || scale > 2.))
            {
              ContactProblem scaled = p;
              for (std::size_t i = 0; i < scaled.W.n_rows(); ++i)
                for (std::size_t j = 0; j < scaled.W.n_cols(); ++j)
                  scaled.W(i, j) /= scale;
              for (double &v : scaled.free_velocity)
                v /= scale;
              for (double &b : scaled.gap_term)
                b /= scale;
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

      // 3. A smaller pivot tolerance. The candidate test y_p > tol * eps *
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

      // 4. Another covering vector: a different path of Lemke's method.
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

      // 5. Regularised: W + eps max|W| I is positive definite (for a W whose
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



    ContactSolution
    continue_with_other_routes(const ContactProblem  &p,
                               const ContactOptions  &options,
                               const ContactSolution &failed)
    {
      return solve_contact_problem_by_routes(p, options, &failed).solution;
    }



    std::vector<std::vector<unsigned int>>
    independent_contact_groups(const ContactProblem &p)
    {
      const unsigned int        n = p.n_contacts, d = p.n_directions;
      std::vector<unsigned int> parent(n);
      std::iota(parent.begin(), parent.end(), 0u);
      const auto root = [&](unsigned int a) {
        while (parent[a] != a)
          a = parent[a] = parent[parent[a]];
        return a;
      };
      for (std::size_t i = 0; i < std::size_t(n) * d; ++i)
        {
          const double *row = p.W.row(i);
          for (std::size_t j = 0; j < std::size_t(n) * d; ++j)
            if (row[j] != 0.)
              parent[root(i / d)] = root(j / d);
        }
      std::vector<std::vector<unsigned int>> groups;
      std::vector<int>                       group_of_root(n, -1);
      for (unsigned int c = 0; c < n; ++c)
        {
          const unsigned int r = root(c);
          if (group_of_root[r] < 0)
            {
              group_of_root[r] = int(groups.size());
              groups.emplace_back();
            }
          groups[group_of_root[r]].push_back(c);
        }
      return groups;
    }



    GroupedContactSolution
    solve_contact_problem_by_groups(const ContactProblem &p,
                                    const ContactOptions &options)
    {
      check_contact_problem(p);
      const auto             groups = independent_contact_groups(p);
      GroupedContactSolution out;
      out.n_groups = static_cast<unsigned int>(groups.size());
      for (const auto &g : groups)
        out.largest_group =
          std::max(out.largest_group, static_cast<unsigned int>(g.size()));
      if (groups.size() <= 1)
        {
          out.solution = solve_contact_problem_by_routes(p, options).solution;
          return out;
        }

      const unsigned int d = p.n_directions;
      ContactSolution   &s = out.solution;
      s.P.assign(std::size_t(d) * p.n_contacts, 0.);
      s.states.assign(p.n_contacts, ContactState::open);
      s.lcp.status                           = Status::solved;
      s.lcp.verification.ok                  = true;
      s.lcp.verification.relative_error      = 0.;
      s.form                                 = FrictionForm::frictionless;
      unsigned int   n_solved_by_first_route = 0;
      ContactProblem sub;
      sub.n_directions = d;
      for (std::size_t k = 0; k < groups.size(); ++k)
        {
          const std::vector<unsigned int> &g = groups[k];
          const std::size_t                m = std::size_t(d) * g.size();
          sub.n_contacts = static_cast<unsigned int>(g.size());
          sub.W.reinit(m, m);
          sub.free_velocity.resize(m);
          sub.gap_term.resize(g.size());
          sub.mu.resize(g.size());
          for (std::size_t a = 0; a < g.size(); ++a)
            {
              sub.gap_term[a] = p.gap_term[g[a]];
              sub.mu[a]       = p.mu[g[a]];
              for (unsigned int i = 0; i < d; ++i)
                {
                  sub.free_velocity[a * d + i] = p.free_velocity[g[a] * d + i];
                  const double *row = p.W.row(std::size_t(g[a]) * d + i);
                  for (std::size_t b = 0; b < g.size(); ++b)
                    for (unsigned int j = 0; j < d; ++j)
                      sub.W(a * d + i, b * d + j) = row[g[b] * d + j];
                }
            }
          const RoutedContactSolution r =
            solve_contact_problem_by_routes(sub, options);
          s.lcp.pivots += r.solution.lcp.pivots;
          if (r.solution.lcp.status != Status::solved)
            {
              std::ostringstream m;
              m << "group " << k + 1 << " of " << groups.size() << " ("
                << g.size() << " contacts, the first is contact " << g[0]
                << "): " << r.solution.message;
              s.lcp.status  = r.solution.lcp.status;
              s.lcp.message = m.str();
              s.message     = s.lcp.message;
              s.P.clear();
              s.states.clear();
              s.lcp.z.clear();
              s.lcp.verification.ok = false;
              return out;
            }
          if (r.successful_route == 0)
            ++n_solved_by_first_route;
          if (r.solution.form != FrictionForm::frictionless)
            {
              s.form     = r.solution.form;
              s.n_facets = std::max(s.n_facets, r.solution.n_facets);
            }
          s.lcp.verification.ok =
            s.lcp.verification.ok && r.solution.lcp.verification.ok;
          s.lcp.verification.relative_error =
            std::max(s.lcp.verification.relative_error,
                     r.solution.lcp.verification.relative_error);
          s.lcp.z.insert(s.lcp.z.end(),
                         r.solution.lcp.z.begin(),
                         r.solution.lcp.z.end());
          for (std::size_t a = 0; a < g.size(); ++a)
            {
              s.states[g[a]] = r.solution.states[a];
              for (unsigned int i = 0; i < d; ++i)
                s.P[g[a] * d + i] = r.solution.P[a * d + i];
            }
        }
      std::ostringstream m;
      m << groups.size() << " independent groups of contacts (largest "
        << out.largest_group << " contacts) solved separately; "
        << n_solved_by_first_route << " by their first route, "
        << groups.size() - n_solved_by_first_route << " by a later one";
      s.lcp.message = m.str();
      s.message     = s.lcp.message;
      return out;
    }
  } // namespace lcp
} // namespace impactfe
