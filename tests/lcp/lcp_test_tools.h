// Helpers shared by the tests in tests/lcp: a portable RNG, complete
// enumeration of an LCP (independent of the solver: its own Gaussian
// elimination), and small printing helpers.
#ifndef impactfe_tests_lcp_test_tools_h
#define impactfe_tests_lcp_test_tools_h

#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/dense_matrix.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>
#include <vector>

namespace lcp_test
{
  using impactfe::lcp::DenseMatrix;

  /// xorshift64*: the same sequence on every platform.
  class Rng
  {
  public:
    explicit Rng(const std::uint64_t seed)
      : state(seed ? seed : 0x9E3779B97F4A7C15ull)
    {}

    /// Uniform in [0, 1) with 53 random bits.
    double
    uniform()
    {
      state ^= state >> 12;
      state ^= state << 25;
      state ^= state >> 27;
      const std::uint64_t r = state * 2685821657736338717ull;
      return static_cast<double>(r >> 11) * (1.0 / 9007199254740992.0);
    }

    /// Uniform in [a, b).
    double
    uniform(const double a, const double b)
    {
      return a + (b - a) * uniform();
    }

    /// Uniform integer in [0, m).
    unsigned int
    integer(const unsigned int m)
    {
      return static_cast<unsigned int>(uniform() * m) % m;
    }

  private:
    std::uint64_t state;
  };

  /// Solve A x = b by Gaussian elimination with partial pivoting.
  /// Returns false if a pivot is below tol * max|A|.
  inline bool
  gauss_solve(std::vector<std::vector<double>> A,
              std::vector<double>              b,
              std::vector<double>             &x,
              const double                     tol = 1e-12)
  {
    const std::size_t n    = b.size();
    double            amax = 0.;
    for (const auto &r : A)
      for (const double v : r)
        amax = std::max(amax, std::abs(v));
    for (std::size_t k = 0; k < n; ++k)
      {
        std::size_t p = k;
        for (std::size_t i = k + 1; i < n; ++i)
          if (std::abs(A[i][k]) > std::abs(A[p][k]))
            p = i;
        if (!(std::abs(A[p][k]) > tol * amax))
          return false;
        std::swap(A[p], A[k]);
        std::swap(b[p], b[k]);
        for (std::size_t i = k + 1; i < n; ++i)
          {
            const double f = A[i][k] / A[k][k];
            for (std::size_t j = k; j < n; ++j)
              A[i][j] -= f * A[k][j];
            b[i] -= f * b[k];
          }
      }
    x.assign(n, 0.);
    for (std::size_t i = n; i-- > 0;)
      {
        double s = b[i];
        for (std::size_t j = i + 1; j < n; ++j)
          s -= A[i][j] * x[j];
        x[i] = s / A[i][i];
      }
    return true;
  }

  /// All solutions z of LCP(q, M) found on nonsingular complementary bases
  /// (2^n linear solves), feasibility to the tolerance tol (relative).
  inline std::vector<std::vector<double>>
  enumerate(const DenseMatrix         &M,
            const std::vector<double> &q,
            const double               tol = 1e-10)
  {
    const std::size_t                n = q.size();
    std::vector<std::vector<double>> solutions;
    double                           scale = 1.;
    for (const double v : q)
      scale = std::max(scale, std::abs(v));
    for (unsigned long mask = 0; mask < (1ul << n); ++mask)
      {
        std::vector<std::size_t> act;
        for (std::size_t i = 0; i < n; ++i)
          if (mask & (1ul << i))
            act.push_back(i);
        std::vector<double> z(n, 0.);
        if (!act.empty())
          {
            std::vector<std::vector<double>> A(act.size(),
                                               std::vector<double>(act.size()));
            std::vector<double>              b(act.size()), x;
            for (std::size_t a = 0; a < act.size(); ++a)
              {
                for (std::size_t c = 0; c < act.size(); ++c)
                  A[a][c] = M(act[a], act[c]);
                b[a] = -q[act[a]];
              }
            if (!gauss_solve(A, b, x))
              continue;
            for (std::size_t a = 0; a < act.size(); ++a)
              z[act[a]] = x[a];
          }
        bool ok = true;
        for (std::size_t i = 0; i < n && ok; ++i)
          {
            double w = q[i];
            for (std::size_t j = 0; j < n; ++j)
              w += M(i, j) * z[j];
            ok = z[i] >= -tol * scale && w >= -tol * scale;
          }
        if (ok)
          solutions.push_back(z);
      }
    return solutions;
  }

