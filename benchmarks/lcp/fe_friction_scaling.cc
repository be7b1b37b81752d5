// Cold vs warm solves of the frictional contact LCP on real finite element
// Delassus operators (issue 3).
//
// The scene: a thin elastic block (plane strain, Q1, n_c - 1 by 2 square
// cells of side dx) lies on a rigid plane y = 0 with Coulomb friction
// (mu = 0.3) and is thrown onto it, down and sideways, with the velocity
// (v_t, -v_n (0.2 + 1.6 x / L)) (harder at the right end, so that some
// contacts stick and some slip). Every node of the bottom face is a contact
// candidate, so the LCP has n_c contacts. MultibodySystem<2> builds the
// Delassus operator W = H^T M~^{-1} H in setup() (one sparse solve per column)
// and advances a few steps of the theta-Euler scheme; its own LCP solves are
// warm started.
//
// After each step the step's contact problem is rebuilt from what the
// system exposes, on all candidates:
//   W (delassus_operator()), b_N (the scheme's gap term at the start of the
//   step), P (impulses()) and V = H^T v^{i+1}, so that V_free = V - W P,
// and solved twice with the LCP module:
//   cold: solve_contact_problem(problem): Lemke's method on the Klarbring
//         form (size 3 n_c) from the all-slack basis;
//   warm: solve_contact_problem(problem, {}, states): the contact states of
//         the previous step's warm solution (open / stick / slip+ / slip-),
//         block pivoting on W, Lemke only if that fails;
//   open: the same from "all open" (no history, as in the time loop's first
//         contact step).
// All must be solved and verified, and give the same impulses (relative
// difference <= 1e-8, checked; the program exits with 1 otherwise).
//
// Output: one CSV row per (n_c, step) on stdout (or the file given with
// --csv), and a summary on stderr. Seconds are CPU seconds of the (single)
// thread, so that other processes on the machine do not inflate them. Not a
// test: timings depend on the machine.
//
//   fe_friction_scaling [--steps S] [--cold-steps C] [--csv FILE] [--dump DIR]
//                       [--youngs-modulus E] [--tangential-speed v_t]
//                       [--body-force f] [n_c ...]
//
// --cold-steps C: solve cold only in the first C steps after the first one
// (cold Lemke on thousands of contacts takes minutes); default all.
// --dump DIR: write the contact problem of step 2 of each size to
// DIR/fe_friction_<n_c>_step_2.dat (Siconos format, for lcp-solve).
// cold_assembly_seconds: the Klarbring LCP assembly alone (a separate call;
// it is part of cold_seconds too).
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/contact/contact_set.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/problem_io.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

using namespace impactfe;

namespace
{
  double
  seconds_since(const double start)
  {
    return thread_cpu_seconds() - start;
  }


  /// max |a - b| over the impulse scale of lcp::verify_contact_solution():
  /// max(||b||, (||V_free|| + ||b_N||) / ||W||).
  double
  relative_difference(const lcp::ContactProblem &p,
                      const std::vector<double> &a,
                      const std::vector<double> &b)
  {
    double d = 0.;
    for (std::size_t i = 0; i < a.size(); ++i)
      d = std::max(d, std::abs(a[i] - b[i]));
    const double scale = std::max(lcp::linfty_norm(b),
                                  (lcp::linfty_norm(p.free_velocity) +
                                   lcp::linfty_norm(p.gap_term)) /
                                    p.W.linfty_norm());
    return d / scale;
  }

  /// The scene's parameters (SI units).
  struct Scene
  {
    double cell_size        = 0.01;  // dx [m]
    double youngs_modulus   = 1e6;   // [Pa]
    double density          = 1000.; // [kg/m^3]
    double poissons_ratio   = 0.3;
    double mu               = 0.3;
    double normal_speed     = 1.;   // v_n [m/s], downwards
    double tangential_speed = 0.3;  // v_t [m/s], along +x
    double time_step        = 1e-4; // h [s]; P-wave speed 37 m/s: c h = 0.37 dx
    double downward_body_force = 0.; // [N/m^3], presses the block down
  };

