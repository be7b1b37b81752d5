#include <deal.II/base/exceptions.h>

#include <impactfe/dynamics/sparse_cholesky.h>

#include <cholmod.h>

#include <algorithm>
#include <string>
#include <vector>

#include "../utilities/blas_lapack.h"

namespace impactfe
{
  namespace
  {
    // A simplicial factor's arrays (SparseCholesky::Data) as the row
    // kernels of its substitutions use them.
    struct SimplicialRows
    {
      const int    *row_start, *row_column;
      const double *row_value;
      const int    *column_start, *column_row;
      const double *column_value, *inverse_diagonal;
      const int    *permutation;
      // a bidiagonal L (a 1D body in its natural order): chain[i] =
      // L_{i,i-1}, 0 where row i has no entry, chain[0] = chain[n] = 0;
      // nullptr for any other factor
      const double *chain;
      double       *z;
      std::size_t   n;
    };
  } // namespace

  // CHOLMOD's state: its common block, the factor, and the solution/work
  // arrays that cholmod_solve2 reuses from one call to the next (the
  // solves of several right-hand sides at once).
  struct SparseCholesky::Data
  {
    cholmod_common  common;
    cholmod_factor *factor         = nullptr;
    cholmod_dense  *block_solution = nullptr;
    cholmod_dense  *block_work_y   = nullptr;
    cholmod_dense  *block_work_e   = nullptr;
    // A simplicial factor L D L^T = P A P^T, copied out of CHOLMOD: the
    // strictly lower part of L by columns (for the backward substitution)
    // and by rows (forward), each sorted, 1 / D, the permutation, and the
    // work vector of a solve.
    std::vector<int>            column_start, column_row;
    std::vector<double>         column_value;
    std::vector<int>            row_start, row_column;
    std::vector<double>         row_value;
    std::vector<double>         inverse_diagonal;
    std::vector<int>            permutation;
    std::vector<double>         chain;
    mutable std::vector<double> work;
    // A supernodal factor's values rounded to single precision and the
    // work vector of its solve (solve_single_precision(), made at its
    // first call).
    mutable std::vector<float> single_values, single_work, single_block;
    // The work space of solve_lower() and of solve() with a supernodal
    // factor (rows below a supernode), and solve()'s permuted vector.
    mutable std::vector<double> rows_below, super_work;

    SimplicialRows
    rows() const
    {
      return SimplicialRows{row_start.data(),
                            row_column.data(),
                            row_value.data(),
                            column_start.data(),
                            column_row.data(),
                            column_value.data(),
                            inverse_diagonal.data(),
                            permutation.data(),
                            chain.empty() ? nullptr : chain.data(),
                            work.data(),
                            inverse_diagonal.size()};
    }

    Data()
    {
      cholmod_start(&common);
    }

    void
    free_all()
    {
      cholmod_free_factor(&factor, &common);
      cholmod_free_dense(&block_solution, &common);
      cholmod_free_dense(&block_work_y, &common);
      cholmod_free_dense(&block_work_e, &common);
      single_values.clear(); // rounded from the factor just freed
      rows_below.clear();
      super_work.clear();
    }

    ~Data()
    {
      free_all();
      cholmod_finish(&common);
    }
  };



  namespace
  {
    // The most rows of any supernode of @p L (a bound on the rows below
    // any of its leading columns).
    std::size_t
    most_rows(const cholmod_factor &L)
    {
      const int  *pi   = static_cast<const int *>(L.pi);
      std::size_t most = 1;
      for (std::size_t s = 0; s < L.nsuper; ++s)
        most = std::max<std::size_t>(most, pi[s + 1] - pi[s]);
      return most;
    }
  } // namespace



  SparseCholesky::SparseCholesky()
    : data(std::make_unique<Data>())
  {}



  SparseCholesky::~SparseCholesky() = default;



  namespace
  {
    // The upper triangle (i <= j) of a symmetric matrix in compressed
    // columns, as CHOLMOD reads it: row j of the CSR storage is column j of
    // A^T = A. The arrays live as long as the object.
    struct UpperTriangle
    {
      std::vector<int>    column_start;
      std::vector<int>    row_index;
      std::vector<double> values;
      cholmod_sparse      view;

