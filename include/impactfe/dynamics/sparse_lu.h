#ifndef impactfe_dynamics_sparse_lu_h
#define impactfe_dynamics_sparse_lu_h

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <cstdint>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * Sparse LU factorisation of a general (non-symmetric) matrix with
   * UMFPACK, for Newton's method: the fill-reducing analysis is made once
   * per sparsity pattern and kept, each factorize() only redoes the
   * numerical factorisation, and a solve is one forward and one backward
   * substitution.
   *
   * Why not deal.II's SparseDirectUMFPACK: it redoes the analysis at every
   * factorisation, and its solves run UMFPACK's iterative refinement (up to
   * two more substitution pairs plus residuals per solve): in a profile of
   * the 3D Taylor bar that took more time than the substitutions
   * themselves. The step matrices
   * here are well conditioned (mass plus h^2 times the tangent), so one
   * substitution pair is accurate to rounding.
   */
  class SparseLU
  {
  public:
    /**
     * @p symmetric_pattern: the matrices have a symmetric pattern and
     * diagonals that make good pivots (a symmetric matrix with some rows
     * changed), so UMFPACK's symmetric strategy (a symmetric ordering of
     * A + A^T, diagonal pivots preferred) applies: on the active set
     * method's state matrices of the thin slab at 10^4 contacts (61 206
     * unknowns) a numerical factorisation took 0.55 s with it against
     * 1.05 s without. The ordering is METIS's nested dissection (AMD if
     * UMFPACK has no METIS): on the 2D slab 1 m long at 30 001 contacts
     * (300 010 unknowns) UMFPACK's analysis took 0.96 s with it against
     * 8.7 s with its default AMD, for the same numerical factorisation
     * time (0.53 s); on the 3D thin slab at 10^4 contacts (mu = 3, 5
     * steps) 0.24 s against 0.11 s, and its six factorisations, analysis
     * included, 4.2 s against 4.9 s.
     */
    explicit SparseLU(const bool symmetric_pattern = false);
    ~SparseLU();
    SparseLU(const SparseLU &) = delete;
    SparseLU &
    operator=(const SparseLU &) = delete;

    /**
     * Factorise @p matrix. The analysis of the first call is reused while
     * the matrix keeps the same SparsityPattern object with the same size
     * and number of entries (a pattern rebuilt in place with the same
     * entries in the same places is not noticed). Throws with a
     * message naming @p name if the matrix is singular.
     */
    void
    factorize(const SparseMatrix<double> &matrix,
              const std::string          &name = "matrix");

    /** x = A^{-1} b (@p x and @p b distinct). */
    void
    solve(const Vector<double> &b, Vector<double> &x) const;

  private:
    void
    free_numeric();
    void
    free_symbolic();

    const bool             symmetric_pattern;
    const SparsityPattern *analysed_pattern = nullptr;
    /// The matrix by columns of A^T (deal.II's rows) with sorted indices,
    /// and where each entry of SparseMatrix's storage goes in them.
    std::vector<std::int64_t> column_starts, row_indices;
    std::vector<std::size_t>  destination;
    std::vector<double>       values;
    std::vector<double>       control;
    void                     *symbolic = nullptr;
    void                     *numeric  = nullptr;
  };
} // namespace impactfe

#endif
