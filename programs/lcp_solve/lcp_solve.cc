// lcp-solve: solve LCP and frictional contact problem files (Siconos numerics
// text formats and FCLib HDF5 files) with impactfe's LCP module. The options
// are in usage() below; the output lines, the exit codes (0 solved, 1 not
// solved or not converged, 2 bad command line or file) and the methods are in
// doc/lcp.md, "lcp-solve".
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/exact_cone.h>
#include <impactfe/lcp/fclib_io.h>
#include <impactfe/lcp/lemke.h>
#include <impactfe/lcp/problem_io.h>
#include <impactfe/utilities/blas_threads.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <string>
#include <vector>

using namespace impactfe::lcp;
using impactfe::ContactState;

namespace
{
  void
  usage(std::ostream &out)
  {
    out
      << "usage: lcp-solve [options] FILE...\n"
         "Options:\n"
         "  --solution   print the solution (z, or the contact impulses P) after each line\n"
         "  --warm       warm start: LCP files from the guess 'z_i > 0 where q_i < 0';\n"
         "               contact files from the states 'closed (stick) where V_N + b_N < 0,\n"
         "               open elsewhere' (2D friction: block pivoting, then Lemke)\n"
         "  --form F     LCP form for friction-contact files (default auto)\n"
         "  --facets k   facets of the 3D friction cone: even, in [4, 256] (default 8)\n"
         "  --cone C     facets (default: the polygonal cone) or exact (the circular\n"
         "               cone, by an interior point method and re-aligned facet\n"
         "               LCPs; contact files)\n"
         "  --tolerance e  exact-cone error to reach with --cone exact, and the\n"
         "               relative natural-map residual (default 1e-10)\n"
         "  --threads t  BLAS threads (default 1: the times are one core's)\n"
         "  --route R    with --cone exact: auto (default: interior-point-then-facets),\n"
         "               facets-then-interior-point, facets or interior-point\n"
         "               (the order of the two routes; doc/lcp.md)\n"
         "  --verbose    print how each problem was solved (forms, routes, groups)\n"
         "  --reference  contact problems: print the exact-cone error of P, and for\n"
         "               FCLib files with a /solution that solution's error and\n"
         "               |P - r|/|r|\n"
         "  --write-fclib OUT  write the (one) contact problem and P to the FCLib\n"
         "               HDF5 file OUT\n"
         "Output per problem: file n status pivots relative_error seconds\n";
  }

  /// The message of a bad command line; exit code 2.
  int
  bad_argument(const std::string &what)
  {
    std::cerr << "lcp-solve: error: " << what << "\n";
    return 2;
  }

  /// The integer in @p text if it is one in [lo, hi], else -1.
  long
  integer_in(const char *text, const long lo, const long hi)
  {
    char      *end = nullptr;
    const long v   = std::strtol(text, &end, 10);
    return *end == '\0' && v >= lo && v <= hi ? v : -1;
  }

  void
  print_vector(const char *name, const std::vector<double> &v)
  {
    std::printf("%s", name);
    for (const double x : v)
      std::printf(" %.17g", x);
    std::printf("\n");
  }
} // namespace