  struct StepRow
  {
    unsigned int n_contacts = 0, step = 0, lcp_size = 0;
    double       setup_seconds         = 0.;
    bool         cold_done             = false;
    unsigned int cold_pivots           = 0;
    double       cold_seconds          = 0.;
    double       cold_assembly_seconds = 0.; // Klarbring LCP assembly alone
    std::string  warm_path;
    unsigned int warm_pivots = 0, warm_block_iterations = 0, warm_lcp_size = 0;
    double       warm_seconds = 0.;
    // block pivoting from "all open" (no history: the time loop's first step)
    std::string  open_path;
    unsigned int open_pivots = 0, open_block_iterations = 0;
    double       open_seconds = 0.;
    unsigned int n_open = 0, n_stick = 0, n_slip = 0;
    double       difference = 0.; // max |P_cold - P_warm| / impulse scale
    double       system_difference = 0.; // the system's P against the warm one
    double       open_difference   = 0.; // from all open against warm
  };



  /// One block of n_c bottom nodes, a few steps. Rows are appended.
  bool
  run(const unsigned int    n_contacts,
      const unsigned int    n_steps,
      const unsigned int    cold_steps,
      const Scene          &scene,
      const std::string    &dump_directory,
      std::vector<StepRow> &rows)
  {
    MaterialParameters material;
    material.youngs_modulus = scene.youngs_modulus;
    material.density        = scene.density;
    material.poissons_ratio = scene.poissons_ratio;
    material.plane_model    = PlaneModel::plane_strain;
    DiscretizationParameters discretization;

    const auto     setup_start = thread_cpu_seconds();
    ElasticBody<2> block("block", material, discretization, /*thickness=*/1.);
    // colorize: the face y = 0 gets boundary id 2
    GridGenerator::subdivided_hyper_rectangle(
      block.triangulation(),
      std::vector<unsigned int>{n_contacts - 1, 2},
      Point<2>(0., 0.),
      Point<2>((n_contacts - 1) * scene.cell_size, 2. * scene.cell_size),
      /*colorize=*/true);
    block.setup();
    if (scene.downward_body_force != 0.)
      block.set_body_force(Tensor<1, 2>({0., -scene.downward_body_force}));

    TimeSteppingParameters time_stepping;
    time_stepping.scheme    = Scheme::theta_euler;
    time_stepping.theta     = 0.55;
    time_stepping.time_step = scene.time_step;
    time_stepping.end_time  = n_steps * scene.time_step;
    ContactSolverParameters solver_parameters;
    solver_parameters.warm_start = true;

    MultibodySystem<2> system(time_stepping, solver_parameters);
    system.add_body(block);
    system.contacts() = ContactSet(/*n_directions=*/2);
    const unsigned int n_added =
      system.contacts().add_node_to_plane(system.bodies(),
                                          0,
                                          /*boundary_id=*/2,
                                          Point<2>(0., 0.),
                                          Tensor<1, 2>({0., 1.}),
                                          scene.mu);
    AssertThrow(n_added == n_contacts, ExcInternalError());
    // v = (v_t, -v_n (0.2 + 1.6 x / L)): the left end lands softly, the right
    // end hard, so that the normal impulses vary along the face and the
    // contacts stick where they are large and slip where they are small.
    {
      Vector<double>              &velocity = system.state().velocity.block(0);
      const std::vector<Point<2>> &vertices =
        block.triangulation().get_vertices();
      const double length = (n_contacts - 1) * scene.cell_size;
      for (unsigned int v = 0; v < vertices.size(); ++v)
        {
          velocity(block.vertex_dof(v, 0)) = scene.tangential_speed;
          velocity(block.vertex_dof(v, 1)) =
            -scene.normal_speed * (0.2 + 1.6 * vertices[v][0] / length);
        }
    }
    system.setup();
    const double setup_seconds = seconds_since(setup_start);

    const ContactSet       &contacts = system.contacts();
    const lcp::DenseMatrix &W        = system.delassus_operator();
    lcp::ContactProblem     problem;
    problem.n_directions = 2;
    problem.n_contacts   = n_contacts;
    problem.W            = W;
    problem.mu.assign(n_contacts, scene.mu);

    std::vector<impactfe::ContactState> states(n_contacts,
                                               impactfe::ContactState::open);
    std::vector<double>                 V, WP;
    bool                                all_good = true;
    for (unsigned int step = 1; step <= n_steps; ++step)
      {
        system.integrator().gap_term(contacts,
                                     system.state(),
                                     problem.gap_term);
        system.do_time_step();
        contacts.local_velocities(system.state().velocity, V);
        const std::vector<double> &P_system = system.impulses();
        W.vmult(WP, P_system);
        problem.free_velocity.resize(V.size());
        for (std::size_t i = 0; i < V.size(); ++i)
          problem.free_velocity[i] = V[i] - WP[i];

        StepRow row;
        row.n_contacts    = n_contacts;
        row.step          = step;
        row.setup_seconds = setup_seconds;

        // warm: the states of the previous step
        auto                       start = thread_cpu_seconds();
        const lcp::ContactSolution warm =
          lcp::solve_contact_problem(problem, {}, states);
        row.warm_seconds          = seconds_since(start);
        row.warm_path             = lcp::to_string(warm.lcp.start_path);
        row.warm_pivots           = warm.lcp.pivots;
        row.warm_block_iterations = warm.block_pivoting_iterations;
        row.warm_lcp_size         = warm.lcp.z.size();
        if (warm.lcp.status != lcp::Status::solved)
          {
            std::cerr << "n_c = " << n_contacts << ", step " << step
                      << ": warm solve failed: " << warm.message << "\n";
            return false;
          }
        const lcp::ContactVerification check =
          lcp::verify_contact_solution(problem, warm.P);
        row.n_open            = check.n_separated;
        row.n_stick           = check.n_sticking;
        row.n_slip            = check.n_sliding;
        all_good              = all_good && check.ok;
        row.system_difference = relative_difference(problem, P_system, warm.P);

        // no history: block pivoting from "all open"
        start                                = thread_cpu_seconds();
        const lcp::ContactSolution from_open = lcp::solve_contact_problem(
          problem,
          {},
          std::vector<impactfe::ContactState>(n_contacts,
                                              impactfe::ContactState::open));
        row.open_seconds          = seconds_since(start);
        row.open_path             = lcp::to_string(from_open.lcp.start_path);
        row.open_pivots           = from_open.lcp.pivots;
        row.open_block_iterations = from_open.block_pivoting_iterations;
        if (from_open.lcp.status != lcp::Status::solved)
          {
            std::cerr << "n_c = " << n_contacts << ", step " << step
                      << ": solve from all open failed: " << from_open.message
                      << "\n";
            return false;
          }
        row.open_difference = relative_difference(problem, from_open.P, warm.P);
        all_good            = all_good && row.open_difference <= 1e-8;

        if (!dump_directory.empty() && step == 2)
          lcp::write_friction_contact_file(dump_directory + "/fe_friction_" +
                                             std::to_string(n_contacts) +
                                             "_step_2.dat",
                                           problem);

        // cold: Lemke from scratch
        row.lcp_size = 3 * n_contacts;
        if (step >= 2 && step <= 1 + cold_steps)
          {
            start = thread_cpu_seconds();
            lcp::assemble_contact_lcp(problem);
            row.cold_assembly_seconds = seconds_since(start);

            start = thread_cpu_seconds();
            const lcp::ContactSolution cold =
              lcp::solve_contact_problem(problem);
            row.cold_seconds = seconds_since(start);
            row.cold_done    = true;
            row.cold_pivots  = cold.lcp.pivots;
            row.lcp_size     = cold.lcp.z.size();
            if (cold.lcp.status != lcp::Status::solved)
              {
                std::cerr << "n_c = " << n_contacts << ", step " << step
                          << ": cold solve failed: " << cold.message << "\n";
                return false;
              }
            row.difference = relative_difference(problem, warm.P, cold.P);
            all_good       = all_good && row.difference <= 1e-8;
          }
        states = warm.states;
        rows.push_back(row);
      }
    return all_good;
  }
} // namespace



