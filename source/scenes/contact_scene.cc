#include <deal.II/base/multithread_info.h>

#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/mesh_input.h>
#include <impactfe/scenes/contact_scene.h>
#include <impactfe/utilities/program.h>

#if __has_include(<valgrind/callgrind.h>)
#  include <valgrind/callgrind.h>
#else
#  define CALLGRIND_START_INSTRUMENTATION
#  define CALLGRIND_STOP_INSTRUMENTATION
#  define CALLGRIND_TOGGLE_COLLECT
#endif

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <limits>
#include <sstream>

namespace impactfe
{
  void
  SceneParameters::declare_parameters(
    ParameterHandler  &prm,
    const std::string &default_output_directory,
    const bool         distributed)
  {
    DiscretizationParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    ContactSolverParameters::declare_parameters(prm, distributed);
    OutputParameters::declare_parameters(prm, default_output_directory);
    ContactVerificationParameters::declare_parameters(prm);
    prm.declare_entry(
      "Number of threads",
      "1",
      Patterns::Integer(0),
      "Threads that deal.II's vector and matrix operations and the BLAS "
      "(OpenBLAS) may use [-]; 0: one per core. A contact time step is a "
      "chain of small operations that threads do not shorten: with 2 "
      "threads the 1D bars' time loop took 2.7 times the CPU time and no "
      "less wall time, and idle OpenBLAS workers doubled the plate's "
      "(doc/performance.md)." +
        std::string(distributed ? " contact_mpi reads it and ignores it: one "
                                  "thread per MPI rank." :
                                  ""));
  }



  void
  SceneParameters::parse_parameters(ParameterHandler &prm)
  {
    discretization.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    contact_solver.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
    n_threads = prm.get_integer("Number of threads");
    // A step past the end would write nothing, and the user would look for
    // a file that was never made.
    const unsigned int n_steps = time_stepping.n_steps();
    AssertThrow(contact_solver.dump_step <= static_cast<int>(n_steps),
                ExcMessage("Contact solver: 'Dump LCP of step' = " +
                           std::to_string(contact_solver.dump_step) +
                           ", but the run has " + std::to_string(n_steps) +
                           " steps ('End time' / 'Time step')."));
  }



  template <int dim>
  ContactScene<dim>::ContactScene(const std::string &program_name)
    : program_name(program_name)
  {}



  template <int dim>
  void
  ContactScene<dim>::run(int argc, char *argv[])
  {
    const std::string default_file = std::string(IMPACTFE_SOURCE_DIR) +
                                     "/parameter_files/" + program_name +
                                     ".prm";
    const CommandLine command_line =
      parse_command_line(argc, argv, program_name, default_file);
    if (answer_informational_option(
          command_line, program_name, default_file, [&](ParameterHandler &prm) {
            declare_parameters(prm);
            SceneParameters::declare_parameters(prm, "results/" + program_name);
          }))
      return;
    require_one_process(program_name,
                        "distributed runs are made by contact_mpi "
                        "(doc/parallel.md), which runs the 2D and 3D "
                        "scenes of the serial programs "
                        "(parameter_files/*_mpi.prm).");
    run(command_line.parameter_file);
  }



  // @sect3{The run}
  // The set-up and the initial output are timed together, the loop's steps
  // on their own.
  template <int dim>
  void
  ContactScene<dim>::run(const std::string &parameter_file)
  {
    read_parameters(parameter_file);
    set_thread_limit(parameters.n_threads);

    Stopwatch setup_timer;
    setup_timer.start();
    setup_system();
    output_results(StepReport());
    setup_timer.stop();
    setup_cpu_seconds = setup_timer.seconds();

    // The loop's CPU time without the output's: the process clock is read
    // once around the whole loop, and the output's share is taken off in
    // proportion to wall time. CPU clocks are system calls, too dear to be
    // read at every step (see wall_seconds()).
    Stopwatch loop_timer;
    Stopwatch loop_wall(Stopwatch::Clock::wall);
    Stopwatch step_wall(Stopwatch::Clock::wall);
    // A free-flight step covers k steps of h (`Free-flight step factor`),
    // and is tried only where k steps of h are left before the end time.
    const unsigned int n_steps = parameters.time_stepping.n_steps();
    // Under `valgrind --tool=callgrind --instr-atstart=no
    // --collect-atstart=no` the instructions of the time steps alone are
    // counted (the output's are not): a cost that does not depend on the
    // machine's load (benchmarks/work_precision/count_instructions.py).
    // Outside valgrind these macros cost a few instructions per step.
    CALLGRIND_START_INSTRUMENTATION;
    loop_timer.start();
    loop_wall.start();
    for (unsigned int step = 0; step < n_steps;)
      {
        step_wall.start();
        CALLGRIND_TOGGLE_COLLECT;
        const StepReport report =
          multibody_system->do_time_step(n_steps - step);
        CALLGRIND_TOGGLE_COLLECT;
        step_wall.stop();
        ++n_steps_taken;
        step += report.n_substeps;
        output_results(report);
      }
    loop_wall.stop();
    loop_timer.stop();
    CALLGRIND_STOP_INSTRUMENTATION;
    loop_cpu_seconds =
      loop_wall.seconds() > 0. ?
        loop_timer.seconds() * step_wall.seconds() / loop_wall.seconds() :
        loop_timer.seconds();
    recorder->finish();
    report_results();
  }



