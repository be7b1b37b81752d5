// Lemke's method with an explicit, rank-one updated basis inverse.
//
// Notation. The LCP w = M z + q is written as the linear system
//     I w - M z - d z0 = q
// in the 2n+1 variables w_0..w_{n-1} (index i), z_0..z_{n-1} (index n+i) and
// the artificial z0 (index 2n). A basis is a list basic[p], p = 0..n-1, of
// variables; x[p] is the value of basic[p]; Binv = B^{-1} where column p of B
// is the system column of basic[p]. Rows of B^{-1} are indexed by basis
// positions p, columns by constraint rows c.
#include <impactfe/lcp/lemke.h>
#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "floating_point_mode.h"
#include "text.h"

namespace impactfe
{
  namespace lcp
  {
    std::string
    to_string(const Status status)
    {
      switch (status)
        {
          case Status::solved:
            return "solved";
          case Status::ray_termination:
            return "ray-termination";
          case Status::pivot_limit:
            return "pivot-limit";
          case Status::numerical_failure:
            return "failed";
          case Status::infeasible:
            return "infeasible";
        }
      return "failed";
    }



    std::string
    to_string(const StartPath path)
    {
      switch (path)
        {
          case StartPath::cold:
            return "cold";
          case StartPath::guess_solved:
            return "guess-solved";
          case StartPath::guess_lemke:
            return "guess-lemke";
          case StartPath::guess_fallback_cold:
            return "guess-fallback-cold";
          case StartPath::block_pivoting:
            return "block-pivoting";
        }
      return "cold";
    }



    /**
     * Everything a solve needs besides M and q, kept by LemkeSolver from one
     * solve to the next: the basis and its inverse (LemkeEngine below), the
     * work vectors of the ratio tests, refactorisation and drift check, and
     * the Result. Sizes only grow, so repeated solves allocate nothing.
     */
    struct LemkeSolver::Workspace
    {
      Result result;

      std::vector<double> d, binv, x;
      std::vector<int>    basic, position, slack_pos, dense_cols, dense_index;

      std::vector<double> y, delta, basis_sum, covering, residual, basic_z;
      std::vector<double> slack_row, slack_update, z_end, w_end;
      std::vector<int>    ties, kept_ties, basic_z_positions, dense_rows;
      DenseMatrix         basis_block, basis_block_inverse;
      LUFactorization     lu;
      std::string         note, why;

      std::size_t
      memory_consumption() const
      {
        std::size_t bytes = lcp::memory_consumption(result.z) +
                            lcp::memory_consumption(result.w) +
                            result.message.capacity() + note.capacity() +
                            why.capacity();
        for (const auto *v : {&d,
                              &binv,
                              &x,
                              &y,
                              &delta,
                              &basis_sum,
                              &covering,
                              &residual,
                              &basic_z,
                              &slack_row,
                              &slack_update,
                              &z_end,
                              &w_end})
          bytes += lcp::memory_consumption(*v);
        for (const auto *v : {&basic,
                              &position,
                              &slack_pos,
                              &dense_cols,
                              &dense_index,
                              &ties,
                              &kept_ties,
                              &basic_z_positions,
                              &dense_rows})
          bytes += lcp::memory_consumption(*v);
        return bytes + basis_block.memory_consumption() +
               basis_block_inverse.memory_consumption() +
               lu.memory_consumption();
      }
    };



    namespace
    {
      constexpr double eps = std::numeric_limits<double>::epsilon();

      /// verify() with the residual stored in @p residual.
      Verification
      verify_into(const DenseMatrix         &M,
                  const std::vector<double> &q,
                  const std::vector<double> &z,
                  const std::vector<double> &w,
                  const double               tolerance_factor,
                  std::vector<double>       &residual)
      {
        const std::size_t n = q.size();
        if (M.n_rows() != n || M.n_cols() != n || z.size() != n ||
            w.size() != n)
          throw std::invalid_argument("verify: inconsistent sizes");
        residual.resize(n);
        for (std::size_t i = 0; i < n; ++i)
          {
            double        r  = w[i] - q[i];
            const double *mi = M.row(i);
            for (std::size_t j = 0; j < n; ++j)
              r -= mi[j] * z[j];
            residual[i] = r;
          }
        return verify_with_residual(
          M.linfty_norm(), q, z, w, residual, tolerance_factor);
      }