      explicit UpperTriangle(const SparseMatrix<double> &matrix,
                             const bool                  drop_zeros = false)
        : column_start(matrix.m() + 1, 0)
      {
        const unsigned int n = matrix.m();
        row_index.reserve(matrix.n_nonzero_elements() / 2 + n);
        values.reserve(matrix.n_nonzero_elements() / 2 + n);
        for (unsigned int j = 0; j < n; ++j)
          {
            for (auto entry = matrix.begin(j); entry != matrix.end(j); ++entry)
              if (entry->column() <= j &&
                  !(drop_zeros && entry->column() != j && entry->value() == 0.))
                {
                  row_index.push_back(entry->column());
                  values.push_back(entry->value());
                }
            column_start[j + 1] = row_index.size();
          }
        view.nrow   = n;
        view.ncol   = n;
        view.nzmax  = values.size();
        view.p      = column_start.data();
        view.i      = row_index.data();
        view.nz     = nullptr;
        view.x      = values.data();
        view.z      = nullptr;
        view.stype  = 1; // symmetric, upper triangle stored
        view.itype  = CHOLMOD_INT;
        view.xtype  = CHOLMOD_REAL;
        view.dtype  = CHOLMOD_DOUBLE;
        view.sorted = false; // deal.II stores the diagonal first
        view.packed = true;
      }
    };
  } // namespace



  void
  SparseCholesky::factorize(const SparseMatrix<double> &matrix,
                            const std::string          &name,
                            const bool                  drop_zeros)
  {
    AssertThrow(matrix.m() == matrix.n(),
                ExcMessage("Cholesky factorisation of " + name +
                           ": the matrix is not square."));
    data->free_all();
    UpperTriangle upper(matrix, drop_zeros);
    // A tridiagonal matrix (a 1D body numbered along its cells) has no
    // fill in its own order, and its factor is then a chain that
    // solve_together() can run two at a time; CHOLMOD's orderings reverse
    // it and put one end elsewhere, which costs no fill but breaks the
    // chain.
    bool tridiagonal = true;
    for (unsigned int j = 0; j < matrix.m() && tridiagonal; ++j)
      for (int p = upper.column_start[j]; p < upper.column_start[j + 1]; ++p)
        tridiagonal =
          tridiagonal && upper.row_index[p] + 1 >= static_cast<int>(j);
    cholmod_common &common       = data->common;
    const int       nmethods     = common.nmethods;
    const int       first_method = common.method[0].ordering;
    if (tridiagonal)
      {
        common.nmethods           = 1;
        common.method[0].ordering = CHOLMOD_NATURAL;
      }
    data->factor              = cholmod_analyze(&upper.view, &common);
    common.nmethods           = nmethods;
    common.method[0].ordering = first_method;
    AssertThrow(data->factor != nullptr,
                ExcMessage("Cholesky factorisation of " + name +
                           ": the analysis failed (CHOLMOD status " +
                           std::to_string(data->common.status) + ")."));
    factorize_analysed(upper.view, name);
  }



  void
  SparseCholesky::factorize_analysed(cholmod_sparse_struct &upper,
                                     const std::string     &name)
  {
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
    data->column_start.clear();
    data->chain.clear();
    if (!data->factor->is_super)
      copy_simplicial_factor();
    else
      {
        // solve()'s work space, so that the time loop does not allocate
        data->super_work.assign(data->factor->n, 0.);
        data->rows_below.resize(most_rows(*data->factor));
      }
  }



