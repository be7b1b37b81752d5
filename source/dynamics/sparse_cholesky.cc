#include <deal.II/base/exceptions.h>

#include <impactfe/dynamics/sparse_cholesky.h>

#include <cholmod.h>

#include <algorithm>
#include <string>
#include <vector>

namespace impactfe
{
  // CHOLMOD's state: its common block, the factor, the right-hand side and
  // the solution/work arrays that cholmod_solve2 reuses from one call to
  // the next.
  struct SparseCholesky::Data
  {
    cholmod_common  common;
    cholmod_factor *factor   = nullptr;
    cholmod_dense  *rhs      = nullptr;
    cholmod_dense  *solution = nullptr;
    cholmod_dense  *work_y   = nullptr;
    cholmod_dense  *work_e   = nullptr;
    // The same for several right-hand sides at once.
    cholmod_dense *block_solution = nullptr;
    cholmod_dense *block_work_y   = nullptr;
    cholmod_dense *block_work_e   = nullptr;

    Data()
    {
      cholmod_start(&common);
    }

    void
    free_all()
    {
      cholmod_free_factor(&factor, &common);
      cholmod_free_dense(&rhs, &common);
      cholmod_free_dense(&solution, &common);
      cholmod_free_dense(&work_y, &common);
      cholmod_free_dense(&work_e, &common);
      cholmod_free_dense(&block_solution, &common);
      cholmod_free_dense(&block_work_y, &common);
      cholmod_free_dense(&block_work_e, &common);
    }

    ~Data()
    {
      free_all();
      cholmod_finish(&common);
    }
  };



  SparseCholesky::SparseCholesky()
    : data(std::make_unique<Data>())
  {}



  SparseCholesky::~SparseCholesky() = default;



  void
  SparseCholesky::factorize(const SparseMatrix<double> &matrix,
                            const std::string          &name)
  {
    AssertThrow(matrix.m() == matrix.n(),
                ExcMessage("Cholesky factorisation of " + name +
                           ": the matrix is not square."));
    data->free_all();
    const unsigned int n = matrix.m();

    // The upper triangle (i <= j) of the symmetric matrix in compressed
    // columns: row j of the CSR storage is column j of A^T = A.
    std::vector<int>    column_start(n + 1, 0);
    std::vector<int>    row_index;
    std::vector<double> values;
    row_index.reserve(matrix.n_nonzero_elements() / 2 + n);
    values.reserve(matrix.n_nonzero_elements() / 2 + n);
    for (unsigned int j = 0; j < n; ++j)
      {
        for (auto entry = matrix.begin(j); entry != matrix.end(j); ++entry)
          if (entry->column() <= j)
            {
              row_index.push_back(entry->column());
              values.push_back(entry->value());
            }
        column_start[j + 1] = row_index.size();
      }

    cholmod_sparse upper;
    upper.nrow   = n;
    upper.ncol   = n;
    upper.nzmax  = values.size();
    upper.p      = column_start.data();
    upper.i      = row_index.data();
    upper.nz     = nullptr;
    upper.x      = values.data();
    upper.z      = nullptr;
    upper.stype  = 1; // symmetric, upper triangle stored
    upper.itype  = CHOLMOD_INT;
    upper.xtype  = CHOLMOD_REAL;
    upper.dtype  = CHOLMOD_DOUBLE;
    upper.sorted = false; // deal.II stores the diagonal first
    upper.packed = true;

    data->factor = cholmod_analyze(&upper, &data->common);
    AssertThrow(data->factor != nullptr,
                ExcMessage("Cholesky factorisation of " + name +
                           ": the analysis failed (CHOLMOD status " +
                           std::to_string(data->common.status) + ")."));
    cholmod_factorize(&upper, data->factor, &data->common);
    AssertThrow(data->common.status == CHOLMOD_OK,
                ExcMessage(
                  "Cholesky factorisation of " + name +
                  (data->common.status == CHOLMOD_NOT_POSDEF ?
                     std::string(": the matrix is not positive definite "
                                 "(check the material data and the time "
                                 "step).") :
                     ": CHOLMOD status " + std::to_string(data->common.status) +
                       ".")));
    data->rhs = cholmod_zeros(n, 1, CHOLMOD_REAL, &data->common);
  }



  namespace
  {
    /**
     * CHOLMOD 3 (SuiteSparse 5, Debian bookworm) allocates the workspace Y
     * of a simplicial solve as 4 x n and then sets Y->nrow (and Y->d) to the
     * number of right-hand sides, so that the next cholmod_solve2() finds Y
     * "of the wrong size" and allocates it again: two allocations per solve
     * in the time loop. Giving Y back the shape it was allocated with (its
     * nzmax holds 4 n entries) lets CHOLMOD reuse it. Any other shape is
     * left alone: CHOLMOD then simply allocates, as before.
     */
    void
    restore_simplicial_workspace(cholmod_dense *Y, const std::size_t n)
    {
      if (Y != nullptr && Y->ncol == n && Y->nzmax >= 4 * n && Y->nrow < 4)
        {
          Y->nrow = 4;
          Y->d    = 4;
        }
    }
  } // namespace



  void
  SparseCholesky::solve(Vector<double> &x) const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    const std::size_t n = data->factor->n;
    AssertDimension(x.size(), n);
    double *b = static_cast<double *>(data->rhs->x);
    std::copy(x.begin(), x.end(), b);
    const int ok = cholmod_solve2(CHOLMOD_A,
                                  data->factor,
                                  data->rhs,
                                  nullptr,
                                  &data->solution,
                                  nullptr,
                                  &data->work_y,
                                  &data->work_e,
                                  &data->common);
    AssertThrow(ok, ExcMessage("CHOLMOD solve failed."));
    restore_simplicial_workspace(data->work_y, n);
    const double *s = static_cast<const double *>(data->solution->x);
    std::copy(s, s + n, x.begin());
  }



  void
  SparseCholesky::solve(double *columns, const unsigned int n_columns) const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    if (n_columns == 0)
      return;
    const std::size_t n = data->factor->n;
    cholmod_dense     block;
    block.nrow   = n;
    block.ncol   = n_columns;
    block.nzmax  = n * n_columns;
    block.d      = n;
    block.x      = columns;
    block.z      = nullptr;
    block.xtype  = CHOLMOD_REAL;
    block.dtype  = CHOLMOD_DOUBLE;
    const int ok = cholmod_solve2(CHOLMOD_A,
                                  data->factor,
                                  &block,
                                  nullptr,
                                  &data->block_solution,
                                  nullptr,
                                  &data->block_work_y,
                                  &data->block_work_e,
                                  &data->common);
    AssertThrow(ok, ExcMessage("CHOLMOD solve failed."));
    restore_simplicial_workspace(data->block_work_y, n);
    const double *s = static_cast<const double *>(data->block_solution->x);
    std::copy(s, s + n * n_columns, columns);
  }



  std::size_t
  SparseCholesky::size() const
  {
    return data->factor == nullptr ? 0 : data->factor->n;
  }



  std::size_t
  SparseCholesky::n_factor_entries() const
  {
    if (data->factor == nullptr)
      return 0;
    // Supernodal factors count their entries in xsize; simplicial in nzmax.
    return data->factor->is_super ? data->factor->xsize : data->factor->nzmax;
  }
} // namespace impactfe
