#include <impactfe/utilities/column_sum.h>
#include <impactfe/utilities/vectorized_kernel.h>

#include <stdexcept>

namespace impactfe
{
  namespace
  {
    IMPACTFE_VECTORIZED_KERNEL void
    add_four_columns(double *__restrict y,
                     const std::size_t    n,
                     const double        *a,
                     const double *const *c)
    {
      const double a0 = a[0], a1 = a[1], a2 = a[2], a3 = a[3];
      const double *__restrict c0 = c[0];
      const double *__restrict c1 = c[1];
      const double *__restrict c2 = c[2];
      const double *__restrict c3 = c[3];
      for (std::size_t i = 0; i < n; ++i)
        {
          double t = y[i];
          t += a0 * c0[i];
          t += a1 * c1[i];
          t += a2 * c2[i];
          t += a3 * c3[i];
          y[i] = t;
        }
    }



    IMPACTFE_VECTORIZED_KERNEL void
    add_column(double *__restrict y,
               const std::size_t n,
               const double      a,
               const double *__restrict c)
    {
      for (std::size_t i = 0; i < n; ++i)
        y[i] += a * c[i];
    }
  } // namespace



  void
  add_columns(double              *y,
              const std::size_t    n,
              const double        *a,
              const double *const *c,
              const unsigned int   n_columns)
  {
    if (n_columns > 4)
      throw std::invalid_argument("add_columns(): at most four columns");
    if (n_columns == 4)
      add_four_columns(y, n, a, c);
    else
      for (unsigned int k = 0; k < n_columns; ++k)
        add_column(y, n, a[k], c[k]);
  }
} // namespace impactfe
