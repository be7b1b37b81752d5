// Energy of a free vibrating bar (no contact): Newmark (beta = 1/4,
// gamma = 1/2) and the theta-method with theta = 1/2 are the trapezoidal
// rule and conserve 1/2 v^T M v + 1/2 u^T K u exactly (to rounding).
// theta > 1/2 and the theta-Euler method dissipate, so the energy must
// decrease monotonically. The mean velocity (momentum / mass) is exact for
// every scheme: rigid translation is in the kernel of K.

#include "../tests.h"

#include "bar_scene.h"

int
main()
{
  using namespace impactfe_tests;
  initlog();

  struct Case
  {
    Scheme scheme;
    double theta;
    bool   conserving;
  };
  for (const Case c : {Case{Scheme::newmark, 0.5, true},
                       Case{Scheme::theta, 0.5, true},
                       Case{Scheme::modified_theta, 0.5, true},
                       Case{Scheme::theta, 0.55, false},
                       Case{Scheme::theta_euler, 0.5, false},
                       Case{Scheme::theta_euler, 0.55, false}})
    {
      BarScene scene(c.scheme, c.theta, 0.05, /*wall=*/false);
      scene.set_initial_velocity(0.2, 1.);
      scene.system->setup();
      const double e0       = scene.energy();
      const double p0       = scene.system->momentum(0)[0];
      double       previous = e0, max_growth = 0., max_momentum_error = 0.;
      for (unsigned int step = 0; step < 400; ++step)
        {
          scene.system->do_time_step();
          const double e = scene.energy();
          max_growth     = std::max(max_growth, (e - previous) / e0);
          previous       = e;
          max_momentum_error =
            std::max(max_momentum_error,
                     std::abs(scene.system->momentum(0)[0] - p0) /
                       std::abs(p0));
        }
      const std::string name = to_string(c.scheme) + " theta = " +
                               std::to_string(c.theta).substr(0, 4);
      deallog << name << ": E(400 h)/E(0) = " << rounded(previous / e0, 6)
              << std::endl;
      if (c.conserving)
        check(std::abs(previous / e0 - 1.) < 1e-12,
              name + ": energy conserved");
      else
        check(max_growth <= 1e-14 && previous < e0,
              name + ": energy decreases at every step");
      check(max_momentum_error < 1e-12, name + ": momentum conserved");
    }
  return n_failed_checks == 0 ? 0 : 1;
}
