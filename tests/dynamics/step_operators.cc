// The two kernels of a time step against independent computations:
// * FreeRhsOperator (F~ = (M + a_C C + a_K K) x + b_K K y + gamma f in one
//   pass) against deal.II's products, for the coefficients of all four
//   schemes, on bodies with and without damping;
// * F~ relative to the rigid translation (FreeRhsOperator::apply() and
//   add_translation()) on a body that slides at 1 m/s: the free velocity
//   equals the plain solve, and keeps the momentum, e_d^T M v = e_d^T (M x
//   + gamma f) (K e_d = 0), to round-off;
// * SparseCholesky::solve() against the residual of M~ x = b and against
//   CHOLMOD's own solve (the multi-column path), on a 1D bar and 2D and 3D
//   blocks, whose factors are simplicial or supernodal (both solved by our
//   substitutions; a supernodal factor's narrow supernodes by plain loops,
//   its wide ones, which the 3D block has, by BLAS);
// * SparseCholesky::solve_together() (two bidiagonal factors at a time)
//   against each factor's own solve, to the bit, and the residual.
#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/sparse_cholesky.h>
#include <impactfe/time_integration/free_rhs_operator.h>
#include <impactfe/time_integration/time_integrator.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../tests.h"

using namespace impactfe;

namespace
{
  template <int dim>
  std::unique_ptr<ElasticBody<dim>>
  make_body(const std::vector<unsigned int> &cells, const double viscosity)
  {
    MaterialParameters material;
    material.youngs_modulus = 2e11;
    material.density        = 7800.;
    material.poissons_ratio = 0.3;
    material.viscosity      = viscosity;
    auto       body         = std::make_unique<ElasticBody<dim>>("body",
                                                   material,
                                                   DiscretizationParameters(),
                                                   1.);
    Point<dim> corner;
    for (unsigned int d = 0; d < dim; ++d)
      corner[d] = 0.1 * cells[d];
    GridGenerator::subdivided_hyper_rectangle(body->triangulation(),
                                              cells,
                                              Point<dim>(),
                                              corner);
    body->setup();
    return body;
  }

  // Deterministic, not symmetric in the entries, O(1).
  void
  fill(Vector<double> &v, const double phase)
  {
    for (unsigned int i = 0; i < v.size(); ++i)
      v[i] = std::sin(0.7 * i + phase) + 0.3 * std::cos(1.3 * i * i + phase);
  }

  template <int dim>
  void
  check_free_rhs(const std::string               &name,
                 const std::vector<unsigned int> &cells,
                 const double                     viscosity)
  {
    const auto          body = make_body<dim>(cells, viscosity);
    const unsigned int  n    = body->n_dofs();
    MechanicalOperators op;
    op.mass.push_back(&body->mass_matrix());
    op.stiffness.push_back(&body->stiffness_matrix());
    op.damping.push_back(body->has_damping() ? &body->damping_matrix() :
                                               nullptr);
    op.external_force.reinit(std::vector<types::global_dof_index>{n});
    fill(op.external_force.block(0), 0.5);

    BlockVector<double> x(std::vector<types::global_dof_index>{n}), y(x),
      rhs(x);
    fill(x.block(0), 1.);
    fill(y.block(0), 2.);
    for (const Scheme scheme : {Scheme::theta,
                                Scheme::theta_euler,
                                Scheme::modified_theta,
                                Scheme::newmark})
      {
        TimeSteppingParameters ts;
        ts.scheme                            = scheme;
        ts.time_step                         = 1e-6;
        const auto                integrator = create_time_integrator(ts);
        const FreeRhsCoefficients c = integrator->free_rhs_coefficients();
        FreeRhsOperator           free_rhs;
        free_rhs.reinit(op, c);
        // the 1D bar's rows go by their diagonals, the others by entries
        impactfe_tests::check(free_rhs.tridiagonal(0) == (dim == 1),
                              name + ", " + to_string(scheme) +
                                ": rows by diagonals in 1D only",
                              "");
        FreeRhsOperator::Translations translation;
        free_rhs.apply(x, y, rhs, translation); // no components: t = 0

        // The same with deal.II's products, term by term.
        Vector<double> expected(n), tmp(n);
        body->mass_matrix().vmult(expected, x.block(0));
        body->stiffness_matrix().vmult(tmp, x.block(0));
        expected.add(c.velocity_stiffness, tmp);
        if (body->has_damping())
          {
            body->damping_matrix().vmult(tmp, x.block(0));
            expected.add(c.velocity_damping, tmp);
          }
        body->stiffness_matrix().vmult(tmp, y.block(0));
        expected.add(c.displacement_stiffness, tmp);
        expected.add(c.force, op.external_force.block(0));
        double scale = 0., diff = 0.;
        for (unsigned int i = 0; i < n; ++i)
          {
            scale = std::max(scale, std::abs(expected[i]));
            diff  = std::max(diff, std::abs(expected[i] - rhs.block(0)[i]));
          }
        impactfe_tests::check(diff <= 1e-13 * scale,
                              name + ", " + to_string(scheme) +
                                ": F~ equals deal.II's products",
                              "");
      }
  }

