#include <impactfe/lcp/active_set.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "text.h"

namespace impactfe
{
  namespace lcp
  {
    namespace
    {
      double
      dot(const std::vector<double> &a,
          const std::vector<double> &b,
          const std::size_t          n)
      {
        double s = 0.;
        for (std::size_t i = 0; i < n; ++i)
          s += a[i] * b[i];
        return s;
      }

      double
      max_abs(const std::vector<double> &a)
      {
        double m = 0.;
        for (const double v : a)
          m = std::max(m, std::abs(v));
        return m;
      }

      /// The outward direction of feature @p f of the k-gon (2 j: vertex j,
      /// at 2 pi j / k; 2 j + 1: the normal of edge j, at (2 j + 1) pi / k).
      double
      feature_angle(const int f, const unsigned int k)
      {
        return std::acos(-1.) * f / k;
      }

      /// By how much xi = (xi1, xi2) lies outside the regular k-gon with
      /// vertices R d_j (max_j n_j . xi - R cos(pi / k); < 0 inside), and in
      /// @p feature the vertex or edge that its projection on it lies on.
      double
      polygon_projection(const double       xi1,
                         const double       xi2,
                         const double       R,
                         const unsigned int k,
                         int               &feature)
      {
        const double pi = std::acos(-1.);
        if (!(R > 1e-12 * std::hypot(xi1, xi2)))
          {
            // the polygon is (nearly) a point: the feature whose normal
            // cone holds xi is the vertex nearest its direction
            const double angle = std::atan2(xi2, xi1);
            feature =
              2 * (static_cast<int>(std::lround(angle * k / (2. * pi)) + k) %
                   static_cast<int>(k));
            double excess = -1e300;
            for (unsigned int j = 0; j < k; ++j)
              {
                const double e = feature_angle(2 * j + 1, k);
                excess =
                  std::max(excess, std::cos(e) * xi1 + std::sin(e) * xi2);
              }
            return excess - std::max(R, 0.) * std::cos(pi / k);
          }
        const double length = 2. * R * std::sin(pi / k);
        double       excess = -1e300, nearest = 1e300;
        feature = 0;
        for (unsigned int j = 0; j < k; ++j)
          {
            const double e = feature_angle(2 * j + 1, k),
                         a = feature_angle(2 * j, k);
            excess = std::max(excess, std::cos(e) * xi1 + std::sin(e) * xi2);
            // the edge from R d_j along t_j = (-sin e, cos e)
            const double v1 = R * std::cos(a), v2 = R * std::sin(a);
            const double tau =
              -std::sin(e) * (xi1 - v1) + std::cos(e) * (xi2 - v2);
            int    f   = 2 * j + 1;
            double end = tau;
            if (tau <= 0.)
              f = 2 * j, end = 0.;
            else if (tau >= length)
              f = 2 * ((j + 1) % k), end = length;
            const double p1 = v1 - std::sin(e) * end - xi1,
                         p2 = v2 + std::cos(e) * end - xi2;
            if (p1 * p1 + p2 * p2 < nearest)
              {
                nearest = p1 * p1 + p2 * p2;
                feature = f;
              }
          }
        return excess - R * std::cos(pi / k);
      }

    } // namespace



    bool
    ExactRowsSchedule::start_exact() const
    {
      return hold > 0;
    }



    void
    ExactRowsSchedule::finish(const bool used_exact_rows)
    {
      if (hold > 0)
        {
          --hold;
          just_released = hold == 0;
          return;
        }
      if (used_exact_rows)
        {
          period = just_released ?
                     std::min<unsigned int>(2 * period + 1, 1u << 20) :
                     0;
          hold   = period;
        }
      just_released = used_exact_rows && hold == 0;
    }



    void
    ActiveSetSolver::expand(const std::vector<double> &x_unknowns,
                            const std::vector<double> &mu,
                            std::vector<double>       &P_full) const
    {
      std::fill(P_full.begin(), P_full.end(), 0.);
      for (std::size_t k = 0; k < unknowns.size(); ++k)
        P_full[unknowns[k]] = x_unknowns[k];
      const unsigned int nd =
        P_full.size() / std::max<std::size_t>(state.size(), 1);
      if (nd == 2) // 3D: P_T of sliding contacts are unknowns
        for (unsigned int a = 0; a < state.size(); ++a)
          if (is_sliding(state[a]))
            P_full[2 * a + 1] = mu[a] * P_full[2 * a] * direction[a];
      if (nd == 3 && n_facets > 0) // polygonal cone: vertex or edge
        for (unsigned int a = 0; a < state.size(); ++a)
          if (is_sliding(state[a]))
            {
              const double p_n = P_full[3 * a];
              const double e   = feature_angle(feature[a], n_facets);
              if (feature[a] % 2 == 0)
                {
                  P_full[3 * a + 1] = mu[a] * p_n * std::cos(e);
                  P_full[3 * a + 2] = mu[a] * p_n * std::sin(e);
                }
              else
                {
                  const double alpha = P_full[3 * a + 1];
                  const double gamma =
                    mu[a] * p_n * std::cos(std::acos(-1.) / n_facets);
                  P_full[3 * a + 1] =
                    -alpha * std::sin(e) + gamma * std::cos(e);
                  P_full[3 * a + 2] = alpha * std::cos(e) + gamma * std::sin(e);
                }
            }
    }



    bool
    ActiveSetSolver::is_slip_row(const unsigned int row) const
    {
      return dimension == 3 && n_facets == 0 && row % 3 != 0 &&
             is_sliding(state[row / 3]);
    }



    bool
    ActiveSetSolver::is_edge_row(const unsigned int row) const
    {
      return dimension == 3 && n_facets > 0 && row % 3 == 1 &&
             is_sliding(state[row / 3]) && feature[row / 3] % 2 == 1;
    }



    void
    ActiveSetSolver::edge_tangent(const unsigned int a,
                                  double            &t1,
                                  double            &t2) const
    {
      const double e = feature_angle(feature[a], n_facets);
      t1             = -std::sin(e);
      t2             = std::cos(e);
    }



