#include <deal.II/base/exceptions.h>

#include <deal.II/lac/lapack_templates.h>

#include <impactfe/dynamics/schur_complement.h>
#include <impactfe/dynamics/sparse_cholesky.h>
#include <impactfe/dynamics/sparse_lu.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <type_traits>

#include "../utilities/blas_lapack.h"

namespace impactfe
{
  void
  DenseSchurComplement::compute(
    const SparseMatrix<double>                 &matrix,
    const std::vector<types::global_dof_index> &dofs,
    const std::string                          &name)
  {
    std::vector<types::global_dof_index> ordered(dofs);
    std::vector<double>                  factor;
    if (!ordered.empty())
      {
        check_dense_size(ordered.size(), name);
        SparseCholesky cholesky;
        factor = cholesky.factorize_with_trailing_block(matrix, ordered, name);
      }
    compute_from_factor(ordered, std::move(factor), name);
  }



  void
  DenseSchurComplement::check_dense_size(const std::size_t  n,
                                         const std::string &name)
  {
    AssertThrow(n < 46340, // n^2 within a BLAS int
                ExcMessage("The Schur complement of " + name + " on " +
                           std::to_string(n) +
                           " contact DoFs is too large to be dense."));
  }



  void
  DenseSchurComplement::compute_from_factor(
    const std::vector<types::global_dof_index> &dofs,
    std::vector<double>                         factor,
    const std::string                          &name)
  {
    AssertThrow(factor.size() == dofs.size() * dofs.size(),
                ExcMessage("The Cholesky factor of the Schur complement of " +
                           name + " does not match its " +
                           std::to_string(dofs.size()) + " DoFs."));
    // Computed aside and kept only when everything succeeded, so that a
    // failure leaves the object as it was.
    std::vector<types::global_dof_index> new_dofs(dofs);
    std::vector<double> new_inverse(std::move(factor)), new_schur;
    if (!new_dofs.empty())
      {
        check_dense_size(new_dofs.size(), name);
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
    std::vector<Group> new_groups =
      find_groups(new_dofs.size(), new_schur, new_inverse);
    // only the groups' blocks are kept when there are several
    if (!new_groups.empty())
      {
        new_schur.clear();
        new_inverse.clear();
      }
    contact_dofs.swap(new_dofs);
    inverse.swap(new_inverse);
    schur.swap(new_schur);
    groups.swap(new_groups);
    schur_single.assign(schur.begin(), schur.end());
    for (auto *dense : {&schur, &inverse})
      dense->shrink_to_fit();
    schur_single.shrink_to_fit();
  }



  // The groups are the connected components of the pattern of the lower
  // triangles of S and S^{-1} (exact zeros between disconnected parts of
  // A): a union-find over the entries.
  std::vector<DenseSchurComplement::Group>
  DenseSchurComplement::find_groups(const std::size_t          n,
                                    const std::vector<double> &schur,
                                    const std::vector<double> &inverse)
  {
    std::vector<Group> groups;
    if (n < 2)
      return groups;
    std::vector<unsigned int> parent(n);
    std::iota(parent.begin(), parent.end(), 0u);
    const auto root = [&](unsigned int i) {
      while (parent[i] != i)
        i = parent[i] = parent[parent[i]];
      return i;
    };
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = j + 1; i < n; ++i)
        if (schur[j * n + i] != 0. || inverse[j * n + i] != 0.)
          {
            const unsigned int a = root(i), b = root(j);
            if (a != b)
              parent[std::max(a, b)] = std::min(a, b);
          }
    std::vector<int>          group_of_root(n, -1);
    std::vector<unsigned int> group_of(n);
    unsigned int              n_found = 0;
    for (std::size_t i = 0; i < n; ++i)
      {
        const unsigned int r = root(i);
        if (group_of_root[r] < 0)
          group_of_root[r] = n_found++;
        group_of[i] = group_of_root[r];
      }
    if (n_found < 2)
      return groups;
    groups.resize(n_found);
    for (std::size_t i = 0; i < n; ++i)
      groups[group_of[i]].index.push_back(i);
    for (Group &group : groups)
      {
        const std::size_t m = group.index.size();
        group.schur.assign(m * m, 0.);
        group.inverse.assign(m * m, 0.);
        for (std::size_t c = 0; c < m; ++c)
          for (std::size_t r = c; r < m; ++r)
            {
              // the lower triangle: row index[r] >= column index[c]
              const std::size_t at     = group.index[c] * n + group.index[r];
              group.schur[c * m + r]   = schur[at];
              group.inverse[c * m + r] = inverse[at];
            }
        group.schur_single.assign(group.schur.begin(), group.schur.end());
      }
    return groups;
  }



