// check_figures_are_numbers(): a run's summary figure that is not finite
// (0/0 of a state that underflowed: the impulse balance was printed as
// -nan with exit code 0) fails the run whatever its bounds, one line per
// figure; finite figures, zero included, pass without a line.
#include <impactfe/dynamics/contact_monitor.h>

#include <cmath>
#include <limits>
#include <sstream>
#include <string>

#include "../tests.h"

int
main()
{
  impactfe_tests::initlog();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  std::ostringstream finite;
  const bool         finite_ok = impactfe::check_figures_are_numbers(
    finite, {{"impulse balance error", 0.}, {"energy ratio", 1e300}});
  impactfe_tests::check(finite_ok && finite.str().empty(),
                        "finite figures pass without a line");

  std::ostringstream out;
  const bool         ok =
    impactfe::check_figures_are_numbers(out,
                                        {{"impulse balance error", nan},
                                         {"penetration", 0.},
                                         {"energy ratio", inf}});
  std::istringstream lines(out.str());
  for (std::string line; std::getline(lines, line);)
    dealii::deallog << line << std::endl;
  impactfe_tests::check(!ok, "a figure that is nan or inf fails");
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