  // The ordering: CHOLMOD's own fill-reducing ordering of the other
  // unknowns (its analysis of that block), then the trailing ones. With
  // them last, the trailing block of L is the Cholesky factor of their
  // Schur complement: A = [A_II A_IC; A_CI A_CC] = L L^T with
  // L = [L_II 0; X L_CC] gives A_CC = X X^T + L_CC L_CC^T and
  // X = A_CI L_II^{-T}, so L_CC L_CC^T = A_CC - A_CI A_II^{-1} A_IC. Its
  // cost is about that of one factorisation (the trailing unknowns of a
  // contact surface are a separator like the top ones of nested
  // dissection), where computing the Schur complement by solves would take
  // one solve per trailing unknown.
  std::vector<double>
  SparseCholesky::factorize_with_trailing_block(
    const SparseMatrix<double>           &matrix,
    std::vector<types::global_dof_index> &trailing,
    const std::string                    &name)
  {
    AssertThrow(matrix.m() == matrix.n(),
                ExcMessage("Cholesky factorisation of " + name +
                           ": the matrix is not square."));
    const unsigned int n   = matrix.m();
    const unsigned int n_c = trailing.size();
    std::vector<int>   position(n, -1);
    for (unsigned int i = 0; i < n_c; ++i)
      {
        AssertThrow(trailing[i] < n && position[trailing[i]] < 0,
                    ExcMessage("Cholesky factorisation of " + name +
                               ": the trailing unknowns must be distinct "
                               "rows of the matrix."));
        position[trailing[i]] = i;
      }
    std::vector<int> ordering;
    ordering.reserve(n);
    UpperTriangle upper(matrix);
    {
      // The block of the other unknowns, analysed alone.
      std::vector<types::global_dof_index> others;
      for (unsigned int i = 0; i < n; ++i)
        if (position[i] < 0)
          others.push_back(i);
      std::vector<int> other_index(n, -1);
      for (unsigned int k = 0; k < others.size(); ++k)
        other_index[others[k]] = k;
      std::vector<int>    start(1, 0), rows;
      std::vector<double> values;
      for (const auto j : others)
        {
          for (int p = upper.column_start[j]; p < upper.column_start[j + 1];
               ++p)
            if (other_index[upper.row_index[p]] >= 0)
              {
                rows.push_back(other_index[upper.row_index[p]]);
                values.push_back(upper.values[p]);
              }
          start.push_back(rows.size());
        }
      cholmod_sparse block = upper.view;
      block.nrow = block.ncol = others.size();
      block.nzmax             = values.size();
      block.p                 = start.data();
      block.i                 = rows.data();
      block.x                 = values.data();
      cholmod_factor *symbolic =
        others.empty() ? nullptr : cholmod_analyze(&block, &data->common);
      AssertThrow(others.empty() || symbolic != nullptr,
                  ExcMessage("Cholesky factorisation of " + name +
                             ": the analysis failed (CHOLMOD status " +
                             std::to_string(data->common.status) + ")."));
      if (symbolic != nullptr)
        {
          const int *perm = static_cast<const int *>(symbolic->Perm);
          for (unsigned int k = 0; k < others.size(); ++k)
            ordering.push_back(others[perm[k]]);
          cholmod_free_factor(&symbolic, &data->common);
        }
    }
    for (const auto d : trailing)
      ordering.push_back(d);

    data->free_all();
    cholmod_common &common       = data->common;
    const int       nmethods     = common.nmethods;
    const int       first_method = common.method[0].ordering;
    const int       postorder    = common.postorder;
    const int       supernodal   = common.supernodal;
    common.nmethods              = 1;
    common.method[0].ordering    = CHOLMOD_GIVEN;
    common.postorder             = false; // keeps the trailing block last
    common.supernodal            = CHOLMOD_SUPERNODAL;
    data->factor =
      cholmod_analyze_p(&upper.view, ordering.data(), nullptr, 0, &common);
    common.nmethods           = nmethods;
    common.method[0].ordering = first_method;
    common.postorder          = postorder;
    common.supernodal         = supernodal;
    AssertThrow(data->factor != nullptr,
                ExcMessage("Cholesky factorisation of " + name +
                           ": the analysis failed (CHOLMOD status " +
                           std::to_string(common.status) + ")."));
    factorize_analysed(upper.view, name);

    // Copy L_CC out of the supernodes that hold the last n_c columns;
    // their rows are all trailing ones. The order of the trailing unknowns
    // is the factor's (returned in trailing).
    const cholmod_factor *L    = data->factor;
    const int            *perm = static_cast<const int *>(L->Perm);
    for (unsigned int i = 0; i < n_c; ++i)
      trailing[i] = perm[n - n_c + i];
    AssertThrow(std::all_of(trailing.begin(),
                            trailing.end(),
                            [&](const auto d) { return position[d] >= 0; }),
                ExcMessage("Cholesky factorisation of " + name +
                           ": CHOLMOD did not keep the given ordering."));
    std::vector<double> block(static_cast<std::size_t>(n_c) * n_c, 0.);
    const int          *super = static_cast<const int *>(L->super);
    const int          *pi    = static_cast<const int *>(L->pi);
    const int          *px    = static_cast<const int *>(L->px);
    const int          *s     = static_cast<const int *>(L->s);
    const double       *x     = static_cast<const double *>(L->x);
    const int           first = n - n_c;
    for (std::size_t k = 0; k < L->nsuper; ++k)
      if (super[k + 1] > first)
        {
          const int n_rows = pi[k + 1] - pi[k];
          for (int j = std::max(super[k], first); j < super[k + 1]; ++j)
            for (int r = 0; r < n_rows; ++r)
              if (const int row = s[pi[k] + r]; row >= j)
                block[static_cast<std::size_t>(j - first) * n_c + row - first] =
                  x[px[k] + static_cast<std::size_t>(j - super[k]) * n_rows +
                    r];
        }
    return block;
  }