  unsigned int
  DenseSchurComplement::n_groups() const
  {
    return groups.empty() ? (contact_dofs.empty() ? 0 : 1) : groups.size();
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
    // Row and column d of a matrix with a symmetric pattern made those of
    // the identity (the entries stay in the pattern, as zeros).
    void
    make_identity_row_and_column(SparseMatrix<double>         &A,
                                 const types::global_dof_index d)
    {
      for (auto it = A.begin(d); it != A.end(d); ++it)
        if (it->column() != d)
          {
            A.set(it->column(), d, 0.);
            it->value() = 0.;
          }
        else
          it->value() = 1.;
    }



    // y += A x for the m x m symmetric block whose lower triangle starts
    // at A (leading dimension lda)
    template <typename Number>
    void
    add_symmetric_block(const int     m,
                        const Number *A,
                        const int     lda,
                        const Number *x,
                        Number       *y)
    {
      const Number one  = 1;
      const int    step = 1;
      if constexpr (std::is_same_v<Number, double>)
        dsymv_("L", &m, &one, A, &lda, x, &step, &one, y, &step);
      else
        ssymv_("L", &m, &one, A, &lda, x, &step, &one, y, &step);
    }

    // y = A x for the n x n symmetric A (lower triangle)
    template <typename Number>
    void
    symv(const types::blas_int n, const Number *A, const Number *x, Number *y)
    {
      std::fill(y, y + n, Number(0));
      add_symmetric_block(n, A, n, x, y);
    }

    void
    symmetric_product(const std::vector<double> &matrix,
                      const types::blas_int      n,
                      const double              *x,
                      double                    *y)
    {
      if (n > 0)
        symv(n, matrix.data(), x, y);
    }
  } // namespace



  namespace
  {
    // y[index] += A x[index] for a group's block A (lower triangle), in
    // the precision of A, through the work vectors x_work and y_work.
    template <typename Number>
    void
    add_group_product(const std::vector<unsigned int> &index,
                      const std::vector<Number>       &A,
                      const double                    *x,
                      double                          *y,
                      std::vector<Number>             &x_work,
                      std::vector<Number>             &y_work)
    {
      const types::blas_int m = index.size();
      x_work.resize(m);
      y_work.resize(m);
      for (types::blas_int i = 0; i < m; ++i)
        x_work[i] = x[index[i]];
      symv(m, A.data(), x_work.data(), y_work.data());
      for (types::blas_int i = 0; i < m; ++i)
        y[index[i]] += y_work[i];
    }
  } // namespace



  void
  DenseSchurComplement::group_product(const unsigned int g,
                                      const double      *x,
                                      double            *y,
                                      const bool         use_inverse,
                                      const bool         single_precision) const
  {
    const Group &group = groups[g];
    if (single_precision)
      add_group_product(
        group.index, group.schur_single, x, y, x_single, y_single);
    else
      add_group_product(group.index,
                        use_inverse ? group.inverse : group.schur,
                        x,
                        y,
                        x_group,
                        y_group);
  }



  void
  DenseSchurComplement::all_groups_product(const double *x,
                                           double       *y,
                                           const bool    use_inverse,
                                           const bool    single_precision) const
  {
    std::fill(y, y + size(), 0.);
    for (unsigned int g = 0; g < groups.size(); ++g)
      group_product(g, x, y, use_inverse, single_precision);
  }



  void
  DenseSchurComplement::vmult(const double *x, double *y) const
  {
    if (!groups.empty())
      all_groups_product(x, y, false, false);
    else
      symmetric_product(schur, size(), x, y);
  }