  // A block sliding at 1 m/s, displaced by 0.1 m, with a small vibration,
  // theta-Euler at a Courant number of about 500 (c_K K dominates M~).
  template <int dim>
  void
  check_translation(const std::string               &name,
                    const std::vector<unsigned int> &cells)
  {
    const auto          body = make_body<dim>(cells, 0.);
    const unsigned int  n    = body->n_dofs();
    MechanicalOperators op;
    op.mass.push_back(&body->mass_matrix());
    op.stiffness.push_back(&body->stiffness_matrix());
    op.damping.push_back(nullptr);
    op.external_force.reinit(std::vector<types::global_dof_index>{n});
    fill(op.external_force.block(0), 0.5);
    std::array<Vector<double>, dim> unit;
    op.dof_components.assign(1, std::vector<unsigned char>(n, 0));
    BlockVector<double> x(std::vector<types::global_dof_index>{n}), y(x),
      rhs(x);
    fill(x.block(0), 1.);
    fill(y.block(0), 2.);
    x.block(0) *= 1e-3;
    y.block(0) *= 1e-5;
    for (unsigned int d = 0; d < dim; ++d)
      {
        Tensor<1, dim> e;
        e[d] = 1.;
        unit[d].reinit(n);
        body->fill_uniform(unit[d], e);
        for (unsigned int i = 0; i < n; ++i)
          if (unit[d][i] != 0.)
            op.dof_components[0][i] = d;
        x.block(0).add(d == 0 ? 1. : 0.2, unit[d]);
        y.block(0).add(d == 0 ? 0.1 : -0.05, unit[d]);
      }

    TimeSteppingParameters ts;
    ts.scheme                            = Scheme::theta_euler;
    ts.time_step                         = 1e-2;
    const auto                integrator = create_time_integrator(ts);
    const FreeRhsCoefficients c          = integrator->free_rhs_coefficients();
    SparseMatrix<double>      step_matrix(body->sparsity_pattern());
    step_matrix.copy_from(body->mass_matrix());
    step_matrix.add(integrator->stiffness_coefficient(),
                    body->stiffness_matrix());
    SparseCholesky cholesky;
    cholesky.factorize(step_matrix, name);

    FreeRhsOperator free_rhs;
    free_rhs.reinit(op, c);
    FreeRhsOperator::Translations translation;
    free_rhs.apply(x, y, rhs, translation);
    Vector<double> v = rhs.block(0);
    cholesky.solve(v);
    BlockVector<double> completed(rhs);
    completed.block(0) = v;
    free_rhs.add_translation(translation, completed);

    // the plain solve, F~ by deal.II's products
    Vector<double> plain(n), tmp(n);
    body->mass_matrix().vmult(plain, x.block(0));
    body->stiffness_matrix().vmult(tmp, x.block(0));
    plain.add(c.velocity_stiffness, tmp);
    body->stiffness_matrix().vmult(tmp, y.block(0));
    plain.add(c.displacement_stiffness, tmp);
    plain.add(c.force, op.external_force.block(0));
    cholesky.solve(plain);
    tmp = completed.block(0);
    tmp -= plain;
    impactfe_tests::check(tmp.linfty_norm() <= 1e-8 * plain.linfty_norm(),
                          name + ": t + M~^{-1} F~(x - t, y - s) equals the "
                                 "plain solve to 1e-8",
                          "");

    double largest = 0.;
    for (unsigned int d = 0; d < dim; ++d)
      {
        Vector<double> m_unit(n);
        body->mass_matrix().vmult(m_unit, unit[d]);
        const double before = m_unit * x.block(0) +
                              c.force * (unit[d] * op.external_force.block(0));
        const double after = m_unit * completed.block(0);
        largest =
          std::max(largest, std::abs(after - before) / (m_unit * unit[d]));
      }
    impactfe_tests::check(largest <= 1e-13,
                          name + ": momentum of the free velocity, per unit "
                                 "mass, kept to 1e-13 m/s",
                          "");
  }

