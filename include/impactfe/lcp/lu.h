// Dense LU factorisation with partial pivoting, for the LCP module.
#ifndef impactfe_lcp_lu_h
#define impactfe_lcp_lu_h

#include <impactfe/lcp/dense_matrix.h>

#include <cstddef>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /**
     * LU factorisation with partial (row) pivoting of a square dense matrix,
     * P A = L U. Used for the refactorisation of Lemke's basis and for
     * inverting small blocks (W_TT) in the contact LCP assembly.
     */
    class LUFactorization
    {
    public:
      /**
       * Factorise @p A. Returns false (and leaves the object unusable) if a
       * pivot is at most @p relative_pivot_tolerance times the largest
       * absolute entry of A, i.e. if A is singular to that tolerance.
       */
      bool
      factorize(const DenseMatrix &A, double relative_pivot_tolerance = 1e-13);

      /// Solve A x = b in place (b becomes x).
      void
      solve(std::vector<double> &b) const;

      /// The inverse of A (n solves).
      DenseMatrix
      inverse() const;

      /// The inverse of A in @p X (resized; no allocation when it has the
      /// capacity already).
      void
      inverse(DenseMatrix &X) const;

      /// min |u_kk| / max |a_ij|: a cheap (and rough) indicator of singularity.
      double
      min_pivot_ratio() const
      {
        return pivot_ratio;
      }

      std::size_t
      size() const
      {
        return n;
      }

      /// Bytes of heap storage held.
      std::size_t
      memory_consumption() const
      {
        return lu.memory_consumption() +
               permutation.capacity() * sizeof(std::size_t) +
               work.capacity() * sizeof(double);
      }

    private:
      std::size_t              n = 0;
      DenseMatrix              lu;
      std::vector<std::size_t> permutation;
      double                   pivot_ratio = 0.;
      /// Work vector of solve(), kept so that repeated solves do not allocate.
      mutable std::vector<double> work;
    };

    /**
     * Cholesky factorisation A = U^T U of a symmetric positive definite
     * matrix (only the upper triangle of A is read), U upper triangular and
     * stored by rows, which read by columns is LAPACK's lower factor
     * L = U^T: the factorisation is LAPACK's dpotrf, the solves BLAS's
     * dtrsm. Used by the block pivoting of the contact problem on the
     * sticking block of the Delassus operator, at (1/3) n^3 flops, half
     * those of the LU.
     */
    class CholeskyFactorization
    {
    public:
      /**
       * Factorise @p A. Returns false (and leaves the object unusable) if a
       * pivot U_kk^2 is at most @p relative_pivot_tolerance times the largest
       * diagonal entry of A, i.e. A is not (numerically) positive definite.
       */
      bool
      factorize(const DenseMatrix &A, double relative_pivot_tolerance = 1e-13);

      /// Solve A X = B in place for all columns of B (n x r, by rows).
      void
      solve(DenseMatrix &B) const;

      std::size_t
      size() const
      {
        return n;
      }

      /// Bytes of heap storage held.
      std::size_t
      memory_consumption() const
      {
        return u.memory_consumption();
      }

    private:
      std::size_t n = 0;
      DenseMatrix u;
    };
  } // namespace lcp
} // namespace impactfe

#endif
