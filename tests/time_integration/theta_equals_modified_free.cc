// Away from contact the modified theta-method is the theta-method: same
// dynamics and displacement update (only the gap used in Signorini
// differs). A vibrating, drifting bar far from a wall must give identical
// states with both schemes, and no contact impulse at all.

#include "../tests.h"

#include "bar_scene.h"

int
main()
{
  using namespace impactfe_tests;
  initlog();

  for (const double theta : {0.5, 0.55, 1.})
    {
      BarScene a(Scheme::theta, theta, 0.01, true, /*gap=*/10.);
      BarScene b(Scheme::modified_theta, theta, 0.01, true, /*gap=*/10.);
      a.set_initial_velocity(0.1, 0.3);
      b.set_initial_velocity(0.1, 0.3);
      a.system->setup();
      b.system->setup();
      double max_difference = 0., max_force = 0.;
      for (unsigned int step = 0; step < 300; ++step)
        {
          max_force              = std::max({max_force,
                                             a.system->do_time_step().normal_force,
                                             b.system->do_time_step().normal_force});
          BlockVector<double> du = a.system->state().displacement;
          du -= b.system->state().displacement;
          BlockVector<double> dv = a.system->state().velocity;
          dv -= b.system->state().velocity;
          max_difference =
            std::max({max_difference, du.linfty_norm(), dv.linfty_norm()});
        }
      deallog << "theta = " << theta << std::endl;
      check(max_difference == 0.,
            "identical u and v over 300 steps",
            std::to_string(max_difference));
      check(max_force == 0., "no contact force");
    }
  return n_failed_checks == 0 ? 0 : 1;
}
