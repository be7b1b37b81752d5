#ifndef impactfe_dynamics_sparse_cholesky_h
#define impactfe_dynamics_sparse_cholesky_h

#include <deal.II/lac/block_vector.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

struct cholmod_sparse_struct;

namespace impactfe
{
  using namespace dealii;

  /**
   * Sparse Cholesky factorisation M~ = L L^T of a symmetric positive
   * definite matrix (CHOLMOD, SuiteSparse, fill-reducing ordering), made
   * once; each solve is one forward and one backward substitution into work
   * space kept from the previous solve, so the time loop neither allocates
   * nor refactorises.
   *
   * Why not deal.II's SparseDirectUMFPACK: it factorises as a general LU and
   * its solve runs UMFPACK's iterative refinement (2 to 3 triangular-solve
   * pairs plus residuals per solve, doc/performance.md). The step matrices
   * M + c_C C + c_K K are symmetric positive definite, so one Cholesky
   * solve pair is exact to rounding.
   */
  class SparseCholesky
  {
  public:
    SparseCholesky();
    ~SparseCholesky();
    SparseCholesky(const SparseCholesky &) = delete;
    SparseCholesky &
    operator=(const SparseCholesky &) = delete;

    /**
     * Factorise @p matrix (only its upper triangle is read). Throws with a
     * message naming @p name if the matrix is not positive definite. With
     * @p drop_zeros, entries off the diagonal that are exactly zero are
     * left out of the pattern (rows and columns made those of the
     * identity then cost no fill).
     */
    void
    factorize(const SparseMatrix<double> &matrix,
              const std::string          &name       = "matrix",
              const bool                  drop_zeros = false);

    /**
     * Factorise @p matrix with the unknowns @p trailing eliminated last and
     * return the trailing block L_CC of the factor: dense, lower
     * triangular, column-major, trailing.size() squared. L_CC L_CC^T is the
     * Schur complement A_CC - A_CI A_II^{-1} A_IC of the other unknowns I.
     * On return @p trailing holds the same unknowns in the order of L_CC's
     * rows. The factorisation serves solve() as well.
     */
    std::vector<double>
    factorize_with_trailing_block(
      const SparseMatrix<double>           &matrix,
      std::vector<types::global_dof_index> &trailing,
      const std::string                    &name = "matrix");

    /** x <- M~^{-1} x. */
    void
    solve(Vector<double> &rhs_and_solution) const;

    /**
     * x_b <- M~_b^{-1} x_b for every block b of @p x, M~_b the matrix of
     * factors[b]: the same answers as factors[b]->solve(x.block(b)), but
     * two simplicial factors at a time with their rows alternating, so
     * that the processor runs one substitution's chain while the other's
     * waits (the solves of the 1D bars are latency-bound).
     */
    static void
    solve_together(const std::vector<std::unique_ptr<SparseCholesky>> &factors,
                   BlockVector<double>                                &x);

    /**
     * X <- M~^{-1} X for @p n_columns right-hand sides stored one after the
     * other (column-major, n rows each). The supernodal solve works on all
     * of them at once with dense blocks, much faster per column than
     * separate solves.
     */
    void
    solve(double *columns, const unsigned int n_columns) const;

    /**
     * x <- M~^{-1} x with a supernodal factor rounded to single precision
     * (made at the first call): half the memory traffic of solve(), for a
     * preconditioner applied inside a flexible Krylov method, where it
     * changes no answer. A simplicial factor solves in double precision.
     */
    void
    solve_single_precision(Vector<double> &rhs_and_solution) const;

    /**
     * The factor's ordering of a supernodal factorisation (that of
     * factorize_with_trailing_block()): position k of the factor holds
     * unknown permutation()[k] of the matrix.
     */
    const int *
    permutation() const;
    /**
     * z <- L^{-1} z, or L^{-T} z with @p transpose, for @p z in the factor's
     * order (permutation()): half of a solve, for solvers that work
     * between the two substitutions (the substructured solves of the
     * distributed programs). Supernodal factors only.
     *
     * With @p n_leading, only the first n_leading columns of L take part:
     * with L = [L_11 0; L_21 L_22] (L_11 of that size), forward gives
     * z_1 <- L_11^{-1} z_1 and z_2 <- z_2 - L_21 z_1, and the transpose
     * z_1 <- L_11^{-T} (z_1 - L_21^T z_2), z_2 unchanged. The transpose
     * with @p first_column computes only the entries k >= first_column
     * of z_1 (the later rows of L_11^T do not need the earlier ones), and
     * leaves the others as they were. The forward substitution skips a
     * leading run of zeros in z by itself.
     */
    void
    solve_lower(double            *z,
                const bool         transpose    = false,
                const unsigned int n_leading    = static_cast<unsigned int>(-1),
                const unsigned int first_column = 0) const;
    /** Rows (= columns) of the factorised matrix. */
    std::size_t
    size() const;

    /**
     * Whether CHOLMOD chose a simplicial factor (small fill: 1D, small 2D
     * meshes): solve() then substitutes in a copy of L D L^T in arrays of
     * its own; a supernodal factor is substituted supernode by supernode.
     */
    bool
    simplicial() const;

    /**
     * Whether L is bidiagonal (a tridiagonal matrix, a 1D body numbered
     * along its cells, is factorised in its own order, which makes no
     * fill): solve_together() solves two such factors at a time.
     */
    bool
    bidiagonal() const;

    /** Entries of L (the cost of one solve pair is about 4 of these). */
    std::size_t
    n_factor_entries() const;

  private:
    /// Factorise after an analysis (data->factor), and check the result.
    void
    factorize_analysed(cholmod_sparse_struct &upper, const std::string &name);

    /// Keep a simplicial factor as L D L^T in our own arrays (solve()).
    void
    copy_simplicial_factor();

    struct Data;
    std::unique_ptr<Data> data;
  };
} // namespace impactfe

#endif