  inline double
  max_diff(const std::vector<double> &a, const std::vector<double> &b)
  {
    if (a.size() != b.size())
      return 1e300;
    double m = 0.;
    for (std::size_t i = 0; i < a.size(); ++i)
      m = std::max(m, std::abs(a[i] - b[i]));
    return m;
  }

  inline double
  linfty(const std::vector<double> &a)
  {
    double m = 0.;
    for (const double v : a)
      m = std::max(m, std::abs(v));
    return m;
  }

  /// "a b c" with each value rounded to 6 significant digits.
  inline std::string
  str(const std::vector<double> &v)
  {
    std::ostringstream s;
    for (std::size_t i = 0; i < v.size(); ++i)
      {
        double r = v[i];
        if (std::abs(r) < 1e-10)
          r = 0.;
        else
          {
            const double sc = std::pow(
              10., 5 - static_cast<int>(std::floor(std::log10(std::abs(r)))));
            r = std::round(r * sc) / sc;
          }
        s << (i ? " " : "") << r;
      }
    return s.str();
  }

  inline DenseMatrix
  matrix(const std::vector<std::vector<double>> &rows)
  {
    DenseMatrix M(rows.size(), rows.empty() ? 0 : rows[0].size());
    for (std::size_t i = 0; i < rows.size(); ++i)
      for (std::size_t j = 0; j < rows[i].size(); ++j)
        M(i, j) = rows[i][j];
    return M;
  }
  /// W = B B^T + shift I: symmetric positive definite for any square B.
  inline DenseMatrix
  gram_plus_shift(const DenseMatrix &B, const double shift = 0.5)
  {
    const std::size_t m = B.n_rows();
    DenseMatrix       W(m, m);
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t j = 0; j < m; ++j)
        {
          double s = (i == j ? shift : 0.);
          for (std::size_t k = 0; k < B.n_cols(); ++k)
            s += B(i, k) * B(j, k);
          W(i, j) = s;
        }
    return W;
  }

  /// The contact problem of a body with generalized velocity @p v and
  /// diagonal mass matrix @p m_diag: W = G M^-1 G^T and V_free = G v, with
  /// one row of G per local direction (@p n_directions per contact).
  inline impactfe::lcp::ContactProblem
  condensed(const std::vector<std::vector<double>> &G,
            const std::vector<double>              &m_diag,
            const std::vector<double>              &v,
            const std::vector<double>              &mu,
            const unsigned int                      n_directions = 3)
  {
    impactfe::lcp::ContactProblem p;
    p.n_directions = n_directions;
    p.n_contacts   = G.size() / n_directions;
    p.W.reinit(G.size(), G.size());
    p.free_velocity.assign(G.size(), 0.);
    for (std::size_t i = 0; i < G.size(); ++i)
      {
        for (std::size_t j = 0; j < G.size(); ++j)
          for (std::size_t d = 0; d < m_diag.size(); ++d)
            p.W(i, j) += G[i][d] * G[j][d] / m_diag[d];
        for (std::size_t d = 0; d < v.size(); ++d)
          p.free_velocity[i] += G[i][d] * v[d];
      }
    p.gap_term.assign(p.n_contacts, 0.);
    p.mu = mu;
    return p;
  }

  /// max |a - b| over the impulse scale of verify_contact_solution():
  /// max(||b||, (||V_free|| + ||b_N||) / ||W||), so that answers that are
  /// both zero up to rounding compare equal.
  inline double
  relative_difference(const impactfe::lcp::ContactProblem &p,
                      const std::vector<double>           &a,
                      const std::vector<double>           &b)
  {
    const double scale =
      std::max(linfty(b),
               (linfty(p.free_velocity) + linfty(p.gap_term)) /
                 p.W.linfty_norm());
    return max_diff(a, b) / scale;
  }
} // namespace lcp_test

#endif
