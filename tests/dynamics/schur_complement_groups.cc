// DenseSchurComplement of a matrix that holds several bodies: A is three
// disconnected 2D five-point operators (each with its own coefficients, a
// 6 x 6 grid, the unknowns of the three interleaved), C a scrambled choice
// of each body's unknowns. S keeps only the three diagonal blocks
// (n_groups() = 3), and its products equal independent computations:
// - S^{-1} y = (A^{-1} y)_C with y zero off C (a solve with a Cholesky
//   factorisation of the whole A);
// - S (S^{-1} y) = y;
// - S y in single precision within 1e-6 of S y;
// - the parts of add_part_of_product() for 1, 2, 3 and 5 parts sum to the
//   products (S^{-1} to 1e-14; S in single precision to 1e-6), with groups
//   and with one group;
// - fewer bytes than the two dense |C| x |C| matrices;
// and C from one body alone is one group.

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <impactfe/dynamics/schur_complement.h>
#include <impactfe/dynamics/sparse_cholesky.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;

namespace
{
  const unsigned int m = 6, n_bodies = 3;

  // grid point (i, j) of body b: the bodies' unknowns interleaved
  unsigned int
  index(const unsigned int b, const unsigned int i, const unsigned int j)
  {
    return (i + m * j) * n_bodies + b;
  }

  double
  largest_difference(const std::vector<double> &a, const std::vector<double> &b)
  {
    double d = 0.;
    for (unsigned int i = 0; i < a.size(); ++i)
      d = std::max(d, std::abs(a[i] - b[i]));
    return d;
  }

  double
  largest(const std::vector<double> &a)
  {
    double d = 0.;
    for (const double x : a)
      d = std::max(d, std::abs(x));
    return d;
  }

  // The parts of add_part_of_product() for 1, 2, 3 and 5 parts sum to
  // S^{-1} y (to 1e-14) and to S y (in single precision, to 1e-6).
  bool
  parts_sum_to_products(const DenseSchurComplement &schur)
  {
    const unsigned int  n_c = schur.size();
    std::vector<double> y(n_c), Sinv_y(n_c), S_y(n_c);
    for (unsigned int a = 0; a < n_c; ++a)
      y[a] = std::sin(1. + 3. * a);
    schur.vmult_inverse(y.data(), Sinv_y.data());
    schur.vmult(y.data(), S_y.data());
    bool parts_ok = true;
    for (const unsigned int n_parts : {1u, 2u, 3u, 5u})
      {
        std::vector<double> inverse_sum(n_c, 0.), schur_sum(n_c, 0.);
        for (unsigned int part = 0; part < n_parts; ++part)
          {
            schur.add_part_of_product(
              y.data(), inverse_sum.data(), part, n_parts, true);
            schur.add_part_of_product(
              y.data(), schur_sum.data(), part, n_parts, false);
          }
        parts_ok =
          parts_ok &&
          largest_difference(inverse_sum, Sinv_y) <= 1e-14 * largest(Sinv_y) &&
          largest_difference(schur_sum, S_y) <= 1e-6 * largest(S_y);
      }
    return parts_ok;
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  const unsigned int     n = n_bodies * m * m;
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int b = 0; b < n_bodies; ++b)
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int i = 0; i < m; ++i)
        {
          const unsigned int p = index(b, i, j);
          dsp.add(p, p);
          if (i + 1 < m)
            dsp.add(p, index(b, i + 1, j)), dsp.add(index(b, i + 1, j), p);
          if (j + 1 < m)
            dsp.add(p, index(b, i, j + 1)), dsp.add(index(b, i, j + 1), p);
        }
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> A(pattern);
  for (unsigned int p = 0; p < n; ++p)
    for (auto it = pattern.begin(p); it != pattern.end(p); ++it)
      {
        const unsigned int b = p % n_bodies;
        A.set(p,
              it->column(),
              it->column() == p ?
                4.2 + b + 0.01 * (p % 7) :
                -1. - 0.1 * b - 0.001 * ((p + it->column()) % 5));
      }

  // C: each body's row j = 0 and column i = m - 1, in a scrambled order
  std::vector<types::global_dof_index> contact_dofs;
  for (unsigned int k = 0; k < m; ++k)
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        contact_dofs.push_back(index(b, (5 * k + b) % m, 0));
        if (k > 0)
          contact_dofs.push_back(index((b + 1) % n_bodies, m - 1, k));
      }
  std::reverse(contact_dofs.begin() + 5, contact_dofs.end());

  DenseSchurComplement schur;
  schur.compute(A, contact_dofs, "the three bodies");
  check(schur.n_groups() == n_bodies,
        "three bodies: " + std::to_string(schur.n_groups()) + " groups");

  const auto         &C   = schur.dofs();
  const unsigned int  n_c = C.size();
  std::vector<double> y(n_c), Sinv_y(n_c), S_Sinv_y(n_c), S_y(n_c),
    S_y_single(n_c);
  for (unsigned int a = 0; a < n_c; ++a)
    y[a] = std::sin(1. + 3. * a);
  schur.vmult_inverse(y.data(), Sinv_y.data());

  SparseCholesky full;
  full.factorize(A, "A");
  Vector<double> x(n);
  for (unsigned int a = 0; a < n_c; ++a)
    x[C[a]] = y[a];
  full.solve(x);
  std::vector<double> expected(n_c);
  for (unsigned int a = 0; a < n_c; ++a)
    expected[a] = x[C[a]];
  check(largest_difference(Sinv_y, expected) <= 1e-13 * largest(expected),
        "S^{-1} y = (A^{-1} y)_C");

  schur.vmult(Sinv_y.data(), S_Sinv_y.data());
  check(largest_difference(S_Sinv_y, y) <= 1e-13 * largest(y),
        "S (S^{-1} y) = y");

  schur.vmult(y.data(), S_y.data());
  schur.vmult_single_precision(y.data(), S_y_single.data());
  check(largest_difference(S_y, S_y_single) <= 1e-6 * largest(S_y),
        "S y in single precision: within 1e-6 of S y");

  check(parts_sum_to_products(schur),
        "the parts of the products for 1, 2, 3, 5 parts sum to the products");

  check(schur.memory_consumption() <
          std::size_t(n_c) * n_c * (2 * sizeof(double) + sizeof(float)),
        "fewer bytes than the dense S, S^{-1} and single-precision S");

  // one body's unknowns: one group
  std::vector<types::global_dof_index> one_body;
  for (const auto d : contact_dofs)
    if (d % n_bodies == 1)
      one_body.push_back(d);
  DenseSchurComplement single;
  single.compute(A, one_body, "body 2");
  check(single.n_groups() == 1, "one body: one group");
  // one group: the parts are blocks of the lower triangle
  check(parts_sum_to_products(single),
        "one body: the parts of the products for 1, 2, 3, 5 parts sum to "
        "the products");
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