int
main(int argc, char **argv)
{
  bool solution = false, warm = false, reference = false, verbose = false;
  unsigned int     blas_threads = 1;
  std::string      fclib_output;
  ContactOptions   options;
  ConeModel        cone = ConeModel::facets;
  ExactConeOptions cone_options;
  // Cold problems (no last step's facets to start from): the interior point
  // route first (doc/lcp.md).
  cone_options.route = ExactConeRoute::interior_point_then_facets;
  cone_options.cone_error_tolerance = cone_options.tolerance;
  std::vector<std::string> files;
  bool                     route_given = false, tolerance_given = false;
  // options for friction-contact files only, which an LCP file ignores
  std::vector<std::string> contact_options;
  for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
      if (i + 1 == argc &&
          (a == "--write-fclib" || a == "--threads" || a == "--tolerance" ||
           a == "--facets" || a == "--form" || a == "--cone" || a == "--route"))
        return bad_argument(a + " needs a value");
      if (a == "--solution")
        solution = true;
      else if (a == "--warm")
        warm = true;
      else if (a == "--reference")
        reference = true;
      else if (a == "--verbose")
        verbose = true;
      else if (a == "--write-fclib" && i + 1 < argc)
        fclib_output = argv[++i];
      else if (a == "--help" || a == "-h")
        {
          usage(std::cout);
          return 0;
        }
      else if (a == "--form" && i + 1 < argc)
        {
          contact_options.push_back(a);
          const std::string f = argv[++i];
          if (f == "klarbring")
            options.form = FrictionForm::klarbring;
          else if (f == "facets")
            options.form = FrictionForm::facets;
          else if (f == "auto" || f == "automatic")
            options.form = FrictionForm::automatic;
          else
            return bad_argument("unknown form '" + f +
                                "' (klarbring, facets or auto)");
        }
      else if ((a == "--cone" || a == "--route") && i + 1 < argc)
        {
          const std::string value = argv[++i];
          contact_options.push_back(a);
          try
            {
              if (a == "--cone")
                cone = cone_model_from_string(value);
              else
                route_given = true,
                cone_options.route =
                  value == "auto" ? ExactConeRoute::interior_point_then_facets :
                                    exact_cone_route_from_string(value);
            }
          catch (const std::invalid_argument &e)
            {
              return bad_argument(a + ": " + e.what());
            }
        }
      else if (a == "--threads" && i + 1 < argc)
        {
          const long t = integer_in(argv[++i], 1, 1024);
          if (t < 0)
            return bad_argument("--threads needs an integer in [1, 1024]");
          blas_threads = static_cast<unsigned int>(t);
        }
      else if (a == "--tolerance" && i + 1 < argc)
        {
          char *end              = nullptr;
          cone_options.tolerance = std::strtod(argv[++i], &end);
          if (*end != '\0' || !(cone_options.tolerance > 0.) ||
              !std::isfinite(cone_options.tolerance))
            return bad_argument("--tolerance needs a finite number > 0");
          cone_options.cone_error_tolerance = cone_options.tolerance;
          tolerance_given                   = true;
        }
      else if (a == "--facets" && i + 1 < argc)
        {
          // the programs' rule for 'Number of facets'
          const long k = integer_in(argv[++i], 4, 256);
          if (k < 0 || k % 2 != 0)
            return bad_argument(
              "--facets needs an even integer in [4, 256], got '" +
              std::string(argv[i]) + "' (--cone exact for the circular cone)");
          options.n_facets = static_cast<unsigned int>(k);
          contact_options.push_back(a);
        }
      else if (!a.empty() && a[0] == '-')
        {
          std::cerr << "lcp-solve: error: unknown option '" << a << "'\n";
          usage(std::cerr);
          return 2;
        }
      else
        files.push_back(a);
    }
  if ((route_given || tolerance_given) && cone != ConeModel::exact)
    return bad_argument(std::string(route_given ? "--route" : "--tolerance") +
                        " applies to --cone exact only");
  impactfe::set_blas_thread_limit(blas_threads);
  if (files.empty())
    {
      usage(std::cerr);
      return 2;
    }
  if (!fclib_output.empty() && files.size() != 1)
    return bad_argument("--write-fclib needs exactly one input file, " +
                        std::to_string(files.size()) + " given");

  int exit_code = 0;
  for (const std::string &file : files)
    {
      try
        {
          ProblemFile   f;
          FclibSolution file_solution;
          if (is_hdf5_file(file))
            {
              FclibProblem fclib = read_fclib_file(file);
              f.type             = ProblemType::friction_contact;
              f.contact          = std::move(fclib.contact);
              file_solution      = std::move(fclib.solution);
            }
          else
            f = read_problem_file(file);
          if (!fclib_output.empty() && f.type != ProblemType::friction_contact)
            throw std::runtime_error(
              file + ": --write-fclib needs a friction-contact problem");
          // the seconds of the solve, before anything is printed
          using Clock                    = std::chrono::steady_clock;
          const auto t0                  = Clock::now();
          auto       seconds_since_start = [&t0]() {
            return std::chrono::duration<double>(Clock::now() - t0).count();
          };
          double              seconds = 0.;
          Result              r;
          std::size_t         n = 0;
          std::vector<double> P;
          if (f.type == ProblemType::lcp)
            {
              if (!contact_options.empty())
                {
                  std::string list;
                  for (const std::string &o : contact_options)
                    list += (list.empty() ? "" : ", ") + o;
                  std::fprintf(stderr,
                               "lcp-solve: note: %s is an LCP file; %s "
                               "%s to friction-contact files, not to it\n",
                               file.c_str(),
                               list.c_str(),
                               contact_options.size() == 1 ? "applies" :
                                                             "apply");
                }
              n       = f.lcp.q.size();
              r       = solve_lcp(f.lcp.M, f.lcp.q, warm, options.lemke);
              seconds = seconds_since_start();
            }
          else
            {
              const ContactProblem    &p = f.contact;
              ContactSolution          s;
              GroupedExactConeSolution exact;
              if (cone == ConeModel::exact)
                {
                  // --warm is for the LCP routes (and LCP files in the
                  // same batch)
                  if (warm)
                    std::fprintf(stderr,
                                 "lcp-solve: note: %s: --warm is not used "
                                 "by --cone exact\n",
                                 file.c_str());
                  exact = solve_exact_cone_by_groups(p, options, cone_options);
                  s     = exact.solution;
                }
              else if (warm)
                {
                  std::vector<ContactState> guess(p.n_contacts,
                                                  ContactState::open);
                  for (unsigned int c = 0; c < p.n_contacts; ++c)
                    if (p.free_velocity[c * p.n_directions] + p.gap_term[c] <
                        0.)
                      guess[c] = ContactState::stick;
                  s = solve_contact_problem(p, options, guess);
                }
              else if (options.form == FrictionForm::automatic)
                s = solve_contact_problem_by_groups(p, options).solution;
              else
                s = solve_contact_problem(p, options);
              seconds = seconds_since_start();
              n       = s.lcp.z.size();
              if (cone == ConeModel::exact) // the unknowns; no one LCP
                n = p.W.n_rows();
              else if (n == 0) // not solved: the size of the assembled LCP
                n = assemble_contact_lcp(p, options).q.size();
              r         = s.lcp;
              r.message = s.message; // every route tried
              P         = s.P;
              if (cone == ConeModel::exact && r.status == Status::solved)
                {
                  std::printf("cone %s exact iterations=%u cone_error=%.3e "
                              "converged=%s\n",
                              file.c_str(),
                              exact.report.iterations,
                              exact.report.cone_error,
                              exact.report.converged ? "yes" : "no");
                  if (!exact.report.converged)
                    {
                      std::fprintf(stderr,
                                   "lcp-solve: %s: the exact cone was not "
                                   "reached: cone error %.3e, residual "
                                   "%.3e (tolerance %.1e on both) (%s)\n",
                                   file.c_str(),
                                   exact.report.cone_error,
                                   exact.report.residual,
                                   cone_options.tolerance,
                                   s.message.c_str());
                      exit_code = std::max(exit_code, 1);
                    }
                }
            }
          if (r.status == Status::solved)
            std::printf("%s %zu %s %u %.3e %.3e\n",
                        file.c_str(),
                        n,
                        to_string(r.status).c_str(),
                        r.pivots,
                        r.verification.relative_error,
                        seconds);
          else
            {
              std::printf("%s %zu %s %u - %.3e\n",
                          file.c_str(),
                          n,
                          to_string(r.status).c_str(),
                          r.pivots,
                          seconds);
              std::fprintf(stderr,
                           "lcp-solve: %s: %s\n",
                           file.c_str(),
                           r.message.c_str());
              exit_code = std::max(exit_code, 1);
            }
          if (verbose && r.status == Status::solved)
            std::printf("how %s: %s\n", file.c_str(), r.message.c_str());
          if (solution && r.status == Status::solved)
            {
              if (f.type == ProblemType::lcp)
                print_vector("z", r.z);
              else
                print_vector("P", P);
            }
          if (reference && f.type == ProblemType::friction_contact)
            {
              std::printf("reference %s exact_cone_error ", file.c_str());
              if (P.empty())
                std::printf("-");
              else
                std::printf("%.3e", exact_cone_error(f.contact, P));
              if (file_solution.r.size() == f.contact.W.n_rows())
                {
                  std::printf(" file_solution_exact_cone_error %.3e",
                              exact_cone_error(f.contact, file_solution.r));
                  if (!P.empty() &&
                      std::any_of(file_solution.r.begin(),
                                  file_solution.r.end(),
                                  [](const double x) { return x != 0.; }))
                    std::printf(" relative_difference %.3e",
                                relative_difference(P, file_solution.r));
                }
              std::printf("\n");
            }
          if (!fclib_output.empty())
            {
              const FclibSolution s =
                P.empty() ? FclibSolution() : local_solution(f.contact, P);
              FclibInfo info;
              info.title       = file;
              info.description = "written by impactfe lcp-solve";
              write_fclib_local_file(fclib_output,
                                     f.contact,
                                     info,
                                     P.empty() ? nullptr : &s);
            }
        }
      catch (const std::exception &e)
        {
          std::fflush(stdout);
          std::cerr << "lcp-solve: error: "
                    << (dynamic_cast<const std::bad_alloc *>(&e) == nullptr ?
                          std::string(e.what()) :
                          file + ": out of memory (its matrices, held dense, "
                                 "do not fit in this machine's memory)")
                    << std::endl;
          exit_code = 2;
        }
    }
  return exit_code;
}