    // The Newton equation of a sliding contact in 3D, in P (see the class
    // documentation): with n = xi/|xi| and beta = mu P_N/|xi| of the last
    // iterate and xi(P) = P_T - C (q_T + (W P)_T),
    //   P_T - mu n P_N - beta (I - n n^T) xi(P) = 0;
    // slip_row() is its P-linear part without C q_T, slip_rhs() the rest.
    double
    ActiveSetSolver::slip_row(const unsigned int         row,
                              const std::vector<double> &P_full,
                              const std::vector<double> &WP,
                              const std::vector<double> &mu) const
    {
      const unsigned int a = row / 3, iN = 3 * a;
      const double       n1 = direction[2 * a], n2 = direction[2 * a + 1];
      const double       e1      = P_full[iN + 1] - c[iN + 1] * WP[iN + 1];
      const double       e2      = P_full[iN + 2] - c[iN + 2] * WP[iN + 2];
      const double       n_dot_e = n1 * e1 + n2 * e2;
      const unsigned int k       = row - iN - 1;
      const double       n_k     = k == 0 ? n1 : n2;
      const double       e_k     = k == 0 ? e1 : e2;
      // divided by c: in velocity units, like the other rows
      return (P_full[row] - mu[a] * n_k * P_full[iN] -
              beta[a] * (e_k - n_k * n_dot_e)) /
             c[row];
    }



    double
    ActiveSetSolver::slip_rhs(const unsigned int         row,
                              const std::vector<double> &q) const
    {
      const unsigned int a = row / 3, iN = 3 * a;
      const double       n1 = direction[2 * a], n2 = direction[2 * a + 1];
      const double       f1 = c[iN + 1] * q[iN + 1], f2 = c[iN + 2] * q[iN + 2];
      const unsigned int k   = row - iN - 1;
      const double       n_k = k == 0 ? n1 : n2;
      return -beta[a] * ((k == 0 ? f1 : f2) - n_k * (n1 * f1 + n2 * f2)) /
             c[row];
    }



