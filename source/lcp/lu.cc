#include <impactfe/lcp/lu.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "../utilities/blas_lapack.h"

namespace impactfe
{
  namespace lcp
  {
    bool
    LUFactorization::factorize(const DenseMatrix &A,
                               const double       relative_pivot_tolerance)
    {
      n  = A.n_rows();
      lu = A;
      permutation.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        permutation[i] = i;

      const double amax = A.max_abs();
      pivot_ratio = (n == 0 ? 1. : std::numeric_limits<double>::infinity());
      if (n == 0)
        return true;
      if (!(amax > 0.) || !std::isfinite(amax))
        {
          pivot_ratio = 0.;
          return false;
        }

      // Right-looking LU in panels of `panel` columns. Each panel is factorised
      // column by column (pivot search, row exchange over whole rows,
      // elimination inside the panel); then its rows of U to the right are
      // finished and the trailing matrix receives the panel's update row by
      // row. A trailing row is thus read once per panel instead of once per
      // column, while every entry receives the same updates in the same order
      // as in the unblocked algorithm: same pivots, same rounding.
      constexpr std::size_t panel = 48;
      for (std::size_t kb = 0; kb < n; kb += panel)
        {
          const std::size_t ke = std::min(n, kb + panel);
          for (std::size_t k = kb; k < ke; ++k)
            {
              // partial pivoting: the largest entry of column k at or below row
              // k
              std::size_t p    = k;
              double      pmax = std::abs(lu(k, k));
              for (std::size_t i = k + 1; i < n; ++i)
                if (std::abs(lu(i, k)) > pmax)
                  {
                    pmax = std::abs(lu(i, k));
                    p    = i;
                  }
              pivot_ratio = std::min(pivot_ratio, pmax / amax);
              if (!(pmax > relative_pivot_tolerance * amax))
                return false;
              if (p != k)
                {
                  std::swap(permutation[p], permutation[k]);
                  double *rp = lu.row(p);
                  double *rk = lu.row(k);
                  for (std::size_t j = 0; j < n; ++j)
                    std::swap(rp[j], rk[j]);
                }
              const double *rk    = lu.row(k);
              const double  pivot = rk[k];
              for (std::size_t i = k + 1; i < n; ++i)
                {
                  double *ri = lu.row(i);
                  if (ri[k] == 0.)
                    continue;
                  const double l = ri[k] / pivot;
                  ri[k]          = l;
                  for (std::size_t j = k + 1; j < ke; ++j)
                    ri[j] -= l * rk[j];
                }
            }
          if (ke == n)
            break;
          // rows kb..ke-1 of U right of the panel
          for (std::size_t k = kb; k < ke; ++k)
            {
              const double *rk = lu.row(k);
              for (std::size_t i = k + 1; i < ke; ++i)
                {
                  double      *ri = lu.row(i);
                  const double l  = ri[k];
                  if (l == 0.)
                    continue;
                  for (std::size_t j = ke; j < n; ++j)
                    ri[j] -= l * rk[j];
                }
            }
          // the trailing matrix, four pivot rows per pass over row i (the
          // subtractions are still made one after the other, in order)
          for (std::size_t i = ke; i < n; ++i)
            {
              double     *ri = lu.row(i);
              std::size_t k  = kb;
              for (; k + 4 <= ke; k += 4)
                {
                  const double l0 = ri[k], l1 = ri[k + 1], l2 = ri[k + 2],
                               l3  = ri[k + 3];
                  const double *r0 = lu.row(k), *r1 = lu.row(k + 1),
                               *r2 = lu.row(k + 2), *r3 = lu.row(k + 3);
                  for (std::size_t j = ke; j < n; ++j)
                    ri[j] = (((ri[j] - l0 * r0[j]) - l1 * r1[j]) - l2 * r2[j]) -
                            l3 * r3[j];
                }
              for (; k < ke; ++k)
                {
                  const double l = ri[k];
                  if (l == 0.)
                    continue;
                  const double *rk = lu.row(k);
                  for (std::size_t j = ke; j < n; ++j)
                    ri[j] -= l * rk[j];
                }
            }
        }
      return true;
    }