  template <int dim>
  void
  check_cholesky(const std::string               &name,
                 const std::vector<unsigned int> &cells,
                 const bool                       expect_simplicial)
  {
    const auto           body = make_body<dim>(cells, 0.);
    const unsigned int   n    = body->n_dofs();
    SparseMatrix<double> step_matrix(body->sparsity_pattern());
    step_matrix.copy_from(body->mass_matrix());
    step_matrix.add(1e-12, body->stiffness_matrix()); // h^2 theta^2, h ~ 1 us
    SparseCholesky cholesky;
    cholesky.factorize(step_matrix, name);
    impactfe_tests::check(cholesky.simplicial() == expect_simplicial,
                          name + ": the factor is " +
                            (expect_simplicial ? "simplicial" : "supernodal"),
                          "");

    Vector<double> b(n), x(n), residual(n);
    fill(b, 3.);
    x = b;
    cholesky.solve(x);
    step_matrix.vmult(residual, x);
    residual -= b;
    impactfe_tests::check(residual.linfty_norm() <= 1e-13 * b.linfty_norm(),
                          name + ": |M~ x - b| <= 1e-13 |b|",
                          "");

    // CHOLMOD's solve of the same right-hand side (two columns: b, 2b).
    std::vector<double> columns(2 * n);
    for (unsigned int i = 0; i < n; ++i)
      {
        columns[i]     = b[i];
        columns[n + i] = 2. * b[i];
      }
    cholesky.solve(columns.data(), 2);
    double diff = 0.;
    for (unsigned int i = 0; i < n; ++i)
      diff = std::max({diff,
                       std::abs(columns[i] - x[i]),
                       std::abs(columns[n + i] - 2. * x[i])});
    impactfe_tests::check(diff <= 1e-13 * x.linfty_norm(),
                          name + ": solve() equals CHOLMOD's solve",
                          "");
  }

  // The step matrix of a body, factorised.
  template <int dim>
  std::unique_ptr<SparseCholesky>
  step_factor(const ElasticBody<dim> &body, SparseMatrix<double> &matrix)
  {
    matrix.reinit(body.sparsity_pattern());
    matrix.copy_from(body.mass_matrix());
    matrix.add(1e-12, body.stiffness_matrix());
    auto cholesky = std::make_unique<SparseCholesky>();
    cholesky->factorize(matrix, "step matrix");
    return cholesky;
  }

  // SparseCholesky::solve_together() on four bodies: 1D bars of 320, 200
  // and 7 cells (bidiagonal factors: the first two are solved as a pair
  // with rows alternating, of different lengths, the third alone, being
  // the odd one) and a 2D block between them (simplicial, not a chain).
  // Each block must equal the body's own solve() to the bit, and solve
  // M~ x = b.
  void
  check_solve_together()
  {
    const auto                          bar_320   = make_body<1>({320}, 0.);
    const auto                          block_6x3 = make_body<2>({6, 3}, 0.);
    const auto                          bar_200   = make_body<1>({200}, 0.);
    const auto                          bar_7     = make_body<1>({7}, 0.);
    std::array<SparseMatrix<double>, 4> matrices;
    std::vector<std::unique_ptr<SparseCholesky>> factors;
    factors.push_back(step_factor(*bar_320, matrices[0]));
    factors.push_back(step_factor(*block_6x3, matrices[1]));
    factors.push_back(step_factor(*bar_200, matrices[2]));
    factors.push_back(step_factor(*bar_7, matrices[3]));
    const std::array<bool, 4> chain = {{true, false, true, true}};
    for (unsigned int b = 0; b < 4; ++b)
      impactfe_tests::check(factors[b]->bidiagonal() == chain[b],
                            "solve_together: factor " + std::to_string(b) +
                              (chain[b] ? " is" : " is not") + " bidiagonal",
                            "");
    std::vector<types::global_dof_index> sizes;
    for (const auto &factor : factors)
      sizes.push_back(factor->size());
    BlockVector<double> b(sizes), x(sizes);
    for (unsigned int k = 0; k < 4; ++k)
      fill(b.block(k), 1. + k);
    x = b;
    SparseCholesky::solve_together(factors, x);
    for (unsigned int k = 0; k < 4; ++k)
      {
        Vector<double> alone = b.block(k), residual(alone.size());
        factors[k]->solve(alone);
        alone -= x.block(k);
        impactfe_tests::check(alone.linfty_norm() == 0.,
                              "solve_together: block " + std::to_string(k) +
                                " equals its own solve to the bit",
                              "");
        matrices[k].vmult(residual, x.block(k));
        residual -= b.block(k);
        impactfe_tests::check(residual.linfty_norm() <=
                                1e-13 * b.block(k).linfty_norm(),
                              "solve_together: block " + std::to_string(k) +
                                ": |M~ x - b| <= 1e-13 |b|",
                              "");
      }
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  check_free_rhs<1>("1D bar, 320 cells", {320}, 0.);
  check_free_rhs<2>("2D block 6 x 3, damped", {6, 3}, 1e3);
  check_free_rhs<3>("3D bar 8 x 2 x 2, damped", {8, 2, 2}, 1e3);
  check_translation<1>("1D bar, 320 cells, sliding", {320});
  check_translation<2>("2D block 60 x 30, sliding", {60, 30});
  check_translation<3>("3D block 12 x 6 x 6, sliding", {12, 6, 6});
  check_cholesky<1>("1D bar, 320 cells", {320}, true);
  check_cholesky<2>("2D block 6 x 3", {6, 3}, true);
  check_cholesky<2>("2D block 60 x 60", {60, 60}, false);
  check_cholesky<3>("3D block 10 x 10 x 10", {10, 10, 10}, false);
  check_solve_together();
  return impactfe_tests::n_failed_checks;
}