    // Restarted flexible GMRES on K x = rhs, K = (W E)(unknown rows), right
    // preconditioned by Z restricted to the unknowns. Starts from x and
    // leaves in `work` the product W P of the final P = E x: the caller's
    // V = q + W P needs no further product.
    unsigned int
    ActiveSetSolver::gmres(const DelassusProduct     &W,
                           const DelassusProduct     &preconditioner,
                           const std::vector<double> &mu,
                           const double               tolerance,
                           const unsigned int         max_iterations,
                           const unsigned int         restart,
                           bool                      &stalled)
    {
      const std::size_t  m = unknowns.size();
      const unsigned int k_max =
        std::max<unsigned int>(1, std::min<std::size_t>(restart, m));
      auto apply_K = [&](const std::vector<double> &in,
                         std::vector<double>       &out) {
        apply_newton_operator(W, mu, in, out);
      };
      // (Nearly) every closed contact slides: the normal preconditioner
      // for the normal rows, c for the tangents' velocity rows. It treats
      // the sticking contacts' tangents as free, a perturbation of rank up
      // to the number of sticking tangents: with half the contacts sticking
      // (2D slab, 30001 contacts) GMRES needed 400 iterations instead of
      // 12. Hence at most 1 % of them sticking.
      std::size_t n_sliding = 0, n_sticking = 0;
      for (std::size_t k = 0; k < m; ++k)
        if (unknowns[k] % dimension == 0)
          ++(is_sliding(state[unknowns[k] / dimension]) ? n_sliding :
                                                          n_sticking);
      // With the exact rows at the states (normal_state_update), every
      // solve uses the normal preconditioner, sticking tangents included.
      const bool can_invert_states = normal_preconditioner != nullptr &&
                                     normal_state_update != nullptr &&
                                     dimension > 1;
      bool normal_rows = normal_preconditioner != nullptr && dimension > 1 &&
                         ((100 * n_sticking <= n_sliding && n_sliding > 0) ||
                          (can_invert_states && exact_normal_rows));
      // The normal preconditioner's states: its own approximation, or
      // (exact_normal_rows) the current ones.
      auto send_normal_states = [&]() {
        normal_states.clear();
        normal_slip.clear();
        if (exact_normal_rows)
          {
            const unsigned int nt = dimension - 1, n = state.size();
            normal_states.resize(n);
            normal_slip.assign(n * nt, 0.);
            for (unsigned int a = 0; a < n; ++a)
              {
                normal_states[a] = !is_closed(state[a]) ? 0 :
                                   is_sliding(state[a]) ? 1 :
                                                          2;
                if (!is_sliding(state[a]))
                  continue;
                if (n_facets == 0)
                  for (unsigned int k = 0; k < nt; ++k)
                    normal_slip[a * nt + k] = mu[a] * direction[a * nt + k];
                else
                  {
                    // a vertex d_j, or an edge's normal part cos(pi/k) n_j
                    const double e = feature_angle(feature[a], n_facets);
                    const double scale =
                      feature[a] % 2 == 0 ?
                        mu[a] :
                        mu[a] * std::cos(std::acos(-1.) / n_facets);
                    normal_slip[a * 2]     = scale * std::cos(e);
                    normal_slip[a * 2 + 1] = scale * std::sin(e);
                  }
              }
          }
        (*normal_state_update)(normal_states, normal_slip);
      };
      // Whether this solve may switch to the exact normal rows: after
      // exact_normal_rows_after iterations, at the end of a restart cycle
      // (flexible GMRES allows a preconditioner that changes); only from
      // W_NN^{-1}: a slow solve with the full preconditioner (many
      // sticking contacts, typically a first step) says little about the
      // next ones, and switching there made the 2D slab at 10^4 contacts
      // 2.5 times slower (a factorisation at every change of the states).
      const bool may_switch =
        normal_rows && can_invert_states && !exact_normal_rows;
      if (normal_rows && normal_state_update != nullptr)
        send_normal_states();
      // a sticking contact's tangent row, given to the normal
      // preconditioner at exact states
      auto exact_stick_row = [&](const unsigned int row) {
        return normal_rows && exact_normal_rows && row % dimension != 0 &&
               is_closed(state[row / dimension]) &&
               !is_sliding(state[row / dimension]);
      };
      auto apply_Z = [&](const std::vector<double> &in,
                         std::vector<double>       &out) {
        // slip rows (3D): c, their operator is (I + O(beta (1 - c W_TT))) / c
        // with c W_TT ~ 1
        // edge rows (polygonal cone): the velocity and the impulse along
        // the edge's tangent t
        std::fill(full_in.begin(), full_in.end(), 0.);
        double t1 = 0., t2 = 0.;
        for (std::size_t k = 0; k < m; ++k)
          {
            const unsigned int row = unknowns[k];
            if (normal_rows)
              {
                if (row % dimension == 0 || exact_stick_row(row))
                  full_in[row] = in[k];
              }
            else if (is_edge_row(row))
              {
                edge_tangent(row / 3, t1, t2);
                full_in[row]     = t1 * in[k];
                full_in[row + 1] = t2 * in[k];
              }
            else if (!is_slip_row(row))
              full_in[row] = in[k];
          }
        if (normal_rows)
          (*normal_preconditioner)(full_in, full_out);
        else
          preconditioner(full_in, full_out);
        for (std::size_t k = 0; k < m; ++k)
          {
            const unsigned int row = unknowns[k];
            if (normal_rows && row % dimension != 0 && !is_slip_row(row) &&
                !exact_stick_row(row))
              out[k] = c[row] * in[k];
            else if (is_slip_row(row))
              {
                // block triangular: the slip rows' main term is
                // P_T - mu n P_N, with P_N from the normal rows
                const unsigned int a = row / 3;
                out[k]               = c[row] * in[k] + mu[a] *
                                            direction[2 * a + row % 3 - 1] *
                                            full_out[3 * a];
              }
            else if (is_edge_row(row))
              {
                edge_tangent(row / 3, t1, t2);
                out[k] = t1 * full_out[row] + t2 * full_out[row + 1];
              }
            else
              out[k] = full_out[row];
          }
      };

      basis.resize(k_max + 1);
      for (auto &v : basis)
        v.resize(m);
      preconditioned.resize(k_max);
      for (auto &v : preconditioned)
        v.resize(m);
      hessenberg.assign((k_max + 1) * k_max, 0.);
      givens_cos.resize(k_max);
      givens_sin.resize(k_max);
      g.resize(k_max + 1);
      y_small.resize(k_max);
      std::vector<double> &r = basis[k_max], w(m);
      auto                 H = [&](unsigned int i, unsigned int j) -> double                 &{
        return hessenberg[i * k_max + j];
      };

      const double rhs_norm = std::sqrt(dot(rhs, rhs, m));
      const double target   = tolerance * rhs_norm;
      if (std::all_of(x.begin(), x.begin() + m, [](double v) {
            return v == 0.;
          }))
        {
          // a refinement's start: K 0 = 0, W P = 0 without a product
          std::copy(rhs.begin(), rhs.begin() + m, r.begin());
          std::fill(work.begin(), work.end(), 0.);
          product_valid = false;
        }
      else
        {
          apply_K(x, r);
          for (std::size_t k = 0; k < m; ++k)
            r[k] = rhs[k] - r[k];
        }
      // The first cycle's W P and true residual by recurrence, from the
      // products W E z_j that its iterations make anyway: one product less
      // per solve, a third of a front's iteration (a solve from the last
      // answer, changed in a few rows, takes one or two GMRES iterations).
      // Later cycles (few solves have them) make the product, and so does
      // the first if this solve started from a product by recurrence (the
      // same P as the last solve's answer: contacts that only closed, or
      // the confirming tight solve), so that rounding in the recurrence
      // cannot build up over cycles or over solves.
      bool recurrence = !product_from_recurrence;
      start_product   = work;
      if (basis_products.size() < k_max)
        basis_products.resize(k_max);
      double       beta       = std::sqrt(dot(r, r, m));
      unsigned int iterations = 0;
      stalled                 = false;
      while (beta > target && iterations < max_iterations)
        {
          for (std::size_t k = 0; k < m; ++k)
            basis[0][k] = r[k] / beta;
          std::fill(g.begin(), g.end(), 0.);
          g[0]           = beta;
          unsigned int j = 0;
          while (j < k_max && iterations < max_iterations)
            {
              // flexible GMRES: Z v_j is kept, so a preconditioner that is
              // not exactly linear (single precision) costs no accuracy
              apply_Z(basis[j], preconditioned[j]);
              apply_K(preconditioned[j], w);
              if (recurrence)
                basis_products[j] = work;
              for (unsigned int i = 0; i <= j; ++i)
                {
                  H(i, j) = dot(w, basis[i], m);
                  for (std::size_t k = 0; k < m; ++k)
                    w[k] -= H(i, j) * basis[i][k];
                }
              const double h_next = std::sqrt(dot(w, w, m));
              if (j + 1 < k_max + 1 && h_next > 0. && j + 1 < k_max)
                for (std::size_t k = 0; k < m; ++k)
                  basis[j + 1][k] = w[k] / h_next;
              for (unsigned int i = 0; i < j; ++i)
                {
                  const double t =
                    givens_cos[i] * H(i, j) + givens_sin[i] * H(i + 1, j);
                  H(i + 1, j) =
                    -givens_sin[i] * H(i, j) + givens_cos[i] * H(i + 1, j);
                  H(i, j) = t;
                }
              const double rho = std::hypot(H(j, j), h_next);
              givens_cos[j]    = rho > 0. ? H(j, j) / rho : 1.;
              givens_sin[j]    = rho > 0. ? h_next / rho : 0.;
              H(j, j)          = rho;
              g[j + 1]         = -givens_sin[j] * g[j];
              g[j]             = givens_cos[j] * g[j];
              ++j;
              ++iterations;
              if (std::abs(g[j]) <= target || h_next == 0. ||
                  (may_switch && iterations == exact_normal_rows_after))
                break;
            }
          for (int i = static_cast<int>(j) - 1; i >= 0; --i)
            {
              double s = g[i];
              for (unsigned int l = i + 1; l < j; ++l)
                s -= H(i, l) * y_small[l];
              y_small[i] = H(i, i) != 0. ? s / H(i, i) : 0.;
            }
          for (unsigned int i = 0; i < j; ++i)
            for (std::size_t k = 0; k < m; ++k)
              x[k] += y_small[i] * preconditioned[i][k];
          // the true residual (and W P of the new x)
          if (recurrence)
            {
              work.swap(start_product);
              for (unsigned int i = 0; i < j; ++i)
                for (std::size_t k = 0; k < work.size(); ++k)
                  work[k] += y_small[i] * basis_products[i][k];
              expand(x, mu, P);
              product_P               = P;
              product_valid           = true;
              product_from_recurrence = true;
              newton_rows(mu, r);
              recurrence = false;
            }
          else
            apply_K(x, r);
          for (std::size_t k = 0; k < m; ++k)
            r[k] = rhs[k] - r[k];
          const double new_beta = std::sqrt(dot(r, r, m));
          if (may_switch && !exact_normal_rows &&
              iterations >= exact_normal_rows_after && new_beta > target)
            {
              exact_normal_rows = last_report.exact_normal_rows = true;
              normal_rows                                       = true;
              send_normal_states();
              beta = new_beta;
              continue;
            }
          if (new_beta > 0.999 * beta)
            {
              stalled = new_beta > target;
              beta    = new_beta;
              break;
            }
          beta = new_beta;
        }
      stalled = stalled || beta > target;
      last_report.linear_iterations += iterations;
      residual.assign(r.begin(), r.begin() + m);
      return iterations;
    }



