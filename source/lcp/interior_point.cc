#include <impactfe/lcp/interior_point.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "lapack.h"

namespace impactfe
{
  namespace lcp
  {
    namespace
    {
      // @sect3{The second-order cone}
      // A block of size 1 is the half line x_0 >= 0 (a contact without
      // friction), a block of size d >= 2 the cone L = {|x_T| <= x_0} with
      // J = diag(1, -1, ...), the Jordan product a o b = (a.b, a_0 b_T +
      // b_0 a_T) and the identity e = (1, 0, ...).

      /// a^T J a (d >= 2), a_0 (d == 1): positive inside the cone.
      double
      hyperbolic(const double *a, const unsigned int d)
      {
        if (d == 1)
          return a[0];
        double s = a[0] * a[0];
        for (unsigned int k = 1; k < d; ++k)
          s -= a[k] * a[k];
        return s;
      }

      void
      jordan_product(const double      *a,
                     const double      *b,
                     const unsigned int d,
                     double            *out)
      {
        double dot = a[0] * b[0];
        for (unsigned int k = 1; k < d; ++k)
          {
            dot += a[k] * b[k];
            out[k] = a[0] * b[k] + b[0] * a[k];
          }
        out[0] = dot;
      }

      /// t with l o t = xi (l inside the cone).
      void
      jordan_solve(const double      *l,
                   const double      *xi,
                   const unsigned int d,
                   double            *t)
      {
        if (d == 1)
          {
            t[0] = xi[0] / l[0];
            return;
          }
        double ll = 0., lxi = 0.;
        for (unsigned int k = 1; k < d; ++k)
          {
            ll += l[k] * l[k];
            lxi += l[k] * xi[k];
          }
        t[0] = (l[0] * xi[0] - lxi) / (l[0] * l[0] - ll);
        for (unsigned int k = 1; k < d; ++k)
          t[k] = (xi[k] - t[0] * l[k]) / l[0];
      }

      /// The largest alpha with x + alpha dx in the cone (x inside it).
      double
      max_step(const double *x, const double *dx, const unsigned int d)
      {
        constexpr double infinity = std::numeric_limits<double>::infinity();
        double           alpha    = dx[0] < 0. ? -x[0] / dx[0] : infinity;
        if (d == 1)
          return alpha;
        // hyperbolic(x + alpha dx) = c + 2 b alpha + a alpha^2 >= 0, c > 0.
        const double a = hyperbolic(dx, d), c = hyperbolic(x, d);
        double       b = x[0] * dx[0];
        for (unsigned int k = 1; k < d; ++k)
          b -= x[k] * dx[k];
        const double disc = b * b - a * c;
        if (a == 0.)
          {
            if (b < 0.)
              alpha = std::min(alpha, -c / (2. * b));
          }
        else if (disc >= 0.)
          {
            // the roots q/a and c/q, without cancellation
            const double q = -(b + std::copysign(std::sqrt(disc), b));
            for (const double root : {q / a, q != 0. ? c / q : infinity})
              if (root > 0.)
                alpha = std::min(alpha, root);
          }
        return alpha;
      }

      /**
       * The Nesterov-Todd scaling of a pair x, y inside the cone: the
       * symmetric positive definite W (an automorphism of the cone) with
       * W x = W^{-1} y = lambda, W = beta (2 v v^T - J), v the Jordan square
       * root of the scaling point (Vandenberghe's CVXOPT notes, Section 4).
       */
      struct Scaling
      {
        double W[9], W_inverse[9], G2[9], lambda[3];
      };