      bool
      all_finite(const std::vector<double> &v)
      {
        for (const double x : v)
          if (!std::isfinite(x))
            return false;
        return true;
      }

      void
      check_input(const DenseMatrix         &M,
                  const std::vector<double> &q,
                  const LemkeOptions        &options)
      {
        if (M.n_rows() != M.n_cols())
          throw std::invalid_argument("LCP: M is not square");
        if (q.size() != M.n_rows())
          throw std::invalid_argument("LCP: q and M have different sizes");
        if (!all_finite(M.data()) || !all_finite(q))
          throw std::invalid_argument("LCP: M or q has a non-finite entry");
        const std::vector<double> &d = options.covering_vector;
        if (!d.empty())
          {
            if (d.size() != q.size())
              throw std::invalid_argument(
                "LCP: covering vector has the wrong size");
            for (const double v : d)
              if (!(v > 0.) || !std::isfinite(v))
                throw std::invalid_argument(
                  "LCP: covering vector must be positive");
          }
      }



      class LemkeEngine
      {
      public:
        /// The engine's storage is @p workspace's (sized here, reused).
        LemkeEngine(const DenseMatrix         &M_,
                    const std::vector<double> &q_,
                    const LemkeOptions        &options_,
                    LemkeSolver::Workspace    &workspace)
          : n(static_cast<int>(q_.size()))
          , M(M_)
          , q(q_)
          , options(options_)
          , ws(workspace)
          , d(workspace.d)
          , basic(workspace.basic)
          , position(workspace.position)
          , slack_pos(workspace.slack_pos)
          , binv(workspace.binv)
          , dense_cols(workspace.dense_cols)
          , dense_index(workspace.dense_index)
          , x(workspace.x)
          , note(workspace.note)
        {
          d.clear();
          basic.assign(n, 0);
          position.assign(2 * n + 1, -1);
          slack_pos.assign(n, -1);
          // Columns of binv are read only after they are written (a slack
          // leaving the basis, or a refactorisation): no fill needed.
          binv.resize(static_cast<std::size_t>(n) * n);
          dense_cols.clear();
          dense_index.assign(n, -1);
          x.assign(n, 0.);
          note.clear();
          // lists of at most n entries: reserved once, so that they never
          // grow during a solve
          dense_cols.reserve(n);
          ws.ties.reserve(n);
          ws.kept_ties.reserve(n);
          ws.basic_z_positions.reserve(n);
          ws.dense_rows.reserve(n);
          norm_M = M.linfty_norm();
          norm_q = linfty_norm(q);
          vtol   = options.verification_tolerance_factor * eps * std::max(n, 1);
        }

        /// Basis: w_i basic at position i, covering vector d.
        void
        init_slack_basis(const std::vector<double> &covering)
        {
          d.assign(covering.begin(), covering.end());
          for (int i = 0; i < n; ++i)
            {
              basic[i]     = i;
              position[i]  = i;
              slack_pos[i] = i;
            }
          dense_cols.clear();
          std::fill(dense_index.begin(), dense_index.end(), -1);
          x.assign(q.begin(), q.end());
          binv_max = 1.;
          update_scale();
        }

        /// Complementary basis from the guess. False if it is singular.
        bool
        init_guess_basis(const std::vector<bool> &guess)
        {
          std::fill(position.begin(), position.end(), -1);
          for (int i = 0; i < n; ++i)
            {
              const int v  = guess[i] ? n + i : i;
              basic[i]     = v;
              position[v]  = i;
              slack_pos[i] = guess[i] ? -1 : i;
            }
          d.assign(n, 0.);
          update_scale();
          return refactor();
        }

        /// d = B e for the current basis (so that B^{-1} d = e).
        void
        set_covering_to_basis_sum()
        {
          std::vector<double> &sum = ws.basis_sum;
          sum.assign(n, 0.);
          for (int p = 0; p < n; ++p)
            add_column(basic[p], 1., sum);
          d.assign(sum.begin(), sum.end());
          update_scale();
        }

        bool
        basic_solution_feasible() const
        {
          const double tol = vtol * linfty_norm(x);
          for (const double v : x)
            if (v < -tol)
              return false;
          return true;
        }

        void
        extract(std::vector<double> &z, std::vector<double> &w) const
        {
          z.assign(n, 0.);
          w.assign(n, 0.);
          for (int p = 0; p < n; ++p)
            {
              const int v = basic[p];
              if (v < n)
                w[v] = x[p];
              else if (v < 2 * n)
                z[v - n] = x[p];
            }
        }