  void
  DenseSchurComplement::vmult_single_precision(const double *x, double *y) const
  {
    const types::blas_int n = size();
    if (n == 0)
      return;
    if (!groups.empty())
      {
        all_groups_product(x, y, false, true);
        return;
      }
    x_single.assign(x, x + n);
    y_single.resize(n);
    symv(n, schur_single.data(), x_single.data(), y_single.data());
    std::copy(y_single.begin(), y_single.end(), y);
  }



  void
  DenseSchurComplement::vmult_inverse(const double *x, double *y) const
  {
    if (!groups.empty())
      all_groups_product(x, y, true, false);
    else
      symmetric_product(inverse, size(), x, y);
  }



  namespace
  {
    // y += op(A) x (@p transpose "N" or "T") for a rows x columns block
    // (leading dimension lda)
    template <typename Number>
    void
    add_block(const char   *transpose,
              const int     rows,
              const int     columns,
              const Number *A,
              const int     lda,
              const Number *x,
              Number       *y)
    {
      const Number one  = 1;
      const int    step = 1;
      if constexpr (std::is_same_v<Number, double>)
        dgemv_(
          transpose, &rows, &columns, &one, A, &lda, x, &step, &one, y, &step);
      else
        sgemv_(
          transpose, &rows, &columns, &one, A, &lda, x, &step, &one, y, &step);
    }

    // y += the part of A x that the columns first <= j < end of A's lower
    // triangle (column-major, n x n) give: their diagonal block D =
    // A[first:end, first:end] by one symmetric product and the block R =
    // A[end:n, first:end] below it by R x and R^T x. Three BLAS-2 calls
    // ran a half of a 2002 x 2002 product 1.5 times faster than an axpy
    // and a dot per column (whose call overheads dominated; 2026-12-02).
    template <typename Number>
    void
    add_lower_columns(const Number      *A,
                      const std::size_t  n,
                      const unsigned int first,
                      const unsigned int end,
                      const Number      *x,
                      Number            *y)
    {
      const int m = end - first;
      if (m <= 0)
        return;
      add_symmetric_block(m, A + first * n + first, n, x + first, y + first);
      const int below = n - end;
      if (below > 0)
        {
          const Number *R = A + first * n + end;
          add_block("N", below, m, R, n, x + first, y + end);
          add_block("T", below, m, R, n, x + end, y + first);
        }
    }
  } // namespace



  std::pair<unsigned int, unsigned int>
  DenseSchurComplement::part_columns(const unsigned int part,
                                     const unsigned int n_parts) const
  {
    // columns [0, c) of the triangle hold c n - c^2 / 2 entries: the
    // fraction k / n_parts of n^2 / 2 at c = n (1 - sqrt(1 - k / n_parts))
    const double n      = size();
    const auto   column = [&](const unsigned int k) {
      return k >= n_parts ? size() :
                              static_cast<unsigned int>(std::lround(
                              n * (1. - std::sqrt(1. - double(k) / n_parts))));
    };
    return {column(part), column(part + 1)};
  }



  void
  DenseSchurComplement::add_part_of_product(const double      *x,
                                            double            *y,
                                            const unsigned int part,
                                            const unsigned int n_parts,
                                            const bool use_inverse) const
  {
    AssertThrow(part < n_parts,
                ExcMessage("DenseSchurComplement::add_part_of_product(): "
                           "part " +
                           std::to_string(part) + " of " +
                           std::to_string(n_parts) + "."));
    if (!groups.empty())
      {
        // each group to one part: the groups in order, a part taking
        // groups until it holds its share of the entries
        std::size_t total = 0;
        for (const Group &group : groups)
          total += group.index.size() * group.index.size();
        std::size_t before = 0;
        for (unsigned int g = 0; g < groups.size(); ++g)
          {
            const std::size_t m = groups[g].index.size();
            // the part of the group's middle entry
            const unsigned int owner = std::min<std::size_t>(
              n_parts - 1, (2 * before + m * m) * n_parts / (2 * total));
            before += m * m;
            if (owner == part)
              group_product(g, x, y, use_inverse, !use_inverse);
          }
        return;
      }
    const auto [first, end] = part_columns(part, n_parts);
    const std::size_t n     = size();
    if (use_inverse)
      {
        add_lower_columns(inverse.data(), n, first, end, x, y);
        return;
      }
    x_single.assign(x, x + n);
    y_single.assign(n, 0.f);
    add_lower_columns(
      schur_single.data(), n, first, end, x_single.data(), y_single.data());
    for (std::size_t i = 0; i < n; ++i)
      y[i] += y_single[i];
  }



