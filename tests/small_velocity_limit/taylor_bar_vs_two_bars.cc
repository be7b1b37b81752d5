// The small-velocity limit of the finite-strain Taylor bar (issue 13): at
// 1 m/s with nu = 0 the copper bar stays elastic (impact stress
// rho c v0 = 32 MPa against sigma_y = 400 MPa) and is a 1D bar; hitting a
// rigid wall at v0 is, by symmetry, half of two equal bars meeting at
// 2 v0. So taylor_bar (axisymmetric, finite strain, Hencky, F-bar) and
// two_bars_1d (P1, small strain) run with the same cells along the bar
// (50), lumped mass, the same step and theta = 1, and their contact force
// histories are compared step by step. They differ by the geometric and
// material nonlinearity, of the order of the strain eps = v0/c = 2.8e-4
// relative to the force; the bound is 10 eps of the peak force. Both are
// also compared with the exact contact time 2 L0/c and the exact force
// rho c v0 A.

#include <deal.II/base/numbers.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

namespace
{
  const double E = 117e9, rho = 8930., L = 32.4e-3, r0 = 3.2e-3, v0 = 1.;

  // A column of a history.csv.
  std::vector<double>
  column(const std::string &file, const std::string &name)
  {
    std::ifstream in(file);
    std::string   line, cell;
    std::getline(in, line);
    std::istringstream header(line);
    unsigned int       index = 0, found = ~0u;
    for (; std::getline(header, cell, ','); ++index)
      if (cell == name)
        found = index;
    std::vector<double> values;
    while (std::getline(in, line))
      {
        std::istringstream row(line);
        for (unsigned int i = 0; std::getline(row, cell, ','); ++i)
          if (i == found)
            values.push_back(std::stod(cell));
      }
    return values;
  }

  void
  run(const std::string &executable,
      const std::string &prm,
      const std::string &text)
  {
    std::ofstream(prm) << text;
    const std::string command =
      executable + " " + prm + " > " + prm + ".log 2>&1";
    impactfe_tests::check(std::system(command.c_str()) == 0, prm + " ran");
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  const std::string output =
    "subsection Output\n  set VTU output = false\n  set Plot = false\n"
    "  set Print performance data = false\n";
  run(TAYLOR_BAR_EXECUTABLE,
      "taylor_bar.prm",
      "subsection Geometry\n  set Radial cells = 2\n  set Axial cells = 50\n"
      "end\nsubsection Initial conditions\n  set Impact velocity = 1\nend\n"
      "subsection Time\n  set End time = 25e-6\n  set Time step = 1e-7\n"
      "  set Theta = 1\nend\nsubsection Material\n  set Poisson's ratio = 0\n"
      "end\n" +
        output + "  set Output directory = taylor_bar\nend\n");
  std::ostringstream bars;
  bars << std::setprecision(12)
       << "subsection Geometry\n  set Bar length = " << L
       << "\n  set Number of cells per bar = 50\n  set Initial gap = 0\n"
       << "  set Cross-section area = " << dealii::numbers::PI * r0 * r0
       << "\nend\n"
       << "subsection Material\n  set Young's modulus = " << E
       << "\n  set Density = " << rho << "\nend\n"
       << "subsection Initial conditions\n  set Impact velocity = " << 2. * v0
       << "\nend\nsubsection Discretization\n  set Mass matrix = lumped\nend\n"
       << "subsection Time stepping\n  set Scheme = theta\n  set Theta = 1\n"
       << "  set Time step = 1e-7\n  set End time = 25e-6\nend\n"
       << output << "  set Output directory = two_bars\nend\n";
  run(TWO_BARS_1D_EXECUTABLE, "two_bars.prm", bars.str());

  // two_bars_1d's history starts with the row of t = 0; taylor_bar's with
  // the first step.
  const std::vector<double> force_1d =
    column("two_bars/history.csv", "normal_force");
  const std::vector<double> force_axi =
    column("taylor_bar/history.csv", "normal_force");
  const std::vector<double> time_axi = column("taylor_bar/history.csv", "time");
  impactfe_tests::check(force_1d.size() == force_axi.size() + 1,
                        "the same number of steps");
  double peak = 0., difference = 0., last_1d = 0., last_axi = 0.;
  for (unsigned int i = 0; i < force_axi.size(); ++i)
    {
      peak = std::max(peak, std::abs(force_1d[i + 1]));
      difference =
        std::max(difference, std::abs(force_1d[i + 1] - force_axi[i]));
      if (force_1d[i + 1] > 0.)
        last_1d = time_axi[i];
      if (force_axi[i] > 0.)
        last_axi = time_axi[i];
    }
  const double c = std::sqrt(E / rho), strain = v0 / c;
  const double exact_force = rho * c * v0 * dealii::numbers::PI * r0 * r0;
  dealii::deallog << "strain v0/c = " << impactfe_tests::rounded(strain, 3)
                  << std::endl;
  dealii::deallog
    << "force histories: largest difference / peak force < 10 v0/c: "
    << (difference / peak < 10. * strain ? "yes" : "no") << std::endl;
  dealii::deallog << "last step with a contact force: the same: "
                  << (last_1d == last_axi ? "yes" : "no")
                  << ", within 1 % of 2 L0/c: "
                  << (std::abs(last_axi - 2. * L / c) < 0.01 * 2. * L / c ?
                        "yes" :
                        "no")
                  << std::endl;
  const double plateau =
    force_axi[static_cast<unsigned int>(0.5 * L / c / 1e-7)];
  dealii::deallog << "force at t = L0/(2c) against rho c v0 A (exact "
                  << impactfe_tests::rounded(exact_force, 4)
                  << " N): within 0.1 %: "
                  << (std::abs(plateau - exact_force) < 1e-3 * exact_force ?
                        "yes" :
                        "no")
                  << std::endl;
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