  // CHOLMOD picks a simplicial factor when the matrix's fill is small (1D
  // bars, small 2D meshes). Its solve then costs little more than its
  // ~4 nnz(L) flops, and the packing into cholmod_dense objects and
  // CHOLMOD's dispatch cost as much: the substitutions below do only the
  // flops. (Supernodal factors have substitutions of their own too,
  // solve_supernodal(); only the multi-column solve calls CHOLMOD.)
  void
  SparseCholesky::copy_simplicial_factor()
  {
    cholmod_factor *L  = data->factor;
    const int       ok = cholmod_change_factor(CHOLMOD_REAL,
                                         /*to_ll=*/false,
                                         /*to_super=*/false,
                                         /*to_packed=*/true,
                                         /*to_monotonic=*/true,
                                         L,
                                         &data->common);
    AssertThrow(ok && !L->is_ll && !L->is_super,
                ExcMessage("CHOLMOD could not give the factor as L D L^T."));
    const std::size_t n     = L->n;
    const int        *start = static_cast<const int *>(L->p);
    const int        *count = static_cast<const int *>(L->nz);
    const int        *row   = static_cast<const int *>(L->i);
    const double     *value = static_cast<const double *>(L->x);
    const int        *perm  = static_cast<const int *>(L->Perm);
    Data             &d     = *data;
    d.inverse_diagonal.resize(n);
    d.column_start.assign(1, 0);
    d.column_row.clear();
    d.column_value.clear();
    std::vector<int>                    row_count(n, 0);
    std::vector<std::pair<int, double>> column;
    for (std::size_t j = 0; j < n; ++j)
      {
        AssertThrow(count[j] >= 1 && row[start[j]] == static_cast<int>(j),
                    ExcMessage("CHOLMOD's factor has no diagonal entry in "
                               "column " +
                               std::to_string(j) + "."));
        d.inverse_diagonal[j] = 1. / value[start[j]];
        column.clear();
        for (int p = start[j] + 1; p < start[j] + count[j]; ++p)
          column.emplace_back(row[p], value[p]);
        std::sort(column.begin(), column.end());
        for (const auto &[i, l] : column)
          {
            d.column_row.push_back(i);
            d.column_value.push_back(l);
            ++row_count[i];
          }
        d.column_start.push_back(d.column_row.size());
      }
    // The rows: walking the columns in order leaves each row sorted.
    d.row_start.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      d.row_start[i + 1] = d.row_start[i] + row_count[i];
    d.row_column.resize(d.column_row.size());
    d.row_value.resize(d.column_row.size());
    std::vector<int> next(d.row_start.begin(), d.row_start.end() - 1);
    for (std::size_t j = 0; j < n; ++j)
      for (int p = d.column_start[j]; p < d.column_start[j + 1]; ++p)
        {
          const int q     = next[d.column_row[p]]++;
          d.row_column[q] = j;
          d.row_value[q]  = d.column_value[p];
        }
    d.permutation.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      d.permutation[k] = perm != nullptr ? perm[k] : static_cast<int>(k);
    data->work.assign(n, 0.);
    // A chain: every row holds at most its left neighbour.
    d.chain.assign(n + 1, 0.);
    for (std::size_t i = 0; i < n && !d.chain.empty(); ++i)
      {
        const int entries = d.row_start[i + 1] - d.row_start[i];
        if (entries == 1 &&
            d.row_column[d.row_start[i]] + 1 == static_cast<int>(i))
          d.chain[i] = d.row_value[d.row_start[i]];
        else if (entries != 0)
          d.chain.clear();
      }
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



  namespace
  {
    // The BLAS of the supernodal substitutions, in either precision.
    void
    triangular_solve(const char  *trans,
                     const int   *n,
                     const float *a,
                     const int   *lda,
                     float       *x)
    {
      const int one = 1;
      strsv_("L", trans, "N", n, a, lda, x, &one);
    }

    void
    triangular_solve(const char   *trans,
                     const int    *n,
                     const double *a,
                     const int    *lda,
                     double       *x)
    {
      const int one = 1;
      dtrsv_("L", trans, "N", n, a, lda, x, &one);
    }

    void
    matrix_vector(const char  *trans,
                  const int   *m,
                  const int   *n,
                  const float  alpha,
                  const float *a,
                  const int   *lda,
                  const float *x,
                  const float  beta,
                  float       *y)
    {
      const int one = 1;
      sgemv_(trans, m, n, &alpha, a, lda, x, &one, &beta, y, &one);
    }

    void
    matrix_vector(const char   *trans,
                  const int    *m,
                  const int    *n,
                  const double  alpha,
                  const double *a,
                  const int    *lda,
                  const double *x,
                  const double  beta,
                  double       *y)
    {
      const int one = 1;
      dgemv_(trans, m, n, &alpha, a, lda, x, &one, &beta, y, &one);
    }

    // L z = z (forward) or L^T z = z, by supernodes, z in the factor's
    // order: a supernode's columns k1 <= k < k2 and its rows (the first
    // k2 - k1 of them those columns) hold a dense, column-major block;
    // forward, its triangle is solved and the rows below updated;
    // backward, the reverse. Only the columns k < @p n_leading take part
    // (a supernode may be cut: its own later rows then count as rows
    // below); backward, only the columns k >= @p first_column are
    // computed. @p t: work space for the rows below a supernode.
    //
    // Supernodes of at most narrow_supernode columns are done by plain
    // loops, column by column, the others by BLAS (a triangular solve and
    // a matrix-vector product): the two calls cost more than the
    // arithmetic of a narrow supernode. Thin 2D meshes have nothing else
    // (13 columns on average on a slab of 30000 x 4 cells: a solve pair
    // 17 -> 6.5 ms); 3D meshes have wide ones too, which BLAS does faster.
    constexpr int narrow_supernode = 32;

    template <typename Number>
    void
    narrow_forward(const Number *block,
                   const int     n_columns,
                   const int     n_rows,
                   const int    *rows,
                   Number       *z_own,
                   Number       *z)
    {
      for (int j = 0; j < n_columns; ++j)
        {
          const Number *column = block + std::size_t(j) * n_rows;
          const Number  x_j    = z_own[j] / column[j];
          z_own[j]             = x_j;
          for (int i = j + 1; i < n_columns; ++i)
            z_own[i] -= column[i] * x_j;
          for (int i = n_columns; i < n_rows; ++i)
            z[rows[i]] -= column[i] * x_j;
        }
    }

    // The transpose; @p ld the block's leading dimension, @p rows the
    // rows from the first computed column on.
    template <typename Number>
    void
    narrow_backward(const Number *block,
                    const int     n_columns,
                    const int     n_rows,
                    const int     ld,
                    const int    *rows,
                    Number       *z_own,
                    const Number *z)
    {
      for (int j = n_columns; j-- > 0;)
        {
          const Number *column = block + std::size_t(j) * ld;
          Number        sum    = z_own[j];
          for (int i = n_columns; i < n_rows; ++i)
            sum -= column[i] * z[rows[i]];
          for (int i = j + 1; i < n_columns; ++i)
            sum -= column[i] * z_own[i];
          z_own[j] = sum / column[j];
        }
    }
    template <typename Number>
    void
    supernodal_substitution(const cholmod_factor &L,
                            const Number         *Lx,
                            Number               *z,
                            Number               *t,
                            const bool            forward,
                            const int             n_leading,
                            const int             first_column = 0)
    {
      const int *super = static_cast<const int *>(L.super);
      const int *pi    = static_cast<const int *>(L.pi);
      const int *px    = static_cast<const int *>(L.px);
      const int *rows  = static_cast<const int *>(L.s);
      // forward: a leading run of zeros in z stays zero, and the
      // supernodes that hold only its columns change nothing
      std::size_t first = 0;
      if (forward)
        while (first < L.nsuper && super[first + 1] <= n_leading &&
               std::all_of(z + super[first],
                           z + super[first + 1],
                           [](const Number v) { return v == Number(0); }))
          ++first;
      if (forward)
        for (std::size_t s = first; s < L.nsuper && super[s] < n_leading; ++s)
          {
            const int k1          = super[s],
                      n_columns   = std::min(super[s + 1], n_leading) - k1;
            const int     n_rows  = pi[s + 1] - pi[s];
            const int     n_below = n_rows - n_columns;
            const Number *block   = Lx + px[s];
            if (n_columns <= narrow_supernode)
              {
                narrow_forward(
                  block, n_columns, n_rows, rows + pi[s], z + k1, z);
                continue;
              }
            triangular_solve("N", &n_columns, block, &n_rows, z + k1);
            if (n_below > 0)
              {
                matrix_vector("N",
                              &n_below,
                              &n_columns,
                              Number(1),
                              block + n_columns,
                              &n_rows,
                              z + k1,
                              Number(0),
                              t);
                const int *below = rows + pi[s] + n_columns;
                for (int i = 0; i < n_below; ++i)
                  z[below[i]] -= t[i];
              }
          }
      else
        // backward: the columns first_column <= k < n_leading; a supernode
        // cut by first_column keeps its columns from there on (the block
        // from its row and column skip on)
        for (std::size_t s = L.nsuper; s-- > 0 && super[s + 1] > first_column;)
          {
            if (super[s] >= n_leading)
              continue;
            const int k1          = std::max(super[s], first_column),
                      skip        = k1 - super[s],
                      n_columns   = std::min(super[s + 1], n_leading) - k1;
            const int     ld      = pi[s + 1] - pi[s];
            const int     n_below = ld - skip - n_columns;
            const Number *block   = Lx + px[s] + std::size_t(skip) * ld + skip;
            if (n_columns <= narrow_supernode)
              {
                narrow_backward(block,
                                n_columns,
                                n_columns + n_below,
                                ld,
                                rows + pi[s] + skip,
                                z + k1,
                                z);
                continue;
              }
            if (n_below > 0)
              {
                const int *below = rows + pi[s] + skip + n_columns;
                for (int i = 0; i < n_below; ++i)
                  t[i] = z[below[i]];
                matrix_vector("T",
                              &n_below,
                              &n_columns,
                              Number(-1),
                              block + n_columns,
                              &ld,
                              t,
                              Number(1),
                              z + k1);
              }
            triangular_solve("T", &n_columns, block, &ld, z + k1);
          }
    }

  } // namespace



  namespace
  {
    // The substitutions of a simplicial factor L D L^T, a row at a time.
    // These recurrences are latency-bound: the term of the neighbour just
    // computed (column i-1 of row i, row j+1 of column j: the whole of a
    // 1D chain) is taken from a register, not through memory, and
    // subtracted last, so that only it waits for the row before; the
    // other terms, which the processor can sum ahead, go into two sums,
    // which halves their own chain (a 2D strip's rows hold 15 entries).

    // z_i <- z_i - sum_k L_ik z_k (k < i), and its value
    DEAL_II_ALWAYS_INLINE inline double
    forward_row(const SimplicialRows &f, const std::size_t i, double previous)
    {
      const int    *col = f.row_column;
      const double *L   = f.row_value;
      const double *z   = f.z;
      int           end = f.row_start[i + 1];
      const bool    neighbour =
        end > f.row_start[i] && col[end - 1] + 1 == static_cast<int>(i);
      if (neighbour)
        --end;
      double sum = z[i], other = 0.;
      int    p = f.row_start[i];
      for (; p + 2 <= end; p += 2)
        {
          sum -= L[p] * z[col[p]];
          other -= L[p + 1] * z[col[p + 1]];
        }
      if (p < end)
        sum -= L[p] * z[col[p]];
      sum += other;
      if (neighbour)
        sum -= L[end] * previous;
      f.z[i] = sum;
      return sum;
    }

    // z_j <- z_j / D_j - sum_k L_kj z_k (k > j), and its value
    DEAL_II_ALWAYS_INLINE inline double
    backward_row(const SimplicialRows &f, const std::size_t j, double previous)
    {
      const int    *row   = f.column_row;
      const double *L     = f.column_value;
      const double *z     = f.z;
      const int     begin = f.column_start[j], end = f.column_start[j + 1];
      const bool    neighbour =
        begin < end && row[begin] == static_cast<int>(j + 1);
      double sum = z[j] * f.inverse_diagonal[j], other = 0.;
      int    p = begin + (neighbour ? 1 : 0);
      for (; p + 2 <= end; p += 2)
        {
          sum -= L[p] * z[row[p]];
          other -= L[p + 1] * z[row[p + 1]];
        }
      if (p < end)
        sum -= L[p] * z[row[p]];
      sum += other;
      if (neighbour)
        sum -= L[begin] * previous;
      f.z[j] = sum;
      return sum;
    }

    inline void
    gather(const SimplicialRows &f, const Vector<double> &x)
    {
      for (std::size_t k = 0; k < f.n; ++k)
        f.z[k] = x[f.permutation[k]];
    }

    inline void
    scatter(const SimplicialRows &f, Vector<double> &x)
    {
      for (std::size_t k = 0; k < f.n; ++k)
        x[f.permutation[k]] = f.z[k];
    }

    // L D L^T z = P x, then x = P^T z, for two bidiagonal factors at
    // once, their rows alternating: a chain's step (a multiplication and a
    // subtraction, about 7 cycles) waits for the step before, so the one
    // chain's step runs while the other's waits. Each factor's arithmetic
    // is that of forward_row() and backward_row() (which add nothing but
    // exact zeros besides), in the same order: the answers are those of
    // separate solves, to the bit.
    void
    solve_two_chains(const SimplicialRows &a,
                     Vector<double>       &x_a,
                     const SimplicialRows &b,
                     Vector<double>       &x_b)
    {
      gather(a, x_a);
      gather(b, x_b);
      double *const z_a = a.z, *const z_b = b.z;
      const double *const l_a = a.chain, *const l_b = b.chain;
      const double *const d_a = a.inverse_diagonal, *const d_b =
                                                      b.inverse_diagonal;
      const std::size_t both       = std::min(a.n, b.n);
      double            previous_a = 0., previous_b = 0.;
      for (std::size_t i = 0; i < both; ++i)
        {
          previous_a = z_a[i] = z_a[i] - l_a[i] * previous_a;
          previous_b = z_b[i] = z_b[i] - l_b[i] * previous_b;
        }
      for (std::size_t i = both; i < a.n; ++i)
        previous_a = z_a[i] = z_a[i] - l_a[i] * previous_a;
      for (std::size_t i = both; i < b.n; ++i)
        previous_b = z_b[i] = z_b[i] - l_b[i] * previous_b;
      // backward: the longer chain's last rows alone first, then both
      previous_a = previous_b = 0.;
      std::size_t j_a = a.n, j_b = b.n;
      for (; j_a > j_b; --j_a)
        previous_a = z_a[j_a - 1] =
          z_a[j_a - 1] * d_a[j_a - 1] - l_a[j_a] * previous_a;
      for (; j_b > j_a; --j_b)
        previous_b = z_b[j_b - 1] =
          z_b[j_b - 1] * d_b[j_b - 1] - l_b[j_b] * previous_b;
      for (; j_a > 0; --j_a, --j_b)
        {
          previous_a = z_a[j_a - 1] =
            z_a[j_a - 1] * d_a[j_a - 1] - l_a[j_a] * previous_a;
          previous_b = z_b[j_b - 1] =
            z_b[j_b - 1] * d_b[j_b - 1] - l_b[j_b] * previous_b;
        }
      scatter(a, x_a);
      scatter(b, x_b);
    }
  } // namespace



  void
  SparseCholesky::solve(Vector<double> &x) const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    const std::size_t n = data->factor->n;
    AssertDimension(x.size(), n);
    if (!data->column_start.empty())
      {
        // L D L^T z = P x, then x = P^T z
        const SimplicialRows f = data->rows();
        gather(f, x);
        double previous = 0.;
        for (std::size_t i = 0; i < n; ++i)
          previous = forward_row(f, i, previous);
        previous = 0.;
        for (std::size_t j = n; j-- > 0;)
          previous = backward_row(f, j, previous);
        scatter(f, x);
        return;
      }
    // A supernodal factor: L L^T z = P x by supernodes (as
    // solve_single_precision(), in double precision), then x = P^T z;
    // CHOLMOD's own solve makes two BLAS calls per supernode, which on
    // the small supernodes of thin 2D meshes cost more than the
    // arithmetic (doc/performance.md, "Supernodal substitutions").
    const cholmod_factor &L    = *data->factor;
    const int            *perm = static_cast<const int *>(L.Perm);
    double               *z    = data->super_work.data();
    for (std::size_t k = 0; k < n; ++k)
      z[k] = x[perm[k]];
    const double *values = static_cast<const double *>(L.x);
    const int     all    = n;
    supernodal_substitution(L, values, z, data->rows_below.data(), true, all);
    supernodal_substitution(L, values, z, data->rows_below.data(), false, all);
    for (std::size_t k = 0; k < n; ++k)
      x[perm[k]] = z[k];
  }



