#include <deal.II/base/exceptions.h>

#include <impactfe/dynamics/sparse_lu.h>

#include <umfpack.h>

#include <algorithm>
#include <numeric>

namespace impactfe
{
  SparseLU::~SparseLU()
  {
    free_numeric();
    free_symbolic();
  }



  void
  SparseLU::free_numeric()
  {
    if (numeric != nullptr)
      umfpack_dl_free_numeric(&numeric);
    numeric = nullptr;
  }



  SparseLU::SparseLU(const bool symmetric_pattern)
    : symmetric_pattern(symmetric_pattern)
  {}



  void
  SparseLU::free_symbolic()
  {
    if (symbolic != nullptr)
      umfpack_dl_free_symbolic(&symbolic);
    symbolic = nullptr;
  }



  void
  SparseLU::factorize(const SparseMatrix<double> &matrix,
                      const std::string          &name)
  {
    const SparsityPattern &pattern = matrix.get_sparsity_pattern();
    const auto             n       = static_cast<std::int64_t>(matrix.m());
    if (&pattern != analysed_pattern ||
        column_starts.size() != static_cast<std::size_t>(n + 1) ||
        destination.size() != pattern.n_nonzero_elements())
      {
        // deal.II stores rows with the diagonal first; UMFPACK wants sorted
        // indices. Row i of A is column i of A^T: factorise A^T, solve
        // with UMFPACK_At.
        free_numeric();
        free_symbolic();
        analysed_pattern = nullptr; // until the analysis has succeeded
        column_starts.assign(n + 1, 0);
        row_indices.clear();
        destination.assign(pattern.n_nonzero_elements(), 0);
        std::vector<std::pair<std::int64_t, std::size_t>> row;
        for (std::int64_t i = 0; i < n; ++i)
          {
            row.clear();
            for (auto entry = pattern.begin(i); entry != pattern.end(i);
                 ++entry)
              row.emplace_back(entry->column(), entry->global_index());
            std::sort(row.begin(), row.end());
            for (const auto &[column, index] : row)
              {
                destination[index] = row_indices.size();
                row_indices.push_back(column);
              }
            column_starts[i + 1] = row_indices.size();
          }
        values.resize(row_indices.size());
        control.resize(UMFPACK_CONTROL);
        umfpack_dl_defaults(control.data());
        control[UMFPACK_IRSTEP] = 0;
        if (symmetric_pattern)
          {
            control[UMFPACK_STRATEGY] = UMFPACK_STRATEGY_SYMMETRIC;
            control[UMFPACK_ORDERING] = UMFPACK_ORDERING_METIS;
          }
        const auto analyse = [&]() {
          return umfpack_dl_symbolic(n,
                                     n,
                                     column_starts.data(),
                                     row_indices.data(),
                                     nullptr,
                                     &symbolic,
                                     control.data(),
                                     nullptr);
        };
        int status = analyse();
        if (status != UMFPACK_OK &&
            control[UMFPACK_ORDERING] != UMFPACK_ORDERING_AMD)
          {
            // an UMFPACK built without METIS
            free_symbolic();
            control[UMFPACK_ORDERING] = UMFPACK_ORDERING_AMD;
            status                    = analyse();
          }
        AssertThrow(status == UMFPACK_OK,
                    ExcMessage("SparseLU: the analysis of " + name +
                               " failed (UMFPACK status " +
                               std::to_string(status) + ")."));
        analysed_pattern = &pattern;
      }
    // The matrix's entries come in the pattern's storage order.
    std::size_t k = 0;
    for (std::int64_t i = 0; i < n; ++i)
      for (auto entry = matrix.begin(i); entry != matrix.end(i); ++entry)
        values[destination[k++]] = entry->value();
    free_numeric();
    const int status = umfpack_dl_numeric(column_starts.data(),
                                          row_indices.data(),
                                          values.data(),
                                          symbolic,
                                          &numeric,
                                          control.data(),
                                          nullptr);
    AssertThrow(status == UMFPACK_OK,
                ExcMessage("SparseLU: the factorisation of " + name +
                           " failed (UMFPACK status " + std::to_string(status) +
                           (status == UMFPACK_WARNING_singular_matrix ?
                              ": singular matrix" :
                              "") +
                           ")."));
  }



  void
  SparseLU::solve(const Vector<double> &b, Vector<double> &x) const
  {
    Assert(numeric != nullptr, ExcMessage("SparseLU: factorize() first."));
    x.reinit(b.size(), /*omit_zeroing_entries=*/true);
    const int status = umfpack_dl_solve(UMFPACK_At,
                                        column_starts.data(),
                                        row_indices.data(),
                                        values.data(),
                                        x.begin(),
                                        b.begin(),
                                        numeric,
                                        control.data(),
                                        nullptr);
    AssertThrow(status == UMFPACK_OK,
                ExcMessage("SparseLU: a solve failed (UMFPACK status " +
                           std::to_string(status) + ")."));
  }
} // namespace impactfe