        /// Run Lemke's method from the current basis: z0 enters first.
        void
        run(const unsigned int cap, Result &result)
        {
          const int            z0 = 2 * n;
          std::vector<double> &y  = ws.y;
          y.resize(n);

          // --- the artificial variable enters
          compute_column(z0, y);
          int r = initial_ratio_test(y);
          if (r < 0)
            {
              fail(result,
                   Status::numerical_failure,
                   "no row can start the path (is d > 0?)");
              return;
            }
          int leaving = basic[r];
          pivot(r, z0, y);
          result.pivots += 1;

          unsigned int since_refactor = 0;
          while (leaving != z0)
            {
              if (result.pivots >= cap)
                {
                  fail(result, Status::pivot_limit);
                  internal::set_text(result.message,
                                     "pivot cap %u reached; z0 = %g",
                                     cap,
                                     x[position[z0]]);
                  return;
                }
              const int entering = (leaving < n ? leaving + n : leaving - n);
              compute_column(entering, y);
              if (!all_finite(y))
                {
                  fail(result,
                       Status::numerical_failure,
                       "non-finite entering column");
                  return;
                }
              r = ratio_test(y);
              if (r < 0)
                {
                  // z0 within rounding of 0 (a degenerate end of the path,
                  // e.g. a singular W): the point without z0 may already
                  // solve the LCP. Accepted only if it passes verify().
                  extract(ws.z_end, ws.w_end);
                  const Verification v =
                    verify_into(M,
                                q,
                                ws.z_end,
                                ws.w_end,
                                options.verification_tolerance_factor,
                                ws.residual);
                  if (v.ok)
                    {
                      result.status       = Status::solved;
                      result.verification = v;
                      internal::set_text(
                        note,
                        "; at the last pivot the entering column had no "
                        "positive entry, but z0 = %f was within rounding of "
                        "0 and the point without it passed verification",
                        x[position[z0]]);
                      return;
                    }
                  result.driving_variable = entering;
                  fail(result, Status::ray_termination);
                  result.ray_z.assign(n, 0.);
                  if (entering >= n)
                    result.ray_z[entering - n] = 1.;
                  for (int p = 0; p < n; ++p)
                    if (basic[p] >= n && basic[p] < 2 * n)
                      result.ray_z[basic[p] - n] = -y[p];
                  internal::set_text(
                    result.message,
                    "ray termination after %u pivots: %s%d cannot enter (no "
                    "positive entry in its column); z0 = %g",
                    result.pivots,
                    entering < n ? "w_" : "z_",
                    entering % n,
                    x[position[z0]]);
                  return;
                }
              leaving = basic[r];
              pivot(r, entering, y);
              result.pivots += 1;
              ++since_refactor;

              // --- keep the basis inverse accurate
              const unsigned int K =
                options.refactor_interval > 0 ?
                  options.refactor_interval :
                  std::max<unsigned int>(100u, static_cast<unsigned int>(n));
              bool do_refactor = (since_refactor >= K);
              if (!do_refactor && options.drift_check_interval > 0 &&
                  result.pivots % options.drift_check_interval == 0)
                do_refactor = drifted();
              if (do_refactor && leaving != z0)
                {
                  since_refactor = 0;
                  if (!refactor())
                    {
                      fail(result,
                           Status::numerical_failure,
                           "basis became singular at refactorisation");
                      return;
                    }
                }
            }
          result.status = Status::solved;
        }

