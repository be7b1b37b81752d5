// Cost of a time step as the problem grows (issue 5, "Cost as problems
// grow").
//
// The scene: an elastic block (plane strain, Q1, nx by ny square cells, 1 m
// wide) thrown onto a rigid plane y = 0 with Coulomb friction (mu = 0.3),
// down and sideways, with the velocity (v_t, -v_n (0.2 + 1.6 x / L)) and
// pressed by a body force, so that the whole bottom face is in contact, part
// sticking and part sliding. Every node of the bottom face is a contact
// candidate; with --top-candidates the nodes of the top face are candidates
// too (they never come near the plane: they show what candidates that cannot
// touch cost). The theta-Euler scheme (theta = 0.55) runs a few steps.
//
// One size per process, so that the memory peak (getrusage's maximum
// resident set size) belongs to that size. Prints one CSV line (with
// --header, the header first):
//   nx, ny, n_dofs, n_candidates, n_steps,
//   assembly: mesh, DoFs, mass and stiffness matrices (ElasticBody::setup),
//   factorization: M~ and its UMFPACK factorisation (once),
//   delassus: the columns of W (one solve each, when a candidate first
//             enters an LCP), in total, and how many candidates had them,
//   free_per_step, lcp_per_step, update_per_step: means over the steps,
//   max_active, max_lcp_size, peak_rss_mb,
//   stored_columns_mb: what storing the vectors M~^{-1} H_j (as the code
//             did before the columns were computed on demand) would take,
//   factor_entries: entries of the Cholesky factor L of M~,
//   floor_rhs_seconds, floor_solve_seconds: the two kernels a step cannot
//             avoid, timed alone on the same matrices (best of 5 batches):
//             the free right-hand side F~ (FreeRhsOperator::apply) and one
//             solve pair with M~ (SparseCholesky::solve),
//   floor_update_seconds: the velocity update as each step made it, timed
//             alone and averaged over the steps: the sum of the step's k
//             stored columns M~^{-1} H_j (add_columns(), k vectors of
//             n_dofs) if it summed them, a second solve pair if it had
//             impulses and no stored sum, nothing if it had no impulse.
//             A step needs F~, the free velocity's solve pair and that
//             update: the floor its cost is compared with (issue 16).
// Seconds are CPU seconds of the thread. Not a test: timings depend on the
// machine. benchmarks/scaling/run_scaling.py runs the sweeps and plots them.
//
// --cell-size H makes the block nx H wide instead of 1 m (cells of a fixed
// size: the step then has the same Courant number at every nx).
// --method chooses the contact solver (`Contact solver/Method`): Lemke's
// method on the dense W, the matrix-free active set method, or automatic
// (the default: active set from 300 candidates on). The RESULT line gives
// its statistics and, to compare methods, the last step's normal force and
// the final kinetic energy to 15 digits.
//
// --state-lag K sets `Contact solver/Exact normal rows state lag`;
// --step-trace prints each step's wall seconds, active set and GMRES
// iterations, products and factorisations to stderr (where a run's time
// goes: doc/lcp.md, "Large contact sets").
//
//   block_scaling --nx NX --ny NY [--steps S] [--top-candidates]
//                 [--method lemke|active-set|automatic] [--cell-size H]
//                 [--state-lag K] [--step-trace] [--header]
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/contact/contact_set.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/dynamics/sparse_cholesky.h>
#include <impactfe/time_integration/free_rhs_operator.h>
#include <impactfe/utilities/column_sum.h>
#include <impactfe/utilities/program.h>

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <map>
#include <string>
#include <vector>

using namespace impactfe;

namespace
{
  double
  peak_rss_megabytes()
  {
    rusage usage;
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss / 1024.; // ru_maxrss is in kB on Linux
  }

  /// Seconds per call of @p kernel: best of 5 batches of enough calls.
  template <typename Kernel>
  double
  seconds_per_call(const Kernel &kernel)
  {
    unsigned int calls = 1;
    for (;;) // find a batch of at least 0.02 s
      {
        const double start = thread_cpu_seconds();
        for (unsigned int i = 0; i < calls; ++i)
          kernel();
        if (thread_cpu_seconds() - start >= 0.02 || calls >= (1u << 20))
          break;
        calls *= 2;
      }
    double best = 1e300;
    for (unsigned int batch = 0; batch < 5; ++batch)
      {
        const double start = thread_cpu_seconds();
        for (unsigned int i = 0; i < calls; ++i)
          kernel();
        best = std::min(best, (thread_cpu_seconds() - start) / calls);
      }
    return best;
  }



