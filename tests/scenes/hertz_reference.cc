// HertzImpact, the reference of the Hertz scenes, against an independent
// computation: the impact ODE m delta'' = -F(delta), delta(0) = 0,
// delta'(0) = v, integrated with RK4 at 20000 steps per contact. Its
// largest approach, peak force and contact duration must be the closed
// forms' (the Beta-function constant of t_c included), and the work of
// F up to delta_max must be the kinetic energy m v^2 / 2. Checked for a
// rigid flat and for an elastic one (E* from both moduli).

#include <impactfe/scenes/hertz_impact.h>

#include <cmath>

#include "../tests.h"

using namespace impactfe;

namespace
{
  void
  check(const HertzImpact &hertz)
  {
    const double m = hertz.mass, v = hertz.velocity;
    const double dt = hertz.contact_duration() / 20000.;
    // State (delta, delta'): RK4 until delta < 0 again.
    double     delta = 0., rate = v, t = 0., largest = 0.;
    const auto accel = [&](const double d) { return -hertz.force(d) / m; };
    while (true)
      {
        const double k1x = rate, k1v = accel(delta);
        const double k2x = rate + 0.5 * dt * k1v,
                     k2v = accel(delta + 0.5 * dt * k1x);
        const double k3x = rate + 0.5 * dt * k2v,
                     k3v = accel(delta + 0.5 * dt * k2x);
        const double k4x = rate + dt * k3v, k4v = accel(delta + dt * k3x);
        const double next = delta + dt / 6. * (k1x + 2. * k2x + 2. * k3x + k4x);
        const double next_rate =
          rate + dt / 6. * (k1v + 2. * k2v + 2. * k3v + k4v);
        if (next < 0.)
          {
            // Linear interpolation of the crossing of delta = 0.
            t += dt * delta / (delta - next);
            break;
          }
        delta = next;
        rate  = next_rate;
        t += dt;
        largest = std::max(largest, delta);
      }
    // Work of F from 0 to delta_max (Simpson, 2000 intervals).
    const unsigned int n    = 2000;
    const double       step = hertz.max_approach() / n;
    double             work = 0.;
    for (unsigned int i = 0; i <= n; ++i)
      work += (i == 0 || i == n ? 1. : (i % 2 ? 4. : 2.)) *
              hertz.force(i * step) * step / 3.;
    const auto rel = [](const double a, const double b) {
      return std::abs(a - b) / std::abs(b);
    };
    dealii::deallog << "E* = " << hertz.effective_modulus()
                    << " Pa; delta_max = " << hertz.max_approach()
                    << " m, F_max = " << hertz.peak_force()
                    << " N, t_c = " << hertz.contact_duration() << " s"
                    << std::endl;
    dealii::deallog
      << "  ODE against the closed forms: delta_max "
      << (rel(largest, hertz.max_approach()) < 1e-6 ? "ok" : "WRONG")
      << ", F_max "
      << (rel(hertz.force(largest), hertz.peak_force()) < 1e-6 ? "ok" : "WRONG")
      << ", t_c " << (rel(t, hertz.contact_duration()) < 1e-5 ? "ok" : "WRONG")
      << ", |rebound velocity + v| / v "
      << (rel(-rate, v) < 1e-3 ? "< 1e-3" : "WRONG") << std::endl;
    dealii::deallog << "  work of F up to delta_max / (m v^2 / 2) - 1: "
                    << (rel(work, 0.5 * m * v * v) < 1e-8 ? "< 1e-8" : "WRONG")
                    << "; t_c v / delta_max = "
                    << impactfe_tests::rounded(hertz.contact_duration() * v /
                                                 hertz.max_approach(),
                                               5)
                    << std::endl;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  HertzImpact steel_ball;
  steel_ball.radius         = 0.01;
  steel_ball.mass           = 0.0326726;
  steel_ball.youngs_modulus = 2.1e11;
  steel_ball.poissons_ratio = 0.3;
  steel_ball.velocity       = 5.;
  check(steel_ball);
  HertzImpact on_aluminium         = steel_ball;
  on_aluminium.flat_youngs_modulus = 7e10;
  on_aluminium.flat_poissons_ratio = 0.33;
  check(on_aluminium);
}