    void
    ActiveSetSolver::apply_newton_operator(const DelassusProduct     &W,
                                           const std::vector<double> &mu,
                                           const std::vector<double> &in,
                                           std::vector<double>       &out,
                                           const bool                 fresh)
    {
      expand(in, mu, P);
      if (!product_valid || P != product_P ||
          (fresh && product_from_recurrence))
        {
          W(P, work);
          ++last_report.operator_applications;
          product_P               = P;
          product_valid           = true;
          product_from_recurrence = false;
        }
      newton_rows(mu, out);
    }



    void
    ActiveSetSolver::newton_rows(const std::vector<double> &mu,
                                 std::vector<double>       &out) const
    {
      for (std::size_t k = 0; k < unknowns.size(); ++k)
        {
          const unsigned int row = unknowns[k];
          if (is_slip_row(row))
            out[k] = slip_row(row, P, work, mu);
          else if (is_edge_row(row))
            {
              double t1 = 0., t2 = 0.;
              edge_tangent(row / 3, t1, t2);
              out[k] = t1 * work[row] + t2 * work[row + 1];
            }
          else
            out[k] = work[row];
        }
    }



    void
    ActiveSetSolver::assemble_rhs(const std::vector<double> &q,
                                  const std::vector<double> &b)
    {
      const unsigned int nd = dimension;
      rhs.resize(unknowns.size());
      for (std::size_t k = 0; k < unknowns.size(); ++k)
        {
          const unsigned int row = unknowns[k];
          if (is_slip_row(row))
            rhs[k] = slip_rhs(row, q);
          else if (is_edge_row(row))
            {
              double t1 = 0., t2 = 0.;
              edge_tangent(row / 3, t1, t2);
              rhs[k] = -(t1 * q[row] + t2 * q[row + 1]);
            }
          else
            rhs[k] = row % nd == 0 ? -(q[row] + b[row / nd]) : -q[row];
        }
    }



    // Classical iterative refinement: the residual of x is computed with a
    // fresh product (the directions have moved since the last solve), a
    // correction is solved to a modest relative accuracy against it and
    // added. GMRES's true residual of the correction is that of the sum, and
    // W P of the sum is the sum of the two products, so a pass costs only
    // its GMRES iterations. Stops at the tolerance, at the rounding floor
    // (the residual no longer halves) or after max_refinements passes.
    double
    ActiveSetSolver::refine(const DelassusProduct     &W,
                            const DelassusProduct     &preconditioner,
                            const std::vector<double> &q,
                            const std::vector<double> &b,
                            const std::vector<double> &mu,
                            const ActiveSetOptions    &options)
    {
      const std::size_t m = unknowns.size();
      assemble_rhs(q, b);
      auto impulse_residual = [&]() {
        apply_newton_operator(W, mu, x, residual, true);
        double worst = 0.;
        for (std::size_t k = 0; k < m; ++k)
          {
            residual[k] = rhs[k] - residual[k];
            worst = std::max(worst, c[unknowns[k]] * std::abs(residual[k]));
          }
        return worst / std::max(max_abs(P), 1e-300);
      };
      auto relative_to_impulses = [&]() {
        double worst = 0.;
        for (std::size_t k = 0; k < m; ++k)
          worst = std::max(worst, c[unknowns[k]] * std::abs(residual[k]));
        return worst / std::max(max_abs(P), 1e-300);
      };
      double       error  = impulse_residual();
      unsigned int passes = 0;
      for (unsigned int pass = 0; pass < options.max_refinements &&
                                  error > options.refinement_tolerance;
           ++pass)
        {
          saved_rhs.swap(rhs);
          saved_x.swap(x);
          saved_work     = work;
          saved_residual = residual;
          rhs            = residual;
          x.assign(m, 0.);
          // one pass should do: aim a tenth below the target
          bool stalled = false;
          gmres(W,
                preconditioner,
                mu,
                std::clamp(0.1 * options.refinement_tolerance / error,
                           1e-10,
                           1e-2),
                options.max_linear_iterations,
                options.restart,
                stalled);
          for (std::size_t k = 0; k < m; ++k)
            x[k] += saved_x[k];
          for (std::size_t i = 0; i < work.size(); ++i)
            work[i] += saved_work[i];
          product_valid = false;
          expand(x, mu, P);
          saved_rhs.swap(rhs);
          const double new_error = relative_to_impulses();
          ++last_report.refinements;
          ++passes;
          if (!(new_error < error)) // no gain: keep the x before the pass
            {
              x.swap(saved_x);
              work.swap(saved_work);
              product_valid = false;
              residual.swap(saved_residual);
              expand(x, mu, P);
              break;
            }
          const bool halved = new_error < 0.5 * error;
          error             = new_error;
          if (!halved)
            break;
        }
      // The caller may use the last product's by-products (the time loop's
      // M~^{-1} H P, the velocity correction): make it one with the final P.
      if (passes > 0)
        error = impulse_residual();
      for (std::size_t i = 0; i < V.size(); ++i)
        V[i] = q[i] + work[i];
      return error;
    }



