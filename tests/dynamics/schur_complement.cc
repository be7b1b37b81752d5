// DenseSchurComplement: S = A_CC - A_CI A_II^{-1} A_IC and S^{-1} of a
// sparse symmetric positive definite A (a 7-point operator plus a mass-like
// shift on a 10 x 10 x 10 grid, big enough for CHOLMOD's supernodes), on C =
// the bottom face given in a scrambled order, against independent
// computations:
// - S^{-1} y = (A^{-1} y)_C with y zero off C, by a solve with an ordinary
//   Cholesky factorisation of A;
// - S y from its definition, with A_II^{-1} by a solve with A whose rows and
//   columns of C are the identity's;
// - S S^{-1} y = y;
// - A_II^{-1} by a factorisation that leaves the zeroed entries out of its
//   pattern equals the one that keeps them, with fewer factor entries;
// and the unknowns returned are C, a repeated unknown is refused with a
// message naming the matrix and leaves the object as it was, every unknown
// trailing gives S = A, and none an empty complement.

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
  const unsigned int m = 10; // grid points per direction

  unsigned int
  index(const unsigned int i, const unsigned int j, const unsigned int k)
  {
    return i + m * (j + m * k);
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  const unsigned int     n = m * m * m;
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int k = 0; k < m; ++k)
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int i = 0; i < m; ++i)
        {
          const unsigned int p = index(i, j, k);
          dsp.add(p, p);
          if (i + 1 < m)
            dsp.add(p, index(i + 1, j, k)), dsp.add(index(i + 1, j, k), p);
          if (j + 1 < m)
            dsp.add(p, index(i, j + 1, k)), dsp.add(index(i, j + 1, k), p);
          if (k + 1 < m)
            dsp.add(p, index(i, j, k + 1)), dsp.add(index(i, j, k + 1), p);
        }
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> A(pattern);
  for (unsigned int p = 0; p < n; ++p)
    for (auto it = pattern.begin(p); it != pattern.end(p); ++it)
      A.set(p,
            it->column(),
            it->column() == p ? 6.1 + 0.01 * (p % 7) :
                                -1. - 0.001 * ((p + it->column()) % 5));

  // C: the face k = 0, scrambled.
  std::vector<types::global_dof_index> contact_dofs;
  for (unsigned int j = 0; j < m; ++j)
    for (unsigned int i = 0; i < m; ++i)
      contact_dofs.push_back(index((3 * i + j) % m, j, 0));
  std::reverse(contact_dofs.begin() + 10, contact_dofs.end());

  DenseSchurComplement schur;
  schur.compute(A, contact_dofs, "the test matrix");
  std::vector<types::global_dof_index> sorted_in(contact_dofs),
    sorted_out(schur.dofs());
  std::sort(sorted_in.begin(), sorted_in.end());
  std::sort(sorted_out.begin(), sorted_out.end());
  check(sorted_in == sorted_out && schur.size() == m * m,
        "dofs() are the given unknowns");

  const auto         &C   = schur.dofs();
  const unsigned int  n_c = C.size();
  std::vector<double> y(n_c), Sinv_y(n_c), S_y(n_c), back(n_c);
  for (unsigned int a = 0; a < n_c; ++a)
    y[a] = std::sin(1. + 3. * a);
  schur.vmult_inverse(y.data(), Sinv_y.data());
  schur.vmult(y.data(), S_y.data());

  // (A^{-1} y)_C
  SparseCholesky full;
  full.factorize(A, "A");
  Vector<double> x(n);
  for (unsigned int a = 0; a < n_c; ++a)
    x[C[a]] = y[a];
  full.solve(x);
  double error = 0., scale = 0.;
  for (unsigned int a = 0; a < n_c; ++a)
    {
      error = std::max(error, std::abs(Sinv_y[a] - x[C[a]]));
      scale = std::max(scale, std::abs(x[C[a]]));
    }
  check(error <= 1e-13 * scale, "S^{-1} y = (A^{-1} y)_C");

  // S y = A_CC y - A_CI A_II^{-1} A_IC y
  SparseMatrix<double> interior(pattern);
  interior.copy_from(A);
  std::vector<bool> in_c(n, false);
  for (const auto d : C)
    in_c[d] = true;
  for (unsigned int p = 0; p < n; ++p)
    for (auto it = interior.begin(p); it != interior.end(p); ++it)
      if (in_c[p] || in_c[it->column()])
        it->value() = it->column() == p ? 1. : 0.;
  SparseCholesky interior_factor;
  interior_factor.factorize(interior, "A with C made identity");
  Vector<double> y_full(n), t(n), u(n);
  for (unsigned int a = 0; a < n_c; ++a)
    y_full[C[a]] = y[a];
  A.vmult(t, y_full);
  u = t;
  for (const auto d : C)
    u[d] = 0.;
  interior_factor.solve(u);
  Vector<double> Au(n);
  A.vmult(Au, u);
  error = scale = 0.;
  for (unsigned int a = 0; a < n_c; ++a)
    {
      const double expected = t[C[a]] - Au[C[a]];
      error                 = std::max(error, std::abs(S_y[a] - expected));
      scale                 = std::max(scale, std::abs(expected));
    }
  check(error <= 1e-13 * scale, "S y = A_CC y - A_CI A_II^{-1} A_IC y");

  // The same interior factor without the zeroed entries in its pattern (the
  // active set method's preconditioner): the same solves, less fill.
  SparseCholesky interior_without_zeros;
  interior_without_zeros.factorize(interior, "A_II alone", true);
  Vector<double> u_dropped(t);
  for (const auto d : C)
    u_dropped[d] = 0.;
  interior_without_zeros.solve(u_dropped);
  double drop_error = 0., drop_scale = 0.;
  for (unsigned int p = 0; p < n; ++p)
    {
      drop_error = std::max(drop_error, std::abs(u_dropped[p] - u[p]));
      drop_scale = std::max(drop_scale, std::abs(u[p]));
    }
  check(drop_error <= 1e-13 * drop_scale &&
          interior_without_zeros.n_factor_entries() <
            interior_factor.n_factor_entries(),
        "zeros left out of the pattern: the same A_II^{-1}, fewer entries");

  schur.vmult(Sinv_y.data(), back.data());
  error = 0.;
  for (unsigned int a = 0; a < n_c; ++a)
    error = std::max(error, std::abs(back[a] - y[a]));
  check(error <= 1e-13, "S (S^{-1} y) = y");

  // single precision: S and y rounded to float, 1e-7 of the product's size
  std::vector<double> S_y_single(n_c);
  schur.vmult_single_precision(y.data(), S_y_single.data());
  error = 0.;
  for (unsigned int a = 0; a < n_c; ++a)
    error = std::max(error, std::abs(S_y_single[a] - S_y[a]));
  check(error <= 1e-6 * scale && error > 0.,
        "S y in single precision: within 1e-6 of S y, and not equal");

  check(DenseSchurComplement::pays_off(3267, 60000000) &&
          !DenseSchurComplement::pays_off(3267, 1000000) &&
          !DenseSchurComplement::pays_off(20000, 1000000000),
        "pays_off: 3D cube yes, 2D-like fill no, two matrices of 2.9 GiB "
        "no");

  try
    {
      std::vector<types::global_dof_index> repeated{3, 7, 3};
      schur.compute(A, repeated, "the test matrix");
      check(false, "a repeated unknown throws");
    }
  catch (const std::exception &e)
    {
      check(std::string(e.what()).find("the test matrix") != std::string::npos,
            "a repeated unknown throws, naming the matrix");
    }
  schur.vmult(Sinv_y.data(), back.data());
  error = 0.;
  for (unsigned int a = 0; a < n_c; ++a)
    error = std::max(error, std::abs(back[a] - y[a]));
  check(schur.size() == n_c && error <= 1e-13,
        "a failed compute() leaves S and S^{-1} as they were");

  // Every unknown trailing: S = A, S^{-1} = A^{-1}.
  {
    const unsigned int                   n_small = 8;
    DynamicSparsityPattern               dsp_small(n_small, n_small);
    std::vector<types::global_dof_index> all;
    for (unsigned int i = 0; i < n_small; ++i)
      {
        dsp_small.add(i, i);
        if (i + 1 < n_small)
          dsp_small.add(i, i + 1), dsp_small.add(i + 1, i);
        all.push_back(n_small - 1 - i);
      }
    SparsityPattern small_pattern;
    small_pattern.copy_from(dsp_small);
    SparseMatrix<double> B(small_pattern);
    for (unsigned int i = 0; i < n_small; ++i)
      for (auto it = small_pattern.begin(i); it != small_pattern.end(i); ++it)
        B.set(i, it->column(), it->column() == i ? 3. : -1.);
    DenseSchurComplement whole;
    whole.compute(B, all, "B");
    std::vector<double> e(n_small, 0.), Be(n_small);
    e[2] = 1.;
    whole.vmult(e.data(), Be.data());
    double b_error = 0.;
    for (unsigned int a = 0; a < n_small; ++a)
      b_error =
        std::max(b_error,
                 std::abs(Be[a] - B.el(whole.dofs()[a], whole.dofs()[2])));
    check(b_error <= 1e-14, "every unknown trailing: S = A");
    DenseSchurComplement none;
    none.compute(B, {}, "B");
    check(none.size() == 0 && none.memory_consumption() < 1000,
          "no unknown: an empty complement");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
