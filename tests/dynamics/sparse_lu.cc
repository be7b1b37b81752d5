// SparseLU (UMFPACK, the analysis kept per sparsity pattern, no iterative
// refinement) against solutions known in advance: a non-symmetric 5 x 5
// matrix stored with deal.II's diagonal-first rows, x chosen and b = A x;
// the same pattern with new values (the analysis reused); the transpose
// convention (A x = b, not A^T x = b: A is far from symmetric); a new
// pattern; and a singular matrix, which must throw a message naming it.

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <impactfe/dynamics/sparse_lu.h>

#include <string>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;

namespace
{
  // |x - A^{-1} A x| / |x| after one factorisation and solve.
  double
  solve_error(SparseLU &lu, const SparseMatrix<double> &A)
  {
    Vector<double> x(A.m()), b(A.m()), y;
    for (unsigned int i = 0; i < x.size(); ++i)
      x[i] = 1. + 0.5 * i - 0.1 * i * i;
    A.vmult(b, x);
    lu.factorize(A, "the test matrix");
    lu.solve(b, y);
    y -= x;
    return y.l2_norm() / x.l2_norm();
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  const unsigned int     n = 5;
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int i = 0; i < n; ++i)
    {
      dsp.add(i, i);
      dsp.add(i, (i + 1) % n);
      dsp.add(i, (i + 3) % n);
    }
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> A(pattern);
  for (unsigned int i = 0; i < n; ++i)
    {
      A.set(i, i, 4. + i);
      A.set(i, (i + 1) % n, 1. + 2. * i); // upper and lower entries differ
      A.set(i, (i + 3) % n, -0.5);
    }
  SparseLU lu;
  check(solve_error(lu, A) < 1e-14, "non-symmetric A: A^{-1} (A x) = x");
  for (unsigned int i = 0; i < n; ++i)
    A.set(i, (i + 1) % n, -3. + i);
  check(solve_error(lu, A) < 1e-14,
        "new values on the same pattern (analysis reused)");

  DynamicSparsityPattern dsp_2(n, n);
  for (unsigned int i = 0; i < n; ++i)
    {
      dsp_2.add(i, i);
      dsp_2.add(i, (i + 2) % n);
    }
  SparsityPattern pattern_2;
  pattern_2.copy_from(dsp_2);
  SparseMatrix<double> B(pattern_2);
  for (unsigned int i = 0; i < n; ++i)
    {
      B.set(i, i, 2.);
      B.set(i, (i + 2) % n, 0.3 * (i + 1));
    }
  check(solve_error(lu, B) < 1e-14, "a new pattern (analysed again)");

  SparseMatrix<double> singular(pattern_2);
  for (unsigned int i = 0; i < n; ++i)
    singular.set(i, (i + 2) % n, i == 2 ? 0. : 1.);
  try
    {
      lu.factorize(singular, "the singular matrix");
      check(false, "a singular matrix throws");
    }
  catch (const std::exception &e)
    {
      check(std::string(e.what()).find("the singular matrix") !=
              std::string::npos,
            "a singular matrix throws, naming it");
    }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