int
main(int argc, char **argv)
{
  try
    {
      unsigned int              n_steps = 5, cold_steps = 1000;
      Scene                     scene;
      std::string               csv_file, dump_directory;
      std::vector<unsigned int> sizes;
      for (int i = 1; i < argc; ++i)
        {
          const std::string a = argv[i];
          if (a == "--steps" && i + 1 < argc)
            n_steps = std::atoi(argv[++i]);
          else if (a == "--cold-steps" && i + 1 < argc)
            cold_steps = std::atoi(argv[++i]);
          else if (a == "--csv" && i + 1 < argc)
            csv_file = argv[++i];
          else if (a == "--dump" && i + 1 < argc)
            dump_directory = argv[++i];
          else if (a == "--youngs-modulus" && i + 1 < argc)
            scene.youngs_modulus = std::atof(argv[++i]);
          else if (a == "--tangential-speed" && i + 1 < argc)
            scene.tangential_speed = std::atof(argv[++i]);
          else if (a == "--body-force" && i + 1 < argc)
            scene.downward_body_force = std::atof(argv[++i]);
          else if (std::atoi(a.c_str()) >= 2)
            sizes.push_back(std::atoi(a.c_str()));
          else
            {
              std::cerr
                << "usage: fe_friction_scaling [--steps S] [--cold-steps C] [--csv FILE]\n"
                   "  [--dump DIR] [--youngs-modulus E] [--tangential-speed v_t] [--body-force f]\n"
                   "  [n_c ...]\n";
              return 2;
            }
        }
      if (sizes.empty())
        sizes = {10, 20, 50, 100, 200, 400, 700, 1000, 1500, 2000};

      std::ofstream file;
      if (!csv_file.empty())
        file.open(csv_file);
      std::ostream &out = csv_file.empty() ? std::cout : file;
      out
        << "n_contacts,step,lcp_size,setup_seconds,cold_pivots,cold_seconds,cold_assembly_seconds,warm_path,"
           "warm_lcp_size,"
           "warm_block_iterations,warm_pivots,warm_seconds,open_start_path,open_start_block_iterations,"
           "open_start_pivots,open_start_seconds,open,stick,slip,relative_difference,system_difference,"
           "open_start_difference\n";

      bool         ok = true;
      StepRow      last_row; // the largest size's last step, for RESULT
      unsigned int n_failed_sizes = 0;
      for (const unsigned int n_contacts : sizes)
        {
          std::vector<StepRow> rows;
          const bool           good =
            run(n_contacts, n_steps, cold_steps, scene, dump_directory, rows);
          ok = ok && good;
          n_failed_sizes += good ? 0 : 1;
          if (!rows.empty())
            last_row = rows.back();
          for (const StepRow &r : rows)
            {
              out << r.n_contacts << ',' << r.step << ',' << r.lcp_size << ','
                  << r.setup_seconds << ',';
              if (r.cold_done)
                out << r.cold_pivots << ',' << r.cold_seconds << ','
                    << r.cold_assembly_seconds << ',';
              else
                out << ",,,";
              out << r.warm_path << ',' << r.warm_lcp_size << ','
                  << r.warm_block_iterations << ',' << r.warm_pivots << ','
                  << r.warm_seconds << ',' << r.open_path << ','
                  << r.open_block_iterations << ',' << r.open_pivots << ','
                  << r.open_seconds << ',' << r.n_open << ',' << r.n_stick
                  << ',' << r.n_slip << ',';
              if (r.cold_done)
                out << r.difference;
              out << ',' << r.system_difference << ',' << r.open_difference
                  << '\n';
              out.flush();
              std::cerr << "n_c " << r.n_contacts << " step " << r.step
                        << ": cold "
                        << (r.cold_done ?
                              std::to_string(r.cold_pivots) + " pivots " +
                                std::to_string(r.cold_seconds) + " s" :
                              std::string("-"))
                        << ", warm " << r.warm_path << " "
                        << r.warm_block_iterations << " solves "
                        << r.warm_pivots << " pivots " << r.warm_seconds
                        << " s, from all open " << r.open_block_iterations
                        << " solves " << r.open_pivots << " pivots "
                        << r.open_seconds << " s; open/stick/slip " << r.n_open
                        << "/" << r.n_stick << "/" << r.n_slip << "; |dP| "
                        << r.difference << "\n";
            }
          if (!good)
            std::cerr << "n_c = " << n_contacts
                      << ": a check failed (see above)\n";
        }
      // one machine-readable line (after the CSV rows when they go to
      // standard output; plot_fe_friction_scaling.py skips it)
      std::cout << "RESULT contacts=" << last_row.n_contacts
                << " lcp_size=" << last_row.lcp_size
                << " warm_seconds=" << last_row.warm_seconds
                << " warm_block_iterations=" << last_row.warm_block_iterations
                << " warm_pivots=" << last_row.warm_pivots
                << " relative_difference=" << last_row.difference
                << " failed_sizes=" << n_failed_sizes << std::endl;
      return ok ? 0 : 1;
    }
  catch (const std::exception &e)
    {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
}