  /**
   * The floor kernels of a step of @p system's scheme on @p body, timed
   * alone: F~ and one solve pair with M~ = M + c_K K (no damping here).
   */
  void
  time_floor_kernels(const MultibodySystem<2> &system,
                     const ElasticBody<2>     &body,
                     std::size_t              &factor_entries,
                     double                   &rhs_seconds,
                     double                   &solve_seconds)
  {
    const TimeIntegrator &scheme = system.integrator();
    MechanicalOperators   operators;
    operators.mass      = {&body.mass_matrix()};
    operators.stiffness = {&body.stiffness_matrix()};
    operators.damping   = {nullptr};
    operators.external_force.reinit(
      std::vector<types::global_dof_index>{body.n_dofs()});
    operators.external_force.block(0) = body.external_force();
    FreeRhsOperator rhs_operator;
    rhs_operator.reinit(operators, scheme.free_rhs_coefficients());

    SparseMatrix<double> step_matrix(body.mass_matrix().get_sparsity_pattern());
    step_matrix.copy_from(body.mass_matrix());
    step_matrix.add(scheme.stiffness_coefficient(), body.stiffness_matrix());
    SparseCholesky cholesky;
    cholesky.factorize(step_matrix, "M~");
    factor_entries = cholesky.n_factor_entries();

    BlockVector<double> x(operators.external_force), y(x), rhs(x);
    for (unsigned int i = 0; i < x.size(); ++i)
      {
        x(i) = std::sin(1. + i);
        y(i) = std::cos(1. + i);
      }
    FreeRhsOperator::Translations translation;
    rhs_seconds =
      seconds_per_call([&]() { rhs_operator.apply(x, y, rhs, translation); });
    Vector<double> v(x.block(0));
    solve_seconds = seconds_per_call([&]() {
      cholesky.solve(v);
      v *= 1e-3; // keep the numbers in range over the repetitions
      v(0) += 1.;
    });
  }



  /**
   * The velocity update from @p n_columns stored columns of @p n_dofs
   * entries, four at a time as MultibodySystem::do_time_step() sums them.
   */
  double
  time_column_sum(const unsigned int n_columns, const std::size_t n_dofs)
  {
    std::vector<double> columns(n_columns * n_dofs), v(n_dofs, 0.);
    for (std::size_t i = 0; i < columns.size(); ++i)
      columns[i] = std::sin(1. + i);
    std::vector<double> impulses(n_columns);
    for (unsigned int j = 0; j < n_columns; ++j)
      impulses[j] = 1e-3 * std::cos(1. + j);
    std::vector<const double *> column(n_columns);
    for (unsigned int j = 0; j < n_columns; ++j)
      column[j] = columns.data() + j * n_dofs;
    return seconds_per_call([&]() {
      for (unsigned int j = 0; j < n_columns; j += 4)
        add_columns(v.data(),
                    n_dofs,
                    impulses.data() + j,
                    column.data() + j,
                    std::min(4u, n_columns - j));
      // (each call adds at most 1e-3 n_columns to an entry: in range over
      // the repetitions)
    });
  }