        /// Recompute B^{-1} (and x = B^{-1} q) from the basis columns.
        bool
        refactor()
        {
          std::vector<int> &PC = ws.basic_z_positions;
          std::vector<int> &R  = ws.dense_rows;
          PC.clear();
          R.clear();
          for (int p = 0; p < n; ++p)
            if (basic[p] >= n)
              PC.push_back(p);
          for (int c = 0; c < n; ++c)
            if (slack_pos[c] < 0)
              R.push_back(c);
          const int k = static_cast<int>(PC.size());
          if (k != static_cast<int>(R.size()))
            return false;

          ++refactorisations;
          dense_cols.assign(R.begin(), R.end());
          std::fill(dense_index.begin(), dense_index.end(), -1);
          for (int ii = 0; ii < k; ++ii)
            dense_index[R[ii]] = ii;

          if (k > 0)
            {
              DenseMatrix &BRC = ws.basis_block;
              BRC.reinit(k, k);
              for (int jj = 0; jj < k; ++jj)
                for (int ii = 0; ii < k; ++ii)
                  BRC(ii, jj) = column_entry(basic[PC[jj]], R[ii]);
              LUFactorization &lu = ws.lu;
              if (!lu.factorize(BRC, 1e2 * eps))
                return false;
              DenseMatrix &X = ws.basis_block_inverse; // X(jj, ii)
              lu.inverse(X);

              for (int ii = 0; ii < k; ++ii)
                {
                  double *col = &binv[static_cast<std::size_t>(R[ii]) * n];
                  std::fill(col, col + n, 0.);
                  for (int jj = 0; jj < k; ++jj)
                    col[PC[jj]] = X(jj, ii);
                }
              // rows of slack positions: -B_SC X
              std::vector<double> &b = ws.slack_row;
              std::vector<double> &t = ws.slack_update;
              b.assign(k, 0.);
              t.assign(k, 0.);
              for (int c = 0; c < n; ++c)
                if (slack_pos[c] >= 0)
                  {
                    bool any = false;
                    for (int jj = 0; jj < k; ++jj)
                      {
                        b[jj] = column_entry(basic[PC[jj]], c);
                        any   = any || (b[jj] != 0.);
                      }
                    if (!any)
                      continue;
                    std::fill(t.begin(), t.end(), 0.);
                    for (int jj = 0; jj < k; ++jj)
                      if (b[jj] != 0.)
                        {
                          const double *xr = X.row(jj);
                          for (int ii = 0; ii < k; ++ii)
                            t[ii] += b[jj] * xr[ii];
                        }
                    const int s = slack_pos[c];
                    for (int ii = 0; ii < k; ++ii)
                      binv[static_cast<std::size_t>(R[ii]) * n + s] = -t[ii];
                  }
            }

          binv_max = 1.;
          for (const int c : dense_cols)
            {
              const double *col = &binv[static_cast<std::size_t>(c) * n];
              for (int p = 0; p < n; ++p)
                binv_max = std::max(binv_max, std::abs(col[p]));
            }
          // x = B^{-1} q
          std::fill(x.begin(), x.end(), 0.);
          for (int c = 0; c < n; ++c)
            {
              if (q[c] == 0.)
                continue;
              if (slack_pos[c] >= 0)
                x[slack_pos[c]] += q[c];
              else
                {
                  const double *col = &binv[static_cast<std::size_t>(c) * n];
                  for (int p = 0; p < n; ++p)
                    x[p] += q[c] * col[p];
                }
            }
          return all_finite(x);
        }

        unsigned int refactorisations = 0;

      private:
        const int                  n;
        const DenseMatrix         &M;
        const std::vector<double> &q;
        const LemkeOptions        &options;
        LemkeSolver::Workspace    &ws;
        std::vector<double>       &d;

        std::vector<int>    &basic;     // variable at basis position p
        std::vector<int>    &position;  // basis position of a variable, or -1
        std::vector<int>    &slack_pos; // position of w_c if basic, else -1
        std::vector<double> &binv;      // column-major; valid for dense columns
        std::vector<int>    &dense_cols; // columns c with slack_pos[c] < 0
        std::vector<int>    &dense_index;
        std::vector<double> &x;

      public:
        /// Appended to the message of a solved run (see the ray test in run()).
        std::string &note;

      private:
        double norm_M = 0., norm_q = 0., scale_A = 1., binv_max = 1., vtol = 0.;
        double column_norm = 1.; // of the last column passed to compute_column

        void
        update_scale()
        {
          scale_A = std::max({1., norm_M, linfty_norm(d)});
        }

        double
        column_entry(const int v, const int c) const
        {
          if (v < n)
            return v == c ? 1. : 0.;
          if (v < 2 * n)
            return -M(c, v - n);
          return -d[c];
        }

        /// out += alpha * (system column of variable v)
        void
        add_column(const int            v,
                   const double         alpha,
                   std::vector<double> &out) const
        {
          if (v < n)
            out[v] += alpha;
          else if (v < 2 * n)
            for (int c = 0; c < n; ++c)
              out[c] -= alpha * M(c, v - n);
          else
            for (int c = 0; c < n; ++c)
              out[c] -= alpha * d[c];
        }