  // Every entry is declared with its pattern before the file is read, so a
  // misspelt entry or a value outside its pattern is reported by
  // ParameterHandler with the line number; the checks that patterns cannot
  // express are in each parse_parameters().
  template <int dim>
  void
  ContactScene<dim>::read_parameters(const std::string &file)
  {
    parameter_file_name = file;
    ParameterHandler prm;
    declare_parameters(prm);
    SceneParameters::declare_parameters(prm, "results/" + program_name);
    read_parameter_file(prm, file);
    parameters.parse_parameters(prm);
    parse_parameters(prm);
    parameters.output.check_shape_times(dim == 2,
                                        parameters.time_stepping.n_steps(),
                                        parameters.time_stepping.time_step);
  }



  // @sect3{The set-up}
  template <int dim>
  void
  ContactScene<dim>::setup_system()
  {
    make_bodies();
    for (const auto &b : body_list)
      b->setup();
    apply_loads();
    // `Theta rule = courant`: theta from the shortest cell transit time.
    double cell_transit_time = std::numeric_limits<double>::infinity();
    for (const auto &b : body_list)
      cell_transit_time = std::min(cell_transit_time, b->cell_transit_time());
    parameters.time_stepping.apply_theta_rule(cell_transit_time);

    multibody_system =
      std::make_unique<MultibodySystem<dim>>(parameters.time_stepping,
                                             parameters.contact_solver,
                                             frictional() ? dim : 1);
    for (const auto &b : body_list)
      multibody_system->add_body(*b);
    add_contacts(multibody_system->contacts());
    // A node that touches at t = 0 may get a gap of -1e-18 m from the
    // rounding of a projection (node-to-face): 1e-12 of the body's size is
    // touching, not below.
    std::vector<double> touching_tolerance;
    for (const auto &b : body_list)
      {
        const auto box = GridTools::compute_bounding_box(b->triangulation())
                           .get_boundary_points();
        touching_tolerance.push_back(1e-12 * box.first.distance(box.second));
      }
    for (const auto &c : multibody_system->contacts().candidates())
      AssertThrow(c.initial_gap >= -touching_tolerance[c.body_a],
                  ExcMessage("Initial conditions: a node of the " +
                             body_list[c.body_a]->name() +
                             " is below the obstacle at t = 0 (gap " +
                             format_number(c.initial_gap) + " m)."));
    if (parameters.discretization.mass_redistribution)
      redistribute_mass();
    set_initial_state(multibody_system->state());

    create_output_directory(parameters.output.directory);
    multibody_system->set_dump_directory(parameters.output.directory);
    // Where the time goes (a few clock reads per step, so only when asked).
    multibody_system->enable_cost_breakdown(
      parameters.output.print_performance);
    multibody_system->setup();
    prepare_run();
    // A run that cannot start must not cost the user an earlier run's
    // files: the earlier output is removed only once the state at t = 0
    // is known to be finite.
    check_initial_state();
    std::vector<std::string> body_names;
    for (const auto &b : body_list)
      body_names.push_back(b->name());
    remove_previous_run_output(parameters.output.directory, body_names);
    if (parameters.output.write_meshes)
      for (const auto &b : body_list)
        write_mesh_file(b->triangulation(),
                        parameters.output.directory + "/" + b->name() + ".msh");
    recorder = std::make_unique<SceneRecorder<dim>>(*multibody_system,
                                                    parameters.output,
                                                    history_columns());
  }



