// lcp-solve: solve LCP and frictional contact problem files (Siconos numerics
// text formats and FCLib HDF5 files, see doc/lcp.md) with impactfe's Lemke
// solver.
//
//   lcp-solve [--solution] [--warm] [--form klarbring|facets|auto] [--facets k]
//             [--cone facets|exact] [--route R] [--tolerance e] [--reference]
//             [--verbose] [--threads t] [--write-fclib OUT] FILE...
//
// --cone exact solves contact problems with the circular Coulomb cone
// (ExactConeSolver, group by group: the interior point route, then facet LCPs
// re-aligned with the slip directions where it stops short, until the
// natural-map residual is <= --tolerance, default 1e-10; --route changes the
// order) and prints a line "cone FILE exact iterations=I cone_error=E
// converged=yes"; a problem that does not converge counts as not solved.
// The default, --cone facets, is the polygonal cone of --facets k facets.
// The BLAS runs on --threads t threads (default 1).
//
// --reference prints, for contact problems, the exact-cone error of the
// answer and, for FCLib files that carry a /solution, that solution's error
// and its distance to ours. --write-fclib writes the (single) contact
// problem, with our solution, as an FCLib file: a converter from the text
// formats.
//
// One line per problem: "file n status pivots relative_error seconds"
// (relative_error: Verification::relative_error, complementarity, residual
// and sign conditions in one scale-invariant number)
// (n is the size of the LCP actually solved; "-" when not solved), then with
// --solution the solution z (LCP files) or the impulses P (contact files).
// With --form auto (the default) a contact problem is split into the groups
// of contacts that W does not couple (solve_contact_problem_by_groups()), and
// a group that the first form does not solve is tried by the other routes of
// contact_routes.h; every route is listed on stderr if none succeeds. n is
// then the total size of the groups' LCPs. Status "infeasible" means proven to
// have no solution; "ray-termination" and the others mean Lemke's method did
// not find one (and, for contact problems with --form auto, the problem is
// feasible or that could not be decided).
// Exit code: 0 if every problem was solved, 1 if one was not, 2 on a bad
// command line or an unreadable/malformed file.
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/exact_cone.h>
#include <impactfe/lcp/fclib_io.h>
#include <impactfe/lcp/lemke.h>
#include <impactfe/lcp/problem_io.h>
#include <impactfe/utilities/blas_threads.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
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
      << "usage: lcp-solve [--solution] [--warm] [--form klarbring|facets|auto] [--facets k] FILE...\n"
         "  --solution   print the solution (z, or the contact impulses P) after each line\n"
         "  --warm       warm start: LCP files from the guess 'z_i > 0 where q_i < 0';\n"
         "               contact files from the states 'closed (stick) where V_N + b_N < 0,\n"
         "               open elsewhere' (2D friction: block pivoting, then Lemke)\n"
         "  --form F     LCP form for friction-contact files (default auto)\n"
         "  --facets k   facets of the friction cone in 3D (default 8)\n"
         "  --cone C     facets (default: the polygonal cone) or exact (the circular\n"
         "               cone, by re-aligned facet LCPs; contact files)\n"
         "  --tolerance e  exact-cone error to reach with --cone exact (default 1e-10)\n"
         "  --threads t  BLAS threads (default 1: the times are one core's)\n"
         "  --route R    with --cone exact: auto (default) or interior-point-then-\n"
         "               facets: the interior point route, the facet LCPs where it\n"
         "               stops short; facets-then-interior-point: the other way\n"
         "               round (the time loop's order); facets: facet LCPs only;\n"
         "               interior-point: that route only\n"
         "  --verbose    print how each problem was solved (forms, routes, groups)\n"
         "  --reference  contact problems: print the exact-cone error of P, and for\n"
         "               FCLib files with a /solution that solution's error and\n"
         "               |P - r|/|r|\n"
         "  --write-fclib OUT  write the (one) contact problem and P to the FCLib\n"
         "               HDF5 file OUT\n"
         "Output per problem: file n status pivots relative_error seconds\n";
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
  std::vector<std::string> files;
  for (int i = 1; i < argc; ++i)
    {
      const std::string a = argv[i];
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
          const std::string f = argv[++i];
          if (f == "klarbring")
            options.form = FrictionForm::klarbring;
          else if (f == "facets")
            options.form = FrictionForm::facets;
          else if (f == "auto" || f == "automatic")
            options.form = FrictionForm::automatic;
          else
            {
              std::cerr << "lcp-solve: error: unknown form '" << f
                        << "' (klarbring, facets or auto)\n";
              return 2;
            }
        }
      else if (a == "--cone" && i + 1 < argc)
        {
          try
            {
              cone = cone_model_from_string(argv[++i]);
            }
          catch (const std::invalid_argument &e)
            {
              std::cerr << "lcp-solve: error: --cone: " << e.what() << "\n";
              return 2;
            }
        }
      else if (a == "--threads" && i + 1 < argc)
        {
          char      *end = nullptr;
          const long t   = std::strtol(argv[++i], &end, 10);
          if (*end != '\0' || t < 1 || t > 1024)
            {
              std::cerr
                << "lcp-solve: error: --threads needs an integer >= 1\n";
              return 2;
            }
          blas_threads = static_cast<unsigned int>(t);
        }
      else if (a == "--route" && i + 1 < argc)
        {
          const std::string route = argv[++i];
          try
            {
              cone_options.route =
                route == "auto" ? ExactConeRoute::interior_point_then_facets :
                                  exact_cone_route_from_string(route);
            }
          catch (const std::invalid_argument &e)
            {
              std::cerr << "lcp-solve: error: --route: " << e.what()
                        << " (or auto)\n";
              return 2;
            }
        }
      else if (a == "--tolerance" && i + 1 < argc)
        {
          char *end              = nullptr;
          cone_options.tolerance = std::strtod(argv[++i], &end);
          if (*end != '\0' || !(cone_options.tolerance > 0.))
            {
              std::cerr << "lcp-solve: error: --tolerance needs a number > 0\n";
              return 2;
            }
        }
      else if (a == "--facets" && i + 1 < argc)
        {
          char      *end = nullptr;
          const long k   = std::strtol(argv[++i], &end, 10);
          if (*end != '\0' || k < 2 || k > 10000)
            {
              std::cerr << "lcp-solve: error: --facets needs an integer >= 2\n";
              return 2;
            }
          options.n_facets = static_cast<unsigned int>(k);
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
  impactfe::set_blas_thread_limit(blas_threads);
  if (files.empty())
    {
      usage(std::cerr);
      return 2;
    }
  if (!fclib_output.empty() && files.size() != 1)
    {
      std::cerr << "lcp-solve: error: --write-fclib needs exactly one input "
                   "file, "
                << files.size() << " given\n";
      return 2;
    }

  // The first solve of a process binds symbols and touches pages of the
  // libraries (about 1 ms): made once here, on a one-contact problem, so
  // that the seconds printed are the problems' own.
  if (cone == ConeModel::exact)
    {
      ContactProblem warm_up;
      warm_up.n_directions = 3;
      warm_up.n_contacts   = 1;
      warm_up.W            = DenseMatrix(3, 3);
      warm_up.W(0, 0) = warm_up.W(1, 1) = warm_up.W(2, 2) = 1.;
      warm_up.free_velocity                               = {-1., 1., 0.};
      warm_up.gap_term                                    = {0.};
      warm_up.mu                                          = {0.5};
      solve_exact_cone_by_groups(warm_up, options, cone_options);
    }

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
          const auto t0 = std::chrono::steady_clock::now();
          // the seconds of the solve, before anything is printed
          auto seconds_since_start = [&t0]() {
            return std::chrono::duration<double>(
                     std::chrono::steady_clock::now() - t0)
              .count();
          };
          double              seconds = 0.;
          Result              r;
          std::size_t         n = 0;
          std::vector<double> P;
          if (f.type == ProblemType::lcp)
            {
              n = f.lcp.q.size();
              if (warm)
                {
                  std::vector<bool> guess(n);
                  for (std::size_t i = 0; i < n; ++i)
                    guess[i] = f.lcp.q[i] < 0.;
                  r = solve_lemke_warm(f.lcp.M, f.lcp.q, guess, options.lemke);
                }
              else
                r = solve_lemke(f.lcp.M, f.lcp.q, options.lemke);
              seconds = seconds_since_start();
              // A ray does not say whether the LCP has a solution unless M is
              // copositive-plus; an infeasible LCP has none.
              if (r.status == Status::ray_termination &&
                  lcp_feasibility(f.lcp.M, f.lcp.q, options.lemke) ==
                    Status::ray_termination)
                {
                  r.status = Status::infeasible;
                  r.message +=
                    "; no z >= 0 with M z + q >= 0 (Lemke's ray on the LCP of that linear "
                    "program): the LCP has no solution";
                }
            }
          else
            {
              const ContactProblem    &p = f.contact;
              ContactSolution          s;
              GroupedExactConeSolution exact;
              if (cone == ConeModel::exact)
                {
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
                                   "reached: cone error %.3e > tolerance "
                                   "%.1e (%s)\n",
                                   file.c_str(),
                                   exact.report.cone_error,
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
                  double d2 = 0., r2 = 0.;
                  for (std::size_t k = 0; k < P.size(); ++k)
                    {
                      d2 += (P[k] - file_solution.r[k]) *
                            (P[k] - file_solution.r[k]);
                      r2 += file_solution.r[k] * file_solution.r[k];
                    }
                  std::printf(" file_solution_exact_cone_error %.3e",
                              exact_cone_error(f.contact, file_solution.r));
                  if (!P.empty() && r2 > 0.)
                    std::printf(" relative_difference %.3e",
                                std::sqrt(d2 / std::max(r2, 1e-300)));
                }
              std::printf("\n");
            }
          if (!fclib_output.empty())
            {
              FclibSolution s;
              if (!P.empty())
                {
                  s.r = P;
                  f.contact.W.vmult(s.u, P);
                  for (std::size_t k = 0; k < s.u.size(); ++k)
                    s.u[k] += f.contact.free_velocity[k];
                  for (unsigned int c = 0; c < f.contact.n_contacts; ++c)
                    s.u[c * f.contact.n_directions] += f.contact.gap_term[c];
                }
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
          std::cerr << "lcp-solve: error: " << e.what() << std::endl;
          exit_code = 2;
        }
    }
  return exit_code;
}
