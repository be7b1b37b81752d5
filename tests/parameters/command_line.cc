// The programs' command line: `--help` prints the usage and exits with 0,
// `--print-parameters` writes every entry in the parameter-file format, and
// that file is valid input with the defaults once the entries without a
// default, commented out there, are set (two_bars_1d writes the same
// history on it as on a file that sets nothing but those and the output;
// unedited, it is refused); an unknown
// option or a second file is refused with the usage and exit code 1, before
// anything runs.
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "../tests.h"

namespace
{
  struct Program
  {
    const char *name;
    std::string executable;
  };

  int
  run(const std::string &command, const std::string &log)
  {
    const int status = std::system((command + " > " + log + " 2>&1").c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  std::string
  text_of(const std::string &file)
  {
    std::ifstream      in(file);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
  }

  bool
  contains(const std::string &text, const std::string &part)
  {
    return text.find(part) != std::string::npos;
  }

} // namespace

int
main()
{
  impactfe_tests::initlog();
  const std::string mpi = std::string(MPIEXEC_TWO_RANKS) + " ";
  for (const Program &program :
       {Program{"two_bars_1d", TWO_BARS_1D_EXECUTABLE},
        Program{"two_bars_2d", TWO_BARS_2D_EXECUTABLE},
        Program{"two_bars_3d", TWO_BARS_3D_EXECUTABLE},
        Program{"cylinder_impact", CYLINDER_IMPACT_EXECUTABLE},
        Program{"oblique_plate", OBLIQUE_PLATE_EXECUTABLE},
        Program{"oblique_plate_3d", OBLIQUE_PLATE_3D_EXECUTABLE},
        Program{"block_on_plane", BLOCK_ON_PLANE_EXECUTABLE},
        Program{"block_sliding_3d", BLOCK_SLIDING_3D_EXECUTABLE},
        Program{"hertz_impact", HERTZ_IMPACT_EXECUTABLE},
        Program{"hertz_on_block", HERTZ_ON_BLOCK_EXECUTABLE},
        Program{"taylor_bar", TAYLOR_BAR_EXECUTABLE},
        Program{"contact_mpi", mpi + BLOCK_SLIDING_MPI_EXECUTABLE}})
    {
      const std::string name      = program.name;
      const std::string help      = name + "_help.log";
      const int         help_code = run(program.executable + " --help", help);
      impactfe_tests::check(
        help_code == 0 &&
          text_of(help).rfind("Usage: " + name + " [parameter file]\n", 0) == 0,
        name + " --help: the usage, exit code 0");

      const std::string prm = name + "_parameters.prm";
      const int code = run(program.executable + " --print-parameters", prm);
      const std::string listing = text_of(prm);
      impactfe_tests::check(code == 0 &&
                              listing.rfind("# Listing of Parameters", 0) ==
                                0 &&
                              contains(listing, "subsection Output"),
                            name + " --print-parameters: a parameter file, "
                                   "exit code 0");

      const std::string bad = name + "_bad_option.log";
      const int bad_code = run(program.executable + " --print-parameter", bad);
      impactfe_tests::check(bad_code == 1 &&
                              contains(text_of(bad),
                                       "unknown option '--print-parameter'") &&
                              contains(text_of(bad), "Usage: " + name),
                            name + " --print-parameter: refused with the "
                                   "usage, exit code 1");

      const std::string two = name + "_two_files.log";
      const int two_code    = run(program.executable + " a.prm b.prm", two);
      impactfe_tests::check(two_code == 1 &&
                              contains(text_of(two),
                                       "one parameter file at most, got 2"),
                            name + " a.prm b.prm: refused, exit code 1");
    }

  // lcp-solve's --facets follows the programs' 'Number of facets' (even,
  // in [4, 256]); it took 2 and odd numbers, which the programs refuse
  for (const char *k : {"2", "5", "258", "8x"})
    {
      const std::string log = std::string("lcp_solve_facets_") + k + ".log";
      const int code = run(std::string(LCP_SOLVE_EXECUTABLE) + " --facets " +
                             k + " no_such_problem.dat",
                           log);
      impactfe_tests::check(code == 2 &&
                              contains(text_of(log),
                                       "--facets needs an even integer in "
                                       "[4, 256], got '" +
                                         std::string(k) + "'"),
                            std::string("lcp-solve --facets ") + k +
                              ": refused, exit code 2");
    }

  // an infinite tolerance was taken (and the run called converged)
  {
    const std::string log  = "lcp_solve_tolerance.log";
    const int         code = run(std::string(LCP_SOLVE_EXECUTABLE) +
                           " --cone exact --tolerance inf no_such_problem.dat",
                         log);
    impactfe_tests::check(code == 2 &&
                            contains(text_of(log),
                                     "--tolerance needs a finite number > 0"),
                          "lcp-solve --tolerance inf: refused, exit code 2");
  }
  // options that a file's kind does not use were ignored silently: the
  // contact options on an LCP file, --warm with the exact cone on a
  // contact file. Both files are solved, each with a note.
  {
    std::ofstream("identity.lcp") << "2\n0\n2\n2\n2\t2\n1 0\n0 1\n-1 -1\n";
    std::ofstream("two_contacts.fc")
      << "2\n2\n0 4 4\n4 4\n2 0 1 0  0 1 0 0  1 0 2 0  0 0 0 1\n"
         "-1 0.5 -1 -0.2\n0.3 0.5\n";
    const std::string log  = "lcp_solve_notes.log";
    const int         code = run(std::string(LCP_SOLVE_EXECUTABLE) +
                           " --cone exact --warm identity.lcp two_contacts.fc",
                         log);
    const std::string text = text_of(log);
    impactfe_tests::check(
      code == 0 && contains(text, "identity.lcp 2 solved") &&
        contains(text, "two_contacts.fc 4 solved") &&
        contains(text,
                 "identity.lcp is an LCP file; --cone applies to "
                 "friction-contact files") &&
        contains(text, "two_contacts.fc: --warm is not used by --cone exact"),
      "lcp-solve --cone exact --warm on an LCP and a contact file: both "
      "solved, each with a note on the option it does not use");
  }

  // The listing is input, and holds the defaults: two_bars_1d on it
  // writes the history of a file that sets the output entries and the
  // entries without a default (Young's modulus, the density, the time step
  // and the end time) alone. Those four are commented out in the listing,
  // so that the listing run unedited is refused: before, it set them to
  // placeholders (1 Pa, 1 kg/m^3, 1e-3 s, 1 s) and simulated those.
  {
    const std::string listing = text_of("two_bars_1d_parameters.prm");
    impactfe_tests::check(
      contains(listing, "# set Young's modulus") &&
        contains(listing, "# set Density") &&
        contains(listing, "# set Time step") &&
        contains(listing, "# set End time") &&
        contains(listing, "= (no default: set it)") &&
        !contains(listing, "\n  set Young's modulus"),
      "two_bars_1d --print-parameters: the entries without a default are "
      "commented out");
    const std::string output = "\n  set VTU output = false\n"
                               "  set Plot = false\nend\n";
    const std::string required =
      "subsection Material\n  set Young's modulus = 1\n"
      "  set Density = 1\nend\n"
      "subsection Time stepping\n  set Time step = 1e-3\n"
      "  set End time = 1\nend\n";
    std::ofstream("listing_unedited.prm")
      << "include two_bars_1d_parameters.prm\nsubsection Output\n"
      << "  set Output directory = listing_unedited" << output;
    std::ofstream("listing_run.prm")
      << "include two_bars_1d_parameters.prm\n"
      << required << "subsection Output\n"
      << "  set Output directory = listing_run" << output;
    std::ofstream("default_run.prm")
      << required << "subsection Output\n  set Output directory = default_run"
      << output;
    const int unedited_code =
      run(std::string(TWO_BARS_1D_EXECUTABLE) + " listing_unedited.prm",
          "listing_unedited.log");
    const std::string unedited = text_of("listing_unedited.log");
    impactfe_tests::check(unedited_code == 1 &&
                            contains(unedited, "does not set") &&
                            contains(unedited, "no default") &&
                            contains(unedited, "'Time step' and 'End time'"),
                          "two_bars_1d on its unedited listing: refused, "
                          "naming the entries to set, exit code 1");
    const int listing_code =
      run(std::string(TWO_BARS_1D_EXECUTABLE) + " listing_run.prm",
          "listing_run.log");
    const int default_code =
      run(std::string(TWO_BARS_1D_EXECUTABLE) + " default_run.prm",
          "default_run.log");
    const std::string history = text_of("listing_run/history.csv");
    impactfe_tests::check(listing_code == 0 && default_code == 0 &&
                            contains(history, "contact_velocity") &&
                            history == text_of("default_run/history.csv"),
                          "two_bars_1d on its own listing with those four "
                          "set: runs, and writes the defaults' history.csv");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
