// A bar hitting a rigid wall at v0 (schemes.md, benchmark 1): exact contact
// force rho c v0 A for 2L/c, after which the bar leaves at -v0. Checks:
//  - discrete impulse balance: sum_i h F_i (the impulses) equals the change
//    of momentum, to rounding, at every step (independent of the scheme:
//    rigid translation is in the kernel of K);
//  - total impulse against the exact value 2 m v0, within sqrt(h / T_c),
//    T_c = 2L/c: the error law of a first-order scheme across the jumps of
//    the exact solution (see tests/two_bars_1d);
//  - Signorini: the gap at the end of a step never becomes negative
//    beyond rounding for the schemes that enforce it there (theta,
//    theta-Euler, Newmark); the modified theta-method enforces it on the
//    estimate u + h (1-theta) v, so its end-of-step gap may be < 0: printed.

#include "../tests.h"

#include "bar_scene.h"

int
main()
{
  using namespace impactfe_tests;
  initlog();

  const double       v0 = 1., L = 1., c = 1.;
  const unsigned int n_cells = 40;
  const double       h       = 0.9 * (L / n_cells) / c;
  for (const Scheme scheme : {Scheme::theta,
                              Scheme::theta_euler,
                              Scheme::modified_theta,
                              Scheme::newmark})
    {
      BarScene scene(scheme, 0.55, h, true, 0., 0., n_cells);
      scene.set_initial_velocity(-v0, 0.);
      scene.system->setup();
      const double        mass    = 1.;
      const double        p0      = scene.system->momentum(0)[0];
      double              impulse = 0., max_balance_error = 0., min_gap = 0.;
      std::vector<double> gaps;
      const unsigned int  n_steps = static_cast<unsigned int>(3. * L / c / h);
      for (unsigned int step = 0; step < n_steps; ++step)
        {
          const StepReport report = scene.system->do_time_step();
          // The impulse of a theta-scheme step is force times h. (Newmark
          // spreads r^{i+1} over two steps, with weights gamma and
          // 1 - gamma: only its total is checked.)
          impulse += scene.system->contact_force(0)[0] * h;
          scene.system->contacts().gaps(scene.system->state().displacement,
                                        gaps);
          min_gap = std::min(min_gap, gaps[0]);
          if (scheme != Scheme::newmark)
            max_balance_error =
              std::max(max_balance_error,
                       std::abs(scene.system->momentum(0)[0] - p0 - impulse));
        }
      const double momentum_change = scene.system->momentum(0)[0] - p0;
      deallog << to_string(scheme) << ": momentum change / (2 m v0) = "
              << rounded(momentum_change / (2. * mass * v0), 3) << std::endl;
      if (scheme != Scheme::newmark)
        check(max_balance_error < 1e-12,
              to_string(scheme) +
                ": impulse = change of momentum at every step");
      check(std::abs(momentum_change / (2. * mass * v0) - 1.) <
              std::sqrt(h / (2. * L / c)),
            to_string(scheme) + ": total impulse within sqrt(h/T_c) of 2 m v0");
      if (scheme != Scheme::modified_theta)
        check(min_gap > -1e-12,
              to_string(scheme) + ": no penetration at the end of any step");
      else
        deallog << to_string(scheme)
                << ": min gap / (v0 h) = " << rounded(min_gap / (v0 * h), 2)
                << std::endl;
    }
  return n_failed_checks == 0 ? 0 : 1;
}