  void
  run(const unsigned int nx,
      const unsigned int ny,
      const unsigned int n_steps,
      const bool         top_candidates,
      const std::string &method,
      const double       given_cell_size,
      const int          state_lag,
      const bool         step_trace)
  {
    // [m]: 1 m wide, or nx cells of the given size
    const double cell_size = given_cell_size > 0. ? given_cell_size : 1. / nx;
    const double width     = nx * cell_size;
    const double mu        = 0.3;
    const double v_n = 1., v_t = 0.3; // [m/s]
    const double body_force = 1e4;    // [N/m^3], presses the block down

    MaterialParameters material;
    material.youngs_modulus = 1e6; // [Pa]; P-wave speed 37 m/s
    material.density        = 1000.;
    material.poissons_ratio = 0.3;
    material.plane_model    = PlaneModel::plane_strain;
    DiscretizationParameters discretization;

    double         start = thread_cpu_seconds();
    ElasticBody<2> block("block", material, discretization, 1.);
    // colorize: y = 0 gets boundary id 2, y = top id 3
    GridGenerator::subdivided_hyper_rectangle(block.triangulation(),
                                              std::vector<unsigned int>{nx, ny},
                                              Point<2>(0., 0.),
                                              Point<2>(width, ny * cell_size),
                                              true);
    block.setup();
    block.set_body_force(Tensor<1, 2>({0., -body_force}));
    const double assembly_seconds = thread_cpu_seconds() - start;

    TimeSteppingParameters time_stepping;
    time_stepping.scheme    = Scheme::theta_euler;
    time_stepping.theta     = 0.55;
    time_stepping.time_step = 1e-4; // [s]
    time_stepping.end_time  = n_steps * time_stepping.time_step;
    ContactSolverParameters solver_parameters;
    solver_parameters.warm_start = true;
    solver_parameters.method =
      method == "lemke"      ? ContactSolverParameters::Method::lemke :
      method == "active-set" ? ContactSolverParameters::Method::active_set :
                               ContactSolverParameters::Method::automatic;
    if (state_lag >= 0)
      solver_parameters.exact_normal_rows_state_lag = state_lag;

    MultibodySystem<2> system(time_stepping, solver_parameters, 2);
    system.add_body(block);
    system.contacts().add_node_to_plane(
      system.bodies(), 0, 2, Point<2>(0., 0.), Tensor<1, 2>({0., 1.}), mu);
    if (top_candidates)
      system.contacts().add_node_to_plane(
        system.bodies(), 0, 3, Point<2>(0., 0.), Tensor<1, 2>({0., 1.}), mu);
    {
      Vector<double> &velocity = system.state().velocity.block(0);
      const auto     &vertices = block.triangulation().get_vertices();
      for (unsigned int v = 0; v < vertices.size(); ++v)
        {
          velocity(block.vertex_dof(v, 0)) = v_t;
          velocity(block.vertex_dof(v, 1)) =
            -v_n * (0.2 + 1.6 * vertices[v][0] / width);
        }
    }
    system.enable_cost_breakdown();
    system.setup();

    unsigned int max_active = 0, max_lcp_size = 0;
    // how each step updated the velocity, for the floor: steps by the
    // number of stored columns they summed, and steps that made a solve
    // pair instead (impulses without a stored sum)
    std::map<unsigned int, unsigned int> steps_by_columns_summed;
    unsigned int                         steps_with_update_solve = 0;
    StepReport                           report;
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        const auto start  = std::chrono::steady_clock::now();
        const auto before = system.active_set_statistics();
        report            = system.do_time_step();
        if (step_trace)
          {
            const auto &after = system.active_set_statistics();
            std::fprintf(
              stderr,
              "step %u: %.3f s, %llu active set iterations, %llu GMRES "
              "iterations, %llu products W x, %u factorisations of the exact "
              "normal rows, %u active contacts\n",
              step + 1,
              std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                            start)
                .count(),
              after.iterations - before.iterations,
              after.linear_iterations - before.linear_iterations,
              after.operator_applications - before.operator_applications,
              after.state_factorizations - before.state_factorizations,
              report.active_contacts);
          }
        if (report.stored_columns_summed > 0)
          ++steps_by_columns_summed[report.stored_columns_summed];
        else if (report.active_contacts > 0)
          ++steps_with_update_solve;
        max_active   = std::max(max_active, report.active_contacts);
        max_lcp_size = std::max(max_lcp_size, report.lcp_size);
      }

    const CostBreakdown &costs          = system.cost_breakdown();
    const unsigned int   n_columns      = system.contacts().n_columns();
    std::size_t          factor_entries = 0;
    double               rhs_seconds = 0., solve_seconds = 0.;
    time_floor_kernels(
      system, block, factor_entries, rhs_seconds, solve_seconds);
    const double seconds_per_step =
      (costs.free_velocity + costs.lcp + costs.update) / n_steps;
    double update_seconds = steps_with_update_solve * solve_seconds;
    for (const auto &[n_columns_summed, n_steps_summing] :
         steps_by_columns_summed)
      update_seconds +=
        n_steps_summing * time_column_sum(n_columns_summed, block.n_dofs());
    update_seconds /= n_steps;
    const double floor_per_step = rhs_seconds + solve_seconds + update_seconds;
    std::cout << nx << ',' << ny << ',' << block.n_dofs() << ','
              << system.contacts().n_candidates() << ',' << n_steps << ','
              << assembly_seconds << ',' << costs.factorization << ','
              << costs.delassus << ',' << costs.delassus_candidates << ','
              << costs.free_velocity / n_steps << ',' << costs.lcp / n_steps
              << ',' << costs.update / n_steps << ',' << max_active << ','
              << max_lcp_size << ',' << peak_rss_megabytes() << ','
              << 8. * n_columns * block.n_dofs() / (1024. * 1024.) << ','
              << factor_entries << ',' << rhs_seconds << ',' << solve_seconds
              << ',' << update_seconds << std::endl;
    // The machine-readable summary line (after the CSV row, which
    // run_scaling.py reads).
    std::cout << "RESULT dofs=" << block.n_dofs()
              << " contacts=" << system.contacts().n_candidates()
              << " max_active=" << max_active << " steps=" << n_steps
              << " seconds_per_step=" << seconds_per_step
              << " floor_seconds_per_step=" << floor_per_step
              << " step_over_floor=" << seconds_per_step / floor_per_step
              << " delassus_seconds=" << costs.delassus;
    const auto &active_set = system.active_set_statistics();
    std::cout << " ranks=1 method=" << method
              << " active_set_solves=" << active_set.solves
              << " active_set_iterations=" << active_set.iterations
              << " gmres_iterations=" << active_set.linear_iterations
              << " fallbacks=" << active_set.fallbacks;
    // How the LCPs on Lemke's route were answered (doc/lcp.md).
    const auto &paths = system.lcp_statistics();
    std::cout
      << " lemke_route_solves=" << paths.solves << " block_pivoting_solves="
      << paths
           .by_path[static_cast<unsigned int>(lcp::StartPath::block_pivoting)]
      << " block_pivoting_linear_solves=" << paths.block_pivoting_linear_solves
      << " block_pivoting_reused_factors="
      << paths.block_pivoting_reused_factors
      << " total_pivots=" << system.total_pivots();
    if (active_set.fallbacks > 0)
      std::cerr << "last fallback: " << active_set.last_fallback_reason
                << std::endl;
    if (active_set.solves > active_set.fallbacks)
      std::cout << " lcp_relative_error=" << active_set.largest_violation;
    std::cout << std::setprecision(15)
              << " last_normal_force=" << report.normal_force
              << " last_kinetic_energy=" << system.kinetic_energy()
              << std::setprecision(6) << std::endl;
  }
} // namespace



