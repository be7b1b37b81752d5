// Paper, section 4: if the gap is closed at t_i and stays closed, the
// theta-Euler and modified theta-methods give V_N^{i+1} = 0 exactly (no
// restitution is invented); the theta-method does not.
//
// Part 1: a bar at rest touching a rigid wall (gap 0), pushed into it by a
// body force. The contact stays closed, so every active step must have
// V_N^{i+1} = 0 for the first two schemes (the theta-method too, here,
// because V_N^i = 0: restitution needs a non-zero V_N^i).
// Part 2: the bar reaches the wall at v0 with V_N^0 = -v0 and the gap of
// the scheme closed: g^0 = 0 for theta-Euler and theta, and for modified
// theta its estimate g^0 + h (1-theta) V_N^0 = 0, i.e. g^0 = h (1-theta) v0.
// The first step keeps it closed: theta-Euler and modified theta give
// V_N^1 = 0, the theta-method gives the paper's V_N^1 = (1 - 1/theta) V_N^0
// exactly.

#include "../tests.h"

#include "bar_scene.h"

int
main()
{
  using namespace impactfe_tests;
  initlog();

  const double h = 0.01;
  for (const Scheme scheme :
       {Scheme::theta_euler, Scheme::modified_theta, Scheme::theta})
    {
      BarScene scene(
        scheme, 0.55, h, /*wall=*/true, /*gap=*/0., /*body force=*/-1.);
      scene.system->setup();
      double              max_active_velocity = 0.;
      unsigned int        active_steps        = 0;
      std::vector<double> vn;
      for (unsigned int step = 0; step < 200; ++step)
        {
          const StepReport report = scene.system->do_time_step();
          scene.system->contacts().normal_velocities(
            scene.system->state().velocity, vn);
          if (report.active_contacts == 1)
            {
              ++active_steps;
              max_active_velocity =
                std::max(max_active_velocity, std::abs(vn[0]));
            }
        }
      dealii::deallog << to_string(scheme) << ": active in " << active_steps
                      << " of 200 steps" << std::endl;
      check(max_active_velocity < 1e-13,
            to_string(scheme) + ": V_N^{i+1} = 0 on every active step",
            "max |V_N| = " + std::to_string(max_active_velocity));
      check(active_steps == 200,
            to_string(scheme) + ": contact active on every step");
    }

  const double v0 = 1.;
  for (const double theta : {0.5, 0.55, 0.8})
    for (const Scheme scheme :
         {Scheme::theta_euler, Scheme::modified_theta, Scheme::theta})
      {
        const double gap =
          scheme == Scheme::modified_theta ? h * (1. - theta) * v0 : 0.;
        BarScene scene(scheme, theta, h, true, gap, -1.);
        scene.set_initial_velocity(-v0, 0.);
        scene.system->setup();
        const StepReport    report = scene.system->do_time_step();
        std::vector<double> vn;
        scene.system->contacts().normal_velocities(
          scene.system->state().velocity, vn);
        const double expected =
          scheme == Scheme::theta ? (1. - 1. / theta) * -v0 : 0.;
        const std::string name =
          to_string(scheme) + ", theta = " + std::to_string(theta).substr(0, 4);
        deallog << name << ": V_N^1 / v0 = " << rounded(vn[0] / v0, 6)
                << std::endl;
        check(report.active_contacts == 1 &&
                std::abs(vn[0] - expected) < 1e-12 * v0,
              name + (scheme == Scheme::theta ?
                        ": V_N^1 = (1 - 1/theta) V_N^0 (restitution)" :
                        ": V_N^1 = 0 (no restitution)"));
      }
  return n_failed_checks == 0 ? 0 : 1;
}
