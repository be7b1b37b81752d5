#include <impactfe/scenes/block_on_plane_scene.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <set>

namespace impactfe
{
  BlockOnPlaneScene::BlockOnPlaneScene(const std::string &program_name)
    : ContactScene<2>(program_name)
  {}



  // @sect3{Parameters}
  //
  // The program's subsections; `Obstacle`, `Material`, the common ones and
  // the stability bounds of `Verification` are the library's.
  void
  BlockOnPlaneScene::declare_parameters(ParameterHandler &prm)
  {
    const auto velocity_entries = [&prm](const std::string &what) {
      for (const std::string axis : {"x", "y"})
        prm.declare_entry(axis == "x" ? "Horizontal velocity" :
                                        "Vertical velocity",
                          "0",
                          Patterns::Double(),
                          "Velocity of the " + what + " along " + axis +
                            " at t = 0 [m/s].");
    };
    prm.enter_subsection("Geometry");
    BlockParameters::declare_parameters(prm, "block");
    prm.declare_entry("Thickness",
                      "0.01",
                      Patterns::Double(),
                      "Out-of-plane thickness of both blocks [m]. Must be > "
                      "0.");
    prm.declare_entry("Initial gap",
                      "0",
                      Patterns::Double(),
                      "Distance of the block's lower side from the plane at "
                      "t = 0 [m]. Must be >= 0. The block is centred on the "
                      "Obstacle's 'Point on plane'.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    velocity_entries("block");
    prm.leave_subsection();
    prm.enter_subsection("Loads");
    prm.declare_entry("Gravity",
                      "0, -9.81",
                      Patterns::List(Patterns::Double(), 2, 2),
                      "Acceleration of gravity g, x and y components "
                      "[m/s^2]; it acts on both blocks as the body force rho "
                      "g.");
    prm.declare_entry("Push force",
                      "0, 0",
                      Patterns::List(Patterns::Double(), 2, 2),
                      "Constant total force on the block (body 1), x and y "
                      "components [N], spread uniformly over its volume.");
    prm.leave_subsection();
    prm.enter_subsection("Body 2");
    prm.declare_entry("Enabled",
                      "false",
                      Patterns::Bool(),
                      "Whether a second block lies above the first one. Its "
                      "material is subsection 'Material of body 2'.");
    BlockParameters::declare_parameters(prm, "second block");
    velocity_entries("second block");
    prm.declare_entry("Gap above body 1",
                      "0.01",
                      Patterns::Double(),
                      "Distance between the first block's upper side and "
                      "the second block's lower side at t = 0 [m]. Must be "
                      ">= 0.");
    prm.declare_entry("Friction coefficient",
                      "0",
                      Patterns::Double(),
                      "Coulomb friction coefficient between the two blocks "
                      "[-]. Must be >= 0.");
    prm.leave_subsection();
    declare_figures_entry(prm);
    ObstacleParameters::declare_parameters(prm, "0, 0", "0, 1", "0");
    MaterialParameters::declare_parameters(prm, 2);
    MaterialParameters::declare_parameters(prm, 2, "Material of body 2");
    StabilityBounds::declare_parameters(prm);
  }



  void
  BlockOnPlaneScene::parse_parameters(ParameterHandler &prm)
  {
    const auto get_velocity = [&prm]() {
      return Tensor<1, 2>({prm.get_double("Horizontal velocity"),
                           prm.get_double("Vertical velocity")});
    };
    prm.enter_subsection("Geometry");
    block.parse_parameters(prm, "Geometry");
    thickness   = prm.get_double("Thickness");
    initial_gap = prm.get_double("Initial gap");
    prm.leave_subsection();
    require_positive(thickness, "Geometry", "Thickness");
    require_non_negative(initial_gap, "Geometry", "Initial gap");
    prm.enter_subsection("Initial conditions");
    velocity = get_velocity();
    prm.leave_subsection();
    prm.enter_subsection("Loads");
    gravity = get_vector(prm, "Loads", "Gravity");
    push    = get_vector(prm, "Loads", "Push force");
    prm.leave_subsection();
    prm.enter_subsection("Body 2");
    body_2 = prm.get_bool("Enabled");
    if (body_2)
      {
        block_2.parse_parameters(prm, "Body 2");
        velocity_2 = get_velocity();
        gap_2      = prm.get_double("Gap above body 1");
        mu_2       = prm.get_double("Friction coefficient");
        AssertThrow(block_2.width <= block.width,
                    ExcMessage("Body 2: 'Width' (" +
                               format_number(block_2.width) +
                               ") must not exceed the width of body 1 (" +
                               format_number(block.width) +
                               "): each of its lower nodes must lie above "
                               "the first block."));
        require_non_negative(gap_2, "Body 2", "Gap above body 1");
        require_friction_coefficient(mu_2, "Body 2", "Friction coefficient");
      }
    prm.leave_subsection();
    print_figures = parse_figures_entry(prm);
    obstacle_parameters.parse_parameters(prm, 2);
    material.parse_parameters(prm, 2);
    material_2.parse_parameters(prm, 2, "Material of body 2", body_2);
    bounds.parse_parameters(prm);
  }



  // @sect3{The blocks and the candidates}
  //
  // Each block is built in the plane's frame, centred on the obstacle's
  // point: the lower side of block 1 at the initial gap above the plane,
  // block 2 above it. Gravity acts on every block, the push on the first
  // one, spread over its volume.
  void
  BlockOnPlaneScene::make_bodies()
  {
    const Point<2> p(obstacle_parameters.point[0],
                     obstacle_parameters.point[1]);
    normal = Tensor<1, 2>(
      {obstacle_parameters.normal[0], obstacle_parameters.normal[1]});
    AssertThrow(normal.norm() > 0.,
                ExcMessage("Obstacle: 'Normal' must not be zero: it also "
                           "orients the block."));
    normal /= normal.norm();
    tangent = Tensor<1, 2>({normal[1], -normal[0]});
    block.make_mesh(add_body("block", material, thickness).triangulation(),
                    p,
                    normal,
                    initial_gap);
    if (body_2)
      block_2.make_mesh(
        add_body("block_2", material_2, thickness).triangulation(),
        p,
        normal,
        initial_gap + block.height + gap_2);
  }



  void
  BlockOnPlaneScene::apply_loads()
  {
    const double volume = block.width * block.height * thickness;
    for (unsigned int b = 0; b < n_bodies(); ++b)
      {
        Tensor<1, 2> force = body(b).material().density * gravity;
        if (b == 0)
          force += push / volume;
        body(b).set_body_force(force);
      }
  }



  bool
  BlockOnPlaneScene::frictional() const
  {
    return obstacle_parameters.friction_coefficient > 0. ||
           (body_2 && mu_2 > 0.);
  }



  // The lower side of block 1 (id 2) against the obstacle, and the lower
  // side of block 2 against the upper side of block 1 (id 3).
  void
  BlockOnPlaneScene::add_contacts(ContactSet &contacts)
  {
    obstacle = obstacle_parameters.create<2>(block.width);
    n_plane_candidates =
      contacts.add_node_to_obstacle(system().bodies(),
                                    0,
                                    2,
                                    *obstacle,
                                    obstacle_parameters.friction_coefficient);
    if (body_2)
      contacts.add_node_to_segment(system().bodies(), 1, 2, 0, 3, mu_2);
  }



  void
  BlockOnPlaneScene::set_initial_state(MechanicalState &state)
  {
    body(0).fill_uniform(state.velocity.block(0), velocity);
    if (body_2)
      body(1).fill_uniform(state.velocity.block(1), velocity_2);
  }



  // The mean motion of block 1 (M e_x, M e_y), the vertices of its upper
  // side, and the monitors of the run.
  void
  BlockOnPlaneScene::prepare_run()
  {
    block_mean.reinit(body(0));
    mass_1     = block_mean.mass();
    total_mass = 0.;
    for (unsigned int b = 0; b < n_bodies(); ++b)
      total_mass += body(b).total_mass();
    std::set<unsigned int> top;
    for (const auto &face : body(0).triangulation().active_face_iterators())
      if (face->at_boundary() && face->boundary_id() == 3)
        for (const unsigned int v : face->vertex_indices())
          top.insert(face->vertex_index(v));
    top_vertices.assign(top.begin(), top.end());
    const TimeSteppingParameters &ts = parameters.time_stepping;
    stability = std::make_unique<StabilityMonitor<2>>(system(),
                                                      bounds,
                                                      ts.end_time,
                                                      n_plane_candidates);
    tracker =
      std::make_unique<RigidBlockTracker<2>>(normal, tangent, ts.time_step);
    tracker->start(mean_velocity());
  }



  // @sect3{What a step measures}
  Tensor<1, 2>
  BlockOnPlaneScene::mean_velocity() const
  {
    const Vector<double> &v = system().state().velocity.block(0);
    return block_mean(v);
  }

  // Mean over the upper side's nodes of -u.n.
  double
  BlockOnPlaneScene::top_sinking() const
  {
    const Vector<double> &u = system().state().displacement.block(0);
    double                s = 0.;
    for (const unsigned int v : top_vertices)
      for (unsigned int d = 0; d < 2; ++d)
        s -= body(0).nodal_value(u, v, d) * normal[d];
    return s / top_vertices.size();
  }

  // Weight of the blocks and push, along -n.
  double
  BlockOnPlaneScene::normal_load() const
  {
    return -(total_mass * gravity + push) * normal;
  }

  std::vector<std::string>
  BlockOnPlaneScene::history_columns() const
  {
    return {"mean_velocity_x",
            "mean_velocity_y",
            "plane_reaction",
            "total_energy",
            "active_set_changes"};
  }

  // A state that is not finite stops the run at once, with the step.
  std::vector<double>
  BlockOnPlaneScene::history_values(const StepReport &report)
  {
    const auto &state = system().state();
    AssertThrow(std::isfinite(state.velocity.l2_norm()) &&
                  std::isfinite(state.displacement.l2_norm()),
                ExcMessage("Step " + std::to_string(report.step) +
                           " (t = " + format_number(report.time) +
                           " s): the state is not finite (NaN or inf)."));
    const unsigned int changes = stability->before_record(report);
    return {mean_velocity()[0],
            mean_velocity()[1],
            stability->obstacle_reaction(),
            monitor().total_energy(),
            double(changes)};
  }

  void
  BlockOnPlaneScene::measure_step(const StepReport &report)
  {
    stability->after_record(report, monitor(), top_sinking());
    bool on_plane = false;
    for (unsigned int c = 0; c < n_plane_candidates; ++c)
      on_plane |= system().active_set()[c];
    tracker->record(system().state().time, mean_velocity(), on_plane);
  }



  Tensor<1, 2>
  BlockOnPlaneScene::mean_displacement() const
  {
    const Vector<double> &u = system().state().displacement.block(0);
    return block_mean(u);
  }
} // namespace impactfe