  // Data at the edge of double precision (an impact velocity of 1e308 m/s,
  // say) give a finite state with an infinite energy. The message names the
  // body and the data behind the energy, before anything is written.
  template <int dim>
  void
  ContactScene<dim>::check_initial_state() const
  {
    for (unsigned int b = 0; b < body_list.size(); ++b)
      {
        const std::string &name = body_list[b]->name();
        require_representable_mass(body_list[b]->total_mass(), "the " + name);
        const double v =
          multibody_system->state().velocity.block(b).linfty_norm();
        AssertThrow(std::isfinite(multibody_system->kinetic_energy(b)),
                    ExcMessage(
                      "Initial conditions: the kinetic energy of the " + name +
                      " at t = 0 overflows double precision (largest "
                      "initial velocity " +
                      format_number(v) + " m/s, 'Density' = " +
                      format_number(body_list[b]->material().density) +
                      " kg/m^3): the run is not started."));
        AssertThrow(
          std::isfinite(multibody_system->elastic_energy(b)),
          ExcMessage(
            "Initial conditions: the elastic energy of the " + name +
            " at t = 0 overflows double precision (largest "
            "initial displacement " +
            format_number(
              multibody_system->state().displacement.block(b).linfty_norm()) +
            " m, 'Young's modulus' = " +
            format_number(body_list[b]->material().youngs_modulus) +
            " Pa): the run is not started."));
      }
  }



  // The nodes of every contact candidate, on both sides, lose their mass to
  // their neighbours (ElasticBody::redistribute_mass()); the system then
  // tells its scheme (TimeIntegrator::set_massless_contact_nodes()).
  template <int dim>
  void
  ContactScene<dim>::redistribute_mass()
  {
    std::vector<std::vector<unsigned int>> massless(body_list.size());
    for (const ContactCandidate &c : multibody_system->contacts().candidates())
      {
        massless[c.body_a].push_back(c.vertex_a);
        if (!c.against_rigid_obstacle())
          {
            for (unsigned int j = 0; j < c.n_vertices_b; ++j)
              massless[c.body_b].push_back(c.vertices_b[j]);
          }
      }
    for (unsigned int b = 0; b < body_list.size(); ++b)
      if (!massless[b].empty())
        body_list[b]->redistribute_mass(massless[b]);
  }



  template <int dim>
  void
  ContactScene<dim>::output_results(const StepReport &report)
  {
    recorder->record(report, history_values(report));
    if (report.step > 0)
      measure_step(report);
  }



  // @sect3{The report}
  // The scene's report and entries, then what every program prints: the
  // CPU times (if asked for: tests compare the screen), summary.json and the
  // files.
  template <int dim>
  void
  ContactScene<dim>::report_results()
  {
    const TimeSteppingParameters &ts = parameters.time_stepping;
    std::ostringstream            out;
    JsonObject                    summary;
    summary.add("program", program_name);
    ts.add_to_summary(summary);
    summary.add("setup_cpu_seconds", setup_cpu_seconds)
      .add("loop_cpu_seconds", loop_cpu_seconds);
    const CostBreakdown &costs = multibody_system->cost_breakdown();
    // per step: per call of do_time_step() (a free-flight step is one)
    const double n_steps = std::max(1u, n_steps_taken);
    if (parameters.output.print_performance)
      summary.add("cost",
                  JsonObject()
                    .add("factorization_seconds", costs.factorization)
                    .add("delassus_seconds", costs.delassus)
                    .add("free_velocity_per_step",
                         costs.free_velocity / n_steps)
                    .add("lcp_per_step", costs.lcp / n_steps)
                    .add("update_per_step", costs.update / n_steps)
                    .add("steps", n_steps));
    const bool ok = report(out, summary);
    recorder->add_summary(summary);
    summary.write(parameters.output.directory + "/summary.json");

    if (parameters.output.print_performance)
      {
        out << "  CPU seconds: set-up " << setup_cpu_seconds << ", time loop "
            << loop_cpu_seconds << "; LCP: " << multibody_system->total_pivots()
            << " pivots in total, largest LCP "
            << multibody_system->largest_lcp();
        const auto &paths = multibody_system->lcp_statistics();
        if (paths.block_pivoting_attempts > 0)
          out << "; block pivoting answered "
              << paths.by_path[static_cast<unsigned int>(
                   lcp::StartPath::block_pivoting)]
              << " of " << paths.solves << " LCPs ("
              << paths.block_pivoting_linear_solves << " linear solves, "
              << paths.block_pivoting_reused_factors
              << " with reused factors; gave up "
              << paths.block_pivoting_gave_up << " times)";
        const auto &cone = multibody_system->exact_cone_statistics();
        if (cone.solves > 0)
          out << "; exact cone: " << cone.facet_lcps << " facet LCPs for "
              << cone.solves << " problems (at most " << cone.most_facet_lcps
              << "), largest residual " << cone.largest_residual;
        out << std::endl
            << "  CPU seconds per step: free velocity "
            << costs.free_velocity / n_steps << ", contact problem "
            << costs.lcp / n_steps << ", update " << costs.update / n_steps
            << "; in total: factorisations of M~ " << costs.factorization
            << ", Delassus operator " << costs.delassus << std::endl;
      }
    recorder->report_files(out,
                           plot_columns(),
                           title() + ", " + to_string(ts.scheme));
    print_report(out.str(), std::cout);
    AssertThrow(ok,
                ExcMessage("Verification: at least one bound of subsection "
                           "'Verification' does not hold (see above)."));
  }