int
main(int argc, char **argv)
{
  try
    {
      unsigned int nx = 0, ny = 0, n_steps = 10;
      bool         top_candidates = false, header = false;
      std::string  method    = "automatic";
      double       cell_size = 0.;
      int          state_lag = -1;
      bool         trace     = false;
      for (int i = 1; i < argc; ++i)
        {
          const std::string a = argv[i];
          if (a == "--nx" && i + 1 < argc)
            nx = std::atoi(argv[++i]);
          else if (a == "--ny" && i + 1 < argc)
            ny = std::atoi(argv[++i]);
          else if (a == "--steps" && i + 1 < argc)
            n_steps = std::atoi(argv[++i]);
          else if (a == "--top-candidates")
            top_candidates = true;
          else if (a == "--cell-size" && i + 1 < argc)
            cell_size = std::atof(argv[++i]);
          else if (a == "--method" && i + 1 < argc)
            method = argv[++i];
          else if (a == "--header")
            header = true;
          else if (a == "--state-lag" && i + 1 < argc)
            state_lag = std::atoi(argv[++i]);
          else if (a == "--step-trace")
            trace = true;
          else
            nx = 0;
        }
      if (nx < 1 || ny < 1 || n_steps < 1 || state_lag < -1 ||
          (method != "lemke" && method != "active-set" &&
           method != "automatic"))
        {
          std::cerr
            << "usage: block_scaling --nx NX --ny NY [--steps S] "
               "[--top-candidates] [--method lemke|active-set|automatic] "
               "[--cell-size H] [--state-lag K] [--step-trace] "
               "[--header]   (NX, NY, S >= 1, K >= 0)\n";
          return 1;
        }
      if (header)
        std::cout << "nx,ny,n_dofs,n_candidates,n_steps,assembly_seconds,"
                     "factorization_seconds,delassus_seconds,"
                     "delassus_candidates,free_per_step,lcp_per_step,"
                     "update_per_step,max_active,max_lcp_size,peak_rss_mb,"
                     "stored_columns_mb,factor_entries,floor_rhs_seconds,"
                     "floor_solve_seconds,floor_update_seconds\n";
      run(nx, ny, n_steps, top_candidates, method, cell_size, state_lag, trace);
    }
  catch (std::exception &exc)
    {
      std::cerr << "\n----------------------------------------------------\n"
                << "Exception on processing: " << std::endl
                << exc.what() << std::endl
                << "Aborting!" << std::endl
                << "----------------------------------------------------"
                << std::endl;
      return 1;
    }
  return 0;
}