      bool
      nt_scaling(const double      *x,
                 const double      *y,
                 const unsigned int d,
                 Scaling           &s)
      {
        if (d == 1)
          {
            if (!(x[0] > 0. && y[0] > 0.))
              return false;
            s.W[0]         = std::sqrt(y[0] / x[0]);
            s.W_inverse[0] = 1. / s.W[0];
            s.G2[0]        = y[0] / x[0];
            s.lambda[0]    = std::sqrt(x[0] * y[0]);
            return true;
          }
        const double hx = hyperbolic(x, d), hy = hyperbolic(y, d);
        if (!(hx > 0. && hy > 0. && x[0] > 0. && y[0] > 0.))
          return false;
        const double nx = std::sqrt(hx), ny = std::sqrt(hy);
        double       xy = 0.;
        for (unsigned int k = 0; k < d; ++k)
          xy += x[k] * y[k];
        const double gamma = std::sqrt(0.5 * (1. + xy / (nx * ny)));
        double       w[3], v[3];
        w[0] = (y[0] / ny + x[0] / nx) / (2. * gamma);
        for (unsigned int k = 1; k < d; ++k)
          w[k] = (y[k] / ny - x[k] / nx) / (2. * gamma);
        const double norm = std::sqrt(2. * (w[0] + 1.));
        for (unsigned int k = 0; k < d; ++k)
          v[k] = (w[k] + (k == 0 ? 1. : 0.)) / norm;
        const double beta = std::sqrt(ny / nx);
        for (unsigned int i = 0; i < d; ++i)
          for (unsigned int j = 0; j < d; ++j)
            {
              const double J  = i != j ? 0. : i == 0 ? 1. : -1.;
              const double sv = (i == 0 ? 1. : -1.) * (j == 0 ? 1. : -1.);
              s.W[i * d + j]  = beta * (2. * v[i] * v[j] - J);
              s.W_inverse[i * d + j] = (2. * sv * v[i] * v[j] - J) / beta;
            }
        for (unsigned int i = 0; i < d; ++i)
          {
            s.lambda[i] = 0.;
            for (unsigned int j = 0; j < d; ++j)
              {
                s.lambda[i] += s.W[i * d + j] * x[j];
                double g = 0.;
                for (unsigned int k = 0; k < d; ++k)
                  g += s.W[i * d + k] * s.W[k * d + j];
                s.G2[i * d + j] = g;
              }
          }
        return true;
      }

      void
      multiply(const double      *A,
               const double      *x,
               const unsigned int d,
               double            *out)
      {
        for (unsigned int i = 0; i < d; ++i)
          {
            out[i] = 0.;
            for (unsigned int j = 0; j < d; ++j)
              out[i] += A[i * d + j] * x[j];
          }
      }

      /// max_i |v_i|
      double
      max_norm(const std::vector<double> &v)
      {
        double m = 0.;
        for (const double x : v)
          m = std::max(m, std::abs(x));
        return m;
      }

      /// rho_c = d / trace(W_cc): the natural map's step for contact c.
      double
      contact_step(const ContactProblem &p, const unsigned int c)
      {
        const unsigned int d = p.n_directions;
        double             w = 0.;
        for (unsigned int k = 0; k < d; ++k)
          w += p.W(d * c + k, d * c + k);
        return w > 0. ? d / w : 0.;
      }

      /**
       * proj_K(z) on K = {|z_T| <= mu z_N} (d numbers) and, if @p D is not
       * null, its derivative (d x d, row-major; one element of the
       * generalized Jacobian on the boundaries of the three pieces).
       */
      void
      project_on_cone(const double      *z,
                      const double       mu,
                      const unsigned int d,
                      double            *proj,
                      double            *D)
      {
        double zT = 0.;
        for (unsigned int k = 1; k < d; ++k)
          zT += z[k] * z[k];
        zT = std::sqrt(zT);
        if (D != nullptr)
          std::fill(D, D + d * d, 0.);
        if (zT <= mu * z[0] && z[0] >= 0.) // inside
          {
            std::copy(z, z + d, proj);
            if (D != nullptr)
              for (unsigned int k = 0; k < d; ++k)
                D[k * d + k] = 1.;
          }
        else if (mu * zT <= -z[0]) // in the polar cone
          std::fill(proj, proj + d, 0.);
        else if (mu <= 0. || zT == 0.) // the half line P_T = 0
          {
            std::fill(proj, proj + d, 0.);
            proj[0] = z[0];
            if (D != nullptr)
              D[0] = 1.;
          }
        else // onto the cone's surface
          {
            const double s = 1. / (1. + mu * mu);
            const double a = s * (mu * zT + z[0]);
            proj[0]        = a;
            for (unsigned int k = 1; k < d; ++k)
              proj[k] = mu * a * z[k] / zT;
            if (D != nullptr)
              {
                D[0] = s;
                for (unsigned int k = 1; k < d; ++k)
                  {
                    const double t = z[k] / zT;
                    D[k]           = s * mu * t;
                    D[k * d]       = s * mu * t;
                    for (unsigned int l = 1; l < d; ++l)
                      D[k * d + l] =
                        s * mu * mu * t * z[l] / zT +
                        mu * a * ((k == l ? 1. : 0.) - t * z[l] / zT) / zT;
                  }
              }
          }
      }

