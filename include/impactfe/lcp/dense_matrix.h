// A tiny row-major dense matrix for the LCP module (no deal.II dependency).
#ifndef impactfe_lcp_dense_matrix_h
#define impactfe_lcp_dense_matrix_h

#include <algorithm>
#include <cassert>
#include <cmath>
#include <cstddef>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /**
     * Row-major dense matrix of doubles: just what the LCP module needs.
     * Element (i,j) is stored at values[i*n_cols + j].
     */
    class DenseMatrix
    {
    public:
      DenseMatrix() = default;

      /// An n_rows x n_cols matrix filled with @p value.
      DenseMatrix(const std::size_t n_rows,
                  const std::size_t n_cols,
                  const double      value = 0.)
        : rows(n_rows)
        , cols(n_cols)
        , values(n_rows * n_cols, value)
      {}

      /// Resize to n_rows x n_cols and fill with @p value.
      void
      reinit(const std::size_t n_rows,
             const std::size_t n_cols,
             const double      value = 0.)
      {
        rows = n_rows;
        cols = n_cols;
        values.assign(n_rows * n_cols, value);
      }

      std::size_t
      n_rows() const
      {
        return rows;
      }

      std::size_t
      n_cols() const
      {
        return cols;
      }

      double &
      operator()(const std::size_t i, const std::size_t j)
      {
        assert(i < rows && j < cols);
        return values[i * cols + j];
      }

      double
      operator()(const std::size_t i, const std::size_t j) const
      {
        assert(i < rows && j < cols);
        return values[i * cols + j];
      }

      /// Pointer to the first element of row @p i.
      const double *
      row(const std::size_t i) const
      {
        return values.data() + i * cols;
      }

      double *
      row(const std::size_t i)
      {
        return values.data() + i * cols;
      }

      /// dst = A src (dst is resized).
      void
      vmult(std::vector<double> &dst, const std::vector<double> &src) const
      {
        assert(src.size() == cols);
        dst.assign(rows, 0.);
        for (std::size_t i = 0; i < rows; ++i)
          {
            const double *a = row(i);
            double        s = 0.;
            for (std::size_t j = 0; j < cols; ++j)
              s += a[j] * src[j];
            dst[i] = s;
          }
      }

      /// Infinity norm: the maximal absolute row sum.
      double
      linfty_norm() const
      {
        double m = 0.;
        for (std::size_t i = 0; i < rows; ++i)
          {
            double s = 0.;
            for (std::size_t j = 0; j < cols; ++j)
              s += std::abs(values[i * cols + j]);
            m = std::max(m, s);
          }
        return m;
      }

      /// The largest absolute entry.
      double
      max_abs() const
      {
        double m = 0.;
        for (const double v : values)
          m = std::max(m, std::abs(v));
        return m;
      }

      /// All entries, row by row.
      const std::vector<double> &
      data() const
      {
        return values;
      }

      /// Bytes of heap storage held (the capacity, not just the size).
      std::size_t
      memory_consumption() const
      {
        return values.capacity() * sizeof(double);
      }

    private:
      std::size_t         rows = 0;
      std::size_t         cols = 0;
      std::vector<double> values;
    };

    /** Bytes of heap storage held by a vector (its capacity). */
    template <typename T>
    std::size_t
    memory_consumption(const std::vector<T> &v)
    {
      return v.capacity() * sizeof(T);
    }

    /** max_i |v_i| (0 for an empty vector). */
    inline double
    linfty_norm(const std::vector<double> &v)
    {
      double m = 0.;
      for (const double x : v)
        m = std::max(m, std::abs(x));
      return m;
    }
  } // namespace lcp
} // namespace impactfe

#endif
