#ifndef impactfe_utilities_column_sum_h
#define impactfe_utilities_column_sum_h

#include <cstddef>

namespace impactfe
{
  /**
   * y <- y + a[0] c[0] + ... + a[k-1] c[k-1] for k = n_columns <= 4
   * columns of length @p n, the terms added to each entry in this order:
   * the same operations, and so the same bits, as k single-column updates
   * y += a[j] c[j], but four columns take one pass over y instead of four
   * (the velocity update from stored columns M~^{-1} H_j, whose passes over
   * y were a fifth of a 2D step of 41 contacts, doc/performance.md).
   * @p y must not overlap any column (unlike Vector::add(a, V) with V = y).
   */
  void
  add_columns(double              *y,
              const std::size_t    n,
              const double        *a,
              const double *const *c,
              const unsigned int   n_columns);
} // namespace impactfe

#endif
