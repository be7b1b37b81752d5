/* ---------------------------------------------------------------------
 *
 * two_bars_1d: the impact of two identical elastic bars in 1D
 * (Vola, Pratt, Jean, Raous, section 6.1.1; Carpenter, Taylor and Katona
 * 1991), with the four time schemes of impactfe.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// Bar 1 moves at the impact velocity $v_0$ towards bar 2, at rest. When the
// gap closes at $t_0 = g_0 / v_0$, a compression wave runs into each bar at
// the speed $c = \sqrt{E/\rho}$. For identical bars the exact solution is
// known: during $t_0 \le t \le t_0 + 2L/c$ the interface moves at $v_0/2$
// and carries the stress $\rho c v_0 / 2$; afterwards bar 1 is at rest and
// bar 2 moves at $v_0$. All the energy passes from bar 1 to bar 2.
//
// The bars are discretised with P1 elements, each bar its own mesh. One
// contact candidate pairs bar 1's right end with bar 2's left end
// (node-to-node). Each time step, the library condenses the dynamics on
// that candidate and solves a one-row LCP with Lemke's method.
//
// The program compares the computed contact velocity and contact force with
// the exact solution and prints the normalised errors
// @f[
//   \mathrm{err}_v = \frac{1}{N}\sum_i \frac{|v_c(t_i) - v_c^{ex}(t_i)|}{v_0/2},
//   \qquad
//   \mathrm{err}_f = \frac{1}{N}\sum_i \frac{|F(t_i) - F^{ex}(t_i)|}{\rho c v_0 A/2},
// @f]
// and the ratio of the final to the initial energy.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/output/output.h>
#include <impactfe/time_integration/time_integrator.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>

namespace TwoBars1D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{Parameters}
  //
  // The scene's own subsections, `Geometry` and `Initial conditions`; the
  // others (`Material`, `Discretization`, `Time stepping`, `Contact solver`,
  // `Output`) are the library's.
  struct GeometryParameters
  {
    double       bar_length         = 0.254;
    unsigned int n_cells_per_bar    = 20;
    double       initial_gap        = 0.;
    double       cross_section_area = 6.4516e-4;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Bar length", "0.254", Patterns::Double(), "Length L of each bar [m]. Must be > 0.");
      prm.declare_entry("Number of cells per bar",
                        "20",
                        Patterns::Integer(1),
                        "Number of P1 elements in each bar [-].");
      prm.declare_entry("Initial gap",
                        "0",
                        Patterns::Double(),
                        "Distance between the bars at t = 0 [m]. Must be >= 0.");
      prm.declare_entry("Cross-section area",
                        "6.4516e-4",
                        Patterns::Double(),
                        "Cross-section area A of the bars [m^2]; scales "
                        "masses, forces and energies. Must be > 0.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      bar_length         = prm.get_double("Bar length");
      n_cells_per_bar    = prm.get_integer("Number of cells per bar");
      initial_gap        = prm.get_double("Initial gap");
      cross_section_area = prm.get_double("Cross-section area");
      prm.leave_subsection();
      AssertThrow(bar_length > 0.,
                  ExcMessage("Geometry: 'Bar length' must be > 0, got " +
                             format_number(bar_length) + "."));
      AssertThrow(initial_gap >= 0.,
                  ExcMessage("Geometry: 'Initial gap' must be >= 0, got " +
                             format_number(initial_gap) + "."));
      AssertThrow(cross_section_area > 0.,
                  ExcMessage("Geometry: 'Cross-section area' must be > 0, "
                             "got " +
                             format_number(cross_section_area) + "."));
    }
  };



  struct InitialConditions
  {
    double impact_velocity = 5.13588;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Impact velocity",
                        "5.13588",
                        Patterns::Double(),
                        "Velocity v0 of bar 1 towards bar 2 at t = 0 [m/s]. "
                        "Must be > 0.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      impact_velocity = prm.get_double("Impact velocity");
      prm.leave_subsection();
      AssertThrow(impact_velocity > 0.,
                  ExcMessage("Initial conditions: 'Impact velocity' must be "
                             "> 0, got " +
                             format_number(impact_velocity) + "."));
    }
  };



  // @sect3{Acceptance bounds}
  //
  // Optional bounds on the errors and the energy ratio: the program says
  // whether each holds and exits with a non-zero code if one does not. The
  // tests use them; a user can use them for regression runs.
  struct VerificationParameters
  {
    double max_err_v = -1., max_err_f = -1.;
    double min_energy_ratio = -1., max_energy_ratio = -1.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      prm.declare_entry("Maximum err_v", "-1", Patterns::Double(),
                        "Fail the run if err_v exceeds this [-]. -1: no check.");
      prm.declare_entry("Maximum err_f", "-1", Patterns::Double(),
                        "Fail the run if err_f exceeds this [-]. -1: no check.");
      prm.declare_entry("Minimum energy ratio", "-1", Patterns::Double(),
                        "Fail the run if the final/initial energy is below "
                        "this [-]. -1: no check.");
      prm.declare_entry("Maximum energy ratio", "-1", Patterns::Double(),
                        "Fail the run if the final/initial energy exceeds "
                        "this [-]. -1: no check.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      max_err_v        = prm.get_double("Maximum err_v");
      max_err_f        = prm.get_double("Maximum err_f");
      min_energy_ratio = prm.get_double("Minimum energy ratio");
      max_energy_ratio = prm.get_double("Maximum energy ratio");
      prm.leave_subsection();
    }
  };



  // @sect3{The exact solution}
  //
  // Piecewise constant in time at the contact nodes; used for the errors,
  // the history columns `exact_*` and the plots.
  struct ExactSolution
  {
    double v0, t_contact, duration, contact_force;

    // Velocity of bar 1's contact node (lab frame).
    double
    contact_velocity(const double t) const
    {
      return t < t_contact ? v0 : (t < t_contact + duration ? 0.5 * v0 : 0.);
    }
    // Velocity of bar 2's contact node.
    double
    target_velocity(const double t) const
    {
      return v0 - contact_velocity(t);
    }
    double
    normal_force(const double t) const
    {
      return (t >= t_contact && t < t_contact + duration) ? contact_force : 0.;
    }
  };



  // @sect3{The TwoBarsProblem class}
  class TwoBarsProblem
  {
  public:
    TwoBarsProblem(const std::string &parameter_file);
    void
    run();

  private:
    void
    setup_system();
    void
    assemble_system();
    StepReport
    do_time_step();
    void
    output_results(const StepReport &report);
    void
    report_results();

    GeometryParameters       geometry;
    InitialConditions        initial_conditions;
    MaterialParameters       material;
    DiscretizationParameters discretization;
    TimeSteppingParameters   time_stepping;
    ContactSolverParameters  solver_parameters;
    OutputParameters         output;
    VerificationParameters   verification;
    std::string              parameter_file_name;
    bool                     verification_failed = false;

    std::unique_ptr<ElasticBody<1>>     bar_1, bar_2;
    std::unique_ptr<MultibodySystem<1>> system;
    std::unique_ptr<HistoryWriter>      history;
    std::unique_ptr<SolutionWriter<1>>  solution_writer;
    ExactSolution                       exact;

    // DoFs of the two contact nodes, for the history.
    types::global_dof_index contact_dof_1 = 0, contact_dof_2 = 0;

    // Accumulated errors and contact times.
    double       sum_error_v = 0., sum_error_f = 0.;
    unsigned int n_steps_done = 0;
    double       first_contact = -1., last_contact = -1.;
    double       initial_energy = 0.;
    double       setup_cpu_time = 0., loop_cpu_time = 0.;
  };



  // @sect4{Constructor: reading the parameter file}
  //
  // Every entry is declared with its pattern before the file is read, so a
  // misspelt entry or a value outside its pattern is reported by
  // ParameterHandler with the line number; the checks that patterns cannot
  // express (theta in (0, 1], h > 0, ...) are in each parse_parameters().
  TwoBarsProblem::TwoBarsProblem(const std::string &parameter_file)
    : parameter_file_name(parameter_file)
  {
    ParameterHandler prm;
    GeometryParameters::declare_parameters(prm);
    MaterialParameters::declare_parameters(prm, 1);
    InitialConditions::declare_parameters(prm);
    DiscretizationParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    ContactSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm, "results/two_bars_1d");
    VerificationParameters::declare_parameters(prm);

    AssertThrow(std::filesystem::exists(parameter_file),
                ExcMessage("The parameter file '" + parameter_file +
                           "' does not exist."));
    prm.parse_input(parameter_file);

    geometry.parse_parameters(prm);
    material.parse_parameters(prm, 1);
    initial_conditions.parse_parameters(prm);
    discretization.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    solver_parameters.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
  }



  // @sect4{TwoBarsProblem::setup_system}
  //
  // Two meshes: bar 1 on $[-L-g_0, -g_0]$, bar 2 on $[0, L]$. With
  // `colorize`, the left end of each gets boundary id 0 and the right end
  // id 1. The contact normal points from bar 2 towards bar 1, i.e. along
  // $-x$, so that the gap is $g = (x_1 - x_2)\cdot n \ge 0$.
  void
  TwoBarsProblem::setup_system()
  {
    const double L  = geometry.bar_length;
    const double g0 = geometry.initial_gap;
    bar_1 = std::make_unique<ElasticBody<1>>("bar_1",
                                             material,
                                             discretization,
                                             geometry.cross_section_area);
    bar_2 = std::make_unique<ElasticBody<1>>("bar_2",
                                             material,
                                             discretization,
                                             geometry.cross_section_area);
    GridGenerator::subdivided_hyper_rectangle(bar_1->triangulation(),
                                              std::vector<unsigned int>{geometry.n_cells_per_bar},
                                              Point<1>(-L - g0),
                                              Point<1>(-g0),
                                              /*colorize=*/true);
    GridGenerator::subdivided_hyper_rectangle(bar_2->triangulation(),
                                              std::vector<unsigned int>{geometry.n_cells_per_bar},
                                              Point<1>(0.),
                                              Point<1>(L),
                                              /*colorize=*/true);
    assemble_system();

    system =
      std::make_unique<MultibodySystem<1>>(time_stepping, solver_parameters);
    system->add_body(*bar_1);
    system->add_body(*bar_2);
    system->contacts().add_node_to_node(system->bodies(),
                                        /*body_a=*/0,
                                        /*boundary_a=*/1,
                                        /*body_b=*/1,
                                        /*boundary_b=*/0,
                                        Tensor<1, 1>({-1.}));

    // Initial state: bar 1 moves at v0, bar 2 rests, no deformation.
    bar_1->fill_uniform(system->state().velocity.block(0),
                        Tensor<1, 1>({initial_conditions.impact_velocity}));

    const ContactCandidate &candidate = system->contacts().candidate(0);
    contact_dof_1 = bar_1->vertex_dof(candidate.vertex_a, 0);
    contact_dof_2 = bar_2->vertex_dof(candidate.vertex_b, 0);

    create_output_directory(output.directory);
    system->set_dump_directory(output.directory);
    system->setup();

    const double c = material.longitudinal_wave_speed<1>();
    const double v0 = initial_conditions.impact_velocity;
    exact = {v0,
             g0 / v0,
             2. * L / c,
             0.5 * material.density * c * v0 * geometry.cross_section_area};
    initial_energy = system->kinetic_energy() + system->elastic_energy();
  }



  // @sect4{TwoBarsProblem::assemble_system}
  // Mass, stiffness and (if any) damping of each bar.
  void
  TwoBarsProblem::assemble_system()
  {
    bar_1->setup();
    bar_2->setup();
  }



  // @sect4{TwoBarsProblem::do_time_step}
  // One step of the chosen scheme; the errors against the exact solution
  // are accumulated at each step's end time.
  StepReport
  TwoBarsProblem::do_time_step()
  {
    const StepReport report = system->do_time_step();
    const double     t      = report.time;
    const double     v_c    = system->state().velocity.block(0)(contact_dof_1);
    sum_error_v += std::abs(v_c - exact.contact_velocity(t)) / (0.5 * exact.v0);
    sum_error_f +=
      std::abs(report.normal_force - exact.normal_force(t)) / exact.contact_force;
    ++n_steps_done;
    if (report.normal_force > 0.)
      {
        if (first_contact < 0.)
          first_contact = t;
        last_contact = t;
      }
    return report;
  }



  // @sect4{TwoBarsProblem::output_results}
  void
  TwoBarsProblem::output_results(const StepReport &report)
  {
    const auto  &state = system->state();
    const double t     = state.time;
    history->add_row({t,
                      report.normal_force,
                      report.tangential_force,
                      double(report.active_contacts),
                      double(report.lcp_size),
                      double(report.lcp_pivots),
                      system->kinetic_energy(),
                      system->elastic_energy(),
                      system->momentum(0)[0] + system->momentum(1)[0],
                      state.velocity.block(0)(contact_dof_1),
                      state.velocity.block(1)(contact_dof_2),
                      exact.contact_velocity(t),
                      exact.normal_force(t)});
    if (output.vtu_output && report.step % output.output_interval == 0)
      solution_writer->write(*system, report.step);
  }



  // @sect4{TwoBarsProblem::report_results}
  // The screen report and summary.json. Everything printed is measured in
  // this run; CPU times and pivot counts only if asked for, so that tests
  // can compare the screen output.
  void
  TwoBarsProblem::report_results()
  {
    const double err_v = sum_error_v / n_steps_done;
    const double err_f = sum_error_f / n_steps_done;
    const double energy_ratio =
      (system->kinetic_energy() + system->elastic_energy()) / initial_energy;

    std::cout << "Two elastic bars in 1D, scheme " << to_string(time_stepping.scheme);
    if (time_stepping.scheme == Scheme::newmark)
      std::cout << " (beta = " << time_stepping.newmark_beta
                << ", gamma = " << time_stepping.newmark_gamma << ")";
    else
      std::cout << " (theta = " << time_stepping.theta << ")";
    std::cout << ", h = " << time_stepping.time_step << " s, " << n_steps_done
              << " steps, " << geometry.n_cells_per_bar << " cells per bar"
              << std::endl;
    std::cout << "  Courant number c h / dx = "
              << material.longitudinal_wave_speed<1>() * time_stepping.time_step /
                   (geometry.bar_length / geometry.n_cells_per_bar)
              << std::endl;
    std::cout << "  Contact force > 0 from t = " << first_contact
              << " s to t = " << last_contact << " s (exact: "
              << exact.t_contact << " s to " << exact.t_contact + exact.duration
              << " s)" << std::endl;
    std::cout << "  err_v = " << err_v << ", err_f = " << err_f
              << ", energy_ratio = " << energy_ratio << std::endl;

    const auto check = [this](const std::string &what,
                              const double       value,
                              const std::string &relation,
                              const double       bound) {
      if (bound < 0.)
        return;
      const bool ok = relation == "<=" ? value <= bound : value >= bound;
      std::cout << "  Check " << what << " " << relation << " "
                << std::setprecision(12) << bound << std::setprecision(6)
                << ": " << (ok ? "OK" : "FAILED") << std::endl;
      verification_failed = verification_failed || !ok;
    };
    check("err_v", err_v, "<=", verification.max_err_v);
    check("err_f", err_f, "<=", verification.max_err_f);
    check("energy_ratio", energy_ratio, ">=", verification.min_energy_ratio);
    check("energy_ratio", energy_ratio, "<=", verification.max_energy_ratio);

    JsonObject lcp;
    lcp.add("total_pivots", double(system->total_pivots()))
      .add("largest_lcp", double(system->largest_lcp()))
      .add("failures", 0.);
    JsonObject summary;
    summary.add("program", std::string("two_bars_1d"))
      .add("scheme", to_string(time_stepping.scheme))
      .add("theta", time_stepping.theta)
      .add("time_step", time_stepping.time_step)
      .add("n_steps", double(n_steps_done))
      .add("cells_per_bar", double(geometry.n_cells_per_bar))
      .add("setup_cpu_seconds", setup_cpu_time)
      .add("loop_cpu_seconds", loop_cpu_time)
      .add("lcp", lcp)
      .add("err_v", err_v)
      .add("err_f", err_f)
      .add("energy_ratio", energy_ratio);
    summary.write(output.directory + "/summary.json");

    if (output.print_performance)
      std::cout << "  CPU seconds: set-up " << setup_cpu_time << ", time loop "
                << loop_cpu_time << "; LCP: " << system->total_pivots()
                << " pivots in total, largest LCP " << system->largest_lcp()
                << std::endl;

    std::cout << "Results in " << output.directory
              << "/: history.csv, summary.json";
    if (output.vtu_output)
      std::cout << ", solution.pvd (VTU files)";
    std::cout << std::endl;
    if (output.plot)
      {
        std::string why_not;
        const std::string png =
          plot_history(output.directory + "/history.csv",
                       output.directory + "/history.png",
                       {"contact_velocity", "normal_force"},
                       "Two bars 1D, " + to_string(time_stepping.scheme),
                       why_not);
        if (png.empty())
          std::cout << "No plot: " << why_not << std::endl;
        else
          std::cout << "Plot: " << png << std::endl;
      }
  }



  // @sect4{TwoBarsProblem::run}
  void
  TwoBarsProblem::run()
  {
    CpuStopwatch setup_timer;
    setup_timer.start();
    setup_system();
    history = std::make_unique<HistoryWriter>(
      output.directory + "/history.csv",
      std::vector<std::string>{"time",
                               "normal_force",
                               "tangential_force",
                               "active_contacts",
                               "lcp_size",
                               "lcp_pivots",
                               "kinetic_energy",
                               "elastic_energy",
                               "momentum_x",
                               "contact_velocity",
                               "target_contact_velocity",
                               "exact_contact_velocity",
                               "exact_normal_force"});
    solution_writer = std::make_unique<SolutionWriter<1>>(output.directory);
    output_results(StepReport());
    setup_timer.stop();
    setup_cpu_time = setup_timer.seconds();

    // The time loop is timed on its own (output excluded), so that schemes
    // can be compared by it.
    CpuStopwatch       loop_timer;
    const unsigned int n_steps = time_stepping.n_steps();
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        loop_timer.start();
        const StepReport report = do_time_step();
        loop_timer.stop();
        output_results(report);
      }
    loop_cpu_time = loop_timer.seconds();
    history.reset();
    report_results();
    AssertThrow(!verification_failed,
                ExcMessage("Verification: at least one bound of subsection "
                           "'Verification' does not hold (see above)."));
  }
} // namespace TwoBars1D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      const std::string parameter_file =
        argc > 1 ? argv[1] :
                   std::string(IMPACTFE_SOURCE_DIR) +
                     "/parameter_files/two_bars_1d.prm";
      if (argc > 2)
        {
          std::cerr << "Usage: " << argv[0] << " [parameter file]" << std::endl;
          return 1;
        }
      TwoBars1D::TwoBarsProblem problem(parameter_file);
      problem.run();
    }
  catch (std::exception &exc)
    {
      return impactfe::report_exception(exc);
    }
  catch (...)
    {
      return impactfe::report_unknown_exception();
    }
  return 0;
}