        double
        binv_entry(const int p, const int c) const
        {
          if (slack_pos[c] >= 0)
            return p == slack_pos[c] ? 1. : 0.;
          return binv[static_cast<std::size_t>(c) * n + p];
        }

        /// y = B^{-1} (system column of variable v); sets column_norm to
        /// the largest |entry| of that system column.
        void
        compute_column(const int v, std::vector<double> &y)
        {
          std::fill(y.begin(), y.end(), 0.);
          column_norm = 0.;
          if (v < n)
            {
              column_norm = 1.;
              if (slack_pos[v] >= 0)
                y[slack_pos[v]] = 1.;
              else
                std::copy(&binv[static_cast<std::size_t>(v) * n],
                          &binv[static_cast<std::size_t>(v) * n] + n,
                          y.begin());
              return;
            }
          for (int c = 0; c < n; ++c)
            {
              const double a = column_entry(v, c);
              if (a == 0.)
                continue;
              column_norm = std::max(column_norm, std::abs(a));
              if (slack_pos[c] >= 0)
                y[slack_pos[c]] += a;
              else
                {
                  const double *col = &binv[static_cast<std::size_t>(c) * n];
                  for (int p = 0; p < n; ++p)
                    y[p] += a * col[p];
                }
            }
        }

        /// Lexicographic tie-break among the rows T (divisors delta).
        int
        lexico_break(std::vector<int>          &T,
                     const std::vector<double> &delta) const
        {
          const double tie = options.tie_tolerance_factor * eps;
          for (int c = 0; c < n && T.size() > 1; ++c)
            {
              double umin = std::numeric_limits<double>::infinity();
              for (const int p : T)
                umin = std::min(umin, binv_entry(p, c) / delta[p]);
              std::vector<int> &keep = ws.kept_ties;
              keep.clear();
              for (const int p : T)
                if (binv_entry(p, c) / delta[p] <=
                    umin + tie * binv_max / delta[p])
                  keep.push_back(p);
              T.swap(keep);
            }
          return T.front();
        }

        /// First step: z0 enters with column y; rows with -y_p > 0.
        int
        initial_ratio_test(const std::vector<double> &y) const
        {
          std::vector<double> &delta = ws.delta;
          delta.resize(n);
          double       vmin = std::numeric_limits<double>::infinity();
          const double ptol = pivot_tolerance();
          for (int p = 0; p < n; ++p)
            {
              delta[p] = -y[p];
              if (delta[p] > ptol)
                vmin = std::min(vmin, x[p] / delta[p]);
            }
          if (!(vmin < 0.))
            return -1;
          const double      xnorm = linfty_norm(x);
          const double      tie   = options.tie_tolerance_factor * eps;
          std::vector<int> &T     = ws.ties;
          T.clear();
          for (int p = 0; p < n; ++p)
            if (delta[p] > ptol && x[p] / delta[p] - vmin <=
                                     tie * (std::abs(vmin) + xnorm / delta[p]))
              T.push_back(p);
          return lexico_break(T, delta);
        }

        /// General step: rows with y_p > 0; z0 preferred on ties.
        int
        ratio_test(const std::vector<double> &y) const
        {
          const double ptol = pivot_tolerance();
          double       vmin = std::numeric_limits<double>::infinity();
          for (int p = 0; p < n; ++p)
            if (y[p] > ptol)
              vmin = std::min(vmin, std::max(x[p], 0.) / y[p]);
          if (vmin == std::numeric_limits<double>::infinity())
            return -1;
          const double      xnorm = linfty_norm(x);
          const double      tie   = options.tie_tolerance_factor * eps;
          std::vector<int> &T     = ws.ties;
          T.clear();
          for (int p = 0; p < n; ++p)
            if (y[p] > ptol &&
                std::max(x[p], 0.) / y[p] - vmin <= tie * (vmin + xnorm / y[p]))
              T.push_back(p);
          const int pz0 = position[2 * n];
          for (const int p : T)
            if (p == pz0)
              return p;
          if (T.size() == 1)
            return T.front();
          return lexico_break(T, y);
        }

        double
        pivot_tolerance() const
        {
          return options.pivot_tolerance_factor * eps * column_norm * binv_max;
        }

