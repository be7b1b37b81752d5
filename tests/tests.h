// Minimal test support for the impactfe test suite, in the spirit of
// deal.II's own tests/tests.h (which is not installed with the library).
//
// A test writes everything it wants compared to `deallog`; initlog() attaches
// deallog to the file `output` in the test's working directory, which
// deal.II's test macros compare with `<test>.output` through numdiff.
#ifndef impactfe_tests_tests_h
#define impactfe_tests_tests_h

#include <deal.II/base/logstream.h>

#include <cctype>
#include <cmath>
#include <exception>
#include <fstream>
#include <iomanip>
#include <string>

namespace impactfe_tests
{
  inline std::ofstream logfile;

  // Attach deallog to the file "output"; fixed format, 8 significant digits.
  inline void
  initlog(const unsigned int precision = 8)
  {
    logfile.open("output");
    dealii::deallog.attach(logfile, /*print_job_id=*/false);
    dealii::deallog.depth_console(0);
    logfile << std::setprecision(precision);
  }

  // Round a value to `digits` significant digits so that the last bits of
  // floating point noise never reach the .output file. Zero stays zero and
  // values below `floor` in magnitude are printed as 0.
  inline double
  rounded(const double value, const int digits = 6, const double floor = 1e-12)
  {
    if (std::abs(value) < floor)
      return 0.;
    const double scale =
      std::pow(10.,
               digits - 1 -
                 static_cast<int>(std::floor(std::log10(std::abs(value)))));
    return std::round(value * scale) / scale;
  }

  // Print "name: OK" or "name: FAILED (detail)" and remember the failure so
  // that the test can also fail on its own via the exit code.
  inline int n_failed_checks = 0;

  // An exception's text on one line: deal.II wraps its messages, so a
  // phrase a test looks for may be split between lines.
  inline std::string
  one_line(const std::exception &e)
  {
    std::string text;
    for (const char ch : std::string(e.what()))
      if (!std::isspace(static_cast<unsigned char>(ch)))
        text += ch;
      else if (!text.empty() && text.back() != ' ')
        text += ' ';
    return text;
  }

  inline void
  check(const bool ok, const std::string &name, const std::string &detail = "")
  {
    if (ok)
      dealii::deallog << name << ": OK" << std::endl;
    else
      {
        dealii::deallog << name << ": FAILED " << detail << std::endl;
        ++n_failed_checks;
      }
  }
} // namespace impactfe_tests

#endif