  std::size_t
  DenseSchurComplement::memory_consumption() const
  {
    std::size_t bytes =
      (schur.capacity() + inverse.capacity()) * sizeof(double) +
      schur_single.capacity() * sizeof(float) +
      contact_dofs.capacity() * sizeof(types::global_dof_index);
    for (const Group &group : groups)
      bytes +=
        (group.schur.capacity() + group.inverse.capacity()) * sizeof(double) +
        group.schur_single.capacity() * sizeof(float) +
        group.index.capacity() * sizeof(unsigned int);
    return bytes;
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



  namespace
  {
    // A := Q A Q^T for the block-diagonal orthogonal Q of @p frames (the
    // identity off their DoFs), in A's own pattern. False if the rows of a
    // node's DoFs do not have the same columns (then A' would need entries
    // that A's pattern lacks).
    bool
    rotate_to_frames(
      SparseMatrix<double>                                &A,
      const std::vector<SparseSchurComplement::NodeFrame> &frames)
    {
      const std::size_t n = A.m();
      std::vector<int>  frame_of(n, -1);
      std::vector<int>  slot_of(n, 0);
      for (std::size_t f = 0; f < frames.size(); ++f)
        {
          if (frames[f].dofs.empty() || frames[f].dofs.size() > 3)
            return false;
          for (std::size_t p = 0; p < frames[f].dofs.size(); ++p)
            {
              const auto d = frames[f].dofs[p];
              if (d >= n || frame_of[d] != -1)
                return false;
              frame_of[d] = static_cast<int>(f);
              slot_of[d]  = static_cast<int>(p);
            }
        }

      // Rows: row k of a node becomes sum_p R[k][p] (row p).
      std::vector<int>                     position(n, -1);
      std::vector<types::global_dof_index> columns;
      std::array<std::vector<double>, 3>   values;
      for (const auto &frame : frames)
        {
          const std::size_t d = frame.dofs.size();
          columns.clear();
          for (auto it = A.begin(frame.dofs[0]); it != A.end(frame.dofs[0]);
               ++it)
            {
              position[it->column()] = static_cast<int>(columns.size());
              columns.push_back(it->column());
            }
          bool same = true;
          for (std::size_t p = 0; p < d; ++p)
            {
              values[p].assign(columns.size(), 0.);
              std::size_t count = 0;
              for (auto it = A.begin(frame.dofs[p]); it != A.end(frame.dofs[p]);
                   ++it, ++count)
                if (position[it->column()] < 0)
                  same = false;
                else
                  values[p][position[it->column()]] = it->value();
              same = same && count == columns.size();
            }
          for (std::size_t k = 0; k < d && same; ++k)
            for (auto it = A.begin(frame.dofs[k]); it != A.end(frame.dofs[k]);
                 ++it)
              {
                const int e   = position[it->column()];
                double    sum = 0.;
                for (std::size_t p = 0; p < d; ++p)
                  sum += frame.rotation[k][p] * values[p][e];
                it->value() = sum;
              }
          for (const auto c : columns)
            position[c] = -1;
          if (!same)
            return false;
        }

      // Columns: entry (i, node slot l) becomes sum_q (i, slot q) R[l][q].
      std::vector<int>                   group_of(frames.size(), -1);
      std::vector<std::array<double, 3>> group_values, group_rotated;
      std::vector<std::size_t>           group_frame, group_count;
      for (std::size_t i = 0; i < n; ++i)
        {
          group_frame.clear();
          group_count.clear();
          group_values.clear();
          for (auto it = A.begin(i); it != A.end(i); ++it)
            if (const int f = frame_of[it->column()]; f >= 0)
              {
                if (group_of[f] < 0)
                  {
                    group_of[f] = static_cast<int>(group_frame.size());
                    group_frame.push_back(f);
                    group_count.push_back(0);
                    group_values.push_back({{0., 0., 0.}});
                  }
                group_values[group_of[f]][slot_of[it->column()]] = it->value();
                ++group_count[group_of[f]];
              }
          bool complete = true;
          group_rotated.resize(group_frame.size());
          for (std::size_t g = 0; g < group_frame.size(); ++g)
            {
              const auto       &frame = frames[group_frame[g]];
              const std::size_t d     = frame.dofs.size();
              complete                = complete && group_count[g] == d;
              for (std::size_t l = 0; l < d; ++l)
                {
                  double sum = 0.;
                  for (std::size_t q = 0; q < d; ++q)
                    sum += group_values[g][q] * frame.rotation[l][q];
                  group_rotated[g][l] = sum;
                }
            }
          if (complete)
            for (auto it = A.begin(i); it != A.end(i); ++it)
              if (const int f = frame_of[it->column()]; f >= 0)
                it->value() = group_rotated[group_of[f]][slot_of[it->column()]];
          for (const auto f : group_frame)
            group_of[f] = -1;
          if (!complete)
            return false;
        }
      return true;
    }
  } // namespace



  SparseSchurComplement::NodeFrame
  SparseSchurComplement::NodeFrame::with_normal(
    const std::vector<types::global_dof_index> &dofs,
    const std::vector<double>                  &normal)
  {
    const std::size_t d      = dofs.size();
    double            length = 0.;
    for (const double n_p : normal)
      length += n_p * n_p;
    AssertThrow(d >= 1 && d <= 3 && normal.size() == d &&
                  std::abs(std::sqrt(length) - 1.) < 1e-12,
                ExcMessage("NodeFrame::with_normal(): " + std::to_string(d) +
                           " DoFs and " + std::to_string(normal.size()) +
                           " normal components of length " +
                           std::to_string(std::sqrt(length)) +
                           "; expected 1 to 3 DoFs and a unit normal"));
    NodeFrame frame;
    frame.dofs = dofs;
    auto &n    = frame.rotation[0];
    std::copy(normal.begin(), normal.end(), n.begin());
    if (d == 2)
      frame.rotation[1] = {{-n[1], n[0], 0.}};
    else if (d == 3)
      {
        std::size_t axis = 0;
        for (std::size_t p = 1; p < 3; ++p)
          if (std::abs(n[p]) < std::abs(n[axis]))
            axis = p;
        std::array<double, 3> t{{0., 0., 0.}};
        t[axis]     = 1.;
        double norm = 0.;
        for (std::size_t p = 0; p < 3; ++p)
          {
            t[p] -= n[axis] * n[p];
            norm += t[p] * t[p];
          }
        norm = std::sqrt(norm);
        for (double &t_p : t)
          t_p /= norm;
        frame.rotation[1] = t;
        frame.rotation[2] = {{n[1] * t[2] - n[2] * t[1],
                              n[2] * t[0] - n[0] * t[2],
                              n[0] * t[1] - n[1] * t[0]}};
      }
    return frame;
  }



  struct SparseSchurComplement::StateMatrix
  {
    SparsityPattern      pattern;
    SparseMatrix<double> rotated, matrix;
    SparseLU             factor{true};
    Vector<double>       solution;
  };



  SparseSchurComplement::SparseSchurComplement()  = default;
  SparseSchurComplement::~SparseSchurComplement() = default;
  SparseSchurComplement::SparseSchurComplement(
    SparseSchurComplement &&) noexcept = default;
  SparseSchurComplement &
  SparseSchurComplement::operator=(SparseSchurComplement &&) noexcept = default;



  bool
  SparseSchurComplement::initialize(
    const SparseMatrix<double>                 &matrix,
    const std::vector<types::global_dof_index> &dofs,
    const std::string                          &name,
    const std::vector<NodeFrame>               &frames,
    const bool                                  for_contact_states)
  {
    contact_dofs.clear();
    row_start.assign(1, 0);
    row_column.clear();
    row_value.clear();
    interior.reset();
    frame_dofs.clear();
    frame_size.clear();
    is_contact.clear();
    state_matrix.reset();
    state_code.clear();
    state_skew.clear();
    for_states = false;

    // only for the factorisation, which copies what it needs
    SparseMatrix<double> A(matrix.get_sparsity_pattern());
    A.copy_from(matrix);
    if (!frames.empty() && !rotate_to_frames(A, frames))
      return false;
    std::vector<types::global_dof_index> sorted(dofs);
    std::sort(sorted.begin(), sorted.end());
    sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
    if (for_contact_states && !frames.empty())
      {
        state_matrix = std::make_unique<StateMatrix>();
        state_matrix->pattern.copy_from(A.get_sparsity_pattern());
        state_matrix->rotated.reinit(state_matrix->pattern);
        state_matrix->rotated.copy_from(A);
      }
    for (const auto d : sorted)
      {
        for (auto it = A.begin(d); it != A.end(d); ++it)
          {
            row_column.push_back(it->column());
            row_value.push_back(it->value());
          }
        row_start.push_back(row_column.size());
      }
    // A_II: the rows and columns of C made those of the identity
    for (const auto d : sorted)
      make_identity_row_and_column(A, d);
    auto factor = std::make_unique<SparseCholesky>();
    // without the zeroed entries: the factor of A_II alone, not one with
    // the fill of all of A
    factor->factorize(A, name, true);
    interior = std::move(factor);

    if (state_matrix)
      {
        is_contact.assign(A.m(), 0); // set by set_contact_states()
        for (const auto &frame : frames)
          {
            const auto k =
              std::lower_bound(sorted.begin(), sorted.end(), frame.dofs[0]) -
              sorted.begin();
            AssertThrow(static_cast<std::size_t>(k) < sorted.size() &&
                          sorted[k] == frame.dofs[0],
                        ExcMessage("SparseSchurComplement: a frame's first "
                                   "DoF is not among the Schur complement's"));
            std::array<types::global_dof_index, 3> slots{{0, 0, 0}};
            std::copy(frame.dofs.begin(), frame.dofs.end(), slots.begin());
            frame_dofs.push_back(slots);
            frame_size.push_back(frame.dofs.size());
          }
        AssertThrow(frames.size() == sorted.size(),
                    ExcMessage("SparseSchurComplement: for contact states, "
                               "C must be the frames' normal slots"));
      }
    contact_dofs.swap(sorted);
    return true;
  }



  bool
  SparseSchurComplement::set_contact_states(
    const std::vector<unsigned char>         &states,
    const std::vector<std::array<double, 3>> &skew,
    const double                              skew_tolerance,
    const unsigned int                        max_stale_states)
  {
    if (states.empty())
      {
        for_states = false;
        return false;
      }
    AssertThrow(state_matrix && states.size() == frame_dofs.size() &&
                  skew.size() == frame_dofs.size(),
                ExcMessage("SparseSchurComplement::set_contact_states(): " +
                           std::to_string(states.size()) + " states for " +
                           std::to_string(frame_dofs.size()) +
                           " frames (initialize() with for_contact_states?)"));
    // The products keep the states they invert while at most
    // max_stale_states contacts differ from them (or their skews by more
    // than skew_tolerance).
    if (for_states)
      {
        unsigned int differing = 0;
        for (std::size_t f = 0;
             f < frame_dofs.size() && differing <= max_stale_states;
             ++f)
          {
            bool same = states[f] == state_code[f];
            for (unsigned int l = 1; l < frame_size[f] && same; ++l)
              same = std::abs(skew[f][l] - state_skew[f][l]) <= skew_tolerance;
            differing += same ? 0 : 1;
          }
        if (differing <= max_stale_states)
          return false;
      }
    for_states = false;
    state_code = states;
    state_skew = skew;
    // the unknowns C' of the states: closed normals, sticking tangents
    for (std::size_t f = 0; f < frame_dofs.size(); ++f)
      for (unsigned int l = 0; l < frame_size[f]; ++l)
        is_contact[frame_dofs[f][l]] =
          l == 0 ? states[f] != open_state : states[f] == stick_state;
    const SparseMatrix<double> &A = state_matrix->rotated;
    SparseMatrix<double>       &M = state_matrix->matrix;
    if (M.empty())
      M.reinit(state_matrix->pattern);
    M.copy_from(A);
    // C''s rows and columns: those of the identity
    for (std::size_t f = 0; f < frame_dofs.size(); ++f)
      for (unsigned int l = 0; l < frame_size[f]; ++l)
        if (is_contact[frame_dofs[f][l]])
          make_identity_row_and_column(M, frame_dofs[f][l]);
    // row T_l of a sliding node minus s_l times its row N, on the columns
    // off C'
    for (std::size_t f = 0; f < frame_dofs.size(); ++f)
      for (unsigned int l = 1; l < frame_size[f]; ++l)
        if (const double s_l = skew[f][l];
            s_l != 0. && states[f] == slide_state)
          for (auto it = A.begin(frame_dofs[f][0]);
               it != A.end(frame_dofs[f][0]);
               ++it)
            if (!is_contact[it->column()])
              M.add(frame_dofs[f][l], it->column(), -s_l * it->value());
    state_matrix->factor.factorize(
      M, "the step matrix at the contact states of an active set iteration");
    for_states = true;
    return true;
  }



  bool
  SparseSchurComplement::inverts_contact_states() const
  {
    return for_states;
  }



  const std::vector<unsigned char> &
  SparseSchurComplement::factored_states() const
  {
    return state_code;
  }



  const std::vector<types::global_dof_index> &
  SparseSchurComplement::dofs() const
  {
    return contact_dofs;
  }



  void
  SparseSchurComplement::vmult(const Vector<double> &y,
                               Vector<double>       &out,
                               Vector<double>       &work) const
  {
    apply(y, out, work, false);
  }



  void
  SparseSchurComplement::vmult_single_precision(const Vector<double> &y,
                                                Vector<double>       &out,
                                                Vector<double> &work) const
  {
    apply(y, out, work, true);
  }



  void
  SparseSchurComplement::apply(const Vector<double> &y,
                               Vector<double>       &out,
                               Vector<double>       &work,
                               const bool            single_precision) const
  {
    Assert(interior, ExcMessage("SparseSchurComplement: not initialized"));
    if (for_states)
      {
        // (A_RR - S A_NR) w = A_RC y - S A_NC y on R, then out_C = A_CC y -
        // A_CR w on C' (closed normals, sticking tangents): the multiplier
        // of the bordered system (class documentation); y is zero off C'
        const SparseMatrix<double> &A = state_matrix->rotated;
        A.vmult(out, y);
        work = out;
        for (std::size_t f = 0; f < frame_dofs.size(); ++f)
          {
            if (state_code[f] == slide_state)
              for (unsigned int l = 1; l < frame_size[f]; ++l)
                work(frame_dofs[f][l]) -=
                  state_skew[f][l] * out(frame_dofs[f][0]);
            for (unsigned int l = 0; l < frame_size[f]; ++l)
              if (is_contact[frame_dofs[f][l]])
                work(frame_dofs[f][l]) = 0.;
          }
        state_matrix->factor.solve(work, state_matrix->solution);
        A.vmult(work, state_matrix->solution);
        for (std::size_t f = 0; f < frame_dofs.size(); ++f)
          for (unsigned int l = 0; l < frame_size[f]; ++l)
            if (is_contact[frame_dofs[f][l]])
              out(frame_dofs[f][l]) -= work(frame_dofs[f][l]);
        return;
      }
    // A_IC y and A_CC y touch only the rows next to C, and A_CI u only the
    // rows of C: sparse products over C's rows (A is symmetric).
    out = 0.;
    for (std::size_t k = 0; k < contact_dofs.size(); ++k)
      if (const double y_d = y(contact_dofs[k]); y_d != 0.)
        for (std::size_t e = row_start[k]; e < row_start[k + 1]; ++e)
          out(row_column[e]) += row_value[e] * y_d;
    work = out;
    for (const auto d : contact_dofs)
      work(d) = 0.;
    if (single_precision)
      interior->solve_single_precision(work);
    else
      interior->solve(work);
    for (std::size_t k = 0; k < contact_dofs.size(); ++k)
      {
        double s = 0.;
        for (std::size_t e = row_start[k]; e < row_start[k + 1]; ++e)
          s += row_value[e] * work(row_column[e]);
        out(contact_dofs[k]) -= s;
      }
  }



  std::size_t
  SparseSchurComplement::n_factor_entries() const
  {
    return interior ? interior->n_factor_entries() : 0;
  }
} // namespace impactfe
