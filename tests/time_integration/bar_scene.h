// Small 1D scenes for the time-integration tests: one bar, optionally
// against a rigid wall, built with the library as a program would.
#ifndef impactfe_tests_bar_scene_h
#define impactfe_tests_bar_scene_h

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/multibody_system.h>

#include <cmath>
#include <memory>

namespace impactfe_tests
{
  using namespace dealii;
  using namespace impactfe;

  struct BarScene
  {
    MaterialParameters                  material;
    DiscretizationParameters            discretization;
    TimeSteppingParameters              time_stepping;
    ContactSolverParameters             solver;
    std::unique_ptr<ElasticBody<1>>     bar;
    std::unique_ptr<MultibodySystem<1>> system;

    // A bar on [0, 1] (E = rho = 1, 10 cells). With @p wall, its left end
    // (boundary id 0) is a contact candidate against the wall x = -gap.
    BarScene(const Scheme       scheme,
             const double       theta,
             const double       h,
             const bool         wall,
             const double       gap        = 0.,
             const double       body_force = 0.,
             const unsigned int n_cells    = 10)
    {
      time_stepping.scheme    = scheme;
      time_stepping.theta     = theta;
      time_stepping.time_step = h;
      bar = std::make_unique<ElasticBody<1>>("bar", material, discretization);
      GridGenerator::subdivided_hyper_rectangle(bar->triangulation(),
                                                std::vector<unsigned int>{
                                                  n_cells},
                                                Point<1>(0.),
                                                Point<1>(1.),
                                                true);
      bar->setup();
      bar->set_body_force(Tensor<1, 1>({body_force}));
      system = std::make_unique<MultibodySystem<1>>(time_stepping, solver);
      system->add_body(*bar);
      if (wall)
        system->contacts().add_node_to_plane(
          system->bodies(), 0, 0, Point<1>(-gap), Tensor<1, 1>({1.}));
    }

    // A smooth, non-uniform initial velocity (a vibration plus a drift).
    void
    set_initial_velocity(const double drift, const double amplitude)
    {
      auto &v = system->state().velocity.block(0);
      for (unsigned int vertex = 0; vertex < bar->triangulation().n_vertices();
           ++vertex)
        {
          const double x = bar->triangulation().get_vertices()[vertex][0];
          v(bar->vertex_dof(vertex, 0)) =
            drift + amplitude * std::cos(M_PI * x);
        }
    }

    double
    energy() const
    {
      return system->kinetic_energy() + system->elastic_energy();
    }
  };
} // namespace impactfe_tests

#endif