      /**
       * The natural map F(P) = P - proj_K(P - rho u~(P)) of the
       * circular-cone problem per contact, with u = W P + q, and if @p J is
       * not null its Jacobian (column-major, n x n) at P:
       * J = I - D (I - rho (W + N)), D the projection's derivative and N the
       * derivative of mu |u_T| e_N.
       */
      void
      natural_map(const ContactProblem      &p,
                  const std::vector<double> &q,
                  const std::vector<double> &P,
                  std::vector<double>       &u,
                  std::vector<double>       &F,
                  double                    *J)
      {
        const unsigned int d = p.n_directions;
        const int          n = static_cast<int>(P.size());
        u                    = q;
        const int    one     = 1;
        const double alpha = 1., beta = 1.;
        // W is row-major: as a column-major array it is W^T.
        dgemv_("T",
               &n,
               &n,
               &alpha,
               p.W.row(0),
               &n,
               P.data(),
               &one,
               &beta,
               u.data(),
               &one);
        F.resize(n);
        if (J != nullptr)
          std::fill(J, J + std::size_t(n) * n, 0.);
        double       D[9], z[3], proj[3], t[2] = {0., 0.}, M[3];
        const double mu_zero = 0.;
        for (unsigned int c = 0; c < p.n_contacts; ++c)
          {
            const std::size_t r   = std::size_t(d) * c;
            const double      mu  = d > 1 ? p.mu[c] : mu_zero;
            const double      rho = contact_step(p, c);
            double            uT  = 0.;
            for (unsigned int k = 1; k < d; ++k)
              uT += u[r + k] * u[r + k];
            uT = std::sqrt(uT);
            for (unsigned int k = 0; k < d; ++k)
              z[k] = P[r + k] - rho * (u[r + k] + (k == 0 ? mu * uT : 0.));
            project_on_cone(z, mu, d, proj, J != nullptr ? D : nullptr);
            for (unsigned int k = 0; k < d; ++k)
              F[r + k] = P[r + k] - proj[k];
            if (J == nullptr)
              continue;
            const bool slip_term = mu > 0. && uT > 0.;
            for (unsigned int k = 1; k < d && slip_term; ++k)
              t[k - 1] = u[r + k] / uT;
            // rows r..r+d-1: (I - D) on the diagonal block + rho D M_c
            for (unsigned int a = 0; a < d; ++a)
              for (unsigned int b = 0; b < d; ++b)
                J[(r + a) + std::size_t(n) * (r + b)] =
                  (a == b ? 1. : 0.) - D[a * d + b];
            for (int j = 0; j < n; ++j)
              {
                // M_c(:, j): rows of W, plus mu t^T W_T in the normal row
                for (unsigned int b = 0; b < d; ++b)
                  M[b] = p.W(r + b, j);
                if (slip_term)
                  for (unsigned int k = 1; k < d; ++k)
                    M[0] += mu * t[k - 1] * p.W(r + k, j);
                for (unsigned int a = 0; a < d; ++a)
                  {
                    double s = 0.;
                    for (unsigned int b = 0; b < d; ++b)
                      s += D[a * d + b] * M[b];
                    J[(r + a) + std::size_t(n) * j] += rho * s;
                  }
              }
          }
      }

      double
      two_norm(const std::vector<double> &v)
      {
        double s = 0.;
        for (const double x : v)
          s += x * x;
        return std::sqrt(s);
      }
    } // namespace



