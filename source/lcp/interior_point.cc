#include <impactfe/lcp/interior_point.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "../utilities/blas_lapack.h"
#include "contact_workspace.h"

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

      /// No NaN and no infinity in @p v (max_norm() passes over a NaN).
      bool
      all_finite(const std::vector<double> &v)
      {
        return std::all_of(v.begin(), v.end(), [](const double x) {
          return std::isfinite(x);
        });
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

      /**
       * verify_contact_velocities() on @p P with the friction coefficients
       * @p mu (zeros for a frictionless answer) and the polygon of
       * @p n_facets (0: the circle), to 1e-8. The velocity scale |V_free|
       * + |b_N| + |W| |P| is capped at 1e4 (|V_free| + |b_N|): where no
       * solution exists along a direction of W's null space inside the cone
       * (a contact pair pushing against each other, both approaching), the
       * iterates of an interior point method run off along it and would
       * pass relative checks with any velocity error.
       */
      ContactVerification
      verify_interior_point_answer(const ContactProblem      &p,
                                   const std::vector<double> &P,
                                   const std::vector<double> &mu,
                                   const unsigned int         n_facets)
      {
        if (!all_finite(P))
          return ContactVerification();
        std::vector<double> V;
        p.W.vmult(V, P);
        for (std::size_t i = 0; i < V.size(); ++i)
          V[i] += p.free_velocity[i];
        const double data    = max_norm(p.free_velocity) + max_norm(p.gap_term),
                     largest = max_norm(P);
        double norm_W        = p.W.linfty_norm();
        if (largest > 0. && data > 0.)
          norm_W = std::min(norm_W, 1e4 * data / largest);
        return verify_contact_velocities(p.n_directions,
                                         p.free_velocity,
                                         p.gap_term,
                                         mu,
                                         P,
                                         V,
                                         norm_W,
                                         1e-8,
                                         n_facets);
      }
    } // namespace



    double
    exact_cone_residual(const ContactProblem      &p,
                        const std::vector<double> &P,
                        std::vector<double>       &u)
    {
      // a NaN or an infinity is no answer
      if (!all_finite(P))
        return std::numeric_limits<double>::infinity();
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
      if (!all_finite(F))
        return std::numeric_limits<double>::infinity();
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
              // A nearly singular Newton matrix (redundant contacts: W of
              // lower rank) can give a direction with a NaN, which the
              // step to the boundary's comparisons pass over, and which
              // was then taken as a full step (a rigid box on four
              // corners, with one BLAS and not another). The iterate is
              // kept instead.
              const double alpha =
                std::min(1., 0.99 * step_to_boundary(dx, dy));
              if (!all_finite(dx) || !all_finite(dy))
                {
                  stop = "non-finite direction";
                  break;
                }
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
      // The answer must pass verify_interior_point_answer() (1e-8) too: a
      // tolerance looser than that (lcp-solve --tolerance 1e-6) stops the
      // iterations at a point that can fail it. Then the Newton steps go on
      // to a target a thousand times below the residual reached, twice at
      // most.
      double newton_target = options.tolerance;
      for (unsigned int pass = 0; pass < 3; ++pass)
        {
          last_report.residual = exact_cone_residual(problem, P, work);
          if (pass > 0 &&
              (verify_interior_point_answer(problem, P, problem.mu, 0).ok ||
               !(last_report.residual < newton_target)))
            break;
          if (pass > 0)
            newton_target = 1e-3 * last_report.residual;
          if (!(last_report.residual > newton_target && n > 0 && w_scale > 0. &&
                q_scale > 0.))
            continue;
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
              if (info != 0 || !all_finite(step))
                break;
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
              if (best_residual <= 1e-2 * newton_target)
                break;
            }
          P                    = best;
          last_report.residual = best_residual;
        }

      // @sect3{Verification}
      last_report.converged  = last_report.residual <= options.tolerance;
      last_report.cone_error = exact_cone_error(problem, P);
      const ContactVerification check =
        verify_interior_point_answer(problem, P, problem.mu, 0);
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
      if (check.ok)
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



    // @sect3{The facet form by an interior point method}
    ContactSolution
    solve_facet_form_by_interior_point(const ContactProblem &problem,
                                       const ContactOptions &options,
                                       const unsigned int    max_iterations)
    {
      check_contact_problem(problem);
      const unsigned int dim = problem.n_directions, nc = problem.n_contacts;
      const bool friction = internal::resolved_form(problem, options.form) !=
                            FrictionForm::frictionless;
      const unsigned int k = !friction ? 0 : dim == 2 ? 2 : options.n_facets;
      if (friction && dim == 3 && k < 3)
        throw std::invalid_argument("facet form: need at least 3 facets in 3D");
      std::vector<std::vector<double>> D;
      if (friction)
        internal::facet_directions(dim, k, D);
      ContactSolution out;
      out.form = friction ? FrictionForm::facets : FrictionForm::frictionless;
      out.n_facets       = k;
      out.lcp.status     = Status::numerical_failure;
      out.lcp.start_path = StartPath::cold;

      // Per contact a block of the form's unknowns: (P_N, beta_1..k, sigma)
      // with friction, P_N alone without (a frictionless form, or mu = 0).
      const std::size_t        N = std::size_t(dim) * nc;
      std::vector<std::size_t> start(nc + 1, 0);
      for (unsigned int c = 0; c < nc; ++c)
        start[c + 1] = start[c] + (friction && problem.mu[c] > 0. ? k + 2 : 1);
      const std::size_t nz   = start[nc];
      auto              size = [&](unsigned int c) {
        return static_cast<unsigned int>(start[c + 1] - start[c]);
      };
      std::vector<double> q(problem.free_velocity);
      for (unsigned int c = 0; c < nc; ++c)
        q[dim * c] += problem.gap_term[c];
      const double w_scale = problem.W.max_abs(), q_scale = max_norm(q);
      // P = G z and G^T u, per block.
      auto to_impulses = [&](const std::vector<double> &z,
                             std::vector<double>       &P) {
        P.assign(N, 0.);
        for (unsigned int c = 0; c < nc; ++c)
          {
            P[dim * c] = z[start[c]];
            for (unsigned int j = 0; size(c) > 1 && j < k; ++j)
              for (unsigned int a = 0; a + 1 < dim; ++a)
                P[dim * c + 1 + a] += D[j][a] * z[start[c] + 1 + j];
          }
      };
      auto transpose_product = [&](const std::vector<double> &u,
                                   std::vector<double>       &out_z) {
        out_z.assign(nz, 0.);
        for (unsigned int c = 0; c < nc; ++c)
          {
            out_z[start[c]] = u[dim * c];
            for (unsigned int j = 0; size(c) > 1 && j < k; ++j)
              for (unsigned int a = 0; a + 1 < dim; ++a)
                out_z[start[c] + 1 + j] += D[j][a] * u[dim * c + 1 + a];
          }
      };
      // W u / scale (W row-major: as a column-major array it is W^T).
      const int n_int = static_cast<int>(N), one = 1;
      auto      W_times = [&](const std::vector<double> &u,
                         std::vector<double>       &Wu,
                         const double               scale) {
        Wu.assign(N, 0.);
        const double zero = 0.;
        dgemv_("T",
               &n_int,
               &n_int,
               &scale,
               problem.W.row(0),
               &n_int,
               u.data(),
               &one,
               &zero,
               Wu.data(),
               &one);
      };
      // M z + q_z for the form of W / w_scale and q / q_scale.
      std::vector<double> P, u, Gu, qz;
      transpose_product(q, qz);
      for (double &x : qz)
        x /= q_scale > 0. ? q_scale : 1.;
      auto form_product = [&](const std::vector<double> &z,
                              std::vector<double>       &w) {
        to_impulses(z, P);
        W_times(P, u, 1. / w_scale);
        transpose_product(u, w);
        for (unsigned int c = 0; c < nc; ++c)
          if (size(c) > 1)
            {
              const std::size_t s        = start[c];
              double            beta_sum = 0.;
              for (unsigned int j = 0; j < k; ++j)
                {
                  w[s + 1 + j] += z[s + k + 1]; // + sigma
                  beta_sum += z[s + 1 + j];
                }
              w[s + k + 1] = problem.mu[c] * z[s] - beta_sum;
            }
        for (std::size_t i = 0; i < nz; ++i)
          w[i] += qz[i];
      };

      // Newton's matrix M + Z^-1 W_z = G^T W G + B, B = L + Z^-1 W_z block
      // diagonal, is solved through the impulses of the contacts' blocks
      // (P_N, and P_T where there is friction): with K_c = [B_c G_c^T; G_c
      // 0], B_c dz_c + G_c^T y_c = g_c and G_c dz_c = u_c give y = K^-1_21 g
      // + K^-1_22 u locally, and y = W u globally, so
      //   (W + T) u = K^-1_21 g,  T_c = -K^-1_22 = (G_c B_c^-1 G_c^T)^-1,
      //   dz_c = K^-1_11 g_c + K^-1_12 u_c.
      // K_c stays nonsingular where B_c does not (a sliding contact's basic
      // P_N, beta_j and sigma leave B_c's rows of them near zero), so T is
      // formed without B_c^-1: the form of the monotone methods, W plus the
      // barrier's blocks.
      std::vector<std::size_t> reduced_start(nc + 1, 0), reduced;
      for (unsigned int c = 0; c < nc; ++c)
        {
          const unsigned int d_c = size(c) > 1 ? dim : 1;
          for (unsigned int a = 0; a < d_c; ++a)
            reduced.push_back(std::size_t(dim) * c + a);
          reduced_start[c + 1] = reduced_start[c] + d_c;
        }
      const std::size_t nr           = reduced.size();
      const int         nr_int       = static_cast<int>(nr);
      auto              impulse_size = [&](const unsigned int c) {
        return static_cast<unsigned int>(reduced_start[c + 1] -
                                         reduced_start[c]);
      };

      const double to_impulse =
        w_scale > 0. && q_scale > 0. ? q_scale / w_scale : 0.;
      const std::vector<double> mu_checked =
        friction ? problem.mu : std::vector<double>(nc, 0.);
      auto answer_is_verified = [&](const std::vector<double> &zz) {
        to_impulses(zz, P);
        for (double &x : P)
          x *= to_impulse;
        return verify_interior_point_answer(problem,
                                            P,
                                            mu_checked,
                                            dim == 3 ? k : 0)
          .ok;
      };

      std::vector<double> z(nz, 1.), w(nz, 1.);
      unsigned int        it   = 0;
      std::string         stop = "converged";
      if (q_scale > 0. && w_scale > 0.)
        {
          const double        tolerance = 1e-10;
          std::vector<double> r(nz), gz(nz), dz(nz), dw(nz), dza(nz), dwa(nz),
            rc(nz), Mz(nz), rhs(nr), H(nr * nr);
          std::vector<std::size_t> K_start(nc + 1, 0);
          for (unsigned int c = 0; c < nc; ++c)
            {
              const std::size_t m = size(c) + impulse_size(c);
              K_start[c + 1]      = K_start[c] + m * m;
            }
          std::vector<double> K_inverse(K_start[nc]);
          std::vector<int>    pivots(nr);
          DenseMatrix         K_c, K_c_inverse;
          LUFactorization     lu;
          auto                newton = [&](std::vector<double> &ddz) {
            // rhs = K^-1_21 g per contact; (W + T) u = rhs; dz.
            for (unsigned int c = 0; c < nc; ++c)
              {
                const unsigned int mb = size(c), d_c = impulse_size(c),
                                   m = mb + d_c;
                const double *Ki     = &K_inverse[K_start[c]];
                for (unsigned int a = 0; a < d_c; ++a)
                  {
                    double y = 0.;
                    for (unsigned int b = 0; b < mb; ++b)
                      y += Ki[(mb + a) * m + b] * gz[start[c] + b];
                    rhs[reduced_start[c] + a] = y;
                  }
              }
            int info = 0;
            dgetrs_("N",
                    &nr_int,
                    &one,
                    H.data(),
                    &nr_int,
                    pivots.data(),
                    rhs.data(),
                    &nr_int,
                    &info);
            for (unsigned int c = 0; c < nc; ++c)
              {
                const unsigned int mb = size(c), d_c = impulse_size(c),
                                   m = mb + d_c;
                const double *Ki     = &K_inverse[K_start[c]];
                for (unsigned int a = 0; a < mb; ++a)
                  {
                    double y = 0.;
                    for (unsigned int b = 0; b < mb; ++b)
                      y += Ki[a * m + b] * gz[start[c] + b];
                    for (unsigned int b = 0; b < d_c; ++b)
                      y += Ki[a * m + mb + b] * rhs[reduced_start[c] + b];
                    ddz[start[c] + a] = y;
                  }
              }
          };
          // Predictor, then corrector: z dw + w dz = rc and dw - M dz = -r,
          // so (M + Z^-1 W_z) dz = Z^-1 rc + r.
          auto direction = [&](std::vector<double> &ddz,
                               std::vector<double> &ddw) {
            for (std::size_t i = 0; i < nz; ++i)
              gz[i] = rc[i] / z[i] + r[i];
            newton(ddz);
            for (std::size_t i = 0; i < nz; ++i)
              ddw[i] = (rc[i] - w[i] * ddz[i]) / z[i];
          };
          auto ratio = [&](const std::vector<double> &ddz,
                           const std::vector<double> &ddw) {
            double alpha = 1.;
            for (std::size_t i = 0; i < nz; ++i)
              {
                if (ddz[i] < 0.)
                  alpha = std::min(alpha, -z[i] / ddz[i]);
                if (ddw[i] < 0.)
                  alpha = std::min(alpha, -w[i] / ddw[i]);
              }
            return alpha;
          };
          for (;; ++it)
            {
              form_product(z, Mz);
              double gap = 0.;
              for (std::size_t i = 0; i < nz; ++i)
                {
                  r[i] = w[i] - Mz[i];
                  gap += z[i] * w[i];
                }
              const double nu = gap / nz;
              // Near the end, stop as soon as the impulses pass the
              // verification (a degenerate contact keeps z_i and w_i near
              // sqrt(nu), so a tolerance on nu alone can stop short of it).
              if (max_norm(r) <= tolerance * (1. + max_norm(qz)) &&
                  nu <= tolerance && answer_is_verified(z))
                break;
              if (it == max_iterations)
                {
                  stop = "iteration limit";
                  break;
                }
              // K_c = [B_c G_c^T; G_c 0] and its inverse; H = W + T.
              for (std::size_t j = 0; j < nr; ++j)
                for (std::size_t i = 0; i < nr; ++i)
                  H[i + nr * j] = problem.W(reduced[i], reduced[j]) / w_scale;
              bool singular = false;
              for (unsigned int c = 0; c < nc && !singular; ++c)
                {
                  const unsigned int mb = size(c), d_c = impulse_size(c),
                                     m = mb + d_c;
                  const std::size_t s  = start[c];
                  K_c.reinit(m, m);
                  for (unsigned int a = 0; a < mb; ++a)
                    K_c(a, a) = w[s + a] / z[s + a];
                  if (mb > 1)
                    {
                      for (unsigned int j = 0; j < k; ++j)
                        {
                          K_c(1 + j, k + 1) += 1.;
                          K_c(k + 1, 1 + j) -= 1.;
                          for (unsigned int a = 0; a + 1 < dim; ++a) // G_T
                            {
                              K_c(1 + j, mb + 1 + a) = D[j][a];
                              K_c(mb + 1 + a, 1 + j) = D[j][a];
                            }
                        }
                      K_c(k + 1, 0) += problem.mu[c];
                    }
                  K_c(0, mb) = K_c(mb, 0) = 1.; // G_N
                  if (!lu.factorize(K_c, 0.))
                    {
                      singular = true;
                      break;
                    }
                  lu.inverse(K_c_inverse);
                  double *Ki = &K_inverse[K_start[c]];
                  for (unsigned int a = 0; a < m; ++a)
                    for (unsigned int b = 0; b < m; ++b)
                      Ki[a * m + b] = K_c_inverse(a, b);
                  for (unsigned int a = 0; a < d_c; ++a)
                    for (unsigned int b = 0; b < d_c; ++b)
                      H[(reduced_start[c] + a) + nr * (reduced_start[c] + b)] -=
                        K_c_inverse(mb + a, mb + b);
                }
              int info = 0;
              if (!singular)
                dgetrf_(
                  &nr_int, &nr_int, H.data(), &nr_int, pivots.data(), &info);
              if (singular || info != 0)
                {
                  stop = "singular Newton matrix";
                  break;
                }
              for (std::size_t i = 0; i < nz; ++i)
                rc[i] = -z[i] * w[i];
              direction(dza, dwa);
              const double alpha_affine = ratio(dza, dwa);
              double       gap_affine   = 0.;
              for (std::size_t i = 0; i < nz; ++i)
                gap_affine += (z[i] + alpha_affine * dza[i]) *
                              (w[i] + alpha_affine * dwa[i]);
              const double sigma =
                std::pow(std::clamp(gap_affine / gap, 0., 1.), 3);
              for (std::size_t i = 0; i < nz; ++i)
                rc[i] = -z[i] * w[i] - dza[i] * dwa[i] + sigma * nu;
              direction(dz, dw);
              const double alpha = std::min(1., 0.99 * ratio(dz, dw));
              // a direction with a NaN (nearly singular H) would pass
              // ratio()'s comparisons as a full step: keep the iterate
              if (!all_finite(dz) || !all_finite(dw))
                {
                  stop = "non-finite direction";
                  break;
                }
              if (!(alpha > 1e-10))
                {
                  stop = "stalled";
                  break;
                }
              for (std::size_t i = 0; i < nz; ++i)
                {
                  z[i] += alpha * dz[i];
                  w[i] += alpha * dw[i];
                }
            }
        }
      else
        std::fill(z.begin(), z.end(), 0.);

      // The impulses and the form's variables of the problem as given.
      to_impulses(z, P);
      for (double &x : P)
        x *= to_impulse;
      const ContactVerification check =
        verify_interior_point_answer(problem, P, mu_checked, dim == 3 ? k : 0);
      char text[200];
      std::snprintf(text,
                    sizeof(text),
                    "interior point on the %s: %u iterations (%s)",
                    friction ?
                      ("facet form, k = " + std::to_string(k)).c_str() :
                      "frictionless form",
                    it,
                    stop.c_str());
      out.message = text;
      out.lcp.verification.relative_error =
        std::max({check.max_signorini_violation,
                  check.max_cone_violation,
                  check.max_sliding_violation});
      out.lcp.verification.tolerance = 1e-8;
      out.lcp.verification.ok        = check.ok;
      // z and w in the layout of assemble_contact_lcp(): all P_N, then the
      // beta of each contact, then all sigma (sigma of a contact without
      // friction: the least that keeps its facet rows >= 0). Also for a
      // point that fails the verification: z_i > w_i is the guess that
      // warm-starts Lemke's method then (route 3 of contact_routes.h).
      std::vector<double> V;
      problem.W.vmult(V, P);
      for (std::size_t i = 0; i < N; ++i)
        V[i] += q[i];
      const std::size_t n_form = friction ? std::size_t(k + 2) * nc : nc;
      out.lcp.z.assign(n_form, 0.);
      out.lcp.w.assign(n_form, 0.);
      for (unsigned int c = 0; c < nc; ++c)
        {
          out.lcp.z[c] = P[dim * c];
          out.lcp.w[c] = V[dim * c];
          if (!friction)
            continue;
          double sigma = 0.;
          if (size(c) > 1)
            sigma = z[start[c] + k + 1] * q_scale;
          else
            for (unsigned int j = 0; j < k; ++j)
              {
                double dv = 0.;
                for (unsigned int a = 0; a + 1 < dim; ++a)
                  dv += D[j][a] * V[dim * c + 1 + a];
                sigma = std::max(sigma, -dv);
              }
          double beta_sum = 0.;
          for (unsigned int j = 0; j < k; ++j)
            {
              const double beta =
                size(c) > 1 ? z[start[c] + 1 + j] * to_impulse : 0.;
              double dv = 0.;
              for (unsigned int a = 0; a + 1 < dim; ++a)
                dv += D[j][a] * V[dim * c + 1 + a];
              out.lcp.z[nc + std::size_t(c) * k + j] = beta;
              out.lcp.w[nc + std::size_t(c) * k + j] = dv + sigma;
              beta_sum += beta;
            }
          out.lcp.z[nc + std::size_t(nc) * k + c] = sigma;
          out.lcp.w[nc + std::size_t(nc) * k + c] =
            problem.mu[c] * P[dim * c] - beta_sum;
        }
      if (!check.ok)
        {
          out.message += "; the answer fails the verification";
          out.lcp.message = out.message;
          return out;
        }
      out.lcp.status  = Status::solved;
      out.lcp.message = out.message;
      out.P           = P;
      out.states      = contact_states(problem, P);
      return out;
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