        /// Exchange basic[r] for `entering`, whose updated column is y.
        void
        pivot(const int r, const int entering, const std::vector<double> &y)
        {
          const int    leaving = basic[r];
          const double yr      = y[r];

          for (const int c : dense_cols)
            {
              double      *col = &binv[static_cast<std::size_t>(c) * n];
              const double v   = col[r];
              if (v == 0.)
                continue;
              const double f = v / yr;
              for (int p = 0; p < n; ++p)
                {
                  col[p] -= f * y[p];
                  binv_max = std::max(binv_max, std::abs(col[p]));
                }
              col[r]   = f;
              binv_max = std::max(binv_max, std::abs(f));
            }
          if (leaving < n)
            {
              // the unit column of the leaving slack becomes dense
              const int c  = leaving;
              slack_pos[c] = -1;
              double *col  = &binv[static_cast<std::size_t>(c) * n];
              for (int p = 0; p < n; ++p)
                {
                  col[p]   = -y[p] / yr;
                  binv_max = std::max(binv_max, std::abs(col[p]));
                }
              col[r]         = 1. / yr;
              binv_max       = std::max(binv_max, std::abs(col[r]));
              dense_index[c] = static_cast<int>(dense_cols.size());
              dense_cols.push_back(c);
            }
          if (entering < n)
            {
              // B^{-1} e_c = e_r exactly once w_c is basic at position r
              const int c       = entering;
              const int idx     = dense_index[c];
              const int last    = dense_cols.back();
              dense_cols[idx]   = last;
              dense_index[last] = idx;
              dense_cols.pop_back();
              dense_index[c] = -1;
              slack_pos[c]   = r;
            }

          const double theta = x[r] / yr;
          for (int p = 0; p < n; ++p)
            x[p] -= theta * y[p];
          x[r] = theta;

          basic[r]           = entering;
          position[entering] = r;
          position[leaving]  = -1;
        }

        /// Is ||q - B x||_inf too large?
        bool
        drifted() const
        {
          // res = q - B x = q - w_B + M z_B + d z0, with M applied row by row
          // (contiguous) rather than column by column
          std::vector<double> &res = ws.residual;
          std::vector<double> &zb  = ws.basic_z;
          res.assign(q.begin(), q.end());
          zb.assign(n, 0.);
          double z0 = 0.;
          for (int p = 0; p < n; ++p)
            {
              const int v = basic[p];
              if (v < n)
                res[v] -= x[p];
              else if (v < 2 * n)
                zb[v - n] = x[p];
              else
                z0 = x[p];
            }
          for (int c = 0; c < n; ++c)
            {
              const double *mc = M.row(c);
              double        s  = 0.;
              for (int j = 0; j < n; ++j)
                s += mc[j] * zb[j];
              res[c] += s + d[c] * z0;
            }
          return linfty_norm(res) > vtol * (norm_q + scale_A * linfty_norm(x));
        }

        void
        fail(Result      &result,
             const Status status,
             const char  *message = "") const
        {
          result.status = status;
          result.z.clear();
          result.w.clear();
          result.ray_z.clear();
          result.verification = Verification();
          result.message.assign(message);
        }
      };



      unsigned int
      pivot_cap(const LemkeOptions &options, const std::size_t n)
      {
        return options.max_pivots > 0 ?
                 options.max_pivots :
                 options.pivot_factor * static_cast<unsigned int>(n + 1);
      }



      /// After a successful run: extract, verify, refactorise once if needed.
      void
      finish(LemkeEngine               &engine,
             const DenseMatrix         &M,
             const std::vector<double> &q,
             const LemkeOptions        &options,
             std::vector<double>       &residual,
             Result                    &result)
      {
        engine.extract(result.z, result.w);
        result.verification = verify_into(M,
                                          q,
                                          result.z,
                                          result.w,
                                          options.verification_tolerance_factor,
                                          residual);
        if (!result.verification.ok)
          {
            if (engine.refactor())
              {
                engine.extract(result.z, result.w);
                result.verification =
                  verify_into(M,
                              q,
                              result.z,
                              result.w,
                              options.verification_tolerance_factor,
                              residual);
              }
            if (!result.verification.ok)
              {
                internal::set_text(
                  result.message,
                  "the final point failed verification (min z %g, min w %g, "
                  "residual %g, max |z_i w_i| %g)",
                  result.verification.min_z,
                  result.verification.min_w,
                  result.verification.residual,
                  result.verification.max_complementarity);
                result.status = Status::numerical_failure;
                result.z.clear();
                result.w.clear();
              }
          }
        result.refactorisations = engine.refactorisations;
      }



