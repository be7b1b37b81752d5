/* ---------------------------------------------------------------------
 *
 * oblique_plate: oblique impact of an elastic plate with a round side on a
 * rigid plane, with Coulomb friction (Vola, Pratt, Jean, Raous, section
 * 6.3; Kim and Kwak 1996), plane stress, modified theta-method.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A rubber-like plate, 80 mm wide and 40 mm high, whose lower side is an
// arc of radius 101 mm, flies at (3, -5) m/s onto a rigid plane. Friction
// (mu = 0.1) acts on the nodes of the round side: some stick, some slide,
// and the plate starts to rotate. The paper shows the nodal normal
// reactions against time (its Fig. 8) and deformed shapes (Fig. 9).
//
// Each step, the dynamics is condensed on the candidates that can touch
// during the step, and Klarbring's LCP of size 3 n_c (normal impulse and
// the two parts of the tangential velocity) is solved by Lemke's method.
// The program checks what must hold:
//  - the impulse of the contact forces equals the change of momentum, in
//    both directions;
//  - |P_T| <= mu P_N at every node and step, and a sliding node has
//    P_T = -mu P_N V_T / |V_T|;
//  - no node penetrates the plane (the modified theta-method enforces the
//    gap at the end of the step);
//  - the energy does not grow.

#include <deal.II/base/parameter_handler.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/bodies/geometry.h>
#include <impactfe/bodies/mesh_input.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/contact/rigid_obstacle.h>
#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/output/output.h>
#include <impactfe/output/scene_recorder.h>
#include <impactfe/time_integration/time_integrator.h>
#include <impactfe/utilities/program.h>

#include <filesystem>
#include <iostream>

namespace ObliquePlate
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{Parameters}
  //
  // The data of the paper's Fig. 7 table: `Geometry` and `Initial
  // conditions` here, the rest in the library's subsections.
  struct GeometryParameters
  {
    double       width       = 0.08;
    double       side_height = 0.04;
    double       radius      = 0.101;
    double       thickness   = 0.01;
    unsigned int nx = 10, ny = 8;
    double       initial_gap = 0.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Width", "0.08", Patterns::Double(),
                        "Width of the plate [m]. Must be > 0.");
      prm.declare_entry("Side height", "0.04", Patterns::Double(),
                        "Height of the plate's vertical sides, above the "
                        "ends of the round side [m]. Must be > 0.");
      prm.declare_entry("Radius of the round side", "0.101", Patterns::Double(),
                        "Radius of the arc that forms the lower side [m]. "
                        "Must exceed half the width.");
      prm.declare_entry("Thickness", "0.01", Patterns::Double(),
                        "Out-of-plane thickness (plane stress) [m]. Must be "
                        "> 0.");
      prm.declare_entry("Number of cells across", "10", Patterns::Integer(1),
                        "Q1 cells along the width [-].");
      prm.declare_entry("Number of cells up", "8", Patterns::Integer(1),
                        "Q1 cells along the height [-].");
      prm.declare_entry("Initial gap", "0", Patterns::Double(),
                        "Height of the lowest point of the round side above "
                        "the plane at t = 0 [m]. Must be >= 0.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      width       = prm.get_double("Width");
      side_height = prm.get_double("Side height");
      radius      = prm.get_double("Radius of the round side");
      thickness   = prm.get_double("Thickness");
      nx          = prm.get_integer("Number of cells across");
      ny          = prm.get_integer("Number of cells up");
      initial_gap = prm.get_double("Initial gap");
      prm.leave_subsection();
      AssertThrow(width > 0. && side_height > 0.,
                  ExcMessage("Geometry: 'Width' and 'Side height' must be > 0, "
                             "got " +
                             format_number(width) + " and " +
                             format_number(side_height) + "."));
      AssertThrow(2. * radius > width,
                  ExcMessage("Geometry: 'Radius of the round side' must "
                             "exceed half the width, got " +
                             format_number(radius) + "."));
      AssertThrow(thickness > 0.,
                  ExcMessage("Geometry: 'Thickness' must be > 0, got " +
                             format_number(thickness) + "."));
      AssertThrow(initial_gap >= 0.,
                  ExcMessage("Geometry: 'Initial gap' must be >= 0, got " +
                             format_number(initial_gap) + "."));
    }
  };



  struct InitialConditions
  {
    double horizontal_velocity = 3., vertical_velocity = -5.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Horizontal velocity", "3", Patterns::Double(),
                        "V_h, along x, at t = 0 [m/s].");
      prm.declare_entry("Vertical velocity", "-5", Patterns::Double(),
                        "V_v, along y, at t = 0 [m/s]. Must be < 0 for an "
                        "impact.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      horizontal_velocity = prm.get_double("Horizontal velocity");
      vertical_velocity   = prm.get_double("Vertical velocity");
      prm.leave_subsection();
      AssertThrow(vertical_velocity < 0.,
                  ExcMessage("Initial conditions: 'Vertical velocity' must "
                             "be < 0 (towards the plane), got " +
                             format_number(vertical_velocity) + "."));
    }
  };



  // @sect3{The ObliquePlateProblem class}
  class ObliquePlateProblem
  {
  public:
    ObliquePlateProblem(const std::string &parameter_file);
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

    GeometryParameters            geometry;
    InitialConditions             initial_conditions;
    MeshParameters                mesh;
    ObstacleParameters            obstacle_parameters;
    MaterialParameters            material;
    DiscretizationParameters      discretization;
    TimeSteppingParameters        time_stepping;
    ContactSolverParameters       solver_parameters;
    OutputParameters              output;
    ContactVerificationParameters verification;
    std::string                   parameter_file_name;

    std::unique_ptr<ElasticBody<2>>     plate;
    std::unique_ptr<RigidObstacle<2>>   obstacle;
    std::unique_ptr<MultibodySystem<2>> system;
    std::unique_ptr<SceneRecorder<2>>     recorder;
    double setup_cpu_time = 0., loop_cpu_time = 0.;
  };



  // @sect4{Constructor: reading the parameter file}
  ObliquePlateProblem::ObliquePlateProblem(const std::string &parameter_file)
    : parameter_file_name(parameter_file)
  {
    ParameterHandler prm;
    GeometryParameters::declare_parameters(prm);
    InitialConditions::declare_parameters(prm);
    MeshParameters::declare_parameters(prm, "Mesh", 2);
    ObstacleParameters::declare_parameters(prm, "0, 0", "0, 1", "0.1");
    MaterialParameters::declare_parameters(prm, 2);
    DiscretizationParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    ContactSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm, "results/oblique_plate");
    ContactVerificationParameters::declare_parameters(prm);

    AssertThrow(std::filesystem::exists(parameter_file),
                ExcMessage("The parameter file '" + parameter_file +
                           "' does not exist."));
    prm.parse_input(parameter_file);

    geometry.parse_parameters(prm);
    initial_conditions.parse_parameters(prm);
    mesh.parse_parameters(prm, "Mesh");
    obstacle_parameters.parse_parameters(prm, 2);
    material.parse_parameters(prm, 2);
    discretization.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    solver_parameters.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);
  }



  // @sect4{ObliquePlateProblem::setup_system}
  //
  // The built-in mesh: 10 x 8 Q1 cells, 99 nodes, as in the paper; the
  // lowest point of the round side at height g0 above the plane y = 0. The
  // 11 nodes of the round side (boundary id 2) are the candidates. With
  // mu > 0 every candidate has a normal and a tangential direction.
  void
  ObliquePlateProblem::setup_system()
  {
    plate = std::make_unique<ElasticBody<2>>("plate",
                                             material,
                                             discretization,
                                             geometry.thickness);
    if (mesh.from_file())
      mesh.read(plate->triangulation(), parameter_file_name);
    else
      Geometry::plate_with_round_side(plate->triangulation(),
                                      Point<2>(0., geometry.initial_gap),
                                      geometry.width,
                                      geometry.side_height,
                                      geometry.radius,
                                      geometry.nx,
                                      geometry.ny);
    assemble_system();

    const bool frictional = obstacle_parameters.friction_coefficient > 0.;
    obstacle = obstacle_parameters.create<2>(geometry.width);
    system   = std::make_unique<MultibodySystem<2>>(time_stepping,
                                                  solver_parameters,
                                                  frictional ? 2 : 1);
    system->add_body(*plate);
    system->contacts().add_node_to_obstacle(system->bodies(),
                                            0,
                                            mesh.contact_boundary_id,
                                            *obstacle,
                                            obstacle_parameters.friction_coefficient);
    for (const auto &c : system->contacts().candidates())
      AssertThrow(c.initial_gap >= 0.,
                  ExcMessage("Initial conditions: a node of the plate is "
                             "below the obstacle at t = 0 (gap " +
                             format_number(c.initial_gap) + " m)."));

    plate->fill_uniform(system->state().velocity.block(0),
                        Tensor<1, 2>({initial_conditions.horizontal_velocity,
                                      initial_conditions.vertical_velocity}));
    create_output_directory(output.directory);
    system->set_dump_directory(output.directory);
    system->setup();
    recorder = std::make_unique<SceneRecorder<2>>(*system, output);
  }



  // @sect4{ObliquePlateProblem::assemble_system}
  void
  ObliquePlateProblem::assemble_system()
  {
    plate->setup();
  }



  // @sect4{ObliquePlateProblem::do_time_step}
  StepReport
  ObliquePlateProblem::do_time_step()
  {
    return system->do_time_step();
  }



  // @sect4{ObliquePlateProblem::output_results}
  void
  ObliquePlateProblem::output_results(const StepReport &report)
  {
    recorder->record(report);
  }



  // @sect4{ObliquePlateProblem::report_results}
  void
  ObliquePlateProblem::report_results()
  {
    const ContactRunSummary &s = recorder->monitor().summary();
    const double             m = plate->total_mass();
    const Tensor<1, 2>       v0({initial_conditions.horizontal_velocity,
                                 initial_conditions.vertical_velocity});
    const Tensor<1, 2>       p_end = system->momentum(0);
    std::cout << "Oblique impact of a plate, scheme "
              << to_string(time_stepping.scheme) << " (theta = "
              << time_stepping.theta << "), h = " << time_stepping.time_step
              << " s, " << s.n_steps << " steps" << std::endl;
    std::cout << "  Mesh: " << plate->triangulation().n_active_cells()
              << " Q1 cells, " << plate->triangulation().n_vertices()
              << " nodes, " << system->contacts().n_candidates()
              << " contact candidates; obstacle: " << obstacle->description()
              << ", mu = " << obstacle_parameters.friction_coefficient
              << std::endl;
    std::cout << "  Mass " << m << " kg; mean velocity at t = 0: " << v0
              << " m/s, at the end: " << p_end / m << " m/s" << std::endl;
    std::cout << "  Tangential / normal impulse = "
              << (s.normal_impulse > 0. ? s.tangential_impulse / s.normal_impulse :
                                          0.)
              << " (Coulomb bound mu = "
              << obstacle_parameters.friction_coefficient << ")" << std::endl;

    const bool ok = print_contact_summary(std::cout,
                                          s,
                                          verification,
                                          system->contacts().n_directions() > 1);

    JsonObject summary;
    summary.add("program", std::string("oblique_plate"))
      .add("scheme", to_string(time_stepping.scheme))
      .add("theta", time_stepping.theta)
      .add("time_step", time_stepping.time_step)
      .add("cells", double(plate->triangulation().n_active_cells()))
      .add("nodes", double(plate->triangulation().n_vertices()))
      .add("setup_cpu_seconds", setup_cpu_time)
      .add("loop_cpu_seconds", loop_cpu_time)
      .add("final_velocity_x", p_end[0] / m)
      .add("final_velocity_y", p_end[1] / m);
    recorder->add_summary(summary);
    summary.write(output.directory + "/summary.json");

    if (output.print_performance)
      std::cout << "  CPU seconds: set-up " << setup_cpu_time << ", time loop "
                << loop_cpu_time << "; LCP: " << system->total_pivots()
                << " pivots in total, largest LCP " << system->largest_lcp()
                << std::endl;
    recorder->report_files(std::cout,
                           {"normal_force", "tangential_force", "sliding"},
                           "Oblique plate, " + to_string(time_stepping.scheme));
    AssertThrow(ok,
                ExcMessage("Verification: at least one bound of subsection "
                           "'Verification' does not hold (see above)."));
  }



  // @sect4{ObliquePlateProblem::run}
  void
  ObliquePlateProblem::run()
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
} // namespace ObliquePlate



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
                     "/parameter_files/oblique_plate.prm";
      ObliquePlate::ObliquePlateProblem problem(parameter_file);
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
