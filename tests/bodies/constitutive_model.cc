// The material interface: the Kelvin-Voigt law through evaluate() against
// Lame's formulas written out here, its tangents against central
// differences, the quadrature-point storage of the internal variables, and
// the damping matrix that ElasticBody assembles from viscosity_tensor()
// against (eta/E) K + a M + b K formed from the assembled K and M.

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/constitutive_model.h>
#include <impactfe/bodies/elastic_body.h>

#include <cmath>
#include <random>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;

namespace
{
  template <int dim>
  Tensor<2, dim>
  random_tensor(std::mt19937 &rng, const double scale)
  {
    std::uniform_real_distribution<double> u(-scale, scale);
    Tensor<2, dim>                         t;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        t[i][j] = u(rng);
    return t;
  }

  // sigma = lambda tr(eps) I + 2 mu eps (3D, plane strain) for a strain
  // eps, written without the library's elasticity tensor.
  template <int dim>
  Tensor<2, dim>
  lame_stress(const double E, const double nu, const Tensor<2, dim> &grad)
  {
    const double   lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    const double   mu     = E / (2. * (1. + nu));
    Tensor<2, dim> eps    = 0.5 * (grad + transpose(grad));
    return lambda * trace(eps) * Tensor<2, dim>(unit_symmetric_tensor<dim>()) +
           2. * mu * eps;
  }

  template <int dim>
  void
  check_law()
  {
    MaterialParameters material;
    material.youngs_modulus = 2e11;
    material.poissons_ratio = 0.3;
    material.viscosity      = 4e5;
    material.plane_model    = PlaneModel::plane_strain;
    const auto   model      = create_constitutive_model<dim>(material);
    std::mt19937 rng(42);

    double stress_error = 0., tangent_error = 0., viscous_error = 0.;
    for (unsigned int sample = 0; sample < 20; ++sample)
      {
        MaterialPointKinematics<dim> kin;
        const Tensor<2, dim>         grad_u = random_tensor<dim>(rng, 1e-3);
        const Tensor<2, dim>         grad_v = random_tensor<dim>(rng, 1.);
        kin.deformation_gradient += grad_u;
        kin.deformation_gradient_rate = grad_v;
        std::vector<double>        old_internal, new_internal;
        MaterialPointResponse<dim> r;
        model->evaluate(kin, old_internal, new_internal, r);
        const Tensor<2, dim> exact =
          lame_stress<dim>(material.youngs_modulus, 0.3, grad_u) +
          (material.viscosity / material.youngs_modulus) *
            lame_stress<dim>(material.youngs_modulus, 0.3, grad_v);
        stress_error =
          std::max(stress_error, (r.stress - exact).norm() / exact.norm());

        // Central differences of P in F and in dF/dt, entry by entry.
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            for (const bool rate : {false, true})
              {
                const double                 delta = rate ? 1e-3 : 1e-7;
                MaterialPointKinematics<dim> plus = kin, minus = kin;
                auto &p = rate ? plus.deformation_gradient_rate :
                                 plus.deformation_gradient;
                auto &m = rate ? minus.deformation_gradient_rate :
                                 minus.deformation_gradient;
                p[k][l] += delta;
                m[k][l] -= delta;
                MaterialPointResponse<dim> rp, rm;
                model->evaluate(plus, old_internal, new_internal, rp);
                model->evaluate(minus, old_internal, new_internal, rm);
                const Tensor<2, dim> fd =
                  (rp.stress - rm.stress) / (2. * delta);
                Tensor<2, dim> analytic;
                for (unsigned int i = 0; i < dim; ++i)
                  for (unsigned int j = 0; j < dim; ++j)
                    analytic[i][j] = rate ? r.viscous_tangent[i][j][k][l] :
                                            r.tangent[i][j][k][l];
                const double scale =
                  rate ? material.viscosity : material.youngs_modulus;
                double &error = rate ? viscous_error : tangent_error;
                error         = std::max(error, (fd - analytic).norm() / scale);
              }
      }
    deallog << dim << "D " << model->name()
            << ", linear: " << model->is_linear()
            << ", internal variables: " << model->n_internal_variables()
            << std::endl;
    // The law sees F = I + Grad u: F - I has an absolute rounding error of
    // eps = 2e-16 on entries of size 1e-3, so P is exact to about
    // eps / 1e-3 = 2e-13 relative, times a few for the sums.
    impactfe_tests::check(stress_error < 1e-11,
                          "P = C:eps(u) + (eta/E) C:eps(v) (Lame)",
                          std::to_string(stress_error));
    impactfe_tests::check(tangent_error < 1e-6, "dP/dF = central differences");
    impactfe_tests::check(viscous_error < 1e-6,
                          "dP/d(dF/dt) = central differences");
  }

  template <int dim>
  void
  check_body()
  {
    MaterialParameters material;
    material.youngs_modulus     = 1e7;
    material.density            = 1e3;
    material.poissons_ratio     = 0.25;
    material.viscosity          = 2e3;
    material.rayleigh_mass      = 3.;
    material.rayleigh_stiffness = 1e-4;
    ElasticBody<dim> body("block", material, DiscretizationParameters());
    GridGenerator::subdivided_hyper_cube(body.triangulation(), 3);
    body.setup();

    // C against (eta/E + b) K + a M, entry by entry.
    const double factor = material.viscosity / material.youngs_modulus +
                          material.rayleigh_stiffness;
    double difference = 0., size = 0.;
    for (unsigned int i = 0; i < body.n_dofs(); ++i)
      for (auto e = body.damping_matrix().begin(i);
           e != body.damping_matrix().end(i);
           ++e)
        {
          const double expected =
            factor * body.stiffness_matrix().el(i, e->column()) +
            material.rayleigh_mass * body.mass_matrix().el(i, e->column());
          difference = std::max(difference, std::abs(e->value() - expected));
          size       = std::max(size, std::abs(expected));
        }
    deallog << dim << "D body: " << body.triangulation().n_active_cells()
            << " cells, law " << body.constitutive_model().name() << std::endl;
    impactfe_tests::check(difference <= 1e-14 * size,
                          "C = (eta/E) K + a M + b K");

    unsigned int points = 0, variables = 0;
    for (const auto &cell : body.triangulation().active_cell_iterators())
      for (const auto &point : body.material_point_history(cell))
        {
          ++points;
          variables += point->old_values.size() + point->new_values.size();
        }
    deallog << "quadrature points with history: " << points
            << ", internal variables stored: " << variables << std::endl;
    impactfe_tests::check(points == body.triangulation().n_active_cells() *
                                      std::pow(2, dim),
                          "one history per quadrature point");
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  check_law<2>();
  check_law<3>();
  check_body<2>();
  check_body<3>();
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