      bool
      trivial(const DenseMatrix         &M,
              const std::vector<double> &q,
              const LemkeOptions        &options,
              std::vector<double>       &residual,
              Result                    &result)
      {
        for (const double v : q)
          if (v < 0.)
            return false;
        result.status = Status::solved;
        result.z.assign(q.size(), 0.);
        result.w.assign(q.begin(), q.end());
        result.pivots       = 0;
        result.verification = verify_into(M,
                                          q,
                                          result.z,
                                          result.w,
                                          options.verification_tolerance_factor,
                                          residual);
        result.message.assign("q >= 0: z = 0 is the solution");
        return true;
      }



      void
      solve_cold(const DenseMatrix         &M,
                 const std::vector<double> &q,
                 const LemkeOptions        &options,
                 LemkeSolver::Workspace    &ws,
                 Result                    &result)
      {
        const std::size_t    n = q.size();
        std::vector<double> &d = ws.covering;
        if (options.covering_vector.empty())
          d.assign(n, 1.);
        else
          d.assign(options.covering_vector.begin(),
                   options.covering_vector.end());
        LemkeEngine engine(M, q, options, ws);
        engine.init_slack_basis(d);
        engine.run(pivot_cap(options, n), result);
        if (result.status == Status::solved)
          {
            finish(engine, M, q, options, ws.residual, result);
            if (result.status == Status::solved)
              {
                internal::set_text(result.message,
                                   "solved by Lemke's method in %u pivots",
                                   result.pivots);
                result.message.append(engine.note);
              }
          }
        result.refactorisations = engine.refactorisations;
      }
    } // namespace



    void
    clear(Result &result)
    {
      result.status = Status::numerical_failure;
      result.z.clear();
      result.w.clear();
      result.pivots           = 0;
      result.refactorisations = 0;
      result.driving_variable = -1;
      result.verification     = Verification();
      result.start_path       = StartPath::cold;
      result.message.clear();
    }



    Verification
    verify(const DenseMatrix         &M,
           const std::vector<double> &q,
           const std::vector<double> &z,
           const std::vector<double> &w,
           const double               tolerance_factor)
    {
      std::vector<double> residual;
      return verify_into(M, q, z, w, tolerance_factor, residual);
    }



    Verification
    verify_with_residual(const double               norm_M,
                         const std::vector<double> &q,
                         const std::vector<double> &z,
                         const std::vector<double> &w,
                         const std::vector<double> &residual,
                         const double               tolerance_factor)
    {
      const std::size_t n = q.size();
      if (z.size() != n || w.size() != n || residual.size() != n)
        throw std::invalid_argument("verify: inconsistent sizes");
      Verification v;
      v.tolerance = tolerance_factor * eps * std::max<std::size_t>(n, 1);
      v.min_z     = n > 0 ? *std::min_element(z.begin(), z.end()) : 0.;
      v.min_w     = n > 0 ? *std::min_element(w.begin(), w.end()) : 0.;

      const double zmax = linfty_norm(z);
      const double s    = linfty_norm(q) + norm_M * zmax;
      double       sum  = 0.;
      for (std::size_t i = 0; i < n; ++i)
        {
          const double zw       = std::abs(z[i] * w[i]);
          v.max_complementarity = std::max(v.max_complementarity, zw);
          sum += zw;
          v.residual = std::max(v.residual, std::abs(residual[i]));
        }
      v.relative_complementarity = (sum == 0. ? 0. : sum / (zmax * s));
      auto rel                   = [](const double a, const double b) {
        return a <= 0. ?
                                   0. :
                                   (b > 0. ? a / b : std::numeric_limits<double>::infinity());
      };
      v.relative_error = std::max({v.relative_complementarity,
                                   rel(v.residual, s),
                                   rel(-v.min_z, zmax),
                                   rel(-v.min_w, s)});
      const double t   = v.tolerance;
      v.ok = std::isfinite(sum) && std::isfinite(v.residual) && all_finite(z) &&
             all_finite(w) && v.min_z >= -t * zmax && v.min_w >= -t * s &&
             v.residual <= t * s && v.max_complementarity <= t * zmax * s;
      return v;
    }