    void
    LUFactorization::solve(std::vector<double> &b) const
    {
      std::vector<double> &x = work;
      x.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        x[i] = b[permutation[i]];
      // forward substitution with unit lower triangle
      for (std::size_t i = 0; i < n; ++i)
        {
          const double *ri = lu.row(i);
          double        s  = x[i];
          for (std::size_t j = 0; j < i; ++j)
            s -= ri[j] * x[j];
          x[i] = s;
        }
      // back substitution
      for (std::size_t ii = n; ii-- > 0;)
        {
          const double *ri = lu.row(ii);
          double        s  = x[ii];
          for (std::size_t j = ii + 1; j < n; ++j)
            s -= ri[j] * x[j];
          x[ii] = s / ri[ii];
        }
      std::copy(x.begin(), x.end(), b.begin());
    }



    DenseMatrix
    LUFactorization::inverse() const
    {
      DenseMatrix X;
      inverse(X);
      return X;
    }



    void
    LUFactorization::inverse(DenseMatrix &X) const
    {
      // Solve for all columns at once, row-oriented for cache efficiency:
      // X = U^{-1} L^{-1} P.
      X.reinit(n, n, 0.);
      // P: row i of P I is e_{permutation[i]}^T
      for (std::size_t i = 0; i < n; ++i)
        X(i, permutation[i]) = 1.;
      // forward: row i -= sum_j<i l_ij row j
      for (std::size_t i = 0; i < n; ++i)
        {
          const double *ri = lu.row(i);
          double       *xi = X.row(i);
          for (std::size_t j = 0; j < i; ++j)
            if (ri[j] != 0.)
              {
                const double  l  = ri[j];
                const double *xj = X.row(j);
                for (std::size_t c = 0; c < n; ++c)
                  xi[c] -= l * xj[c];
              }
        }
      // backward
      for (std::size_t ii = n; ii-- > 0;)
        {
          const double *ri = lu.row(ii);
          double       *xi = X.row(ii);
          for (std::size_t j = ii + 1; j < n; ++j)
            if (ri[j] != 0.)
              {
                const double  u  = ri[j];
                const double *xj = X.row(j);
                for (std::size_t c = 0; c < n; ++c)
                  xi[c] -= u * xj[c];
              }
          const double inv = 1. / ri[ii];
          for (std::size_t c = 0; c < n; ++c)
            xi[c] *= inv;
        }
    }



    bool
    CholeskyFactorization::factorize(const DenseMatrix &A,
                                     const double relative_pivot_tolerance)
    {
      n           = A.n_rows();
      u           = A;
      double dmax = 0.;
      for (std::size_t i = 0; i < n; ++i)
        dmax = std::max(dmax, u(i, i));
      if (n == 0)
        return true;
      if (!(dmax > 0.) || !std::isfinite(dmax))
        return false;
      // U by rows, read by columns, is L = U^T: LAPACK's blocked Cholesky
      // on the lower triangle (column-major) factorises the upper triangle
      // stored by rows, at the speed of the BLAS 3 kernels (block pivoting
      // factorises systems of a few hundred contact rows in each step).
      const int nn   = static_cast<int>(n);
      int       info = 0;
      dpotrf_("L", &nn, u.row(0), &nn, &info);
      if (info != 0)
        return false;
      // the pivots U_kk^2 against the largest diagonal entry of A
      for (std::size_t k = 0; k < n; ++k)
        if (!(u(k, k) * u(k, k) > relative_pivot_tolerance * dmax) ||
            !std::isfinite(u(k, k)))
          return false;
      // the strict lower triangle (by rows) still holds A: not part of U
      for (std::size_t i = 1; i < n; ++i)
        std::fill(u.row(i), u.row(i) + i, 0.);
      return true;
    }



    void
    CholeskyFactorization::solve(DenseMatrix &B) const
    {
      const std::size_t r = B.n_cols();
      if (n == 0 || r == 0)
        return;
      // B by rows is B^T by columns (r x n, leading dimension r), and
      // A^{-1} B = (B^T L^{-T} L^{-1})^T with L = U^T: two triangular
      // solves from the right.
      const int    nn = static_cast<int>(n), rr = static_cast<int>(r);
      const double one = 1.;
      dtrsm_("R", "L", "T", "N", &rr, &nn, &one, u.row(0), &nn, B.row(0), &rr);
      dtrsm_("R", "L", "N", "N", &rr, &nn, &one, u.row(0), &nn, B.row(0), &rr);
    }
  } // namespace lcp
} // namespace impactfe