  void
  SparseCholesky::solve_together(
    const std::vector<std::unique_ptr<SparseCholesky>> &factors,
    BlockVector<double>                                &x)
  {
    AssertDimension(factors.size(), x.n_blocks());
    // pairs of bidiagonal factors alternate their rows
    // (solve_two_chains()); any other factor, or the last of an odd
    // number, solves alone (alternating the general rows of two factors
    // was slower: their loads and branches, not the chains, bound them)
    int waiting = -1;
    for (unsigned int b = 0; b < factors.size(); ++b)
      {
        const SparseCholesky &factor = *factors[b];
        Assert(factor.data->factor != nullptr,
               ExcMessage("factorize() first."));
        AssertDimension(x.block(b).size(), factor.size());
        if (!factor.bidiagonal())
          factor.solve(x.block(b));
        else if (waiting < 0)
          waiting = b;
        else
          {
            solve_two_chains(factors[waiting]->data->rows(),
                             x.block(waiting),
                             factor.data->rows(),
                             x.block(b));
            waiting = -1;
          }
      }
    if (waiting >= 0)
      factors[waiting]->solve(x.block(waiting));
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



  // L L^T z = P x by supernodes in single precision.
  void
  SparseCholesky::solve_single_precision(Vector<double> &x) const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    const cholmod_factor &L = *data->factor;
    if (!L.is_super)
      {
        solve(x);
        return;
      }
    const std::size_t n = L.n;
    AssertDimension(x.size(), n);
    if (data->single_values.empty())
      {
        const double *values = static_cast<const double *>(L.x);
        data->single_values.assign(values, values + L.xsize);
        data->single_work.resize(n);
        data->single_block.resize(most_rows(L));
      }
    const int *perm = static_cast<const int *>(L.Perm);
    float     *z    = data->single_work.data();
    for (std::size_t k = 0; k < n; ++k)
      z[k] = static_cast<float>(x[perm[k]]);
    const int all = n;
    supernodal_substitution(
      L, data->single_values.data(), z, data->single_block.data(), true, all);
    supernodal_substitution(
      L, data->single_values.data(), z, data->single_block.data(), false, all);
    for (std::size_t k = 0; k < n; ++k)
      x[perm[k]] = z[k];
  }



  const int *
  SparseCholesky::permutation() const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    return static_cast<const int *>(data->factor->Perm);
  }



  void
  SparseCholesky::solve_lower(double            *z,
                              const bool         transpose,
                              const unsigned int n_leading,
                              const unsigned int first_column) const
  {
    Assert(data->factor != nullptr, ExcMessage("factorize() first."));
    const cholmod_factor &L = *data->factor;
    AssertThrow(L.is_super,
                ExcMessage("SparseCholesky::solve_lower() needs a supernodal "
                           "factor (factorize_with_trailing_block())."));
    if (data->rows_below.empty())
      data->rows_below.resize(most_rows(L));
    supernodal_substitution(L,
                            static_cast<const double *>(L.x),
                            z,
                            data->rows_below.data(),
                            !transpose,
                            std::min<std::size_t>(n_leading, L.n),
                            transpose ? first_column : 0);
  }



  std::size_t
  SparseCholesky::size() const
  {
    return data->factor == nullptr ? 0 : data->factor->n;
  }



  bool
  SparseCholesky::simplicial() const
  {
    return !data->column_start.empty();
  }



  bool
  SparseCholesky::bidiagonal() const
  {
    return !data->chain.empty();
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
