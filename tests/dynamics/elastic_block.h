// The elastic block of the tests in tests/dynamics: plane strain, 0.6 m x
// 0.3 m, 6 x 3 Q1 cells, E = 1 MPa, rho = 1000 kg/m^3, nu = 0.3; boundary
// ids by face (GridGenerator's colorize): the bottom face y = 0 has id 2;
// and their time stepping, and the scene that throws the block onto a plane.
#ifndef impactfe_tests_dynamics_elastic_block_h
#define impactfe_tests_dynamics_elastic_block_h

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/time_integration/time_integrator.h>

#include <memory>

namespace impactfe_tests
{
  inline std::unique_ptr<impactfe::ElasticBody<2>>
  make_elastic_block()
  {
    using namespace impactfe;
    MaterialParameters material;
    material.youngs_modulus = 1e6;
    material.density        = 1000.;
    material.poissons_ratio = 0.3;
    material.plane_model    = PlaneModel::plane_strain;
    DiscretizationParameters discretization;
    auto                     block =
      std::make_unique<ElasticBody<2>>("block", material, discretization, 1.);
    dealii::GridGenerator::subdivided_hyper_rectangle(
      block->triangulation(),
      std::vector<unsigned int>{6, 3},
      dealii::Point<2>(0., 0.),
      dealii::Point<2>(0.6, 0.3),
      true);
    block->setup();
    return block;
  }

  /// The time stepping of these tests: theta-Euler, theta = 0.55, h = 2 ms.
  inline impactfe::TimeSteppingParameters
  block_time_stepping()
  {
    impactfe::TimeSteppingParameters time_stepping;
    time_stepping.scheme    = impactfe::Scheme::theta_euler;
    time_stepping.theta     = 0.55;
    time_stepping.time_step = 2e-3;
    time_stepping.end_time  = 1.;
    return time_stepping;
  }

  /**
   * The block's scene of step_allocations and lcp_statistics, added to
   * @p system: every node of the bottom face (id 2) a candidate against the
   * plane y = 0 with friction @p mu, and the block thrown down and sideways
   * (0.5 m/s along the plane, 0.1 to 0.5 m/s down from its left end to its
   * right), so that it lands on a corner, rocks and slides.
   */
  inline void
  throw_block_onto_plane(impactfe::MultibodySystem<2>   &system,
                         const impactfe::ElasticBody<2> &block,
                         const double                    mu)
  {
    using namespace dealii;
    system.add_body(block);
    system.contacts().add_node_to_plane(
      system.bodies(), 0, 2, Point<2>(0., 0.), Tensor<1, 2>({0., 1.}), mu);
    Vector<double> &v        = system.state().velocity.block(0);
    const auto     &vertices = block.triangulation().get_vertices();
    for (unsigned int i = 0; i < vertices.size(); ++i)
      {
        v(block.vertex_dof(i, 0)) = 0.5;
        v(block.vertex_dof(i, 1)) = -(0.1 + 0.4 * vertices[i][0] / 0.6);
      }
  }
} // namespace impactfe_tests

#endif
