#ifndef impactfe_dynamics_schur_complement_h
#define impactfe_dynamics_schur_complement_h

#include <deal.II/base/types.h>

#include <deal.II/lac/sparse_matrix.h>

#include <cstddef>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * The Schur complement S = A_CC - A_CI A_II^{-1} A_IC of a symmetric
   * positive definite matrix A on a set C of its unknowns, and its inverse
   * S^{-1} = (A^{-1})_CC, both dense.
   *
   * Why: with A = M~ and C the contact DoFs of the rigid-obstacle
   * candidates, H^T S^{-1} H is the Delassus operator W and H^T S H its
   * inverse when H is square (the active set method's preconditioner). A
   * product with either is then one dense symmetric matrix-vector product,
   * |C|^2 / 2 numbers read, instead of a solve pair with the sparse factor
   * of M~ (4 nnz(L) flops, and as many again for the preconditioner's
   * interior solve). In 3D, where nnz(L) grows like n^(4/3) and the contact
   * surface like n^(2/3), that is the cheaper product by far.
   *
   * Both are computed from one Cholesky factorisation of A that eliminates
   * C last (SparseCholesky::factorize_with_trailing_block()): S = L_CC
   * L_CC^T and S^{-1} from L_CC (LAPACK dpotri), O(|C|^3) flops once, and
   * no solve per contact DoF.
   */
  class DenseSchurComplement
  {
  public:
    /**
     * Compute S and S^{-1} of @p matrix on @p dofs. @p name names the
     * matrix in messages.
     */
    void
    compute(const SparseMatrix<double>                 &matrix,
            const std::vector<types::global_dof_index> &dofs,
            const std::string                          &name);

    /** The unknowns C, in the order of the vectors below. */
    const std::vector<types::global_dof_index> &
    dofs() const;

    /** |C|. */
    unsigned int
    size() const;

    /** y = S x (x, y of size() entries, in the order of dofs()). */
    void
    vmult(const double *x, double *y) const;

    /**
     * y = S x with S rounded to single precision: half the memory traffic
     * of vmult(), for a preconditioner (the active set method's flexible
     * GMRES keeps the preconditioned vectors, so this costs it no
     * accuracy).
     */
    void
    vmult_single_precision(const double *x, double *y) const;
    /** y = S^{-1} x. */
    void
    vmult_inverse(const double *x, double *y) const;

    std::size_t
    memory_consumption() const;

    /**
     * Whether the dense products are cheaper than the sparse ones: the two
     * dense matrices (|C|^2 numbers read per pair of products, S also in
     * single precision) against a
     * solve pair with each of two factors of about @p n_factor_entries
     * entries, and at most @p memory_limit bytes for the two matrices.
     */
    static bool
    pays_off(const std::size_t n_contact_dofs,
             const std::size_t n_factor_entries,
             const std::size_t memory_limit = std::size_t(1) << 30);

  private:
    std::vector<types::global_dof_index> contact_dofs;
    /// S and S^{-1}, column-major; their lower triangles are used.
    std::vector<double> schur, inverse;
    /// S in single precision, and the vectors of its product.
    std::vector<float>         schur_single;
    mutable std::vector<float> x_single, y_single;
  };
} // namespace impactfe

#endif
