// The one exact two-bar solution and error definition of the library
// (TwoBarsExactSolution, TwoBarsErrors), checked against conservation laws
// and hand-computed errors: the contact impulse F * 2L/c transfers bar 1's
// whole momentum rho A L v0 to bar 2, momentum is conserved at every time
// (the interface velocities stand for the bars' rigid motion before and
// after contact), and err_v and err_f of known series.

#include <impactfe/scenes/two_bars_exact.h>

#include <cmath>

#include "../tests.h"

using namespace impactfe;
using dealii::deallog;

int
main()
{
  impactfe_tests::initlog();
  // The paper's Table 1 data: E, rho, L, v0, A = 1 in^2, gap 0.1 mm.
  const double E = 0.20684e12, rho = 0.78957e4, L = 0.254, v0 = 5.13588,
               A = 6.4516e-4, gap = 1e-4;
  const double               c = std::sqrt(E / rho);
  const TwoBarsExactSolution exact(v0, gap, L, c, rho, A);

  deallog << "t_contact = g0/v0: " << exact.t_contact << " s" << std::endl;
  deallog << "duration = 2L/c: " << exact.duration << " s" << std::endl;
  deallog << "contact force = rho c v0 A/2: " << exact.contact_force << " N"
          << std::endl;

  const double impulse  = exact.contact_force * exact.duration;
  const double momentum = rho * A * L * v0;
  impactfe_tests::check(std::abs(impulse - momentum) <= 1e-14 * momentum,
                        "contact impulse = momentum of bar 1");

  // Before and after contact the bars move rigidly: the total momentum,
  // m (v_1 + v_2), is m v0 whenever the interface is not loaded.
  bool conserved = true;
  for (const double t :
       {0., 0.5 * exact.t_contact, exact.t_contact + 1.01 * exact.duration, 1.})
    conserved &= std::abs(exact.contact_velocity(t) + exact.target_velocity(t) -
                          v0) <= 1e-14 * v0;
  impactfe_tests::check(conserved, "momentum conserved outside the contact");
  impactfe_tests::check(exact.contact_velocity(
                          exact.t_contact + 0.5 * exact.duration) == 0.5 * v0,
                        "interface at v0/2 during contact");
  impactfe_tests::check(exact.normal_force(exact.t_contact - 1e-9) == 0. &&
                          exact.normal_force(exact.t_contact + exact.duration +
                                             1e-9) == 0.,
                        "no force before and after contact");

  // The exact solution has zero error; a velocity off by v0/4 at every
  // step and a force off by F/2 give err_v = 1/2 and err_f = 1/2.
  TwoBarsErrors      none(exact), known(exact);
  const unsigned int n = 100;
  for (unsigned int i = 1; i <= n; ++i)
    {
      const double t = i * 2. * (exact.t_contact + exact.duration) / n;
      none.add(t, exact.contact_velocity(t), exact.normal_force(t));
      known.add(t,
                exact.contact_velocity(t) + 0.25 * v0,
                exact.normal_force(t) - 0.5 * exact.contact_force);
    }
  deallog << "steps: " << known.n_steps() << std::endl;
  impactfe_tests::check(none.err_v() == 0. && none.err_f() == 0.,
                        "the exact solution has no error");
  impactfe_tests::check(std::abs(known.err_v() - 0.5) < 1e-14 &&
                          std::abs(known.err_f() - 0.5) < 1e-14,
                        "err_v = err_f = 1/2 for the shifted series");
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