    const ActiveSetReport &
    ActiveSetSolver::solve(const DelassusProduct           &W,
                           const DelassusProduct           &preconditioner,
                           const std::vector<double>       &penalty,
                           const unsigned int               nd,
                           const std::vector<double>       &q,
                           const std::vector<double>       &b,
                           const std::vector<double>       &mu,
                           const std::vector<ContactState> &state_guess,
                           const std::vector<double>       &impulse_guess,
                           const ActiveSetOptions          &options,
                           const DelassusProduct   &normal_preconditioner_in,
                           const NormalStateUpdate &normal_state_update_in)
    {
      const std::size_t n = b.size(), n_rows = n * nd;
      if (nd < 1 || nd > 3)
        throw std::invalid_argument(
          "ActiveSetSolver: n_directions must be 1, 2 or 3, got " +
          std::to_string(nd));
      if (q.size() != n_rows || (nd > 1 && mu.size() != n) ||
          penalty.size() != n_rows)
        throw std::invalid_argument("ActiveSetSolver: inconsistent sizes");
      last_report   = ActiveSetReport();
      product_valid = false;
      normal_preconditioner =
        normal_preconditioner_in ? &normal_preconditioner_in : nullptr;
      normal_state_update =
        normal_state_update_in ? &normal_state_update_in : nullptr;
      exact_normal_rows =
        options.exact_normal_rows || options.exact_normal_rows_after == 0;
      exact_normal_rows_after       = options.exact_normal_rows_after;
      last_report.exact_normal_rows = exact_normal_rows;
      seen.clear();
      cycles            = 0;
      bool moving_front = false;
      last_update.assign(b.size(), 0);
      unsigned int       n_updates = 0;
      double             last_turn = std::numeric_limits<double>::max();
      const unsigned int front_width =
        static_cast<unsigned int>(std::ceil(std::sqrt(double(b.size()))));
      unsigned int verification_updates = 0;
      unsigned int n_changes = 0, n_changes_tight_margin = 0;
      bool         damped_cycle = false;
      // a tight solve that tests whether the inexact margin hides a front
      bool         probing = false, probe_failed = false;
      unsigned int probe_reference = 0;
      std::string  verification_failure;
      P.assign(n_rows, 0.);
      V = q;
      work.assign(n_rows, 0.);
      position.assign(n_rows, -1);

      // c ~ 1 / diag(W): the complementarity constants, in units of
      // impulse per velocity.
      c = penalty;
      full_in.assign(n_rows, 0.);
      full_out.assign(n_rows, 0.);
      double c_max = 0.;
      for (const double ci : c)
        c_max = std::max(c_max, ci);
      for (double &ci : c)
        if (!(ci > 0.))
          ci = c_max > 0. ? c_max : 1.;
      c_max = std::max(c_max, 1e-300);
      // one c_T per contact: proj(P_T - c_T V_T) is Coulomb's law only
      // for a scalar c_T (with two, P_T would align with C^{-1} V_T)
      for (unsigned int a = 0; a < n && nd == 3; ++a)
        c[3 * a + 1] = c[3 * a + 2] = 0.5 * (c[3 * a + 1] + c[3 * a + 2]);
      const double impulse_scale_free = c_max * (max_abs(q) + max_abs(b));

      // The state update from (P, V); a change needs a violation of more
      // than `margin` (see the class documentation).
      // violation[a]: by how much contact a's condition is violated when
      // its state changes (the size of |zeta| or of ||xi| - bound|).
      auto update_states = [&](const double margin) {
        new_state.resize(n);
        violation.assign(n, 0.);
        new_feature.assign(n, -1);
        for (unsigned int a = 0; a < n; ++a)
          {
            const unsigned int iN   = a * nd;
            const double       zeta = P[iN] - c[iN] * (V[iN] + b[a]);
            const bool         closed =
              is_closed(state[a]) ? zeta > -margin : zeta > margin;
            if (!closed)
              new_state[a] = ContactState::open;
            else if (nd == 1)
              new_state[a] = ContactState::stick;
            else if (nd == 3 && n_facets > 0)
              {
                // polygonal cone: the feature of the projection of xi
                int          f = 0;
                const double excess =
                  polygon_projection(P[iN + 1] - c[iN + 1] * V[iN + 1],
                                     P[iN + 2] - c[iN + 2] * V[iN + 2],
                                     mu[a] * std::max(zeta, 0.),
                                     n_facets,
                                     f);
                // From a vertex to the next one, through the edge between
                // them: xi is far outside the polygon (c |V_T| >> mu P_N),
                // so its projection is a vertex unless -V_T is exactly the
                // edge's normal, which is what sliding on the edge means;
                // without this the states alternate between the two
                // vertices. On the edge, alpha decides: beyond the edge's
                // end, the projection is that vertex again.
                if (is_sliding(state[a]) && feature[a] % 2 == 0 && f % 2 == 0)
                  {
                    const int k2 = 2 * n_facets,
                              d  = ((f - feature[a]) % k2 + k2) % k2;
                    if (d == 2 || d == k2 - 2)
                      f = (feature[a] + (d == 2 ? 1 : k2 - 1)) % k2;
                  }
                const bool turns_round =
                  is_sliding(state[a]) &&
                  std::cos(feature_angle(f - feature[a], n_facets)) < -1e-9;
                if (excess <= -margin)
                  new_state[a] = ContactState::stick;
                else if (excess > margin)
                  new_state[a] = turns_round ? ContactState::stick :
                                               ContactState::slip_positive;
                else
                  new_state[a] = is_sliding(state[a]) && !turns_round ?
                                   ContactState::slip_positive :
                                   ContactState::stick;
                if (is_sliding(new_state[a]))
                  new_feature[a] = f;
                violation[a] = std::abs(excess);
              }
            else
              {
                // xi = P_T - c V_T; a slip direction d = xi / |xi|
                double xi_norm = 0., turn = 0.;
                for (unsigned int k = 1; k < nd; ++k)
                  {
                    const double xi = P[iN + k] - c[iN + k] * V[iN + k];
                    new_direction[a * (nd - 1) + k - 1] = xi;
                    xi_norm += xi * xi;
                  }
                xi_norm = std::sqrt(xi_norm);
                for (unsigned int k = 0; k + 1 < nd; ++k)
                  {
                    double &d = new_direction[a * (nd - 1) + k];
                    d         = xi_norm > 0. ? d / xi_norm : 0.;
                    turn += d * direction[a * (nd - 1) + k];
                  }
                // 2D: the sign of P_T names the state; 3D: slip_positive
                // stands for sliding in direction d
                const auto slip_state =
                  nd == 2 && new_direction[a] < 0. ?
                    ContactState::slip_positive :
                    (nd == 2 ? ContactState::slip_negative :
                               ContactState::slip_positive);
                const bool   turns_round = is_sliding(state[a]) && turn < 0.;
                const double bound       = mu[a] * std::max(zeta, 0.);
                if (xi_norm <= bound - margin)
                  new_state[a] = ContactState::stick;
                else if (xi_norm > bound + margin)
                  // a sliding contact whose velocity turned against its
                  // impulse sticks first instead of turning round: turning
                  // round directly makes the method cycle
                  new_state[a] = turns_round ? ContactState::stick : slip_state;
                else // within the margin: keep a consistent state
                  new_state[a] = is_sliding(state[a]) && !turns_round ?
                                   slip_state :
                                   ContactState::stick;
                violation[a] = std::abs(xi_norm - bound);
                new_beta[a] =
                  xi_norm > 0. ? mu[a] * std::max(P[iN], 0.) / xi_norm : 0.;
              }
            if (is_closed(new_state[a]) != is_closed(state[a]))
              violation[a] = std::abs(zeta);
          }
      };

      // A set of states met before means a cycle: then only the most
      // violated part of the changes is made, half as many each time a
      // cycle is met again (down to one contact, as in Murty's method).
      auto damp_cycles = [&]() {
        std::size_t hash = 1469598103934665603ull;
        for (unsigned int a = 0; a < n; ++a)
          hash =
            (hash ^ (static_cast<unsigned char>(new_state[a]) +
                     256u * static_cast<unsigned int>(new_feature[a] + 1))) *
            1099511628211ull;
        if (std::find(seen.begin(), seen.end(), hash) == seen.end())
          {
            seen.push_back(hash);
            return;
          }
        ++cycles;
        changed.clear();
        for (unsigned int a = 0; a < n; ++a)
          if (new_state[a] != state[a] || new_feature[a] != feature[a])
            changed.push_back(a);
        const std::size_t keep =
          std::max<std::size_t>(1, changed.size() >> std::min(cycles, 30u));
        std::sort(changed.begin(), changed.end(), [&](auto i, auto j) {
          return violation[i] > violation[j];
        });
        for (std::size_t k = keep; k < changed.size(); ++k)
          {
            const unsigned int a = changed[k];
            new_state[a]         = state[a];
            new_feature[a]       = feature[a];
            // 2D: a sliding contact's state names the sign of its P_T, which
            // expand() takes from its direction; one kept sliding keeps its
            // direction, or the two would disagree (a contact whose slip
            // turned round and was held back from sticking). In 3D the
            // direction of a sliding contact is its Newton update, whatever
            // the state change held back.
            if (nd == 2 && is_sliding(state[a]))
              new_direction[a] = direction[a];
          }
      };

      // Slip directions: of the guessed impulses, else against the free
      // velocity (2D: the sign of the guessed state).
      const unsigned int nt = nd - 1;
      direction.assign(n * nt, 0.);
      new_direction.assign(n * nt, 0.);
      beta.assign(n, 0.);
      new_beta.assign(n, 0.);
      dimension = nd;
      n_facets  = nd == 3 ? options.n_facets : 0;
      if (n_facets > 0 && n_facets < 3)
        throw std::invalid_argument(
          "ActiveSetSolver: the polygonal cone needs at least 3 facets, got " +
          std::to_string(n_facets));
      feature.assign(n, -1);
      new_feature.assign(n, -1);
      if (impulse_guess.size() == n_rows)
        P = impulse_guess;
      for (unsigned int a = 0; a < n && nt > 0; ++a)
        {
          double norm = 0.;
          for (unsigned int k = 0; k < nt; ++k)
            {
              const double d        = impulse_guess.size() == n_rows ?
                                        P[a * nd + 1 + k] :
                                        -q[a * nd + 1 + k];
              direction[a * nt + k] = d;
              norm += d * d;
            }
          norm = std::sqrt(norm);
          for (unsigned int k = 0; k < nt; ++k)
            direction[a * nt + k] =
              norm > 0. ? direction[a * nt + k] / norm : (k == 0 ? 1. : 0.);
          if (nt == 1 && a < state_guess.size() && is_sliding(state_guess[a]))
            direction[a] =
              state_guess[a] == ContactState::slip_negative ? 1. : -1.;
        }
      if (state_guess.size() == n)
        {
          state = state_guess;
          if (nd == 1)
            for (ContactState &s : state)
              if (is_closed(s))
                s = ContactState::stick;
          // polygonal cone: a guessed sliding contact starts on the feature
          // that its guessed P_T lies on, else where -q_T points
          for (unsigned int a = 0; a < n && n_facets > 0; ++a)
            if (is_sliding(state[a]))
              {
                const unsigned int iN  = 3 * a;
                const double       p_n = P[iN];
                if (impulse_guess.size() == n_rows && mu[a] * p_n > 0.)
                  polygon_projection((1. + 1e-6) * P[iN + 1],
                                     (1. + 1e-6) * P[iN + 2],
                                     mu[a] * p_n,
                                     n_facets,
                                     feature[a]);
                else
                  polygon_projection(2. * direction[2 * a],
                                     2. * direction[2 * a + 1],
                                     1.,
                                     n_facets,
                                     feature[a]);
              }
        }
      else
        {
          state.assign(n, ContactState::open);
          update_states(0.);
          state     = new_state;
          feature   = new_feature;
          direction = new_direction;
          beta      = new_beta;
        }
      // The margin of the state changes after an inexact solve: its error
      // in impulse units, max_k c_k |r_k| of its final residual r (as the
      // refinement measures it), and at least 1e2 times its tolerance
      // relative to the impulses. The free scale c |q| stands in only
      // before there are impulses: it can exceed them by orders of
      // magnitude (a body sliding at 1 m/s, pressed by gravity alone),
      // which made the inexact solves blind to every change and left a
      // stick-slip front that moves one node per iteration to the tight
      // solves.
      auto inexact_margin = [&](const double p_max) {
        if (!(p_max > 0.) || unknowns.empty())
          return 1e2 * options.inexact_linear_tolerance *
                 std::max(p_max, impulse_scale_free);
        double impulse_error = 0.;
        for (std::size_t k = 0; k < unknowns.size(); ++k)
          impulse_error =
            std::max(impulse_error, c[unknowns[k]] * std::abs(residual[k]));
        // never below the tight solves' margin
        return std::max({1e2 * options.inexact_linear_tolerance * p_max,
                         impulse_error,
                         1e-10 * std::max(p_max, impulse_scale_free)});
      };
      // New states and slip directions from (P, V); returns how far the
      // directions of the contacts that keep sliding moved (3D circular
      // cone; in 2D they are the states' signs) and sets @p same if no
      // state changed. The directions are taken over.
      auto update_and_turn = [&](const bool   after_tight_solve,
                                 bool        &same,
                                 const double margin = -1.) {
        // after an inexact solve, only changes above its measured error
        const double p_max        = max_abs(P);
        const double tight_margin = 1e-10 * std::max(p_max, impulse_scale_free);
        // how many states the tight margin would change (see the loop)
        n_changes_tight_margin = 0;
        if (!after_tight_solve && margin < 0.)
          {
            update_states(tight_margin);
            for (unsigned int a = 0; a < n; ++a)
              n_changes_tight_margin +=
                new_state[a] != state[a] || new_feature[a] != feature[a];
          }
        update_states(margin >= 0.      ? margin :
                      after_tight_solve ? tight_margin :
                                          inexact_margin(p_max));
        const unsigned int cycles_before = cycles;
        if (new_state != state || new_feature != feature)
          damp_cycles();
        // a front: a few changes (at most sqrt(n), a front line of a 3D
        // contact zone), none undoing one of the update before, and not
        // the part of a cycle that its damping kept
        damped_cycle  = cycles != cycles_before;
        n_changes     = 0;
        bool reversal = false;
        ++n_updates;
        for (unsigned int a = 0; a < n; ++a)
          if (new_state[a] != state[a] || new_feature[a] != feature[a])
            {
              ++n_changes;
              reversal       = reversal || (last_update[a] != 0 &&
                                      last_update[a] + 1 == n_updates);
              last_update[a] = n_updates;
            }
        double turn = 0.;
        for (unsigned int a = 0; a < n && nd == 3 && n_facets == 0; ++a)
          if (is_sliding(state[a]) && is_sliding(new_state[a]))
            turn = std::max(turn,
                            std::hypot(new_direction[2 * a] - direction[2 * a],
                                       new_direction[2 * a + 1] -
                                         direction[2 * a + 1]));
        same = new_state == state && new_feature == feature;
        // with no change: the 3D slip directions still converging
        moving_front = n_changes > 0 ? !reversal && !damped_cycle &&
                                         n_changes <= front_width :
                                       turn > 0. && turn < last_turn;
        last_turn    = turn;
        for (unsigned int a = 0; a < n; ++a)
          if (is_sliding(new_state[a]))
            {
              for (unsigned int k = 0; k < nt; ++k)
                direction[a * nt + k] = new_direction[a * nt + k];
              beta[a] = new_beta[a];
            }
        return turn;
      };

      // Inexact Newton: while the states change, the linear systems are
      // solved to inexact_linear_tolerance only; once they settle, once
      // more to linear_tolerance, and from then on always to
      // linear_tolerance, so that the inexact solves cannot make the
      // states cycle. A warm start begins inexact too: a tight first solve
      // from right states saved little, and from states that still change
      // (a stick-slip zone that moves with a block) it was spent. Measured:
      // thin 3D slab at 10^4 contacts, 83 -> 75 products in 5 steps; 2D
      // block on a slab, 24 003 candidates, 1 400 -> 1 296 (after the
      // measured margin above, which took it from 2 209 to 1 400).
      bool tight = false, settled_once = false;

      // Past max_iterations the method goes on only while a front moves:
      // the last state update changed some contacts, at most sqrt(n), none
      // that the update before had changed, and it was not a damped cycle
      // (or it changed none but the 3D slip directions still converge, or
      // the states just settled and the tight solve that confirms them is
      // due). A lift-off or stick-slip front moves by one node or a few
      // per iteration, since a node's condition is violated only once its
      // neighbour has changed, so the iterations it needs grow like the
      // nodes it crosses, like 1/h: the run of the 1 m slab of
      // benchmarks/scaling at 30 001 contacts stopped in its 7th step,
      // where 17 nodes opened one per iteration past 50 iterations. Such
      // iterations are cheap in the serial programs (a solve from the last
      // answer, changed in a few rows: 1 to 3 GMRES iterations). A method
      // that does not converge flips many contacts per iteration (at mu =
      // 5 and 10^4 contacts, 100 to 750: doc/lcp.md), flips some back at
      // once, or cycles, and stops at max_iterations; a front stops after
      // at most min(n, max_front_iterations) more.
      for (unsigned int iteration = 1;; ++iteration)
        {
          if (iteration > options.max_iterations &&
              (!moving_front ||
               iteration - options.max_iterations >
                 std::min<std::size_t>(n, options.max_front_iterations)))
            break;
          last_report.iterations = iteration;
          unknowns.clear();
          std::fill(position.begin(), position.end(), -1);
          for (unsigned int a = 0; a < n; ++a)
            if (is_closed(state[a]))
              {
                unknowns.push_back(a * nd);
                if (state[a] == ContactState::stick ||
                    (nd == 3 && n_facets == 0 && is_sliding(state[a])))
                  for (unsigned int k = 1; k < nd; ++k)
                    unknowns.push_back(a * nd + k);
                else if (is_edge_row(a * nd + 1))
                  unknowns.push_back(a * nd + 1);
              }
          const std::size_t m = unknowns.size();
          x.resize(m);
          for (std::size_t k = 0; k < m; ++k)
            {
              const unsigned int row = unknowns[k];
              position[row]          = static_cast<int>(k);
              x[k]                   = P[row];
              if (is_edge_row(row)) // alpha = t . P_T
                {
                  double t1 = 0., t2 = 0.;
                  edge_tangent(row / 3, t1, t2);
                  x[k] = t1 * P[row] + t2 * P[row + 1];
                }
            }
          assemble_rhs(q, b);
          if (m == 0)
            {
              std::fill(P.begin(), P.end(), 0.);
              V = q;
            }
          else
            {
              bool         stalled = false;
              const double linear_tolerance =
                tight ? options.linear_tolerance :
                        std::max(options.linear_tolerance,
                                 options.inexact_linear_tolerance);
              gmres(W,
                    preconditioner,
                    mu,
                    linear_tolerance,
                    options.max_linear_iterations,
                    options.restart,
                    stalled);
              expand(x, mu, P);
              for (std::size_t i = 0; i < n_rows; ++i)
                V[i] = q[i] + work[i];
              if (stalled)
                {
                  last_report.message.clear();
                  internal::append_text(
                    last_report.message,
                    "GMRES did not reach the relative residual %g at "
                    "active-set iteration %u (%u GMRES iterations in this solve)",
                    linear_tolerance,
                    iteration,
                    last_report.linear_iterations);
                  break;
                }
            }

          bool       same      = false;
          const bool was_probe = probing;
          probing              = false;
          double turn          = update_and_turn(tight, same);
          if (same && !tight && m > 0 &&
              turn <= options.inexact_direction_tolerance)
            {
              moving_front = true; // the confirming tight solve
              tight        = true;
              settled_once = true;
              continue;
            }
          // The slip directions converge quadratically (Newton): after a
          // tight solve that moved them by at most the square root of
          // their tolerance, one more Newton step settles them, and the
          // refinement at the moved directions is that step; whether it
          // did is checked below.
          const bool one_step_away =
            same && tight && m > 0 &&
            turn <= std::sqrt(options.direction_tolerance);
          if ((same && turn <= options.direction_tolerance) || one_step_away)
            {
              // at the settled states and directions (those just updated)
              if (m > 0)
                last_report.linear_residual =
                  refine(W, preconditioner, q, b, mu, options);
              if (turn > options.direction_tolerance)
                {
                  turn = update_and_turn(true, same);
                  if (!same || turn > options.direction_tolerance)
                    {
                      state   = new_state;
                      feature = new_feature;
                      tight   = settled_once || same;
                      continue;
                    }
                }
              const double p_max  = max_abs(P);
              double       wp_max = 0.;
              for (std::size_t i = 0; i < n_rows; ++i)
                wp_max = std::max(wp_max, std::abs(V[i] - q[i]));
              const double norm_W = p_max > 0. ? wp_max / p_max : 1. / c_max;
              last_report.verification = verify_contact_velocities(
                nd, q, b, mu, P, V, norm_W, options.tolerance, n_facets);
              last_report.converged = last_report.verification.ok;
              // q and V with the gap terms, in two work vectors (free
              // here) so that the solve does not allocate
              full_in.assign(q.begin(), q.end());
              full_out.assign(V.begin(), V.end());
              for (unsigned int a = 0; a < n; ++a)
                {
                  full_in[a * nd] += b[a];
                  full_out[a * nd] += b[a];
                }
              last_report.cone_error =
                exact_cone_error(nd, full_in, full_out, P, mu);
              // The tight margin, 1e-10 of c |q|, can exceed what the
              // verification allows, 1e-8 of its own impulse scale s_P
              // (the largest impulse, or |q| / ||W||): c ~ 1 / W_jj of the
              // stiffest row is far larger than 1 / ||W|| on graded or
              // thin meshes. A sticking contact just outside the cone then
              // kept its state, and the answer failed the verification (2D
              // block on a slab, 12 003 candidates, 12th step: cone excess
              // 5.2e-8 of s_P). Such a failure is one more Newton step, at
              // most twice per solve: the states again, with a margin of
              // 1e-2 of the verification's tolerance on its scale, but not
              // below ten times the refined answer's own error (changes
              // within it would be noise). The tight margin itself stays:
              // before refine(), a tight solve is accurate only to 1e-12 of
              // its right-hand side, which is 1e-12 c |q| in impulse units.
              std::string failure;
              if (!last_report.converged)
                internal::append_text(
                  failure,
                  "the contact states settled but (P, V) failed the "
                  "verification (Signorini %g, cone %g, sliding %g)",
                  last_report.verification.max_signorini_violation,
                  last_report.verification.max_cone_violation,
                  last_report.verification.max_sliding_violation);
              if (!last_report.converged && verification_updates < 2)
                {
                  const double free_scale =
                    norm_W > 0. ? (max_abs(q) + max_abs(b)) / norm_W : 0.;
                  update_and_turn(true,
                                  same,
                                  std::max(1e-2 * options.tolerance *
                                             std::max(p_max, free_scale),
                                           10. * last_report.linear_residual *
                                             p_max));
                  if (!same)
                    {
                      ++verification_updates;
                      verification_failure =
                        failure + ", and the states that it changed did not "
                                  "lead to a verified answer";
                      state        = new_state;
                      feature      = new_feature;
                      tight        = true;
                      settled_once = true;
                      continue;
                    }
                }
              last_report.message += failure;
              break;
            }
          state   = new_state;
          feature = new_feature;
          // The inexact solves' margin may hide a front: the tight margin
          // would change at least ten times one more state than this small
          // update did (at most sqrt(n) changes: near the answer; not a
          // damped cycle, whose count says nothing about a front). The next
          // solve is then tight, a probe; if its update changes ten times
          // one more state than the inexact one did, the front was hidden
          // and the solves are tight from here on, else they go back to
          // inexact and no probe is made again in this solve. On the 1 m
          // slab of benchmarks/scaling at 30 001 contacts, a stick-slip
          // front moved one node per inexact iteration for 320 iterations
          // of one step; the first tight solve moved it by 910 nodes (the
          // step took 29 iterations). On contact_mpi's block on a slab the
          // tight margin's count after an inexact solve is mostly its
          // error: there tight solves from then on (without the probe's
          // test) changed 2 to 5 states per iteration as the inexact ones
          // did, at twice the GMRES iterations (24 003 candidates: 7 641
          // -> 8 624 products in 20 steps).
          if (was_probe)
            {
              if (n_changes >= 10 * (probe_reference + 1))
                settled_once = true;
              else
                probe_failed = true;
            }
          else if (!tight && !probe_failed && !damped_cycle &&
                   n_changes <= front_width &&
                   n_changes_tight_margin >= 10 * (n_changes + 1))
            {
              probing         = true;
              probe_reference = n_changes;
            }
          // once the states have settled, every solve is tight (a solve is
          // tight only after that, warm starts included), and a probe
          tight = settled_once || probing;
        }
      if (!last_report.converged && last_report.message.empty() &&
          !verification_failure.empty())
        last_report.message = verification_failure + " in " +
                              std::to_string(last_report.iterations) +
                              " active-set iterations";
      if (!last_report.converged && last_report.message.empty())
        last_report.message = "the contact states did not settle in " +
                              std::to_string(last_report.iterations) +
                              " active-set iterations";
      return last_report;
    }



    const std::vector<double> &
    ActiveSetSolver::impulses() const
    {
      return P;
    }



    const std::vector<double> &
    ActiveSetSolver::velocities() const
    {
      return V;
    }



    const std::vector<ContactState> &
    ActiveSetSolver::states() const
    {
      return state;
    }



    const ActiveSetReport &
    ActiveSetSolver::report() const
    {
      return last_report;
    }
  } // namespace lcp
} // namespace impactfe
