#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_templates.h>

#include <impactfe/dynamics/schur_complement.h>
#include <impactfe/dynamics/sparse_cholesky.h>

// y = alpha A x + beta y for a symmetric A of which one triangle is read
// (BLAS level 2; deal.II's lapack_templates.h has no symv).
extern "C" void
dsymv_(const char                    *uplo,
       const dealii::types::blas_int *n,
       const double                  *alpha,
       const double                  *a,
       const dealii::types::blas_int *lda,
       const double                  *x,
       const dealii::types::blas_int *incx,
       const double                  *beta,
       double                        *y,
       const dealii::types::blas_int *incy);
extern "C" void
ssymv_(const char                    *uplo,
       const dealii::types::blas_int *n,
       const float                   *alpha,
       const float                   *a,
       const dealii::types::blas_int *lda,
       const float                   *x,
       const dealii::types::blas_int *incx,
       const float                   *beta,
       float                         *y,
       const dealii::types::blas_int *incy);

namespace impactfe
{
  void
  DenseSchurComplement::compute(
    const SparseMatrix<double>                 &matrix,
    const std::vector<types::global_dof_index> &dofs,
    const std::string                          &name)
  {
    // Computed aside and kept only when everything succeeded, so that a
    // failure leaves the object as it was.
    std::vector<types::global_dof_index> new_dofs(dofs);
    std::vector<double>                  new_inverse, new_schur;
    if (!new_dofs.empty())
      {
        AssertThrow(new_dofs.size() < 46340, // n^2 within a BLAS int
                    ExcMessage("The Schur complement of " + name + " on " +
                               std::to_string(new_dofs.size()) +
                               " contact DoFs is too large to be dense."));
        SparseCholesky factor;
        new_inverse =
          factor.factorize_with_trailing_block(matrix, new_dofs, name);
        const types::blas_int n = new_dofs.size();
        new_schur.assign(new_inverse.size(), 0.);
        // S = L_CC L_CC^T (lower triangle).
        const double one = 1., zero = 0.;
        syrk("L",
             "N",
             &n,
             &n,
             &one,
             new_inverse.data(),
             &n,
             &zero,
             new_schur.data(),
             &n);
        // S^{-1} from the Cholesky factor L_CC (lower triangle, in place).
        types::blas_int info = 0;
        potri("L", &n, new_inverse.data(), &n, &info);
        AssertThrow(info == 0,
                    ExcMessage(
                      "The inverse of the Schur complement of " + name +
                      " on its contact DoFs failed (LAPACK dpotri info " +
                      std::to_string(info) + ")."));
      }
    contact_dofs.swap(new_dofs);
    inverse.swap(new_inverse);
    schur.swap(new_schur);
    schur_single.assign(schur.begin(), schur.end());
  }



  const std::vector<types::global_dof_index> &
  DenseSchurComplement::dofs() const
  {
    return contact_dofs;
  }



  unsigned int
  DenseSchurComplement::size() const
  {
    return contact_dofs.size();
  }



  namespace
  {
    void
    symmetric_product(const std::vector<double> &matrix,
                      const types::blas_int      n,
                      const double              *x,
                      double                    *y)
    {
      if (n == 0)
        return;
      const double          one = 1., zero = 0.;
      const types::blas_int step = 1;
      dsymv_("L", &n, &one, matrix.data(), &n, x, &step, &zero, y, &step);
    }
  } // namespace



  void
  DenseSchurComplement::vmult(const double *x, double *y) const
  {
    symmetric_product(schur, size(), x, y);
  }



  void
  DenseSchurComplement::vmult_single_precision(const double *x, double *y) const
  {
    const types::blas_int n = size();
    if (n == 0)
      return;
    x_single.assign(x, x + n);
    y_single.resize(n);
    const float           one = 1.f, zero = 0.f;
    const types::blas_int step = 1;
    ssymv_("L",
           &n,
           &one,
           schur_single.data(),
           &n,
           x_single.data(),
           &step,
           &zero,
           y_single.data(),
           &step);
    std::copy(y_single.begin(), y_single.end(), y);
  }



  void
  DenseSchurComplement::vmult_inverse(const double *x, double *y) const
  {
    symmetric_product(inverse, size(), x, y);
  }



  std::size_t
  DenseSchurComplement::memory_consumption() const
  {
    return (schur.capacity() + inverse.capacity()) * sizeof(double) +
           schur_single.capacity() * sizeof(float) +
           contact_dofs.capacity() * sizeof(types::global_dof_index);
  }



  bool
  DenseSchurComplement::pays_off(const std::size_t n_contact_dofs,
                                 const std::size_t n_factor_entries,
                                 const std::size_t memory_limit)
  {
    const std::size_t squared = n_contact_dofs * n_contact_dofs;
    return n_contact_dofs > 0 &&
           squared * (2 * sizeof(double) + sizeof(float)) <= memory_limit &&
           squared < 4 * n_factor_entries;
  }
} // namespace impactfe
