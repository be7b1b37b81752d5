#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/exact_cone.h>
#include <impactfe/lcp/interior_point.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace impactfe
{
  namespace lcp
  {
    std::string
    to_string(const ConeModel model)
    {
      return model == ConeModel::exact ? "exact" : "facets";
    }



    std::string
    to_string(const ExactConeRoute route)
    {
      switch (route)
        {
          case ExactConeRoute::facets:
            return "facets";
          case ExactConeRoute::facets_then_interior_point:
            return "facets-then-interior-point";
          case ExactConeRoute::interior_point_then_facets:
            return "interior-point-then-facets";
          case ExactConeRoute::interior_point:
            return "interior-point";
        }
      return "";
    }



    ExactConeRoute
    exact_cone_route_from_string(const std::string &name)
    {
      for (const ExactConeRoute route :
           {ExactConeRoute::facets,
            ExactConeRoute::facets_then_interior_point,
            ExactConeRoute::interior_point_then_facets,
            ExactConeRoute::interior_point})
        if (name == to_string(route))
          return route;
      throw std::invalid_argument(
        "exact cone route '" + name +
        "' is none of facets, facets-then-interior-point, "
        "interior-point-then-facets, interior-point");
    }



    ConeModel
    cone_model_from_string(const std::string &name)
    {
      if (name == "exact")
        return ConeModel::exact;
      if (name == "facets")
        return ConeModel::facets;
      throw std::invalid_argument("friction cone '" + name +
                                  "' is neither 'exact' nor 'facets'");
    }



    // @sect3{Rotated tangent frames}
    // Contact c's frame turned by alpha_c about its normal: the tangent
    // columns of W, then its tangent rows, are combined in place.
    void
    rotate_tangent_frames(const ContactProblem      &p,
                          const std::vector<double> &angles,
                          ContactProblem            &r)
    {
      if (p.n_directions != 3 || angles.size() != p.n_contacts)
        throw std::invalid_argument(
          "rotate_tangent_frames: needs a 3D problem and one angle per "
          "contact");
      r.n_directions      = p.n_directions;
      r.n_contacts        = p.n_contacts;
      r.W                 = p.W;
      r.free_velocity     = p.free_velocity;
      r.gap_term          = p.gap_term;
      r.mu                = p.mu;
      const std::size_t m = r.W.n_rows();
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        {
          const double      cs = std::cos(angles[c]), sn = std::sin(angles[c]);
          const std::size_t t1 = 3 * c + 1, t2 = 3 * c + 2;
          for (std::size_t i = 0; i < m; ++i) // W R
            {
              const double a = r.W(i, t1), b = r.W(i, t2);
              r.W(i, t1) = cs * a + sn * b;
              r.W(i, t2) = -sn * a + cs * b;
            }
          double *row1 = r.W.row(t1), *row2 = r.W.row(t2); // R^T (W R)
          for (std::size_t j = 0; j < m; ++j)
            {
              const double a = row1[j], b = row2[j];
              row1[j] = cs * a + sn * b;
              row2[j] = -sn * a + cs * b;
            }
          const double a = r.free_velocity[t1], b = r.free_velocity[t2];
          r.free_velocity[t1] = cs * a + sn * b;
          r.free_velocity[t2] = -sn * a + cs * b;
        }
    }



    namespace
    {
      /// P = R P' for every contact, in place.
      void
      rotate_back(const std::vector<double> &angles, std::vector<double> &P)
      {
        for (std::size_t c = 0; c < angles.size(); ++c)
          {
            const double cs = std::cos(angles[c]), sn = std::sin(angles[c]);
            const double a = P[3 * c + 1], b = P[3 * c + 2];
            P[3 * c + 1] = cs * a - sn * b;
            P[3 * c + 2] = sn * a + cs * b;
          }
      }

      /// @p x wrapped into (-h, h], h = period/2.
      double
      wrap(const double x, const double period)
      {
        return x - period * std::ceil(x / period - 0.5);
      }

      /**
       * Newton's method on the circular-cone equations at the contact
       * states of @p P, a facet answer whose polygon has its edges at
       * @p edge = cos(pi/k) of the circle's radius: open P_c = 0; closed
       * without friction V_N + b_N = 0, P_T = 0; sticking V_c + b_c = 0;
       * sliding V_N + b_N = 0 and P_T + mu P_N V_T/|V_T| = 0. From an iterate
       * of the facet iteration that has the right states it converges
       * quadratically. Returns true
       * and the new impulses in @p P only if the states hold at the answer
       * (P_N >= 0, open contacts separate, sticking ones inside the cone)
       * and its exact_cone_residual() is <= @p tolerance. Redundant contacts
       * make the Jacobian singular; the Levenberg-Marquardt steps then go
       * to one of the (equally valid) solutions.
       */
      bool
      polish_on_circular_cone(const ContactProblem &p,
                              std::vector<double>  &P,
                              const double          edge,
                              const double          tolerance)
      {
        const unsigned int  nc = p.n_contacts;
        const std::size_t   m  = 3 * std::size_t(nc);
        std::vector<double> V;
        auto                velocities = [&](const std::vector<double> &x) {
          p.W.vmult(V, x);
          for (std::size_t i = 0; i < m; ++i)
            V[i] += p.free_velocity[i] + (i % 3 == 0 ? p.gap_term[i / 3] : 0.);
        };
        velocities(P);
        double scale_P = 0., scale_V = 0.;
        for (std::size_t i = 0; i < m; ++i)
          {
            scale_P = std::max(scale_P, std::abs(P[i]));
            scale_V =
              std::max(scale_V, std::abs(V[i]) + std::abs(p.free_velocity[i]));
          }
        enum class State
        {
          open,
          closed,
          stick,
          slide
        };
        // A contact slides if it moves and its P_T is on the boundary of
        // its polygon: inside it, complementarity holds V_T at 0 and what
        // is left of V_T is round-off.
        std::vector<State> state(nc);
        for (unsigned int c = 0; c < nc; ++c)
          {
            const double *Pc = &P[3 * c], *Vc = &V[3 * c];
            state[c] = Pc[0] <= 1e-9 * scale_P ? State::open :
                       p.mu[c] <= 0.           ? State::closed :
                       std::hypot(Vc[1], Vc[2]) > 1e-9 * scale_V &&
                           std::hypot(Pc[1], Pc[2]) >=
                             (1. - 1e-6) * edge * p.mu[c] * Pc[0] ?
                                       State::slide :
                                       State::stick;
          }

        std::vector<double> x = P, F(m), step(m);
        DenseMatrix         J(m, m), JtJ(m, m);
        LUFactorization     lu;
        for (unsigned int newton = 0; newton < 20; ++newton)
          {
            velocities(x);
            J.reinit(m, m);
            double residual = 0.;
            for (unsigned int c = 0; c < nc; ++c)
              {
                const std::size_t r = 3 * c;
                for (unsigned int d = 0; d < 3; ++d) // rows of P_c = 0
                  {
                    F[r + d]        = x[r + d];
                    J(r + d, r + d) = 1.;
                  }
                if (state[c] == State::open)
                  continue;
                const unsigned int velocity_rows =
                  state[c] == State::closed || state[c] == State::slide ? 1 : 3;
                // Velocity rows times rho_c = 1/W_cc: every row of F is in
                // impulse units, so that J^T J is not dominated by one kind.
                const double w_cc =
                  (p.W(r, r) + p.W(r + 1, r + 1) + p.W(r + 2, r + 2)) / 3.;
                const double rho = w_cc > 0. ? 1. / w_cc : 1.;
                for (unsigned int d = 0; d < velocity_rows; ++d)
                  {
                    F[r + d]    = rho * V[r + d];
                    double *row = J.row(r + d);
                    for (std::size_t j = 0; j < m; ++j)
                      row[j] = rho * p.W(r + d, j);
                  }
                if (state[c] == State::slide)
                  {
                    const double vT = std::hypot(V[r + 1], V[r + 2]);
                    if (vT <= 0.)
                      return false;
                    const double u[2] = {V[r + 1] / vT, V[r + 2] / vT};
                    const double mu   = p.mu[c];
                    for (unsigned int a = 0; a < 2; ++a)
                      {
                        F[r + 1 + a] = x[r + 1 + a] + mu * x[r] * u[a];
                        double *row  = J.row(r + 1 + a);
                        row[r] += mu * u[a];
                        // mu P_N (I - u u^T)/|V_T| times the rows of V_T
                        for (unsigned int b = 0; b < 2; ++b)
                          {
                            const double g =
                              mu * x[r] * ((a == b ? 1. : 0.) - u[a] * u[b]) /
                              vT;
                            const double *w = p.W.row(r + 1 + b);
                            for (std::size_t j = 0; j < m; ++j)
                              row[j] += g * w[j];
                          }
                      }
                  }
              }
            for (const double f : F)
              residual = std::max(residual, std::abs(f));
            if (residual <= 1e-15 * scale_P)
              break;
            // The Levenberg-Marquardt step (J^T J + lambda I) dx = -J^T F:
            // with redundant contacts J is singular but the equations are
            // consistent, and the step goes to one of their solutions.
            double largest = 0.;
            for (std::size_t i = 0; i < m; ++i)
              {
                double *row = JtJ.row(i);
                for (std::size_t j = 0; j <= i; ++j)
                  {
                    double sum = 0.;
                    for (std::size_t k = 0; k < m; ++k)
                      sum += J(k, i) * J(k, j);
                    row[j]    = sum;
                    JtJ(j, i) = sum;
                  }
                largest  = std::max(largest, row[i]);
                double g = 0.;
                for (std::size_t k = 0; k < m; ++k)
                  g -= J(k, i) * F[k];
                step[i] = g;
              }
            for (std::size_t i = 0; i < m; ++i)
              JtJ(i, i) += 1e-14 * largest;
            if (!lu.factorize(JtJ, 0.))
              return false;
            lu.solve(step);
            for (std::size_t i = 0; i < m; ++i)
              x[i] += step[i];
          }
        velocities(x);
        for (unsigned int c = 0; c < nc; ++c)
          {
            const double *xc = &x[3 * c], *Vc = &V[3 * c];
            const double  tol_P = 1e-9 * scale_P, tol_V = 1e-9 * scale_V;
            if (state[c] == State::open ?
                  Vc[0] < -tol_V :
                  (xc[0] < -tol_P ||
                   (state[c] == State::stick &&
                    std::hypot(xc[1], xc[2]) > p.mu[c] * xc[0] + tol_P)))
              return false;
          }
        std::vector<double> u;
        if (!(exact_cone_residual(p, x, u) <= tolerance))
          return false;
        P = x;
        return true;
      }

      bool
      meets_cone_error(const ExactConeOptions &options, const double error)
      {
        return !(options.cone_error_tolerance > 0.) ||
               error <= options.cone_error_tolerance;
      }

      bool
      has_friction(const ContactProblem &p)
      {
        return p.n_directions == 3 &&
               std::any_of(p.mu.begin(), p.mu.end(), [](const double mu) {
                 return mu > 0.;
               });
      }
    } // namespace



    // @sect3{The iteration}
    const ContactSolution &
    ExactConeSolver::solve(const ContactProblem            &problem,
                           const ContactOptions            &options,
                           const ExactConeOptions          &cone_options,
                           const std::vector<double>       &initial_angles,
                           const std::vector<ContactState> &state_guess)
    {
      // W of unit size (scale_to_unit_delassus()): the same impulses and
      // residual, and no false rays from badly scaled W. The standard
      // exact-cone error is reported for the problem as given.
      const bool scaled        = scale_to_unit_delassus(problem, unit) != 1.;
      const ContactProblem &p  = scaled ? unit : problem;
      const unsigned int    nc = p.n_contacts;
      last_report              = ExactConeReport();
      interior_point_tried     = false;
      angles.assign(nc, 0.);
      // Cold problems: the interior point route first, whose cost does not
      // depend on how degenerate the LCPs are (it needs no pivots).
      const ExactConeRoute route = cone_options.route;
      if (route == ExactConeRoute::interior_point ||
          route == ExactConeRoute::interior_point_then_facets)
        {
          solution = ContactSolution();
          try_interior_point(problem, p, cone_options);
          if (route == ExactConeRoute::interior_point || last_report.converged)
            return solution;
          last_report.interior_point = false;
        }
      if (!has_friction(p))
        {
          // One LCP, whose cone is exact.
          solution               = state_guess.empty() ?
                                     facet_solver.solve(p, options) :
                                     facet_solver.solve(p, options, state_guess);
          last_report.iterations = 1;
          // Without friction in 3D (or in 2D) the LCP's cone is the exact
          // one: a verified answer is the answer.
          if (solution.lcp.status == Status::solved)
            {
              last_report.cone_error = exact_cone_error(problem, solution.P);
              last_report.residual =
                exact_cone_residual(p, solution.P, velocity);
              last_report.converged =
                meets_cone_error(cone_options, last_report.cone_error);
            }
          else if (route != ExactConeRoute::facets)
            try_interior_point(problem, p, cone_options);
          return solution;
        }
      // The facets start from the given angles (not from an interior point
      // answer that stopped short).
      angles.assign(nc, 0.);
      if (initial_angles.size() == nc)
        angles = initial_angles;
      last_angle.assign(nc, 0.);
      last_residual.assign(nc, 0.);
      has_residual.assign(nc, false);

      const unsigned int k            = std::max(options.n_facets, 3u);
      const double       pi           = std::acos(-1.);
      const double       gap          = 2. * pi / k; // between facet directions
      const double       edge         = std::cos(pi / k);
      unsigned int       total_pivots = 0;
      bool               stalled      = false;
      bool               polished     = false;
      std::string        failure;
      for (unsigned int it = 1; it <= cone_options.max_iterations; ++it)
        {
          rotate_tangent_frames(p, angles, rotated);
          const ContactSolution &s =
            it > 1 ? facet_solver.solve(rotated, options, &guess) :
            state_guess.empty() ?
                     facet_solver.solve(rotated, options) :
                     facet_solver.solve(rotated, options, state_guess);
          total_pivots += s.lcp.pivots;
          if (s.lcp.status != Status::solved)
            {
              if (it == 1)
                {
                  solution               = s;
                  last_report.iterations = 1;
                  last_report.cone_error =
                    std::numeric_limits<double>::quiet_NaN();
                  if (route != ExactConeRoute::facets)
                    try_interior_point(problem, p, cone_options);
                  return solution;
                }
              failure = "; facet LCP " + std::to_string(it) + " failed (" +
                        s.message + "), the answer of LCP " +
                        std::to_string(it - 1) + " is kept";
              break;
            }
          solution = s;
          rotate_back(angles, solution.P);
          guess.resize(s.lcp.z.size());
          for (std::size_t i = 0; i < s.lcp.z.size(); ++i)
            guess[i] = s.lcp.z[i] > 0.;
          last_report.iterations = it;
          last_report.residual   = exact_cone_residual(p, solution.P, velocity);
          if (last_report.residual <= cone_options.tolerance &&
              meets_cone_error(cone_options,
                               exact_cone_error(problem, solution.P)))
            {
              last_report.converged = true;
              break;
            }
          // Close to the circular cone: try Newton at these states.
          polished_impulses = solution.P;
          if (last_report.residual < 1e-3 &&
              polish_on_circular_cone(
                p, polished_impulses, edge, cone_options.tolerance) &&
              meets_cone_error(cone_options,
                               exact_cone_error(problem, polished_impulses)))
            {
              solution.P = polished_impulses;
              last_report.residual =
                exact_cone_residual(p, solution.P, velocity);
              last_report.converged = true;
              polished              = true;
              break;
            }

          // Turn each closed contact's nearest facet onto the direction
          // the circular cone asks for.
          p.W.vmult(velocity, solution.P);
          double scale_P = 0., scale_V = 0.;
          for (std::size_t i = 0; i < velocity.size(); ++i)
            {
              scale_P = std::max(scale_P, std::abs(solution.P[i]));
              scale_V =
                std::max(scale_V,
                         std::abs(velocity[i]) + std::abs(p.free_velocity[i]));
              velocity[i] += p.free_velocity[i];
            }
          double largest_turn = 0.;
          for (unsigned int c = 0; c < nc; ++c)
            {
              const double *P = &solution.P[3 * c], *V = &velocity[3 * c];
              const bool    had_residual = has_residual[c];
              has_residual[c]            = false;
              if (p.mu[c] <= 0. || P[0] <= 1e-9 * scale_P)
                continue;
              // Inside its polygon it sticks (complementarity: its V_T is
              // round-off), and is inside the circle too.
              if (std::hypot(P[1], P[2]) < (1. - 1e-6) * edge * p.mu[c] * P[0])
                continue;
              const bool sliding = std::hypot(V[1], V[2]) > 1e-9 * scale_V;
              // The predictor of the projection onto the circular cone,
              // P_T - rho V_T with rho = 1/W_TT of the contact: for an
              // isolated contact with W_TT = w I, the direction of the
              // exact P_T.
              const double w_TT =
                0.5 * (p.W(3 * c + 1, 3 * c + 1) + p.W(3 * c + 2, 3 * c + 2));
              const double rho = w_TT > 0. ? 1. / w_TT : 0.;
              const double x = P[1] - rho * V[1], y = P[2] - rho * V[2];
              if (std::hypot(x, y) <= 1e-12 * scale_P)
                continue;
              // The turn that brings the nearest facet onto it is the
              // residual of the fixed point alpha = target(alpha). Where
              // the contact slid at the last iterate too and the residual
              // decreased, a secant step on it (at most 10 plain turns and
              // half a facet) converges faster than the plain turn when
              // W_TT is anisotropic or the contacts are coupled; where the
              // residual is noisy (non-unique impulses of redundant
              // contacts) the plain turn is kept.
              const double residual = wrap(std::atan2(y, x) - angles[c], gap);
              double       turn     = residual;
              if (had_residual && sliding && residual != last_residual[c])
                {
                  const double secant = -residual *
                                        (angles[c] - last_angle[c]) /
                                        (residual - last_residual[c]);
                  if (std::isfinite(secant) && std::abs(secant) < 0.5 * gap &&
                      std::abs(secant) <= 10. * std::abs(residual))
                    turn = secant;
                }
              last_angle[c]    = angles[c];
              last_residual[c] = residual;
              has_residual[c]  = sliding;
              angles[c]        = wrap(angles[c] + turn, 2. * pi);
              largest_turn     = std::max(largest_turn, std::abs(turn));
            }
          if (largest_turn < 1e-14)
            {
              stalled = true;
              break;
            }
        }
      // The standard measure, once, for the answer returned.
      last_report.cone_error = exact_cone_error(problem, solution.P);
      solution.lcp.pivots    = total_pivots;
      char text[200];
      std::snprintf(
        text,
        sizeof(text),
        "; exact cone: %u facet LCP%s (k = %u), residual %.2e, cone "
        "error %.2e, %s",
        last_report.iterations,
        last_report.iterations == 1 ? "" : "s",
        k,
        last_report.residual,
        last_report.cone_error,
        last_report.converged ?
          (polished ? "converged (Newton at the last states)" : "converged") :
          (stalled ? "NOT converged (facets no longer turn)" :
                     "NOT converged"));
      solution.message.append(text);
      solution.message.append(failure);
      if (!last_report.converged && route != ExactConeRoute::facets)
        try_interior_point(problem, p, cone_options);
      return solution;
    }



    // @sect3{The interior point route}
    // Where the facet LCPs fail (rays on the rank-deficient W of redundant
    // contacts) or stop short of the circular cone, the interior point
    // route (interior_point.h) solves the circular-cone problem without an
    // LCP. Its answer replaces the facet answer if it is verified and
    // closer to the circular cone; the facets then start at the directions
    // of its tangential impulses (a warm start for the next time step).
    void
    ExactConeSolver::try_interior_point(const ContactProblem   &problem,
                                        const ContactProblem   &unit_problem,
                                        const ExactConeOptions &cone_options)
    {
      if (!interior_point_tried)
        {
          InteriorPointOptions ip_options;
          ip_options.tolerance = cone_options.tolerance;
          interior_point_solver.solve(unit_problem, ip_options);
          interior_point_tried = true;
        }
      const ContactSolution     &ip         = interior_point_solver.solution();
      const InteriorPointReport &ip_report  = interior_point_solver.report();
      last_report.interior_point_iterations = ip_report.iterations;
      last_report.newton_iterations         = ip_report.newton_iterations;
      const bool facet_answer = solution.lcp.status == Status::solved;
      // With the standard measure as a target too, the smaller of it
      // decides (the residuals of the two answers can rank them otherwise).
      const bool   by_cone_error = cone_options.cone_error_tolerance > 0.;
      const double ip_cone_error =
        ip.lcp.status == Status::solved ? exact_cone_error(problem, ip.P) : 0.;
      if (ip.lcp.status == Status::solved &&
          (!facet_answer ||
           (by_cone_error ? ip_cone_error < last_report.cone_error :
                            ip_report.residual < last_report.residual)))
        {
          const std::string facet_message = solution.message;
          solution                        = ip;
          solution.message = facet_message + "; taken instead: " + ip.message;
          last_report.residual   = ip_report.residual;
          last_report.cone_error = ip_cone_error;
          last_report.converged =
            ip_report.converged &&
            meets_cone_error(cone_options, last_report.cone_error);
          last_report.interior_point = true;
          const unsigned int d       = unit_problem.n_directions;
          for (unsigned int c = 0; c < unit_problem.n_contacts && d == 3; ++c)
            if (std::hypot(ip.P[3 * c + 1], ip.P[3 * c + 2]) > 0.)
              angles[c] = std::atan2(ip.P[3 * c + 2], ip.P[3 * c + 1]);
        }
      else
        solution.message += (solution.message.empty() ? "" : "; ") +
                            std::string("interior point route tried: ") +
                            ip.message;
    }



    const ExactConeReport &
    ExactConeSolver::report() const
    {
      return last_report;
    }



    const std::vector<double> &
    ExactConeSolver::facet_angles() const
    {
      return angles;
    }



    GroupedExactConeSolution
    solve_exact_cone_by_groups(const ContactProblem   &p,
                               const ContactOptions   &options,
                               const ExactConeOptions &cone_options)
    {
      GroupedExactConeSolution out;
      ContactSolution         &s = out.solution;
      s.P.assign(p.W.n_rows(), 0.);
      s.states.assign(p.n_contacts, ContactState::open);
      s.lcp.status          = Status::solved;
      s.lcp.verification.ok = true;
      out.report.converged  = true;
      const auto groups     = independent_contact_groups(p);
      out.n_groups          = static_cast<unsigned int>(groups.size());
      ContactProblem  group;
      ExactConeSolver solver;
      std::string     not_converged;
      for (const auto &contacts : groups)
        {
          restrict_contact_problem(p, contacts, group);
          const ContactSolution &g = solver.solve(group, options, cone_options);
          out.total_iterations += solver.report().iterations;
          out.report.iterations =
            std::max(out.report.iterations, solver.report().iterations);
          // With the standard measure as a target, a group's own (relative
          // to the group's sizes) is not the whole problem's: the whole's is
          // checked after the loop.
          const bool group_converged =
            solver.report().converged ||
            (cone_options.cone_error_tolerance > 0. &&
             solver.report().residual <= cone_options.tolerance);
          out.report.converged = out.report.converged && group_converged;
          if (solver.report().interior_point)
            ++out.n_interior_point;
          out.report.interior_point_iterations =
            std::max(out.report.interior_point_iterations,
                     solver.report().interior_point_iterations);
          if (!group_converged)
            not_converged += "; group of contact " +
                             std::to_string(contacts.front()) + ": " +
                             g.message;
          out.report.residual =
            std::max(out.report.residual, solver.report().residual);
          s.lcp.pivots += g.lcp.pivots;
          if (g.lcp.status != Status::solved)
            {
              s.lcp.status = g.lcp.status;
              s.message    = "group of contact " +
                          std::to_string(contacts.front()) + ": " + g.message;
              s.P.clear();
              out.report.converged  = false;
              out.report.cone_error = std::numeric_limits<double>::quiet_NaN();
              return out;
            }
          s.lcp.verification.relative_error =
            std::max(s.lcp.verification.relative_error,
                     g.lcp.verification.relative_error);
          for (std::size_t a = 0; a < contacts.size(); ++a)
            {
              s.states[contacts[a]] = g.states[a];
              for (unsigned int d = 0; d < p.n_directions; ++d)
                s.P[contacts[a] * p.n_directions + d] =
                  g.P[a * p.n_directions + d];
            }
        }
      out.report.cone_error = exact_cone_error(p, s.P);
      out.report.converged =
        out.report.converged &&
        meets_cone_error(cone_options, out.report.cone_error);
      char text[200];
      std::snprintf(text,
                    sizeof(text),
                    "exact cone in %u groups: %u facet LCPs, at most %u in a "
                    "group, %u group%s by the interior point route, cone "
                    "error %.2e, %s",
                    out.n_groups,
                    out.total_iterations,
                    out.report.iterations,
                    out.n_interior_point,
                    out.n_interior_point == 1 ? "" : "s",
                    out.report.cone_error,
                    out.report.converged ? "converged" : "NOT converged");
      s.message = text + not_converged;
      return out;
    }
  } // namespace lcp
} // namespace impactfe
