// Random P-matrix LCPs, n = 1..10, cross-checked against complete enumeration
// of the 2^n complementary bases (own Gaussian elimination, no solver code).
// A P-matrix LCP has exactly one solution for every q (Cottle-Pang-Stone 1992,
// Thm 3.3.7) and Lemke's method always finds it (ibid., Thm 4.4.12).
//
// Three kinds of P-matrices, fixed seed, portable RNG (lcp_test::Rng):
//  - positive definite, non-symmetric: B B'/n + (S - S') + 0.1 I,
//  - lower triangular with positive diagonal (P, not positive definite),
//  - D1 (B B'/n + 0.1 I) D2 with positive diagonal D1, D2 spanning 1e-3..1e3
//    (P, badly scaled).
// Warm starts from three guesses must give the same z: the exact active set
// (no pivot at all), a random guess and the complement of the exact one.
#include <impactfe/lcp/lemke.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

namespace
{
  DenseMatrix
  random_pmatrix(lcp_test::Rng     &rng,
                 const unsigned int n,
                 const unsigned int kind)
  {
    DenseMatrix M(n, n, 0.);
    if (kind == 1)
      {
        for (unsigned int i = 0; i < n; ++i)
          {
            M(i, i) = rng.uniform(0.5, 2.);
            for (unsigned int j = 0; j < i; ++j)
              M(i, j) = rng.uniform(-3., 3.);
          }
        return M;
      }
    DenseMatrix B(n, n), S(n, n);
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        {
          B(i, j) = rng.uniform(-1., 1.);
          S(i, j) = rng.uniform(-1., 1.);
        }
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = 0; j < n; ++j)
        {
          double s = 0.;
          for (unsigned int k = 0; k < n; ++k)
            s += B(i, k) * B(j, k);
          M(i, j) =
            s / n + (i == j ? 0.1 : 0.) + (kind == 0 ? S(i, j) - S(j, i) : 0.);
        }
    if (kind == 2)
      {
        std::vector<double> d1(n), d2(n);
        for (unsigned int i = 0; i < n; ++i)
          {
            d1[i] = std::pow(10., rng.uniform(-3., 3.));
            d2[i] = std::pow(10., rng.uniform(-3., 3.));
          }
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            M(i, j) *= d1[i] * d2[j];
      }
    return M;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng rng(20240601);

  const char *kinds[] = {"positive definite", "triangular", "scaled"};
  for (unsigned int n = 1; n <= 10; ++n)
    for (unsigned int kind = 0; kind < 3; ++kind)
      {
        unsigned int n_problems = 0, n_unique = 0, n_cold = 0,
                     n_exact_guess = 0, n_random_guess = 0,
                     n_complement_guess = 0;
        for (unsigned int instance = 0; instance < 8; ++instance)
          {
            const DenseMatrix   M = random_pmatrix(rng, n, kind);
            std::vector<double> q(n);
            for (auto &v : q)
              v = rng.uniform(-1., 1.);
            ++n_problems;

            const auto solutions = lcp_test::enumerate(M, q);
            if (solutions.size() != 1)
              continue;
            ++n_unique;
            const std::vector<double> &z = solutions[0];
            const double tol = 1e-8 * std::max(1., lcp_test::linfty(z));

            const Result cold = solve_lemke(M, q);
            if (cold.status == Status::solved && cold.verification.ok &&
                lcp_test::max_diff(cold.z, z) < tol)
              ++n_cold;

            std::vector<bool> exact(n), random(n), complement(n);
            for (unsigned int i = 0; i < n; ++i)
              {
                exact[i]      = z[i] > 0.;
                complement[i] = !exact[i];
                random[i]     = rng.uniform() < 0.5;
              }
            const Result w1 = solve_lemke_warm(M, q, exact);
            if (w1.status == Status::solved &&
                lcp_test::max_diff(w1.z, z) < tol &&
                (w1.pivots == 0 || cold.pivots == 0))
              ++n_exact_guess;
            const Result w2 = solve_lemke_warm(M, q, random);
            if (w2.status == Status::solved && w2.verification.ok &&
                lcp_test::max_diff(w2.z, z) < tol)
              ++n_random_guess;
            const Result w3 = solve_lemke_warm(M, q, complement);
            if (w3.status == Status::solved && w3.verification.ok &&
                lcp_test::max_diff(w3.z, z) < tol)
              ++n_complement_guess;
          }
        const std::string name = "n=" + std::to_string(n) + " " + kinds[kind];
        dealii::deallog << name << ": " << n_problems << " problems, "
                        << n_unique
                        << " with one solution by enumeration; Lemke agrees on "
                        << n_cold
                        << "; warm (exact/random/complement guess) on "
                        << n_exact_guess << "/" << n_random_guess << "/"
                        << n_complement_guess << std::endl;
        impactfe_tests::check(n_unique == n_problems && n_cold == n_problems &&
                                n_exact_guess == n_problems &&
                                n_random_guess == n_problems &&
                                n_complement_guess == n_problems,
                              name);
      }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