    double
    exact_cone_residual(const ContactProblem      &p,
                        const std::vector<double> &P,
                        std::vector<double>       &u)
    {
      std::vector<double> q(p.free_velocity), F;
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        q[p.n_directions * c] += p.gap_term[c];
      natural_map(p, q, P, u, F, nullptr);
      // The impulse scale of verify_contact_solution(): at a grazing
      // step every impulse is round-off, and the velocities set the scale.
      double free = 0., gaps = 0.;
      for (const double v : p.free_velocity)
        free = std::max(free, std::abs(v));
      for (const double b : p.gap_term)
        gaps = std::max(gaps, std::abs(b));
      const double w = p.W.linfty_norm();
      const double scale =
        std::max(max_norm(P), w > 0. ? (free + gaps) / w : 0.);
      const double residual = max_norm(F);
      return scale > 0. ? residual / scale : residual;
    }



    // @sect3{The interior point iteration}
    const ContactSolution &
    CoulombInteriorPointSolver::solve(const ContactProblem       &problem,
                                      const InteriorPointOptions &options)
    {
      check_contact_problem(problem);
      const unsigned int dim = problem.n_directions;
      const std::size_t  N   = std::size_t(dim) * problem.n_contacts;
      answer                 = ContactSolution();
      last_report            = InteriorPointReport();
      answer.form            = FrictionForm::automatic;
      answer.lcp.status      = Status::numerical_failure;

      // q = V_free + b_N; W and q of unit size, P = (q_scale / w_scale) x~.
      std::vector<double> q(problem.free_velocity);
      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        q[dim * c] += problem.gap_term[c];
      const double        w_scale = problem.W.max_abs(), q_scale = max_norm(q);
      std::vector<double> P(N, 0.), work;

      // The unknowns: per contact P_N, and P_T where mu > 0; blocks of
      // size 1 (no friction) or dim.
      std::vector<std::size_t>  full;
      std::vector<double>       E;
      std::vector<unsigned int> block_start, block_size;
      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        {
          const bool friction = dim > 1 && problem.mu[c] > 0.;
          block_start.push_back(full.size());
          block_size.push_back(friction ? dim : 1);
          for (unsigned int k = 0; k < (friction ? dim : 1); ++k)
            {
              full.push_back(std::size_t(dim) * c + k);
              E.push_back(k == 0 ? 1. : problem.mu[c]);
            }
        }
      const int    n = static_cast<int>(full.size());
      unsigned int m = 0; // the barrier's degree
      for (const unsigned int b : block_size)
        m += b == 1 ? 1 : 2;

      std::string stop = "converged";
      if (q_scale > 0. && w_scale > 0. && n > 0)
        {
          if (n > 12000)
            throw std::invalid_argument(
              "interior point route: " + std::to_string(n) +
              " unknowns are too many for its dense matrices");
          std::vector<double> Q(std::size_t(n) * n), H(Q.size());
          std::vector<double> c0(n), x(n, 0.), y(n, 0.), res(n), dx(n), dy(n),
            dxa(n), dya(n), xi(n), rhs(n), Wt(n), normal_row(n, 0.);
          std::vector<int>     pivots(n);
          std::vector<Scaling> scaling(block_size.size());
          for (int j = 0; j < n; ++j)
            {
              c0[j] = E[j] * q[full[j]] / q_scale;
              for (int i = 0; i < n; ++i)
                Q[i + std::size_t(n) * j] =
                  E[i] * E[j] * problem.W(full[i], full[j]) / w_scale;
            }
          for (const unsigned int s : block_start)
            x[s] = y[s] = 1.;
          const double c_norm    = max_norm(c0);
          const double tolerance = 1e-12;
          const int    one       = 1;

          // Newton's direction for the right-hand side xi of the
          // complementarity rows: W t with lambda o t = xi, then
          // (Q + A G^2) dx = A W t + res and dy = W t - G^2 dx.
          auto direction = [&](std::vector<double> &ddx,
                               std::vector<double> &ddy) {
            for (std::size_t b = 0; b < block_size.size(); ++b)
              {
                const unsigned int s = block_start[b], d = block_size[b];
                double             t[3];
                jordan_solve(scaling[b].lambda, &xi[s], d, t);
                multiply(scaling[b].W, t, d, &Wt[s]);
                for (unsigned int k = 0; k < d; ++k)
                  rhs[s + k] = Wt[s + k] + res[s + k];
                for (unsigned int k = 1; k < d; ++k)
                  rhs[s] += normal_row[s + k] * Wt[s + k];
              }
            int info = 0;
            ddx      = rhs;
            dgetrs_("N",
                    &n,
                    &one,
                    H.data(),
                    &n,
                    pivots.data(),
                    ddx.data(),
                    &n,
                    &info);
            for (std::size_t b = 0; b < block_size.size(); ++b)
              {
                const unsigned int s = block_start[b], d = block_size[b];
                multiply(scaling[b].G2, &ddx[s], d, &ddy[s]);
                for (unsigned int k = 0; k < d; ++k)
                  ddy[s + k] = Wt[s + k] - ddy[s + k];
              }
          };
          auto step_to_boundary = [&](const std::vector<double> &ddx,
                                      const std::vector<double> &ddy) {
            double alpha = 1.;
            for (std::size_t b = 0; b < block_size.size(); ++b)
              {
                const unsigned int s = block_start[b], d = block_size[b];
                alpha = std::min({alpha,
                                  max_step(&x[s], &ddx[s], d),
                                  max_step(&y[s], &ddy[s], d)});
              }
            return alpha;
          };

          unsigned int it = 0;
          for (;; ++it)
            {
              double gap = 0.;
              for (int i = 0; i < n; ++i)
                gap += x[i] * y[i];
              const double nu = gap / m;
              // res = A(y) - Q x - c0, with A(y)_N = y_N - |y_T|, smoothed
              // as sqrt(|y_T|^2 + nu^2); normal_row holds -y_T/|y_T|.
              for (std::size_t b = 0; b < block_size.size(); ++b)
                {
                  const unsigned int s = block_start[b], d = block_size[b];
                  double             yT = nu * nu;
                  for (unsigned int k = 1; k < d; ++k)
                    yT += y[s + k] * y[s + k];
                  yT = std::sqrt(yT);
                  for (unsigned int k = 0; k < d; ++k)
                    res[s + k] = y[s + k] - c0[s + k];
                  if (d > 1)
                    res[s] -= yT;
                  for (unsigned int k = 1; k < d; ++k)
                    normal_row[s + k] = yT > 0. ? -y[s + k] / yT : 0.;
                }
              const double minus_one = -1., plus_one = 1.;
              dgemv_("N",
                     &n,
                     &n,
                     &minus_one,
                     Q.data(),
                     &n,
                     x.data(),
                     &one,
                     &plus_one,
                     res.data(),
                     &one);
              if (max_norm(res) <= tolerance * (1. + c_norm) && nu <= tolerance)
                break;
              if (it == options.max_iterations)
                {
                  stop = "iteration limit";
                  break;
                }
              bool inside = true;
              for (std::size_t b = 0; b < block_size.size() && inside; ++b)
                inside = nt_scaling(&x[block_start[b]],
                                    &y[block_start[b]],
                                    block_size[b],
                                    scaling[b]);
              if (!inside)
                {
                  stop = "stalled";
                  break;
                }
              H = Q;
              for (std::size_t b = 0; b < block_size.size(); ++b)
                {
                  const unsigned int s = block_start[b], d = block_size[b];
                  for (unsigned int i = 0; i < d; ++i)
                    for (unsigned int j = 0; j < d; ++j)
                      {
                        double g = scaling[b].G2[i * d + j];
                        if (i == 0)
                          for (unsigned int k = 1; k < d; ++k)
                            g += normal_row[s + k] * scaling[b].G2[k * d + j];
                        H[(s + i) + std::size_t(n) * (s + j)] += g;
                      }
                }
              int info = 0;
              dgetrf_(&n, &n, H.data(), &n, pivots.data(), &info);
              if (info != 0)
                {
                  stop = "singular Newton matrix";
                  break;
                }
              // Predictor: xi = -lambda o lambda.
              for (std::size_t b = 0; b < block_size.size(); ++b)
                {
                  const unsigned int s = block_start[b], d = block_size[b];
                  jordan_product(scaling[b].lambda,
                                 scaling[b].lambda,
                                 d,
                                 &xi[s]);
                  for (unsigned int k = 0; k < d; ++k)
                    xi[s + k] = -xi[s + k];
                }
              direction(dxa, dya);
              const double alpha_affine = step_to_boundary(dxa, dya);
              double       gap_affine   = 0.;
              for (int i = 0; i < n; ++i)
                gap_affine += (x[i] + alpha_affine * dxa[i]) *
                              (y[i] + alpha_affine * dya[i]);
              const double sigma =
                std::pow(std::clamp(gap_affine / gap, 0., 1.), 3);
              // Corrector: xi = -lambda o lambda - (W dx_a) o (W^-1 dy_a)
              // + sigma nu e.
              for (std::size_t b = 0; b < block_size.size(); ++b)
                {
                  const unsigned int s = block_start[b], d = block_size[b];
                  double             a[3], c[3], ac[3];
                  multiply(scaling[b].W, &dxa[s], d, a);
                  multiply(scaling[b].W_inverse, &dya[s], d, c);
                  jordan_product(a, c, d, ac);
                  jordan_product(scaling[b].lambda,
                                 scaling[b].lambda,
                                 d,
                                 &xi[s]);
                  for (unsigned int k = 0; k < d; ++k)
                    xi[s + k] = -xi[s + k] - ac[k];
                  xi[s] += sigma * nu;
                }
              direction(dx, dy);
              const double alpha =
                std::min(1., 0.99 * step_to_boundary(dx, dy));
              if (!(alpha > 1e-10))
                {
                  stop = "stalled";
                  break;
                }
              for (int i = 0; i < n; ++i)
                {
                  x[i] += alpha * dx[i];
                  y[i] += alpha * dy[i];
                }
            }
          last_report.iterations  = it;
          const double to_impulse = q_scale / w_scale;
          for (int i = 0; i < n; ++i)
            P[full[i]] = E[i] * x[i] * to_impulse;
        }
      else if (n == 0)
        stop = "no unknowns";
      last_report.stop = stop;

      // @sect3{Semismooth Newton on the natural map}
      // From the interior point answer, Levenberg-Marquardt steps
      // (J^T J + lambda I) dP = -J^T F with a backtracking line search on
      // |F|: quadratic where the contact states are settled, and steps to
      // one of the solutions where redundant contacts make J singular.
      last_report.residual = exact_cone_residual(problem, P, work);
      if (last_report.residual > options.tolerance && n > 0 && w_scale > 0. &&
          q_scale > 0.)
        {
          const int           nn = static_cast<int>(N);
          std::vector<double> J(N * N), JtJ(N * N), F, F_trial, u, step(N),
            trial;
          std::vector<double> best            = P;
          double              best_residual   = last_report.residual;
          unsigned int        full_steps_left = 3;
          for (unsigned int it = 0; it < options.max_newton_iterations; ++it)
            {
              natural_map(problem, q, P, u, F, J.data());
              const double f = two_norm(F);
              // J^T J (upper triangle) and -J^T F
              const double one = 1., zero = 0., minus_one = -1.;
              const int    inc = 1;
              dsyrk_("U",
                     "T",
                     &nn,
                     &nn,
                     &one,
                     J.data(),
                     &nn,
                     &zero,
                     JtJ.data(),
                     &nn);
              dgemv_("T",
                     &nn,
                     &nn,
                     &minus_one,
                     J.data(),
                     &nn,
                     F.data(),
                     &inc,
                     &zero,
                     step.data(),
                     &inc);
              double largest = 0.;
              for (std::size_t i = 0; i < N; ++i)
                largest = std::max(largest, JtJ[i + N * i]);
              for (std::size_t i = 0; i < N; ++i)
                JtJ[i + N * i] += 1e-14 * largest;
              int info = 0;
              dpotrf_("U", &nn, JtJ.data(), &nn, &info);
              if (info != 0)
                break;
              dpotrs_("U", &nn, &inc, JtJ.data(), &nn, step.data(), &nn, &info);
              ++last_report.newton_iterations;
              double t = 1.;
              for (; t >= 1e-4; t *= 0.5)
                {
                  trial = P;
                  for (std::size_t i = 0; i < N; ++i)
                    trial[i] += t * step[i];
                  natural_map(problem, q, trial, u, F_trial, nullptr);
                  if (two_norm(F_trial) < (1. - 1e-4 * t) * f)
                    break;
                }
              // At the kinks of F (degenerate contacts: no impulse and no
              // velocity) the element of the generalized Jacobian may not
              // give a descent direction; a few full steps are taken anyway
              // (the best iterate is what is returned).
              if (t < 1e-4)
                {
                  if (full_steps_left == 0)
                    break;
                  --full_steps_left;
                  trial = P;
                  for (std::size_t i = 0; i < N; ++i)
                    trial[i] += step[i];
                }
              P                       = trial;
              const double residual_P = exact_cone_residual(problem, P, work);
              if (residual_P < best_residual)
                {
                  best          = P;
                  best_residual = residual_P;
                }
              if (best_residual <= 1e-2 * options.tolerance)
                break;
            }
          P                    = best;
          last_report.residual = best_residual;
        }

      // @sect3{Verification}
      last_report.converged  = last_report.residual <= options.tolerance;
      last_report.cone_error = exact_cone_error(problem, P);
      const bool finite = std::all_of(P.begin(), P.end(), [](const double v) {
        return std::isfinite(v);
      });
      // The verification's velocity scale |V_free| + |b_N| + |W| |P| is
      // capped at 1e4 (|V_free| + |b_N|): iterates that run off along a
      // direction of W's null space inside the cone (a contact pair pushing
      // against each other, both approaching: no solution) would otherwise
      // pass relative checks with any velocity error.
      ContactVerification check;
      if (finite)
        {
          std::vector<double> V(N);
          problem.W.vmult(V, P);
          for (std::size_t i = 0; i < N; ++i)
            V[i] += problem.free_velocity[i];
          const double data = max_norm(problem.free_velocity) +
                              max_norm(problem.gap_term),
                       largest = max_norm(P);
          double norm_W        = problem.W.linfty_norm();
          if (largest > 0. && data > 0.)
            norm_W = std::min(norm_W, 1e4 * data / largest);
          check = verify_contact_velocities(dim,
                                            problem.free_velocity,
                                            problem.gap_term,
                                            problem.mu,
                                            P,
                                            V,
                                            norm_W,
                                            1e-8);
        }
      char text[240];
      std::snprintf(text,
                    sizeof(text),
                    "interior point: %u iterations (%s), %u Newton "
                    "iterations, residual %.2e, cone error %.2e, %s",
                    last_report.iterations,
                    last_report.stop.c_str(),
                    last_report.newton_iterations,
                    last_report.residual,
                    last_report.cone_error,
                    last_report.converged ? "converged" : "NOT converged");
      answer.message = text;
      answer.lcp.verification.relative_error =
        std::max({check.max_signorini_violation,
                  check.max_cone_violation,
                  check.max_sliding_violation});
      answer.lcp.verification.tolerance = 1e-8;
      answer.lcp.verification.ok        = check.ok;
      if (finite && check.ok)
        {
          answer.lcp.status = Status::solved;
          answer.P          = P;
          answer.states     = contact_states(problem, P);
        }
      else
        answer.message += "; the answer fails the verification";
      answer.lcp.message = answer.message;
      return answer;
    }



    const InteriorPointReport &
    CoulombInteriorPointSolver::report() const
    {
      return last_report;
    }



    const ContactSolution &
    CoulombInteriorPointSolver::solution() const
    {
      return answer;
    }
  } // namespace lcp
} // namespace impactfe
