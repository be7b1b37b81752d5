/* ---------------------------------------------------------------------
 * taylor_bar: a copper cylinder hits a rigid wall at 227 m/s and
 * mushrooms (the Taylor bar; the paper's section 6.4, Laursen & Simo
 * 1993). Finite-strain J2 plasticity, axisymmetric or 3D Q1 with F-bar,
 * the theta-method with Newton's method, and the contact LCP solved by
 * Lemke's method at every Newton iterate.
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// The bar (radius r0, length L0) touches the wall z = 0 at t = 0 and moves
// at -v0 e_z. The impact end deforms plastically within microseconds; at
// t = 80 us nearly all the kinetic energy is plastic work. The program
// reports the final length, the radius of the impact end (footprint), the
// largest equivalent plastic strain, Newton's iterations per step and an
// energy balance
//   E_kin(0) = E_kin + E_stored + W_plastic + D_contact + D_scheme + error,
// with D_contact the work the contact impulses take out and D_scheme =
// (theta - 1/2) sum |v1 - v0|_M^2 the theta-scheme's dissipation, both
// summed over the steps. The model (impactfe::FiniteStrainImpact,
// axisymmetric or a 3D quarter of the bar) is in doc/taylor_bar.md.
//
// Started by mpirun on several ranks, the mesh is distributed (p4est) and
// the Newton matrices are solved by MUMPS; rank 0 prints and writes the
// files, and the VTU output comes as one piece per rank with a .pvtu.

#include <deal.II/base/conditional_ostream.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <impactfe/finite_strain/finite_strain_impact.h>
#include <impactfe/output/output.h>
#include <impactfe/utilities/mpi_errors.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>

namespace TaylorBarProgram
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The TaylorBarProblem class}
  class TaylorBarProblem
  {
  public:
    void
    run(const std::string &parameter_file);

    /// Every entry of the program's parameter files.
    static void
    declare_parameters(ParameterHandler &prm);

  private:
    void
    parse_parameters(ParameterHandler &prm);
    void
    setup_system();
    void
    output_results(const FiniteStrainStepReport &report);
    void
    report_results() const;
    bool
    report_checks() const;

    /// All ranks compute every figure (the queries are collective); rank
    /// 0 prints them and writes the files.
    const MPI_Comm communicator = MPI_COMM_WORLD;
    const bool     root = Utilities::MPI::this_mpi_process(communicator) == 0;
    ConditionalOStream pcout{std::cout, root};

    FiniteStrainImpact::Settings        settings;
    MaterialParameters                  material;
    PlasticityParameters                plasticity;
    OutputParameters                    output;
    FiniteStrainImpact::Verification    verification;
    std::unique_ptr<FiniteStrainImpact> bar;
    std::unique_ptr<HistoryWriter>      history;

    unsigned int n_steps       = 0;
    double       worst_balance = 0., initial_momentum = 0.;
    double       cpu_seconds = 0.;
  };



  // @sect3{Parameters}
  //
  // The bar, the step and the wall are FiniteStrainImpact::Settings'; the
  // checks of `Verification` compare the run with results found without
  // it (see report_checks()).
  void
  TaylorBarProblem::declare_parameters(ParameterHandler &prm)
  {
    FiniteStrainImpact::Settings::declare_parameters(prm);
    FiniteStrainImpact::declare_material_parameters(prm); // copper
    PlasticityParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm, "results/taylor_bar");
    FiniteStrainImpact::Verification::declare_parameters(prm);
  }



  void
  TaylorBarProblem::parse_parameters(ParameterHandler &prm)
  {
    settings.parse_parameters(prm);
    material = FiniteStrainImpact::parse_material_parameters(prm);
    plasticity.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm, material);
    output.refuse_mesh_output("the Taylor bar's mesh comes from 'Geometry'");
    n_steps = settings.n_steps();
    output.check_shape_times(false, n_steps, settings.time_step);
  }



  // @sect3{Set-up}
  void
  TaylorBarProblem::setup_system()
  {
    bar =
      FiniteStrainImpact::create(settings, material, plasticity, communicator);
    // Rank 0 makes the directory (before any rank writes a VTU piece
    // there) and writes the files; an error there stops every rank.
    on_rank_zero(communicator, [&]() {
      create_output_directory(output.directory);
      // an earlier run's summary, final cells and VTU records: a run that
      // stops early must not leave them beside its own history, as if
      // they were its results
      remove_previous_run_output(output.directory, {"solution"}, {"solution"});
      history = std::make_unique<HistoryWriter>(
        output.directory + "/history.csv",
        Utilities::split_string_list(
          "time, length_mm, footprint_radius_mm, kinetic_energy, "
          "stored_energy, plastic_work, contact_dissipation, "
          "scheme_dissipation, energy_balance_error, normal_force, "
          "max_equivalent_plastic_strain, newton_iterations, lcp_rows"));
    });
    const unsigned int n_ranks = Utilities::MPI::n_mpi_processes(communicator);
    pcout << "Taylor bar ("
          << (settings.model == FiniteStrainImpact::Model::axisymmetric ?
                "axisymmetric" :
                "3D quarter")
          << "): " << settings.n_radial << " x " << settings.n_axial
          << " cells, " << bar->n_dofs() << " DoFs, " << n_steps << " steps of "
          << settings.time_step << " s, theta = " << settings.theta
          << (settings.f_bar ? ", F-bar" : ", plain Q1")
          << ", mu = " << settings.friction_coefficient
          << (settings.bilateral ? ", bilateral contact" : "")
          << (n_ranks > 1 ? ", " + std::to_string(n_ranks) + " MPI ranks" :
                            std::string())
          << std::endl;
    initial_momentum = bar->axial_momentum();
    bar->write_cells_csv(output.directory + "/cells_initial.csv");
  }



  // @sect3{Output at each step}
  void
  TaylorBarProblem::output_results(const FiniteStrainStepReport &report)
  {
    const FiniteStrainRunTotals &totals = bar->totals();
    const double kinetic = bar->kinetic_energy(), stored = bar->stored_energy(),
                 plastic = bar->plastic_work();
    const double balance = bar->energy_balance_error();
    worst_balance        = std::max(worst_balance, std::abs(balance));
    const double length  = bar->current_length(),
                 radius  = bar->footprint_radius(),
                 alpha   = bar->max_equivalent_plastic_strain();
    on_rank_zero(communicator, [&]() {
      history->add_row({bar->time(),
                        1e3 * length,
                        1e3 * radius,
                        kinetic,
                        stored,
                        plastic,
                        totals.contact_dissipation,
                        totals.scheme_dissipation,
                        balance,
                        report.normal_impulse / settings.time_step,
                        alpha,
                        static_cast<double>(report.newton_iterations),
                        static_cast<double>(report.n_candidates)});
    });
    const unsigned int step =
      static_cast<unsigned int>(std::llround(bar->time() / settings.time_step));
    if (output.vtu_output &&
        (step % output.output_interval == 0 || step == n_steps))
      bar->write_vtu(output.directory, step);
  }



  // @sect3{Results}
  void
  TaylorBarProblem::report_results() const
  {
    const double length            = 1e3 * bar->current_length(),
                 radius            = 1e3 * bar->footprint_radius(),
                 alpha             = bar->max_equivalent_plastic_strain();
    const FiniteStrainRunTotals &t = bar->totals();
    const double momentum_change   = bar->axial_momentum() - initial_momentum;
    // each figure once for the screen (the energies are sums over the
    // ranks); add_to_summary() queries its own
    const double kinetic = bar->kinetic_energy(), stored = bar->stored_energy(),
                 plastic = bar->plastic_work(),
                 deepest = bar->deepest_node_below_wall();
    pcout << std::setprecision(4) << "At t = " << bar->time() << " s:\n"
          << "  final length " << length
          << " mm (L0 = " << 1e3 * settings.length << " mm)\n"
          << "  footprint radius " << radius
          << " mm (r0 = " << 1e3 * settings.radius << " mm)\n"
          << "  largest equivalent plastic strain " << alpha << "\n"
          << "  energy: kinetic " << kinetic << " J, stored " << stored
          << " J, plastic work " << plastic << " J, contact "
          << t.contact_dissipation << " J, scheme " << t.scheme_dissipation
          << " J of " << bar->initial_energy() << " J\n"
          << "  largest energy balance error "
          << format_figure(worst_balance, 1e-9) << " of E_kin(0)\n"
          << "  contact: largest verification violation "
          << format_figure(t.worst_contact_violation, 1e-12)
          << ", last contact force at t = " << t.last_contact_time
          << " s, peak force " << t.peak_contact_force << " N\n"
          << "  deepest node below the wall (folded cells) "
          << format_figure(1e3 * deepest, 1e-9) << " mm\n"
          << "  wall impulse " << t.wall_impulse << " N s, change of momentum "
          << momentum_change << " N s, relative difference "
          << format_figure(std::abs(t.wall_impulse - momentum_change) /
                             std::abs(initial_momentum),
                           1e-9)
          << std::endl;
    if (t.step_reductions > 0)
      pcout << "  Steps redone as 2-8 substeps: " << t.step_reductions
            << std::endl;
    if (output.print_performance)
      pcout << "  Newton: " << t.newton_iterations_per_step()
            << " iterations per step (at most " << t.most_newton_iterations
            << "), quadratic near the solution in "
            << 100. * t.quadratic_fraction() << " %\n  CPU " << cpu_seconds
            << " s" << std::endl;
    JsonObject summary;
    summary.add("program", std::string("taylor_bar"))
      .add("ranks", Utilities::MPI::n_mpi_processes(communicator))
      .add("steps", n_steps)
      .add("energy_balance_relative_error", worst_balance)
      .add("cpu_seconds", cpu_seconds);
    bar->add_to_summary(summary, initial_momentum);
    on_rank_zero(communicator, [&]() {
      summary.write(output.directory + "/summary.json");
      history->close();
      report_output_files(
        std::cout,
        output,
        "history.csv, summary.json, cells_initial.csv, cells_final.csv" +
          std::string(output.vtu_output ? ", solution.pvd (VTU files)" : ""),
        {"length_mm", "footprint_radius_mm", "normal_force", "kinetic_energy"},
        "Taylor bar");
    });
  }



  // @sect3{Checks}
  //
  // Against what is known without the run: the wall impulse equals the
  // change of momentum (the internal forces cancel in the sum), the
  // contact solutions pass Lemke's verification, the dissipations are not
  // negative; optionally the 1D elastic rebound and the published ranges.
  bool
  TaylorBarProblem::report_checks() const
  {
    bool       ok = true;
    const auto check =
      [&](const std::string &what, const double value, const double bound) {
        const bool pass = value <= bound;
        pcout << "  Check: " << what << " = " << format_figure(value, 1e-9)
              << " <= " << bound << ": " << (pass ? "passed" : "FAILED")
              << std::endl;
        ok = ok && pass;
      };
    const FiniteStrainRunTotals &t = bar->totals();
    const double p0 = initial_momentum, dp = bar->axial_momentum() - p0;
    check("|wall impulse - change of momentum| / |p0|",
          std::abs(t.wall_impulse - dp) / std::abs(p0),
          1e-7);
    check("contact verification violation", t.worst_contact_violation, 1e-8);
    check("-(contact dissipation) / E_kin(0)",
          std::max(0., -t.contact_dissipation) / bar->initial_energy(),
          1e-9);
    if (verification.rebound_check)
      {
        const double c = std::sqrt(material.youngs_modulus / material.density);
        const double mass = material.density * numbers::PI * settings.radius *
                            settings.radius * settings.length;
        check("rebound: |contact time - 2 L0/c| / (2 L0/c)",
              std::abs(t.last_contact_time - 2. * settings.length / c) /
                (2. * settings.length / c),
              verification.max_rebound_error);
        check("rebound: |wall impulse - 2 m v0| / (2 m v0)",
              std::abs(t.wall_impulse - 2. * mass * settings.speed) /
                (2. * mass * settings.speed),
              verification.max_rebound_error);
        check("rebound: plastic work / E_kin(0)",
              bar->plastic_work() / bar->initial_energy(),
              1e-12);
      }
    const double length = bar->current_length(),
                 radius = bar->footprint_radius(),
                 alpha  = bar->max_equivalent_plastic_strain();
    if (verification.published_tolerance > 0.)
      {
        // The ranges of published finite-element results (issue 13).
        const auto outside =
          [&](const double value, const double low, const double high) {
            return std::max({0., low - value, value - high}) / low;
          };
        pcout << "  Published: length 21.42-21.7 mm, footprint 7.0-7.1 mm\n";
        check("final length: relative distance to the published range",
              outside(1e3 * length, 21.42, 21.7),
              verification.published_tolerance);
        check("footprint radius: relative distance to the published range",
              outside(1e3 * radius, 7.0, 7.1),
              verification.published_tolerance);
      }
    pcout << "RESULT program=taylor_bar final_length_mm=" << 1e3 * length
          << " footprint_radius_mm=" << 1e3 * radius
          << " max_equivalent_plastic_strain=" << alpha
          << " energy_balance_relative_error=" << worst_balance
          << " n_dofs=" << bar->n_dofs()
          << " ranks=" << Utilities::MPI::n_mpi_processes(communicator)
          << " checks=" << (ok ? "passed" : "failed") << std::endl;
    return ok;
  }



  // @sect3{The run}
  void
  TaylorBarProblem::run(const std::string &parameter_file)
  {
    ParameterHandler prm;
    declare_parameters(prm);
    read_parameter_file(prm, parameter_file);
    parse_parameters(prm);
    set_thread_limit(1);
    setup_system();
    Stopwatch timer;
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        timer.start();
        const FiniteStrainStepReport report = bar->do_time_step();
        timer.stop();
        output_results(report);
      }
    cpu_seconds = timer.seconds();
    bar->write_cells_csv(output.directory + "/cells_final.csv");
    report_results();
    AssertThrow(report_checks(),
                ExcMessage("Taylor bar: a check failed (see above); the "
                           "output files are complete."));
  }
} // namespace TaylorBarProgram



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  try
    {
      const std::string default_file =
        std::string(IMPACTFE_SOURCE_DIR) + "/parameter_files/taylor_bar.prm";
      const impactfe::CommandLine command_line =
        impactfe::parse_command_line(argc, argv, "taylor_bar", default_file);
      if (impactfe::answer_informational_option(
            command_line,
            "taylor_bar",
            default_file,
            &TaylorBarProgram::TaylorBarProblem::declare_parameters))
        return 0;
      TaylorBarProgram::TaylorBarProblem().run(command_line.parameter_file);
    }
  catch (...)
    {
      return impactfe::report_current_exception_on_rank_zero(MPI_COMM_WORLD);
    }
  return 0;
}
