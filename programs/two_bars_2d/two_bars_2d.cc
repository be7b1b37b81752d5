/* ---------------------------------------------------------------------
 *
 * two_bars_2d: the impact of two identical elastic bars in 2D with
 * Poisson's ratio 0.45 (Vola, Pratt, Jean, Raous, section 6.1.2), plane
 * strain or plane stress, node-to-node or node-to-segment contact.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// The data of the 1D bars (Table 1 of the paper), but each bar is now a 2D
// strip of height H meshed with Q1 cells, and Poisson's ratio is 0.45. The
// bars meet along their end faces. With matching meshes, each node of bar
// 1's end is paired with the node of bar 2 at the same height
// (node-to-node); when bar 2's mesh is offset, each node of bar 1 is paired
// with the segment of bar 2's end it faces (node-to-segment).
//
// There is no exact solution in 2D: lateral inertia makes the bar
// dispersive, and the front of the compression wave runs at the
// dilatational speed of the model while the bulk of the pulse follows the
// long-wave bar speed. In plane stress the bar speed is sqrt(E/rho), as in
// 1D; in plane strain the bar cannot contract through its thickness and the
// speed is sqrt(E/((1 - nu^2) rho)). The contact time follows 2L over that
// bar speed.
//
// With nu = 0, however, a uniform state across the height is an exact
// solution of the 2D discrete problem: then the program must reproduce the
// 1D program's results, which a test checks. The errors against the 1D
// exact solution are printed in any case, so one sees how far nu = 0.45
// moves the solution from the 1D one.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/bodies/mesh_input.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/output/output.h>
#include <impactfe/output/scene_recorder.h>
#include <impactfe/time_integration/time_integrator.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <filesystem>
#include <iostream>

namespace TwoBars2D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{Parameters}
  struct GeometryParameters
  {
    double       bar_length  = 0.254;
    double       bar_height  = 0.0254;
    double       thickness   = 0.0254;
    unsigned int n_along     = 20;
    unsigned int n_across    = 4;
    double       initial_gap = 0.;
    bool         node_to_segment = false;
    double       mesh_offset     = 0.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Bar length", "0.254", Patterns::Double(),
                        "Length L of each bar [m]. Must be > 0.");
      prm.declare_entry("Bar height", "0.0254", Patterns::Double(),
                        "Height H of each bar, in the plane [m]. Must be > 0.");
      prm.declare_entry("Thickness", "0.0254", Patterns::Double(),
                        "Out-of-plane thickness [m]; H times the thickness is "
                        "the cross-section of the 1D bars. Must be > 0.");
      prm.declare_entry("Number of cells along", "20", Patterns::Integer(1),
                        "Q1 cells along each bar [-].");
      prm.declare_entry("Number of cells across", "4", Patterns::Integer(1),
                        "Q1 cells across the height of each bar [-]. Even, so "
                        "that a node sits at the centre of the contact zone.");
      prm.declare_entry("Initial gap", "0", Patterns::Double(),
                        "Distance between the bars at t = 0 [m]. Must be >= 0.");
      prm.declare_entry("Contact discretization", "node-to-node",
                        Patterns::Selection("node-to-node|node-to-segment"),
                        "node-to-node: pairs of nodes at the same height "
                        "(matching meshes); node-to-segment: each node of "
                        "bar 1's end against the facing segment of bar 2.");
      prm.declare_entry("Interface mesh offset", "0", Patterns::Double(),
                        "Shift of bar 2's inner rows of nodes, as a fraction "
                        "of a cell height, so that the meshes do not match "
                        "at the interface [-]. In [0, 1); non-zero needs "
                        "node-to-segment.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      bar_length      = prm.get_double("Bar length");
      bar_height      = prm.get_double("Bar height");
      thickness       = prm.get_double("Thickness");
      n_along         = prm.get_integer("Number of cells along");
      n_across        = prm.get_integer("Number of cells across");
      initial_gap     = prm.get_double("Initial gap");
      node_to_segment = prm.get("Contact discretization") == "node-to-segment";
      mesh_offset     = prm.get_double("Interface mesh offset");
      prm.leave_subsection();
      AssertThrow(bar_length > 0. && bar_height > 0. && thickness > 0.,
                  ExcMessage("Geometry: 'Bar length', 'Bar height' and "
                             "'Thickness' must be > 0."));
      AssertThrow(n_across % 2 == 0,
                  ExcMessage("Geometry: 'Number of cells across' must be "
                             "even, got " +
                             std::to_string(n_across) + "."));
      AssertThrow(initial_gap >= 0.,
                  ExcMessage("Geometry: 'Initial gap' must be >= 0, got " +
                             format_number(initial_gap) + "."));
      AssertThrow(mesh_offset >= 0. && mesh_offset < 1.,
                  ExcMessage("Geometry: 'Interface mesh offset' must be in "
                             "[0, 1), got " +
                             format_number(mesh_offset) + "."));
      AssertThrow(mesh_offset == 0. || node_to_segment,
                  ExcMessage("Geometry: an 'Interface mesh offset' of " +
                             format_number(mesh_offset) +
                             " makes the interface meshes non-matching: set "
                             "'Contact discretization' to node-to-segment."));
    }
  };



  struct InitialConditions
  {
    double impact_velocity = 5.13588;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Impact velocity", "5.13588", Patterns::Double(),
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



  // @sect3{The 1D reference}
  //
  // The exact solution of the 1D bars with c = sqrt(E/rho): the program
  // measures the 2D results against it (exact for nu = 0).
  struct OneDimensionalSolution
  {
    double v0, t_contact, duration, contact_force;

    double
    contact_velocity(const double t) const
    {
      return t < t_contact ? v0 : (t < t_contact + duration ? 0.5 * v0 : 0.);
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

    void
    make_bar(ElasticBody<2>     &bar,
             const MeshParameters &mesh,
             const double        x_left,
             const double        row_offset);
    unsigned int
    centre_vertex(const ElasticBody<2> &bar, const types::boundary_id id) const;

    GeometryParameters            geometry;
    InitialConditions             initial_conditions;
    MeshParameters                mesh_1, mesh_2;
    MaterialParameters            material;
    DiscretizationParameters      discretization;
    TimeSteppingParameters        time_stepping;
    ContactSolverParameters       solver_parameters;
    OutputParameters              output;
    ContactVerificationParameters verification;
    double                        max_err_v = -1., max_err_f = -1.;
    std::string                   parameter_file_name;

    std::unique_ptr<ElasticBody<2>>     bar_1, bar_2;
    std::unique_ptr<MultibodySystem<2>> system;
    std::unique_ptr<SceneRecorder<2>>   recorder;
    OneDimensionalSolution              reference;

    // x-velocity DoFs of the nodes at the centre of the contact zone.
    types::global_dof_index centre_dof_1 = 0, centre_dof_2 = 0;
    double       sum_error_v = 0., sum_error_f = 0.;
    unsigned int n_steps_done = 0;
    double       setup_cpu_time = 0., loop_cpu_time = 0.;
  };



  // @sect4{Constructor: reading the parameter file}
  TwoBarsProblem::TwoBarsProblem(const std::string &parameter_file)
    : parameter_file_name(parameter_file)
  {
    ParameterHandler prm;
    GeometryParameters::declare_parameters(prm);
    InitialConditions::declare_parameters(prm);
    MeshParameters::declare_parameters(prm, "Mesh of bar 1", 1);
    MeshParameters::declare_parameters(prm, "Mesh of bar 2", 0);
    MaterialParameters::declare_parameters(prm, 2);
    DiscretizationParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    ContactSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm, "results/two_bars_2d");
    ContactVerificationParameters::declare_parameters(prm);
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum err_v", "-1", Patterns::Double(),
                      "Fail the run if err_v against the 1D exact solution "
                      "exceeds this [-]. -1: no check.");
    prm.declare_entry("Maximum err_f", "-1", Patterns::Double(),
                      "Fail the run if err_f against the 1D exact solution "
                      "exceeds this [-]. -1: no check.");
    prm.leave_subsection();

    AssertThrow(std::filesystem::exists(parameter_file),
                ExcMessage("The parameter file '" + parameter_file +
                           "' does not exist."));
    prm.parse_input(parameter_file);

    geometry.parse_parameters(prm);
    initial_conditions.parse_parameters(prm);
    mesh_1.parse_parameters(prm, "Mesh of bar 1");
    mesh_2.parse_parameters(prm, "Mesh of bar 2");
    material.parse_parameters(prm, 2);
    discretization.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    solver_parameters.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
    prm.enter_subsection("Verification");
    max_err_v = prm.get_double("Maximum err_v");
    max_err_f = prm.get_double("Maximum err_f");
    prm.leave_subsection();
  }



  // @sect4{TwoBarsProblem::make_bar}
  //
  // A bar on [x_left, x_left + L] x [0, H] with `colorize`: boundary id 0
  // on the left end, 1 on the right end, 2 below, 3 above. The inner rows
  // of nodes may be shifted up by a fraction of a cell height (bar 2 with
  // an interface mesh offset), which keeps the outline and moves the nodes
  // of the end face off bar 1's.
  void
  TwoBarsProblem::make_bar(ElasticBody<2>       &bar,
                           const MeshParameters &mesh,
                           const double          x_left,
                           const double          row_offset)
  {
    if (mesh.from_file())
      {
        mesh.read(bar.triangulation(), parameter_file_name);
        return;
      }
    const double H = geometry.bar_height;
    GridGenerator::subdivided_hyper_rectangle(
      bar.triangulation(),
      {geometry.n_along, geometry.n_across},
      Point<2>(x_left, 0.),
      Point<2>(x_left + geometry.bar_length, H),
      /*colorize=*/true);
    if (row_offset > 0.)
      {
        const double dy = H / geometry.n_across;
        GridTools::transform(
          [&](const Point<2> &p) {
            const bool inner = p[1] > 0.5 * dy && p[1] < H - 0.5 * dy;
            return inner ? Point<2>(p[0], p[1] + row_offset * dy) : p;
          },
          bar.triangulation());
      }
  }



  // The vertex of a bar's contact face nearest to the centre of the face.
  unsigned int
  TwoBarsProblem::centre_vertex(const ElasticBody<2>    &bar,
                                const types::boundary_id id) const
  {
    double       y_min = 1e300, y_max = -1e300;
    std::vector<unsigned int> face_vertices;
    for (const auto &cell : bar.dof_handler().get_triangulation().active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == id)
          for (const unsigned int v : cell->face(f)->vertex_indices())
            {
              face_vertices.push_back(cell->face(f)->vertex_index(v));
              const double y = cell->face(f)->vertex(v)[1];
              y_min          = std::min(y_min, y);
              y_max          = std::max(y_max, y);
            }
    AssertThrow(!face_vertices.empty(),
                ExcMessage("Contact: bar '" + bar.name() +
                           "' has no face with boundary id " +
                           std::to_string(id) + "."));
    const double y_c  = 0.5 * (y_min + y_max);
    unsigned int best = face_vertices[0];
    for (const unsigned int v : face_vertices)
      if (std::abs(bar.dof_handler().get_triangulation().get_vertices()[v][1] - y_c) <
          std::abs(bar.dof_handler().get_triangulation().get_vertices()[best][1] - y_c))
        best = v;
    return best;
  }



  // @sect4{TwoBarsProblem::setup_system}
  //
  // Bar 1 on [-L - g0, -g0], bar 2 on [0, L]; bar 1 moves at v0 along +x.
  // The contact normal points from bar 2 towards bar 1 (along -x).
  // Frictionless: one local direction per candidate.
  void
  TwoBarsProblem::setup_system()
  {
    const double L  = geometry.bar_length;
    const double g0 = geometry.initial_gap;
    bar_1 = std::make_unique<ElasticBody<2>>("bar_1", material, discretization,
                                             geometry.thickness);
    bar_2 = std::make_unique<ElasticBody<2>>("bar_2", material, discretization,
                                             geometry.thickness);
    make_bar(*bar_1, mesh_1, -L - g0, 0.);
    make_bar(*bar_2, mesh_2, 0., geometry.mesh_offset);
    assemble_system();

    system = std::make_unique<MultibodySystem<2>>(time_stepping,
                                                  solver_parameters, 1);
    system->add_body(*bar_1);
    system->add_body(*bar_2);
    if (geometry.node_to_segment)
      system->contacts().add_node_to_segment(system->bodies(), 0,
                                             mesh_1.contact_boundary_id, 1,
                                             mesh_2.contact_boundary_id);
    else
      system->contacts().add_node_to_node(system->bodies(), 0,
                                          mesh_1.contact_boundary_id, 1,
                                          mesh_2.contact_boundary_id,
                                          Tensor<1, 2>({-1., 0.}));

    bar_1->fill_uniform(system->state().velocity.block(0),
                        Tensor<1, 2>({initial_conditions.impact_velocity, 0.}));
    centre_dof_1 = bar_1->vertex_dof(centre_vertex(*bar_1,
                                                   mesh_1.contact_boundary_id),
                                     0);
    centre_dof_2 = bar_2->vertex_dof(centre_vertex(*bar_2,
                                                   mesh_2.contact_boundary_id),
                                     0);

    create_output_directory(output.directory);
    system->set_dump_directory(output.directory);
    system->setup();
    recorder = std::make_unique<SceneRecorder<2>>(
      *system,
      output,
      std::vector<std::string>{"contact_velocity",
                               "target_contact_velocity",
                               "exact_1d_contact_velocity",
                               "exact_1d_normal_force"});

    const double c  = std::sqrt(material.youngs_modulus / material.density);
    const double v0 = initial_conditions.impact_velocity;
    reference = {v0, g0 / v0, 2. * L / c,
                 0.5 * material.density * c * v0 * geometry.bar_height *
                   geometry.thickness};
  }



  // @sect4{TwoBarsProblem::assemble_system}
  void
  TwoBarsProblem::assemble_system()
  {
    bar_1->setup();
    bar_2->setup();
  }



  // @sect4{TwoBarsProblem::do_time_step}
  // The errors against the 1D solution, as in two_bars_1d: the velocity of
  // the node at the centre of bar 1's end, and the total contact force.
  StepReport
  TwoBarsProblem::do_time_step()
  {
    const StepReport report = system->do_time_step();
    const double     t      = report.time;
    const double v_c = system->state().velocity.block(0)(centre_dof_1);
    sum_error_v +=
      std::abs(v_c - reference.contact_velocity(t)) / (0.5 * reference.v0);
    sum_error_f += std::abs(report.normal_force - reference.normal_force(t)) /
                   reference.contact_force;
    ++n_steps_done;
    return report;
  }



  // @sect4{TwoBarsProblem::output_results}
  void
  TwoBarsProblem::output_results(const StepReport &report)
  {
    const auto  &state = system->state();
    const double t     = state.time;
    recorder->record(report,
                     {state.velocity.block(0)(centre_dof_1),
                      state.velocity.block(1)(centre_dof_2),
                      reference.contact_velocity(t),
                      reference.normal_force(t)});
  }



  // @sect4{TwoBarsProblem::report_results}
  void
  TwoBarsProblem::report_results()
  {
    const ContactRunSummary &s  = recorder->monitor().summary();
    const double             nu = material.poissons_ratio;
    const double             E = material.youngs_modulus, rho = material.density;
    const bool   plane_strain = material.plane_model == PlaneModel::plane_strain;
    const double bar_speed =
      plane_strain ? std::sqrt(E / ((1. - nu * nu) * rho)) : std::sqrt(E / rho);
    const double err_v = sum_error_v / n_steps_done;
    const double err_f = sum_error_f / n_steps_done;

    std::cout << "Two elastic bars in 2D ("
              << (plane_strain ? "plane strain" : "plane stress")
              << ", nu = " << nu << "), scheme "
              << to_string(time_stepping.scheme);
    if (time_stepping.scheme == Scheme::newmark)
      std::cout << " (beta = " << time_stepping.newmark_beta
                << ", gamma = " << time_stepping.newmark_gamma << ")";
    else
      std::cout << " (theta = " << time_stepping.theta << ")";
    std::cout << ", h = " << time_stepping.time_step << " s, " << n_steps_done
              << " steps" << std::endl;
    std::cout << "  Mesh: " << bar_1->triangulation().n_active_cells()
              << " + " << bar_2->triangulation().n_active_cells()
              << " Q1 cells, " << system->contacts().n_candidates() << " "
              << (geometry.node_to_segment ? "node-to-segment" : "node-to-node")
              << " contact candidates" << std::endl;
    std::cout << "  Wave speeds: bar (long waves) " << bar_speed
              << " m/s, dilatational " << material.longitudinal_wave_speed<2>()
              << " m/s; 2 L / bar speed = "
              << 2. * geometry.bar_length / bar_speed << " s" << std::endl;
    std::cout << "  Against the 1D exact solution: err_v = " << err_v
              << ", err_f = " << err_f << std::endl;
    const double energy_ratio = s.energy_ratio;
    bool ok = print_contact_summary(std::cout, s, verification, false);
    ok &= print_check(std::cout, "err_v", err_v, "<=", max_err_v);
    ok &= print_check(std::cout, "err_f", err_f, "<=", max_err_f);

    JsonObject summary;
    summary.add("program", std::string("two_bars_2d"))
      .add("scheme", to_string(time_stepping.scheme))
      .add("theta", time_stepping.theta)
      .add("time_step", time_stepping.time_step)
      .add("poissons_ratio", nu)
      .add("plane_model",
           std::string(plane_strain ? "plane strain" : "plane stress"))
      .add("bar_wave_speed", bar_speed)
      .add("setup_cpu_seconds", setup_cpu_time)
      .add("loop_cpu_seconds", loop_cpu_time)
      .add("err_v_1d", err_v)
      .add("err_f_1d", err_f)
      .add("final_energy_ratio", energy_ratio);
    recorder->add_summary(summary);
    summary.write(output.directory + "/summary.json");

    if (output.print_performance)
      std::cout << "  CPU seconds: set-up " << setup_cpu_time << ", time loop "
                << loop_cpu_time << "; LCP: " << system->total_pivots()
                << " pivots in total, largest LCP " << system->largest_lcp()
                << std::endl;
    recorder->report_files(std::cout,
                           {"contact_velocity", "target_contact_velocity",
                            "normal_force"},
                           "Two bars 2D, " + to_string(time_stepping.scheme));
    AssertThrow(ok,
                ExcMessage("Verification: at least one bound of subsection "
                           "'Verification' does not hold (see above)."));
  }



  // @sect4{TwoBarsProblem::run}
  void
  TwoBarsProblem::run()
  {
    CpuStopwatch setup_timer;
    setup_timer.start();
    setup_system();
    output_results(StepReport());
    setup_timer.stop();
    setup_cpu_time = setup_timer.seconds();

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
    recorder->finish();
    report_results();
  }
} // namespace TwoBars2D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      if (argc > 2)
        {
          std::cerr << "Usage: " << argv[0] << " [parameter file]" << std::endl;
          return 1;
        }
      const std::string parameter_file =
        argc > 1 ? argv[1] :
                   std::string(IMPACTFE_SOURCE_DIR) +
                     "/parameter_files/two_bars_2d.prm";
      TwoBars2D::TwoBarsProblem problem(parameter_file);
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