  template <int dim>
  std::vector<std::string>
  ContactScene<dim>::history_columns() const
  {
    return {};
  }



  template <int dim>
  std::vector<double>
  ContactScene<dim>::history_values(const StepReport &)
  {
    return {};
  }



  template <int dim>
  void
  ContactScene<dim>::measure_step(const StepReport &)
  {}



  template <int dim>
  void
  ContactScene<dim>::print_report(const std::string &text,
                                  std::ostream      &out) const
  {
    out << text;
  }



  template <int dim>
  ElasticBody<dim> &
  ContactScene<dim>::add_body(const std::string        &name,
                              const MaterialParameters &material,
                              const double              out_of_plane_measure)
  {
    body_list.push_back(std::make_unique<ElasticBody<dim>>(
      name, material, parameters.discretization, out_of_plane_measure));
    return *body_list.back();
  }



  template <int dim>
  ElasticBody<dim> &
  ContactScene<dim>::body(const unsigned int b)
  {
    return *body_list.at(b);
  }



  template <int dim>
  const ElasticBody<dim> &
  ContactScene<dim>::body(const unsigned int b) const
  {
    return *body_list.at(b);
  }



  template <int dim>
  unsigned int
  ContactScene<dim>::n_bodies() const
  {
    return body_list.size();
  }



  template <int dim>
  MultibodySystem<dim> &
  ContactScene<dim>::system()
  {
    return *multibody_system;
  }



  template <int dim>
  const MultibodySystem<dim> &
  ContactScene<dim>::system() const
  {
    return *multibody_system;
  }



  template <int dim>
  const ContactMonitor<dim> &
  ContactScene<dim>::monitor() const
  {
    return recorder->monitor();
  }



  template <int dim>
  const ContactRunSummary &
  ContactScene<dim>::run_summary() const
  {
    return recorder->monitor().summary();
  }



  template <int dim>
  const std::string &
  ContactScene<dim>::parameter_file() const
  {
    return parameter_file_name;
  }



  template <int dim>
  std::string
  ContactScene<dim>::scheme_description(const std::string &time_unit) const
  {
    const TimeSteppingParameters &ts = parameters.time_stepping;
    std::ostringstream            text;
    text << "scheme " << ts.scheme_description() << ", h = " << ts.time_step
         << time_unit << ", " << run_summary().n_steps << " steps";
    if (ts.free_flight_step_factor > 1)
      text << " (" << run_summary().free_flight_steps << " of them "
           << ts.free_flight_step_factor << " h long)";
    return text.str();
  }



  template <int dim>
  bool
  ContactScene<dim>::print_contact_checks(std::ostream &out) const
  {
    return print_contact_summary(out,
                                 run_summary(),
                                 parameters.verification,
                                 multibody_system->contacts().n_directions() >
                                   1);
  }



  template class ContactScene<1>;
  template class ContactScene<2>;
  template class ContactScene<3>;
} // namespace impactfe
