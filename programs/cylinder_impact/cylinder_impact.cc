/* ---------------------------------------------------------------------
 *
 * cylinder_impact: a frictionless elastic cylinder dropped on a rigid
 * plane (Vola, Pratt, Jean, Raous, section 6.2; Taylor and Papadopoulos
 * 1993), plane strain, theta-Euler by default.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A long elastic cylinder (plane strain) moves down at a uniform velocity
// onto a rigid, frictionless plane. The contact zone opens from a point,
// spreads, and closes again as the cylinder bounces off; stress waves run
// through the section meanwhile. There is no exact solution: the program
// reports what the paper plots (the total contact force against time, and
// the deformed shapes) and the checks that must hold whatever the mesh:
//  - the impulse of the contact force equals the change of momentum;
//  - no node penetrates the plane (theta-Euler and the modified
//    theta-method enforce the gap at the end of the step exactly);
//  - the energy does not grow (theta >= 1/2, no external work);
//  - the solution stays symmetric about the vertical axis (frictionless
//    contact, symmetric mesh and data).
//
// Only the nodes of the lower half of the circle are candidates, and only
// the normal direction is modelled (frictionless scene). Each step the LCP
// is restricted to the candidates that can touch during the step.

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

#include <cmath>
#include <filesystem>
#include <iostream>
#include <map>

namespace CylinderImpact
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{Parameters}
  //
  // The scene's subsections `Geometry` and `Initial conditions`; the rest
  // (`Mesh`, `Obstacle`, `Material`, `Discretization`, `Time stepping`,
  // `Contact solver`, `Output`, `Verification`) are the library's.
  struct GeometryParameters
  {
    double       radius    = 10.;
    unsigned int n_core    = 12;
    unsigned int n_rings   = 9;
    double       thickness = 1.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Radius", "10", Patterns::Double(),
                        "Radius R of the cylinder [m]. Must be > 0.");
      prm.declare_entry("Number of core cells", "12", Patterns::Integer(2),
                        "Cells across the square core of the O-grid mesh "
                        "[-]; even.");
      prm.declare_entry("Number of rings", "9", Patterns::Integer(1),
                        "Rings of cells between the core and the circle "
                        "[-].");
      prm.declare_entry("Thickness", "1", Patterns::Double(),
                        "Out-of-plane length of the cylinder [m]; scales "
                        "masses, forces and energies. Must be > 0.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      radius    = prm.get_double("Radius");
      n_core    = prm.get_integer("Number of core cells");
      n_rings   = prm.get_integer("Number of rings");
      thickness = prm.get_double("Thickness");
      prm.leave_subsection();
      AssertThrow(radius > 0.,
                  ExcMessage("Geometry: 'Radius' must be > 0, got " +
                             format_number(radius) + "."));
      AssertThrow(n_core % 2 == 0,
                  ExcMessage("Geometry: 'Number of core cells' must be even, "
                             "got " +
                             std::to_string(n_core) + "."));
      AssertThrow(thickness > 0.,
                  ExcMessage("Geometry: 'Thickness' must be > 0, got " +
                             format_number(thickness) + "."));
    }
  };



  struct InitialConditions
  {
    double impact_velocity = 1.;
    double initial_gap     = 0.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Impact velocity", "1", Patterns::Double(),
                        "Downward velocity of the cylinder at t = 0 [m/s]. "
                        "Must be > 0.");
      prm.declare_entry("Initial gap", "0", Patterns::Double(),
                        "Distance from the lowest point of the built-in "
                        "cylinder to the plane at t = 0 [m]. Must be >= 0. "
                        "(A mesh file is used where it is.)");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      impact_velocity = prm.get_double("Impact velocity");
      initial_gap     = prm.get_double("Initial gap");
      prm.leave_subsection();
      AssertThrow(impact_velocity > 0.,
                  ExcMessage("Initial conditions: 'Impact velocity' must be "
                             "> 0, got " +
                             format_number(impact_velocity) + "."));
      AssertThrow(initial_gap >= 0.,
                  ExcMessage("Initial conditions: 'Initial gap' must be >= 0, "
                             "got " +
                             format_number(initial_gap) + "."));
    }
  };



  // @sect3{The CylinderImpact class}
  class CylinderImpactProblem
  {
  public:
    CylinderImpactProblem(const std::string &parameter_file);
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

    // Mirror pairs of vertices about the vertical axis, and the largest
    // asymmetry of the displacement so far.
    void
    find_mirror_pairs();
    double
    asymmetry() const;

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
    double                        max_symmetry_error = -1.;
    std::string                   parameter_file_name;

    std::unique_ptr<ElasticBody<2>>        cylinder;
    std::unique_ptr<RigidObstacle<2>>      obstacle;
    std::unique_ptr<MultibodySystem<2>>    system;
    std::unique_ptr<SceneRecorder<2>>     recorder;

    std::vector<std::pair<unsigned int, unsigned int>> mirror_pairs;
    double       symmetry_error = 0.;
    double       setup_cpu_time = 0., loop_cpu_time = 0.;
  };



  // @sect4{Constructor: reading the parameter file}
  CylinderImpactProblem::CylinderImpactProblem(const std::string &parameter_file)
    : parameter_file_name(parameter_file)
  {
    ParameterHandler prm;
    GeometryParameters::declare_parameters(prm);
    InitialConditions::declare_parameters(prm);
    MeshParameters::declare_parameters(prm, "Mesh", 1);
    ObstacleParameters::declare_parameters(prm, "0, 0", "0, 1", "0");
    MaterialParameters::declare_parameters(prm, 2);
    DiscretizationParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    ContactSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm, "results/cylinder_impact");
    ContactVerificationParameters::declare_parameters(prm);
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum symmetry error", "-1", Patterns::Double(),
                      "Fail the run if max |u(x) - mirrored u(-x)| / max |u| "
                      "exceeds this [-]. -1: no check.");
    prm.leave_subsection();

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
    prm.enter_subsection("Verification");
    max_symmetry_error = prm.get_double("Maximum symmetry error");
    prm.leave_subsection();
  }



  // @sect4{CylinderImpactProblem::setup_system}
  //
  // The built-in mesh is the O-grid disc of the library (576 cells and 601
  // vertices with 12 core cells and 9 rings, close to the paper's 576 cells
  // and 613 nodes), centred at height R + g0 above the plane y = 0. A mesh
  // file replaces it, with its own coordinates.
  void
  CylinderImpactProblem::setup_system()
  {
    cylinder = std::make_unique<ElasticBody<2>>("cylinder",
                                                material,
                                                discretization,
                                                geometry.thickness);
    if (mesh.from_file())
      mesh.read(cylinder->triangulation(), parameter_file_name);
    else
      Geometry::disc(cylinder->triangulation(),
                     Point<2>(0., geometry.radius + initial_conditions.initial_gap),
                     geometry.radius,
                     geometry.n_core,
                     geometry.n_rings);
    assemble_system();

    // Frictionless: one local direction per candidate (normal only).
    const bool frictional = obstacle_parameters.friction_coefficient > 0.;
    obstacle = obstacle_parameters.create<2>(geometry.radius);
    system   = std::make_unique<MultibodySystem<2>>(time_stepping,
                                                  solver_parameters,
                                                  frictional ? 2 : 1);
    system->add_body(*cylinder);
    system->contacts().add_node_to_obstacle(system->bodies(),
                                            0,
                                            mesh.contact_boundary_id,
                                            *obstacle,
                                            obstacle_parameters.friction_coefficient);
    for (const auto &c : system->contacts().candidates())
      AssertThrow(c.initial_gap >= 0.,
                  ExcMessage("Initial conditions: a node of the cylinder is "
                             "below the obstacle at t = 0 (gap " +
                             format_number(c.initial_gap) + " m)."));

    cylinder->fill_uniform(system->state().velocity.block(0),
                           Tensor<1, 2>({0., -initial_conditions.impact_velocity}));
    create_output_directory(output.directory);
    system->set_dump_directory(output.directory);
    system->setup();
    recorder = std::make_unique<SceneRecorder<2>>(*system, output);
    find_mirror_pairs();
  }



  // @sect4{CylinderImpactProblem::assemble_system}
  void
  CylinderImpactProblem::assemble_system()
  {
    cylinder->setup();
  }



  // @sect4{Symmetry}
  //
  // Vertex pairs (x, y) and (2 x_c - x, y), x_c being the mean abscissa of
  // the vertices. A mesh without this symmetry (e.g. from a file) is not
  // checked.
  void
  CylinderImpactProblem::find_mirror_pairs()
  {
    const auto &vertices = cylinder->triangulation().get_vertices();
    double      x_c = 0., size = 0.;
    for (const auto &x : vertices)
      x_c += x[0] / vertices.size();
    for (const auto &x : vertices)
      size = std::max(size, std::abs(x[0] - x_c));
    const double tolerance = 1e-9 * size;
    std::multimap<long long, unsigned int> by_height;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      by_height.emplace(std::llround(vertices[v][1] / tolerance / 1e3), v);
    mirror_pairs.clear();
    for (unsigned int v = 0; v < vertices.size(); ++v)
      {
        unsigned int partner = numbers::invalid_unsigned_int;
        const long long key  = std::llround(vertices[v][1] / tolerance / 1e3);
        for (long long k = key - 1; k <= key + 1; ++k)
          {
            const auto range = by_height.equal_range(k);
            for (auto it = range.first; it != range.second; ++it)
              {
                const Point<2> &y = vertices[it->second];
                if (std::abs(y[0] - (2. * x_c - vertices[v][0])) < tolerance &&
                    std::abs(y[1] - vertices[v][1]) < tolerance)
                  partner = it->second;
              }
          }
        if (partner == numbers::invalid_unsigned_int)
          {
            mirror_pairs.clear();
            return;
          }
        if (v <= partner)
          mirror_pairs.emplace_back(v, partner);
      }
  }

  double
  CylinderImpactProblem::asymmetry() const
  {
    const Vector<double> &u = system->state().displacement.block(0);
    double                difference = 0., size = 0.;
    for (const auto &[a, b] : mirror_pairs)
      {
        const double ax = cylinder->nodal_value(u, a, 0),
                     ay = cylinder->nodal_value(u, a, 1),
                     bx = cylinder->nodal_value(u, b, 0),
                     by = cylinder->nodal_value(u, b, 1);
        difference = std::max({difference, std::abs(ax + bx), std::abs(ay - by)});
        size       = std::max({size, std::abs(ax), std::abs(ay)});
      }
    return size > 0. ? difference / size : 0.;
  }



  // @sect4{CylinderImpactProblem::do_time_step}
  StepReport
  CylinderImpactProblem::do_time_step()
  {
    return system->do_time_step();
  }



  // @sect4{CylinderImpactProblem::output_results}
  void
  CylinderImpactProblem::output_results(const StepReport &report)
  {
    recorder->record(report);
    if (!mirror_pairs.empty())
      symmetry_error = std::max(symmetry_error, asymmetry());
  }



  // @sect4{CylinderImpactProblem::report_results}
  void
  CylinderImpactProblem::report_results()
  {
    const auto &candidates = system->contacts().candidates();
    std::cout << "Cylinder on a rigid plane, scheme "
              << to_string(time_stepping.scheme) << " (theta = "
              << time_stepping.theta << "), h = " << time_stepping.time_step
              << ", " << recorder->monitor().summary().n_steps << " steps" << std::endl;
    std::cout << "  Mesh: " << cylinder->triangulation().n_active_cells()
              << " Q1 cells, " << cylinder->triangulation().n_vertices()
              << " nodes, " << candidates.size() << " contact candidates; "
              << "obstacle: " << obstacle->description() << std::endl;
    // The horizontal momentum is zero up to round-off (symmetry): printed
    // as such.
    Tensor<1, 2> p_end = system->momentum(0);
    for (unsigned int d = 0; d < 2; ++d)
      if (std::abs(p_end[d]) < 1e-9 * cylinder->total_mass() *
                                 initial_conditions.impact_velocity)
        p_end[d] = 0.;
    std::cout << "  Mass " << cylinder->total_mass() << ", momentum at t = 0: "
              << "(0, "
              << -cylinder->total_mass() * initial_conditions.impact_velocity
              << "), at the end: (" << p_end[0] << ", " << p_end[1] << ")"
              << std::endl;

    bool ok = print_contact_summary(std::cout,
                                    recorder->monitor().summary(),
                                    verification,
                                    system->contacts().n_directions() > 1);
    if (mirror_pairs.empty())
      std::cout << "  Symmetry: not checked (the mesh is not symmetric)"
                << std::endl;
    else
      {
        std::cout << "  Symmetry: max |u(x) - mirrored u(-x)| / max |u| = "
                  << (symmetry_error < 1e-12 ? std::string("< 1e-12") :
                                               format_number(symmetry_error))
                  << std::endl;
        ok &= print_check(std::cout, "symmetry error", symmetry_error, "<=",
                          max_symmetry_error);
      }

    JsonObject summary;
    summary.add("program", std::string("cylinder_impact"))
      .add("scheme", to_string(time_stepping.scheme))
      .add("theta", time_stepping.theta)
      .add("time_step", time_stepping.time_step)
      .add("cells", double(cylinder->triangulation().n_active_cells()))
      .add("nodes", double(cylinder->triangulation().n_vertices()))
      .add("setup_cpu_seconds", setup_cpu_time)
      .add("loop_cpu_seconds", loop_cpu_time)
      .add("symmetry_error", symmetry_error);
    recorder->add_summary(summary);
    summary.write(output.directory + "/summary.json");

    if (output.print_performance)
      std::cout << "  CPU seconds: set-up " << setup_cpu_time << ", time loop "
                << loop_cpu_time << "; LCP: " << system->total_pivots()
                << " pivots in total, largest LCP " << system->largest_lcp()
                << std::endl;
    recorder->report_files(std::cout,
                           {"normal_force", "kinetic_energy"},
                           "Cylinder impact, " + to_string(time_stepping.scheme));
    AssertThrow(ok,
                ExcMessage("Verification: at least one bound of subsection "
                           "'Verification' does not hold (see above)."));
  }



  // @sect4{CylinderImpactProblem::run}
  void
  CylinderImpactProblem::run()
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
} // namespace CylinderImpact



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
                     "/parameter_files/cylinder_impact.prm";
      CylinderImpact::CylinderImpactProblem problem(parameter_file);
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