    // @sect3{LemkeSolver: the solves, with storage kept between them}
    LemkeSolver::LemkeSolver()
      : workspace(std::make_unique<Workspace>())
    {}

    LemkeSolver::~LemkeSolver() = default;

    LemkeSolver::LemkeSolver(LemkeSolver &&) noexcept = default;

    LemkeSolver &
    LemkeSolver::operator=(LemkeSolver &&) noexcept = default;



    const Result &
    LemkeSolver::result() const
    {
      return workspace->result;
    }



    std::size_t
    LemkeSolver::memory_consumption() const
    {
      return workspace->memory_consumption();
    }



    const Result &
    LemkeSolver::solve(const DenseMatrix         &M,
                       const std::vector<double> &q,
                       const LemkeOptions        &options)
    {
      const internal::FlushSubnormalsScope
        flush_subnormals; // see floating_point_mode.h
      check_input(M, q, options);
      Workspace &ws     = *workspace;
      Result    &result = ws.result;
      clear(result);
      result.start_path = StartPath::cold;
      if (trivial(M, q, options, ws.residual, result))
        return result;
      solve_cold(M, q, options, ws, result);
      return result;
    }



    const Result &
    LemkeSolver::solve_warm(const DenseMatrix         &M,
                            const std::vector<double> &q,
                            const std::vector<bool>   &guess,
                            const LemkeOptions        &options)
    {
      const internal::FlushSubnormalsScope
        flush_subnormals; // see floating_point_mode.h
      check_input(M, q, options);
      if (guess.size() != q.size())
        throw std::invalid_argument("LCP: the guess has the wrong size");
      Workspace &ws     = *workspace;
      Result    &result = ws.result;
      clear(result);
      result.start_path = StartPath::cold;
      if (trivial(M, q, options, ws.residual, result))
        return result;

      const std::size_t n   = q.size();
      std::string      &why = ws.why;
      why.clear();
      {
        LemkeEngine engine(M, q, options, ws);
        if (engine.init_guess_basis(guess))
          {
            if (engine.basic_solution_feasible())
              {
                result.start_path = StartPath::guess_solved;
                result.status     = Status::solved;
                finish(engine, M, q, options, ws.residual, result);
                if (result.status == Status::solved)
                  {
                    result.message.assign(
                      "the guessed complementary basis is the solution (0 pivots)");
                    return result;
                  }
                why.assign(
                  "guessed basis looked feasible but failed verification");
                result.pivots = 0;
              }
            else
              {
                engine.set_covering_to_basis_sum();
                result.start_path = StartPath::guess_lemke;
                engine.run(pivot_cap(options, n), result);
                if (result.status == Status::solved)
                  finish(engine, M, q, options, ws.residual, result);
                if (result.status == Status::solved)
                  {
                    internal::set_text(
                      result.message,
                      "solved by Lemke's method from the guessed basis in %u pivots",
                      result.pivots);
                    result.message.append(engine.note);
                    return result;
                  }
                why.assign("Lemke from the guessed basis: ");
                why.append(result.message);
              }
          }
        else
          why.assign("the guessed principal block is singular");
        result.refactorisations = engine.refactorisations;
      }

      if (!options.cold_fallback)
        {
          if (result.status == Status::solved)
            result.status = Status::numerical_failure;
          result.z.clear();
          result.w.clear();
          result.message = "guess rejected (" + why + "); no cold start";
          return result;
        }
      const unsigned int warm_pivots = result.pivots;
      const unsigned int warm_refac  = result.refactorisations;
      clear(result);
      solve_cold(M, q, options, ws, result);
      result.pivots += warm_pivots;
      result.refactorisations += warm_refac;
      result.start_path = StartPath::guess_fallback_cold;
      result.message.insert(0, "); cold: ");
      result.message.insert(0, why);
      result.message.insert(0, "guess rejected (");
      return result;
    }



    Result
    solve_lemke(const DenseMatrix         &M,
                const std::vector<double> &q,
                const LemkeOptions        &options)
    {
      LemkeSolver solver;
      return solver.solve(M, q, options);
    }



    Result
    solve_lemke_warm(const DenseMatrix         &M,
                     const std::vector<double> &q,
                     const std::vector<bool>   &guess,
                     const LemkeOptions        &options)
    {
      LemkeSolver solver;
      return solver.solve_warm(M, q, guess, options);
    }
  } // namespace lcp
} // namespace impactfe
