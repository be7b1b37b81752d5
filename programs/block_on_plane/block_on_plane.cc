/* ---------------------------------------------------------------------
 *
 * block_on_plane: an elastic block on a rigid plane under gravity and a
 * push, with Coulomb friction, optionally with a second block falling on
 * it. The scene of the stability cases (tests/stability, doc/stability.md):
 * large time steps, resting contact, stick-slip, grazing incidence, many
 * simultaneous contacts, mass ratios, long runs of repeated impacts.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A rectangular Q1 block of width $W$ and height $H$ lies (or falls) on a
// rigid obstacle, by default the plane $y = 0$. The block is built in the
// frame of the plane: its lower side is parallel to the plane, at the
// `Initial gap` above it, so that an inclined `Normal` gives a block on an
// inclined plane. Gravity and a constant push act as body forces; a second
// block (`Body 2`, off by default) of its own material can be placed above
// the first one and fall on it.
//
// Besides the checks of every contact program (impulse balance, Signorini,
// Coulomb, energy) this program measures what a stability study needs and
// compares it, where one exists, with an independent value:
//  - the energy $E = \tfrac12 v^T M v + \tfrac12 u^T K u - F^T u$, which
//    includes the work of the constant loads, so that a block falling under
//    gravity has a conserved energy;
//  - over a final phase of the run: the drift of the mean gap, the largest
//    penetration, the changes of the active set (chattering) and the mean
//    plane reaction against the normal load (the time average of the
//    reaction equals the load when the momentum is bounded);
//  - the rigid-block model of sliding: with initial velocity $v_0$ along
//    the plane, normal load $N$, tangential load $m a_t$ and friction
//    coefficient $\mu$, the block decelerates at $d = \mu N/m - a_t$ and
//    sticks at $t^* = v_0/d$ after sliding $v_0^2/(2d)$; if $d \le 0$ it
//    never sticks and $v(T) = v_0 - d T$;
//  - the static compression of a block of Poisson's ratio 0 resting on the
//    plane: its top sinks by $\rho g H^2/(2E)$ (the one-dimensional column,
//    which the Q1 solution reproduces at the nodes);
//  - the apparent restitution of the first impact: the block's mean normal
//    velocity when it leaves the plane over the one before it touched.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/elastic_body.h>
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
#include <iomanip>
#include <iostream>
#include <limits>
#include <set>
#include <sstream>

namespace BlockOnPlane
{
  using namespace dealii;
  using namespace impactfe;

  // A figure of merit as the output prints it: three significant digits,
  // and values below @p round_off as "< round_off", so that the output does
  // not depend on the last bits. Relative errors of the measured times and
  // distances have a floor of 1e-4: below it they are set by the elastic
  // vibrations at the instant of sticking, not by the scheme.
  std::string
  figure(const double x, const double round_off = 1e-12)
  {
    std::ostringstream text;
    if (std::abs(x) < round_off)
      text << "< " << round_off;
    else
      text << std::setprecision(3) << x;
    return text.str();
  }

  // sum_ij |A_ij| |x_i| |x_j|: the round-off of x.Ax is at most a small
  // multiple of eps times this (Higham, Accuracy and Stability of Numerical
  // Algorithms, section 3.1), whatever cancels in x.Ax itself.
  double
  absolute_quadratic_form(const SparseMatrix<double> &A, const Vector<double> &x)
  {
    double sum = 0.;
    for (unsigned int i = 0; i < A.m(); ++i)
      for (auto entry = A.begin(i); entry != A.end(i); ++entry)
        sum += std::abs(entry->value() * x(i) * x(entry->column()));
    return sum;
  }

  // A vector as "(x, y)".
  std::string
  vector_text(const Tensor<1, 2> &v)
  {
    std::ostringstream text;
    text << "(" << v[0] << ", " << v[1] << ")";
    return text.str();
  }

  // Two comma-separated coordinates, e.g. "0, -9.81".
  Tensor<1, 2>
  parse_vector(ParameterHandler &prm, const std::string &entry)
  {
    const std::vector<std::string> parts =
      Utilities::split_string_list(prm.get(entry));
    Tensor<1, 2> v;
    for (unsigned int d = 0; d < 2; ++d)
      v[d] = Utilities::string_to_double(parts[d]);
    return v;
  }



  // @sect3{Parameters}
  //
  // The program's own subsections; the rest (Obstacle, Material,
  // Discretization, Time stepping, Contact solver, Output and the common
  // entries of Verification) are the library's.
  struct GeometryParameters
  {
    double       width = 0.1, height = 0.05, thickness = 0.01;
    unsigned int nx = 8, ny = 4;
    double       initial_gap = 0.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      prm.declare_entry("Width", "0.1", Patterns::Double(),
                        "Width W of the block, along the plane [m]. Must be "
                        "> 0.");
      prm.declare_entry("Height", "0.05", Patterns::Double(),
                        "Height H of the block, along the plane's normal "
                        "[m]. Must be > 0.");
      prm.declare_entry("Thickness", "0.01", Patterns::Double(),
                        "Out-of-plane thickness of both blocks [m]. Must be "
                        "> 0.");
      prm.declare_entry("Number of cells across", "8", Patterns::Integer(1),
                        "Q1 cells along the width [-]; the lower side has "
                        "one more contact node.");
      prm.declare_entry("Number of cells up", "4", Patterns::Integer(1),
                        "Q1 cells along the height [-].");
      prm.declare_entry("Initial gap", "0", Patterns::Double(),
                        "Distance of the block's lower side from the plane "
                        "at t = 0 [m]. Must be >= 0. The block is centred "
                        "on the Obstacle's 'Point on plane'.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Geometry");
      width       = prm.get_double("Width");
      height      = prm.get_double("Height");
      thickness   = prm.get_double("Thickness");
      nx          = prm.get_integer("Number of cells across");
      ny          = prm.get_integer("Number of cells up");
      initial_gap = prm.get_double("Initial gap");
      prm.leave_subsection();
      AssertThrow(width > 0. && height > 0.,
                  ExcMessage("Geometry: 'Width' and 'Height' must be > 0, "
                             "got " +
                             format_number(width) + " and " +
                             format_number(height) + "."));
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
    Tensor<1, 2> velocity;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Horizontal velocity", "0", Patterns::Double(),
                        "Velocity of the block along x at t = 0 [m/s].");
      prm.declare_entry("Vertical velocity", "0", Patterns::Double(),
                        "Velocity of the block along y at t = 0 [m/s].");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Initial conditions");
      velocity[0] = prm.get_double("Horizontal velocity");
      velocity[1] = prm.get_double("Vertical velocity");
      prm.leave_subsection();
    }
  };



  struct LoadParameters
  {
    Tensor<1, 2> gravity, push;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      prm.declare_entry("Gravity", "0, -9.81",
                        Patterns::List(Patterns::Double(), 2, 2),
                        "Acceleration of gravity g, x and y components "
                        "[m/s^2]; it acts on both blocks as the body force "
                        "rho g.");
      prm.declare_entry("Push force", "0, 0",
                        Patterns::List(Patterns::Double(), 2, 2),
                        "Constant total force on the block (body 1), x and "
                        "y components [N], spread uniformly over its volume.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      gravity = parse_vector(prm, "Gravity");
      push    = parse_vector(prm, "Push force");
      prm.leave_subsection();
    }
  };



  // The optional second block, centred above the first. Its lower nodes
  // are node-to-segment candidates against the first block's upper side.
  struct SecondBodyParameters
  {
    bool         enabled = false;
    double       width = 0.1, height = 0.05;
    unsigned int nx = 8, ny = 4;
    double       gap = 0.01;
    Tensor<1, 2> velocity;
    double       friction_coefficient = 0.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Body 2");
      prm.declare_entry("Enabled", "false", Patterns::Bool(),
                        "Whether a second block lies above the first one. "
                        "Its material is subsection 'Material of body 2'.");
      prm.declare_entry("Width", "0.1", Patterns::Double(),
                        "Width of the second block [m]; at most the first "
                        "block's width.");
      prm.declare_entry("Height", "0.05", Patterns::Double(),
                        "Height of the second block [m]. Must be > 0.");
      prm.declare_entry("Number of cells across", "8", Patterns::Integer(1),
                        "Q1 cells along the second block's width [-].");
      prm.declare_entry("Number of cells up", "4", Patterns::Integer(1),
                        "Q1 cells along the second block's height [-].");
      prm.declare_entry("Gap above body 1", "0.01", Patterns::Double(),
                        "Distance between the first block's upper side and "
                        "the second block's lower side at t = 0 [m]. Must "
                        "be >= 0.");
      prm.declare_entry("Horizontal velocity", "0", Patterns::Double(),
                        "Velocity of the second block along x at t = 0 "
                        "[m/s].");
      prm.declare_entry("Vertical velocity", "0", Patterns::Double(),
                        "Velocity of the second block along y at t = 0 "
                        "[m/s].");
      prm.declare_entry("Friction coefficient", "0", Patterns::Double(),
                        "Coulomb friction coefficient between the two blocks "
                        "[-]. Must be >= 0.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm, const double width_of_body_1)
    {
      prm.enter_subsection("Body 2");
      enabled              = prm.get_bool("Enabled");
      width                = prm.get_double("Width");
      height               = prm.get_double("Height");
      nx                   = prm.get_integer("Number of cells across");
      ny                   = prm.get_integer("Number of cells up");
      gap                  = prm.get_double("Gap above body 1");
      velocity[0]          = prm.get_double("Horizontal velocity");
      velocity[1]          = prm.get_double("Vertical velocity");
      friction_coefficient = prm.get_double("Friction coefficient");
      prm.leave_subsection();
      if (!enabled)
        return;
      AssertThrow(width > 0. && height > 0.,
                  ExcMessage("Body 2: 'Width' and 'Height' must be > 0, got " +
                             format_number(width) + " and " +
                             format_number(height) + "."));
      AssertThrow(width <= width_of_body_1,
                  ExcMessage("Body 2: 'Width' (" + format_number(width) +
                             ") must not exceed the width of body 1 (" +
                             format_number(width_of_body_1) +
                             "): each of its lower nodes must lie above "
                             "the first block."));
      AssertThrow(gap >= 0.,
                  ExcMessage("Body 2: 'Gap above body 1' must be >= 0, got " +
                             format_number(gap) + "."));
      AssertThrow(friction_coefficient >= 0.,
                  ExcMessage("Body 2: 'Friction coefficient' must be >= 0, "
                             "got " +
                             format_number(friction_coefficient) + "."));
    }
  };



  // The program's own bounds, in the subsection `Verification` beside the
  // library's. A bound of -1 is not checked.
  struct StabilityBounds
  {
    double final_phase_start        = -1.;
    double max_gap_drift            = -1.;
    double max_final_penetration    = -1.;
    double max_active_set_changes   = -1.;
    double max_reaction_error       = -1.;
    double max_stick_time_error     = -1.;
    double max_distance_error       = -1.;
    double max_final_velocity_error = -1.;
    double max_compression_error    = -1.;
    double min_restitution = -1., max_restitution = -1.;
    double max_energy_increase_in_round_offs = -1.;

    static void
    declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      prm.declare_entry("Start of the final phase", "-1", Patterns::Double(),
                        "Time from which the run counts as its final phase "
                        "(at rest, or in a steady regime), where the gap "
                        "drift, the penetration, the active-set changes and "
                        "the mean reaction are measured [s]. -1: half the "
                        "end time.");
      prm.declare_entry("Maximum gap drift", "-1", Patterns::Double(),
                        "Fail the run if the mean gap of the plane's "
                        "contact nodes at the end differs from its value at "
                        "the start of the final phase by more than this "
                        "[m]. -1: no check.");
      prm.declare_entry("Maximum penetration in the final phase", "-1",
                        Patterns::Double(),
                        "Fail the run if a gap goes below minus this during "
                        "the final phase [m]. -1: no check.");
      prm.declare_entry("Maximum active-set changes per step", "-1",
                        Patterns::Double(),
                        "Fail the run if the contact nodes change between "
                        "active and inactive more often than this per step "
                        "during the final phase (chattering) [1/step]. -1: "
                        "no check.");
      prm.declare_entry("Maximum reaction error", "-1", Patterns::Double(),
                        "Fail the run if the mean plane reaction over the "
                        "final phase differs from the normal load (weight "
                        "of the blocks and push) by more than this fraction "
                        "[-]. -1: no check.");
      prm.declare_entry("Maximum stick time error", "-1", Patterns::Double(),
                        "Fail the run if the time at which the block's mean "
                        "velocity along the plane reaches 0 differs from the "
                        "rigid-block value v0 / (mu N/m - a_t) by more than "
                        "this fraction [-]. -1: no check.");
      prm.declare_entry("Maximum sliding distance error", "-1",
                        Patterns::Double(),
                        "Fail the run if the distance slid by the block's "
                        "centre of mass differs from the rigid-block value "
                        "by more than this fraction [-]. -1: no check.");
      prm.declare_entry("Maximum final velocity error", "-1",
                        Patterns::Double(),
                        "Fail the run if, for a block that never sticks, "
                        "the mean velocity along the plane at the end "
                        "differs from the rigid-block value v0 - d T by more "
                        "than this fraction [-]. -1: no check.");
      prm.declare_entry("Maximum static compression error", "-1",
                        Patterns::Double(),
                        "Fail the run if the time-averaged sinking of the "
                        "block's top over the final phase differs from "
                        "rho g H^2 / (2 E) by more than this fraction "
                        "(Poisson's ratio 0, block at rest) [-]. -1: no "
                        "check.");
      prm.declare_entry("Maximum energy increase in round-offs", "-1",
                        Patterns::Double(),
                        "Fail the run if the largest energy increase in a "
                        "step exceeds this many times the round-off of the "
                        "energy, eps (|u|.|K||u| + |v|.|M||v| + |F|.|u|) "
                        "(entry-wise absolute values, largest over the run) "
                        "[-]. The bound for schemes that cannot increase the "
                        "energy. -1: no check.");
      prm.declare_entry("Minimum restitution", "-1", Patterns::Double(),
                        "Fail the run if the apparent restitution of the "
                        "first impact (mean normal velocity after / before) "
                        "is below this [-]. -1: no check.");
      prm.declare_entry("Maximum restitution", "-1", Patterns::Double(),
                        "Fail the run if the apparent restitution of the "
                        "first impact exceeds this [-]. -1: no check.");
      prm.leave_subsection();
    }

    void
    parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      final_phase_start      = prm.get_double("Start of the final phase");
      max_gap_drift          = prm.get_double("Maximum gap drift");
      max_final_penetration  = prm.get_double("Maximum penetration in the final phase");
      max_active_set_changes = prm.get_double("Maximum active-set changes per step");
      max_reaction_error     = prm.get_double("Maximum reaction error");
      max_stick_time_error   = prm.get_double("Maximum stick time error");
      max_distance_error     = prm.get_double("Maximum sliding distance error");
      max_final_velocity_error = prm.get_double("Maximum final velocity error");
      max_compression_error  = prm.get_double("Maximum static compression error");
      max_energy_increase_in_round_offs =
        prm.get_double("Maximum energy increase in round-offs");
      min_restitution        = prm.get_double("Minimum restitution");
      max_restitution        = prm.get_double("Maximum restitution");
      prm.leave_subsection();
    }
  };



  // @sect3{The rigid-block model of sliding}
  //
  // Along the plane's tangent t, with normal load N (pressing), tangential
  // acceleration a_t of the loads and initial velocity v0 = v(0).t:
  // while sliding in the direction s = sign(v0), dv/dt = a_t - s mu N/m.
  struct RigidSliding
  {
    double v0 = 0., deceleration = 0., stick_time = -1., distance = 0.;

    RigidSliding(const double v0,
                 const double a_t,
                 const double normal_load_per_mass,
                 const double mu,
                 const double end_time)
      : v0(v0)
    {
      const double s = v0 >= 0. ? 1. : -1.;
      deceleration   = mu * normal_load_per_mass - s * a_t;
      if (deceleration > 0. && std::abs(v0) / deceleration <= end_time)
        {
          stick_time = std::abs(v0) / deceleration;
          distance   = s * v0 * v0 / (2. * deceleration);
        }
      else
        distance = v0 * end_time - s * 0.5 * deceleration * end_time * end_time;
    }

    bool
    sticks() const
    {
      return stick_time >= 0.;
    }

    /** Velocity along t at @p t (before sticking). */
    double
    velocity(const double t) const
    {
      const double s = v0 >= 0. ? 1. : -1.;
      return v0 - s * deceleration * t;
    }
  };



  // @sect3{The BlockOnPlaneProblem class}
  class BlockOnPlaneProblem
  {
  public:
    BlockOnPlaneProblem(const std::string &parameter_file);
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
    measure_step(const unsigned int active_set_changes_of_step);
    void
    update_energy_round_off();
    void
    report_results();

    GeometryParameters            geometry;
    InitialConditions             initial_conditions;
    LoadParameters                loads;
    SecondBodyParameters          body_2;
    ObstacleParameters            obstacle_parameters;
    MaterialParameters            material, material_2;
    DiscretizationParameters      discretization;
    TimeSteppingParameters        time_stepping;
    ContactSolverParameters       solver_parameters;
    OutputParameters              output;
    ContactVerificationParameters verification;
    StabilityBounds               bounds;
    bool                          print_figures = true;

    std::vector<std::unique_ptr<ElasticBody<2>>> blocks;
    std::unique_ptr<RigidObstacle<2>>            obstacle;
    std::unique_ptr<MultibodySystem<2>>          system;
    std::unique_ptr<SceneRecorder<2>>            recorder;
    double setup_cpu_time = 0., loop_cpu_time = 0.;

    // The plane's frame: unit normal n (towards the block) and tangent t
    // (n turned by -90 degrees: +x for a horizontal plane).
    Tensor<1, 2> normal, tangent;
    // Candidates [0, n_plane_candidates) are against the obstacle, the
    // others between the blocks.
    unsigned int n_plane_candidates = 0;
    // Vertices of the block's upper side.
    std::vector<unsigned int> top_vertices;
    // M e_x and M e_y of block 1, for its mean velocity and displacement.
    std::array<Vector<double>, 2> mass_weights;
    double                        mass_1 = 0., total_mass = 0.;

    // What the loop measures.
    double       final_phase_start = 0.;
    unsigned int final_phase_steps = 0;
    std::vector<bool> previous_active;
    unsigned long long active_set_changes = 0, final_active_set_changes = 0,
                       final_state_changes = 0;
    std::vector<ContactState> previous_states;
    double mean_gap_at_phase_start = 0., mean_gap = 0.;
    double final_penetration       = 0.;
    double reaction_sum = 0., compression_sum = 0.;
    unsigned int final_contact_steps = 0;
    std::vector<double> gaps;
    // Largest eps (|u|.|K||u| + |v|.|M||v| + |F|.|u|) of the run: the
    // round-off with which the energy is computed. u.Ku sums terms of size
    // |K| |u|^2 (u includes the rigid motion) that cancel down to twice the
    // strain energy.
    double energy_round_off = 0.;
    // First impact: normal velocity before touching and after leaving.
    double velocity_before_impact = 0., velocity_after_impact = 0.;
    // 0 before, 1 from the first contact on, 2 once no node touches the
    // plane and the block moves away from it.
    int impact_phase = 0;
    // Sliding: velocity along t at the previous step, zero crossing.
    double previous_tangential_velocity = 0., measured_stick_time = -1.;

    Tensor<1, 2>
    mean_velocity() const;
    Tensor<1, 2>
    mean_displacement() const;
    double
    plane_reaction() const;
    double
    top_sinking() const;
    double
    normal_load() const;
  };



  // @sect4{Constructor: reading the parameter file}
  BlockOnPlaneProblem::BlockOnPlaneProblem(const std::string &parameter_file)
  {
    ParameterHandler prm;
    GeometryParameters::declare_parameters(prm);
    InitialConditions::declare_parameters(prm);
    LoadParameters::declare_parameters(prm);
    SecondBodyParameters::declare_parameters(prm);
    ObstacleParameters::declare_parameters(prm, "0, 0", "0, 1", "0");
    MaterialParameters::declare_parameters(prm, 2);
    MaterialParameters::declare_parameters(prm, 2, "Material of body 2");
    DiscretizationParameters::declare_parameters(prm);
    TimeSteppingParameters::declare_parameters(prm);
    ContactSolverParameters::declare_parameters(prm);
    OutputParameters::declare_parameters(prm, "results/block_on_plane");
    prm.enter_subsection("Output");
    prm.declare_entry("Print figures of merit", "true", Patterns::Bool(),
                      "Print the figures of merit of the run. false prints "
                      "only the checks of 'Verification' and whether they "
                      "hold: for runs whose figures depend on round-off "
                      "(chattering, friction-induced instabilities), so "
                      "that a test compares what is reproducible.");
    prm.leave_subsection();
    ContactVerificationParameters::declare_parameters(prm);
    StabilityBounds::declare_parameters(prm);

    AssertThrow(std::filesystem::exists(parameter_file),
                ExcMessage("The parameter file '" + parameter_file +
                           "' does not exist."));
    prm.parse_input(parameter_file);

    geometry.parse_parameters(prm);
    initial_conditions.parse_parameters(prm);
    loads.parse_parameters(prm);
    body_2.parse_parameters(prm, geometry.width);
    obstacle_parameters.parse_parameters(prm, 2);
    material.parse_parameters(prm, 2);
    material_2.parse_parameters(prm, 2, "Material of body 2");
    discretization.parse_parameters(prm);
    time_stepping.parse_parameters(prm);
    solver_parameters.parse_parameters(prm);
    output.parse_parameters(prm);
    prm.enter_subsection("Output");
    print_figures = prm.get_bool("Print figures of merit");
    prm.leave_subsection();
    verification.parse_parameters(prm);
    bounds.parse_parameters(prm);

    final_phase_start = bounds.final_phase_start < 0. ?
                          0.5 * time_stepping.end_time :
                          bounds.final_phase_start;
    AssertThrow(final_phase_start < time_stepping.end_time,
                ExcMessage("Verification: 'Start of the final phase' (" +
                           format_number(final_phase_start) +
                           " s) must be before the end time."));
  }



  // @sect4{BlockOnPlaneProblem::setup_system}
  //
  // Each block is a subdivided rectangle in the plane's frame (coordinate
  // xi along t, eta along n), mapped to x = p + xi t + eta n. With
  // `colorize`, its boundary ids are 0 left, 1 right, 2 lower side (the
  // contact candidates), 3 upper side.
  void
  BlockOnPlaneProblem::setup_system()
  {
    const Point<2> p(obstacle_parameters.point[0], obstacle_parameters.point[1]);
    normal = Tensor<1, 2>({obstacle_parameters.normal[0],
                           obstacle_parameters.normal[1]});
    AssertThrow(normal.norm() > 0.,
                ExcMessage("Obstacle: 'Normal' must not be zero: it also "
                           "orients the block."));
    normal /= normal.norm();
    tangent = Tensor<1, 2>({normal[1], -normal[0]});

    const auto make_block = [&](const std::string        &name,
                                const MaterialParameters &block_material,
                                const double              width,
                                const double              height,
                                const unsigned int        nx,
                                const unsigned int        ny,
                                const double              lower_side) {
      auto block = std::make_unique<ElasticBody<2>>(name,
                                                    block_material,
                                                    discretization,
                                                    geometry.thickness);
      GridGenerator::subdivided_hyper_rectangle(block->triangulation(),
                                                {nx, ny},
                                                Point<2>(-0.5 * width,
                                                         lower_side),
                                                Point<2>(0.5 * width,
                                                         lower_side + height),
                                                /*colorize=*/true);
      GridTools::transform(
        [&](const Point<2> &q) { return p + q[0] * tangent + q[1] * normal; },
        block->triangulation());
      return block;
    };
    blocks.push_back(make_block("block",
                                material,
                                geometry.width,
                                geometry.height,
                                geometry.nx,
                                geometry.ny,
                                geometry.initial_gap));
    if (body_2.enabled)
      blocks.push_back(make_block("block_2",
                                  material_2,
                                  body_2.width,
                                  body_2.height,
                                  body_2.nx,
                                  body_2.ny,
                                  geometry.initial_gap + geometry.height +
                                    body_2.gap));
    assemble_system();

    const double mu_plane = obstacle_parameters.friction_coefficient;
    const bool   frictional =
      mu_plane > 0. || (body_2.enabled && body_2.friction_coefficient > 0.);
    obstacle = obstacle_parameters.create<2>(geometry.width);
    system   = std::make_unique<MultibodySystem<2>>(time_stepping,
                                                  solver_parameters,
                                                  frictional ? 2 : 1);
    for (const auto &block : blocks)
      system->add_body(*block);
    n_plane_candidates = system->contacts().add_node_to_obstacle(
      system->bodies(), 0, 2, *obstacle, mu_plane);
    if (body_2.enabled)
      system->contacts().add_node_to_segment(system->bodies(),
                                             1,
                                             2,
                                             0,
                                             3,
                                             body_2.friction_coefficient);
    for (const auto &c : system->contacts().candidates())
      AssertThrow(c.initial_gap >= 0.,
                  ExcMessage("Initial conditions: a node of the block is "
                             "below the obstacle at t = 0 (gap " +
                             format_number(c.initial_gap) + " m)."));

    blocks[0]->fill_uniform(system->state().velocity.block(0),
                            initial_conditions.velocity);
    if (body_2.enabled)
      blocks[1]->fill_uniform(system->state().velocity.block(1),
                              body_2.velocity);

    // Mean motion of block 1, and the vertices of its upper side.
    mass_1 = blocks[0]->total_mass();
    for (unsigned int d = 0; d < 2; ++d)
      {
        Vector<double> unit;
        Tensor<1, 2>   e;
        e[d] = 1.;
        blocks[0]->fill_uniform(unit, e);
        mass_weights[d].reinit(unit.size());
        blocks[0]->mass_matrix().vmult(mass_weights[d], unit);
      }
    total_mass = 0.;
    for (const auto &block : blocks)
      total_mass += block->total_mass();
    std::set<unsigned int> top;
    for (const auto &face : blocks[0]->triangulation().active_face_iterators())
      if (face->at_boundary() && face->boundary_id() == 3)
        for (const unsigned int v : face->vertex_indices())
          top.insert(face->vertex_index(v));
    top_vertices.assign(top.begin(), top.end());

    create_output_directory(output.directory);
    system->set_dump_directory(output.directory);
    system->setup();
    previous_active.assign(system->contacts().n_candidates(), false);
    previous_states.assign(system->contacts().n_candidates(),
                           ContactState::open);
    previous_tangential_velocity = mean_velocity() * tangent;
    velocity_before_impact       = mean_velocity() * normal;
    recorder = std::make_unique<SceneRecorder<2>>(
      *system,
      output,
      std::vector<std::string>{"mean_velocity_x",
                               "mean_velocity_y",
                               "plane_reaction",
                               "total_energy",
                               "active_set_changes"});
  }



  // @sect4{BlockOnPlaneProblem::assemble_system}
  //
  // M, K and the loads: gravity on every block, the push on the first one,
  // spread over its volume.
  void
  BlockOnPlaneProblem::assemble_system()
  {
    const double volume = geometry.width * geometry.height * geometry.thickness;
    for (unsigned int b = 0; b < blocks.size(); ++b)
      {
        blocks[b]->setup();
        Tensor<1, 2> force = blocks[b]->material().density * loads.gravity;
        if (b == 0)
          force += loads.push / volume;
        blocks[b]->set_body_force(force);
      }
  }



  // @sect4{Mean motion, reaction and top of the block}
  Tensor<1, 2>
  BlockOnPlaneProblem::mean_velocity() const
  {
    const Vector<double> &v = system->state().velocity.block(0);
    return Tensor<1, 2>({(mass_weights[0] * v) / mass_1,
                         (mass_weights[1] * v) / mass_1});
  }

  Tensor<1, 2>
  BlockOnPlaneProblem::mean_displacement() const
  {
    const Vector<double> &u = system->state().displacement.block(0);
    return Tensor<1, 2>({(mass_weights[0] * u) / mass_1,
                         (mass_weights[1] * u) / mass_1});
  }

  // Total normal force of the plane on the block in the last step.
  double
  BlockOnPlaneProblem::plane_reaction() const
  {
    const unsigned int nd = system->contacts().n_directions();
    double             P  = 0.;
    for (unsigned int c = 0; c < n_plane_candidates; ++c)
      P += system->impulses()[c * nd];
    return P * system->integrator().force_per_impulse();
  }

  // Mean over the upper side's nodes of -u.n.
  double
  BlockOnPlaneProblem::top_sinking() const
  {
    const Vector<double> &u = system->state().displacement.block(0);
    double                s = 0.;
    for (const unsigned int v : top_vertices)
      for (unsigned int d = 0; d < 2; ++d)
        s -= blocks[0]->nodal_value(u, v, d) * normal[d];
    return s / top_vertices.size();
  }

  // Weight of the blocks and push, along -n.
  double
  BlockOnPlaneProblem::normal_load() const
  {
    return -(total_mass * loads.gravity + loads.push) * normal;
  }



  // @sect4{BlockOnPlaneProblem::do_time_step}
  //
  // One step of the scheme, then the measurements: a state that is not
  // finite stops the run at once, with the step.
  StepReport
  BlockOnPlaneProblem::do_time_step()
  {
    const StepReport report = system->do_time_step();
    const auto      &state  = system->state();
    AssertThrow(std::isfinite(state.velocity.l2_norm()) &&
                  std::isfinite(state.displacement.l2_norm()),
                ExcMessage("Step " + std::to_string(report.step) +
                           " (t = " + format_number(report.time) +
                           " s): the state is not finite (NaN or inf)."));
    return report;
  }



  // @sect4{BlockOnPlaneProblem::output_results}
  //
  // The recorder's files and checks (history.csv gets this program's
  // columns), then this program's measurements of the step.
  void
  BlockOnPlaneProblem::output_results(const StepReport &report)
  {
    unsigned int changes = 0;
    if (report.step > 0)
      {
        const std::vector<bool> &active = system->active_set();
        for (unsigned int c = 0; c < active.size(); ++c)
          changes += active[c] != previous_active[c] ? 1 : 0;
        previous_active = active;
      }
    update_energy_round_off();
    recorder->record(report,
                     {mean_velocity()[0],
                      mean_velocity()[1],
                      plane_reaction(),
                      recorder->monitor().total_energy(),
                      double(changes)});
    if (report.step > 0)
      measure_step(changes);
  }



  // @sect4{BlockOnPlaneProblem::measure_step}
  //
  // Active-set and contact-state changes, the gap, penetration, reaction
  // and top of the block in the final phase, the first impact, and the
  // first time the mean velocity along the plane reaches 0. Called after
  // the recorder, whose monitor classifies the contact states.
  void
  BlockOnPlaneProblem::measure_step(const unsigned int active_set_changes_of_step)
  {
    const double t        = system->state().time;
    const bool   in_final = t >= final_phase_start - 1e-9 * time_stepping.time_step;
    active_set_changes += active_set_changes_of_step;

    system->contacts().gaps(system->state().displacement, gaps);
    mean_gap = 0.;
    for (unsigned int c = 0; c < n_plane_candidates; ++c)
      mean_gap += gaps[c] / n_plane_candidates;

    for (unsigned int c = 0; c < previous_states.size(); ++c)
      {
        const ContactState state = recorder->monitor().state(c);
        final_state_changes += (in_final && state != previous_states[c]) ? 1 : 0;
        previous_states[c] = state;
      }
    if (in_final)
      {
        if (final_phase_steps == 0)
          mean_gap_at_phase_start = mean_gap;
        ++final_phase_steps;
        final_active_set_changes += active_set_changes_of_step;
        for (const double g : gaps)
          final_penetration = std::max(final_penetration, -g);
        reaction_sum += plane_reaction();
        final_contact_steps += plane_reaction() > 0. ? 1 : 0;
        compression_sum += top_sinking();
      }

    // First impact on the plane.
    const double v_n      = mean_velocity() * normal;
    bool         on_plane = false;
    for (unsigned int c = 0; c < n_plane_candidates; ++c)
      on_plane |= system->active_set()[c];
    if (impact_phase == 0 && on_plane)
      impact_phase = 1;
    else if (impact_phase == 1 && !on_plane && v_n > 0.)
      {
        impact_phase          = 2;
        velocity_after_impact = v_n;
      }
    if (impact_phase == 0)
      velocity_before_impact = v_n;

    // The first time the mean velocity along t reaches 0, between this
    // step and the last (linear interpolation).
    const double v_t = mean_velocity() * tangent;
    if (measured_stick_time < 0. && previous_tangential_velocity != 0. &&
        v_t * previous_tangential_velocity <= 0.)
      measured_stick_time =
        t - time_stepping.time_step +
        time_stepping.time_step * previous_tangential_velocity /
          (previous_tangential_velocity - v_t);
    previous_tangential_velocity = v_t;
  }



  // @sect4{BlockOnPlaneProblem::update_energy_round_off}
  void
  BlockOnPlaneProblem::update_energy_round_off()
  {
    double round_off = 0.;
    for (unsigned int b = 0; b < blocks.size(); ++b)
      {
        const Vector<double> &u = system->state().displacement.block(b),
                             &v = system->state().velocity.block(b);
        round_off += absolute_quadratic_form(blocks[b]->stiffness_matrix(), u) +
                     absolute_quadratic_form(blocks[b]->mass_matrix(), v);
        for (unsigned int i = 0; i < u.size(); ++i)
          round_off += std::abs(blocks[b]->external_force()(i) * u(i));
      }
    energy_round_off =
      std::max(energy_round_off,
               std::numeric_limits<double>::epsilon() * round_off);
  }



  // @sect4{BlockOnPlaneProblem::report_results}
  //
  // The screen report (compared by the tests: figures with three
  // significant digits, no timings) and summary.json. Each figure is
  // printed beside its independent value where there is one, and the
  // bounds of `Verification` are checked.
  void
  BlockOnPlaneProblem::report_results()
  {
    const ContactRunSummary &s   = recorder->monitor().summary();
    const double             h   = time_stepping.time_step;
    const double             T   = system->state().time;
    const double             mu  = obstacle_parameters.friction_coefficient;
    const double             c_p = material.longitudinal_wave_speed<2>();
    const double dx = std::min(geometry.width / geometry.nx,
                               geometry.height / geometry.ny);
    // The report goes to a string first: with 'Print figures of merit =
    // false' only its header and the checks reach the screen.
    std::ostringstream out;

    out << "Block on a plane, scheme " << to_string(time_stepping.scheme);
    if (time_stepping.scheme == Scheme::newmark)
      out << " (beta = " << time_stepping.newmark_beta
          << ", gamma = " << time_stepping.newmark_gamma << ")";
    else
      out << " (theta = " << time_stepping.theta << ")";
    out << ", h = " << h << " s, " << s.n_steps << " steps" << std::endl;
    out << "  Block: " << geometry.width << " m x " << geometry.height
        << " m, " << geometry.nx << " x " << geometry.ny << " Q1 cells, "
        << n_plane_candidates << " contact nodes on the plane; obstacle: "
        << obstacle->description() << ", mu = " << mu << std::endl;
    if (body_2.enabled)
      out << "  Body 2: " << body_2.width << " m x " << body_2.height
          << " m, " << body_2.nx << " x " << body_2.ny << " Q1 cells, "
          << system->contacts().n_candidates() - n_plane_candidates
          << " contact nodes on block 1, mu = "
          << body_2.friction_coefficient << "; mass ratio body 2 / body 1 = "
          << figure(blocks[1]->total_mass() / mass_1) << std::endl;
    out << "  Mass " << figure(mass_1) << " kg; wave speed c = "
        << figure(c_p) << " m/s; Courant number c h / dx = "
        << figure(c_p * h / dx) << std::endl;
    out << "  Loads: gravity " << vector_text(loads.gravity) << " m/s^2, push "
        << vector_text(loads.push) << " N; initial velocity "
        << vector_text(initial_conditions.velocity) << " m/s" << std::endl;

    const Tensor<1, 2> v_end = mean_velocity();
    out << "  Mean velocity of the block at the end: (" << figure(v_end[0], 1e-9)
        << ", " << figure(v_end[1], 1e-9) << ") m/s" << std::endl;
    if (system->contacts().n_directions() > 1 && s.normal_impulse > 0.)
      out << "  Tangential / normal impulse = "
          << figure(s.tangential_impulse / s.normal_impulse)
          << " (Coulomb bound mu = " << mu << ")" << std::endl;

    bool ok = print_contact_summary(out,
                                    s,
                                    verification,
                                    system->contacts().n_directions() > 1);

    // The energy's round-off, in units of the energy scale of the summary.
    const double round_off =
      s.energy_scale > 0. ? energy_round_off / s.energy_scale : 0.;
    const double increase_in_round_offs =
      round_off > 0. ? s.max_energy_increase / round_off : 0.;
    out << "  Round-off of the energy eps (|u|.|K||u| + |v|.|M||v| + "
           "|F|.|u|) = "
        << figure(round_off, 1e-300) << " of the same scale; largest increase "
        << "in a step = " << figure(increase_in_round_offs, 100.)
        << " round-offs" << std::endl;
    ok &= print_check(out, "energy increase in a step in round-offs",
                      increase_in_round_offs, "<=",
                      bounds.max_energy_increase_in_round_offs);

    // The final phase.
    const double gap_drift = std::abs(mean_gap - mean_gap_at_phase_start);
    const double changes_per_step =
      double(active_set_changes) / std::max(1u, s.n_steps);
    const double final_changes_per_step =
      double(final_active_set_changes) / std::max(1u, final_phase_steps);
    out << "  Active-set changes: " << active_set_changes << " in the run ("
        << figure(changes_per_step) << " per step)" << std::endl;
    out << "  Final phase from t = " << final_phase_start << " s ("
        << final_phase_steps << " steps): gap drift " << figure(gap_drift)
        << " m, largest penetration " << figure(final_penetration)
        << " m, active-set changes " << final_active_set_changes
        << ", contact state changes " << final_state_changes << std::endl;
    ok &= print_check(out, "gap drift", gap_drift, "<=", bounds.max_gap_drift);
    ok &= print_check(out, "penetration in the final phase", final_penetration,
                      "<=", bounds.max_final_penetration);
    ok &= print_check(out, "active-set changes per step in the final phase",
                      final_changes_per_step, "<=",
                      bounds.max_active_set_changes);

    // Mean reaction against the normal load, if the block is on the plane
    // in the final phase.
    const double load           = normal_load();
    const double mean_reaction  = reaction_sum / std::max(1u, final_phase_steps);
    double       reaction_error = -1.;
    if (load > 0. && final_contact_steps > 0)
      {
        reaction_error = std::abs(mean_reaction - load) / load;
        out << "  Mean plane reaction in the final phase " << figure(mean_reaction)
            << " N, normal load " << figure(load) << " N: relative error "
            << figure(reaction_error, 1e-9) << std::endl;
        ok &= print_check(out, "reaction error", reaction_error, "<=",
                          bounds.max_reaction_error);
      }

    // Static compression: a single block of Poisson's ratio 0, at rest,
    // pressed by gravity normal to the plane.
    const double g_n = -loads.gravity * normal;
    double       compression_error = -1.;
    if (!body_2.enabled && material.poissons_ratio == 0. && g_n > 0. &&
        std::abs(loads.gravity * tangent) == 0. && loads.push.norm() == 0. &&
        initial_conditions.velocity.norm() == 0. &&
        obstacle_parameters.type == ObstacleParameters::Type::plane)
      {
        const double exact = material.density * g_n * geometry.height *
                             geometry.height / (2. * material.youngs_modulus);
        const double mean  = compression_sum / std::max(1u, final_phase_steps);
        compression_error  = std::abs(mean - exact) / exact;
        out << "  Static compression of the top: rho g H^2 / (2 E) = "
            << figure(exact) << " m, time average in the final phase "
            << figure(mean) << " m, at the end " << figure(top_sinking())
            << " m: relative error " << figure(compression_error, 1e-9) << std::endl;
        ok &= print_check(out, "static compression error", compression_error,
                          "<=", bounds.max_compression_error);
      }

    // Sliding against the rigid-block model: a single block that starts on
    // the plane with no normal velocity.
    const Tensor<1, 2> v0 = initial_conditions.velocity;
    double stick_error = -1., distance_error = -1., velocity_error = -1.;
    const double a_t = (loads.gravity + loads.push / mass_1) * tangent;
    if (!body_2.enabled && geometry.initial_gap == 0. && v0 * normal == 0. &&
        (v0 * tangent != 0. || a_t != 0.) &&
        obstacle_parameters.type == ObstacleParameters::Type::plane)
      {
        const RigidSliding rigid(v0 * tangent, a_t, load / mass_1, mu, T);
        const double       distance = mean_displacement() * tangent;
        out << "  Rigid-block sliding: v0 = " << figure(rigid.v0)
            << " m/s, deceleration mu N/m - a_t = "
            << figure(rigid.deceleration) << " m/s^2" << std::endl;
        if (rigid.sticks())
          {
            out << "    sticks at t* = v0 / d = " << figure(rigid.stick_time)
                << " s; measured (mean velocity reaches 0): ";
            if (measured_stick_time >= 0.)
              {
                stick_error = std::abs(measured_stick_time - rigid.stick_time) /
                              rigid.stick_time;
                out << figure(measured_stick_time) << " s, relative error "
                    << figure(stick_error, 1e-4);
              }
            else
              {
                stick_error = 1.;
                out << "never";
              }
            out << std::endl;
          }
        else
          {
            const double v_end = mean_velocity() * tangent;
            velocity_error = std::abs(v_end - rigid.velocity(T)) /
                             std::max(std::abs(rigid.velocity(T)), 1e-300);
            out << "    never sticks: velocity at T = " << T
                << " s: v0 - d T = " << figure(rigid.velocity(T))
                << " m/s, measured " << figure(v_end)
                << " m/s, relative error " << figure(velocity_error, 1e-6)
                << std::endl;
            if (measured_stick_time >= 0.)
              out << "    but the mean velocity reached 0 at t = "
                  << figure(measured_stick_time) << " s" << std::endl;
          }
        distance_error = std::abs(distance - rigid.distance) /
                         std::max(std::abs(rigid.distance), 1e-300);
        out << "    distance slid by the centre of mass: "
            << figure(rigid.distance) << " m, measured " << figure(distance)
            << " m, relative error " << figure(distance_error, 1e-4) << std::endl;
        ok &= print_check(out, "stick time error",
                          rigid.sticks() ? stick_error : 0., "<=",
                          rigid.sticks() ? bounds.max_stick_time_error : -1.);
        ok &= print_check(out, "final velocity error",
                          rigid.sticks() ? 0. : velocity_error, "<=",
                          rigid.sticks() ? -1. : bounds.max_final_velocity_error);
        ok &= print_check(out, "sliding distance error", distance_error, "<=",
                          bounds.max_distance_error);
      }

    // Apparent restitution of the first impact.
    double restitution = -1.;
    if (impact_phase > 0 && velocity_before_impact < 0.)
      {
        restitution = impact_phase == 2 ?
                        -velocity_after_impact / velocity_before_impact :
                        0.;
        out << "  First impact: mean normal velocity before "
            << figure(velocity_before_impact) << " m/s, ";
        if (impact_phase == 2)
          out << "after " << figure(velocity_after_impact) << " m/s";
        else
          out << "the block never leaves the plane";
        out << ": apparent restitution " << figure(restitution, 1e-6)
            << std::endl;
        ok &= print_check(out, "restitution", restitution, ">=",
                          bounds.min_restitution);
        ok &= print_check(out, "restitution", restitution, "<=",
                          bounds.max_restitution);
      }

    JsonObject stability;
    stability.add("courant_number", c_p * h / dx)
      .add("max_penetration", s.max_penetration)
      .add("energy_change", s.energy_ratio - 1.)
      .add("max_energy_increase", s.max_energy_increase)
      .add("energy_round_off", round_off)
      .add("active_set_changes", double(active_set_changes))
      .add("active_set_changes_per_step", changes_per_step)
      .add("final_phase_start", final_phase_start)
      .add("final_active_set_changes_per_step", final_changes_per_step)
      .add("final_state_changes", double(final_state_changes))
      .add("gap_drift", gap_drift)
      .add("final_penetration", final_penetration)
      .add("reaction_error", reaction_error)
      .add("compression_error", compression_error)
      .add("measured_stick_time", measured_stick_time)
      .add("stick_time_error", stick_error)
      .add("distance_error", distance_error)
      .add("final_velocity_error", velocity_error)
      .add("restitution", restitution)
      .add("checks_passed", ok ? 1. : 0.);
    JsonObject summary;
    summary.add("program", std::string("block_on_plane"))
      .add("scheme", to_string(time_stepping.scheme))
      .add("theta", time_stepping.theta)
      .add("time_step", h)
      .add("setup_cpu_seconds", setup_cpu_time)
      .add("loop_cpu_seconds", loop_cpu_time)
      .add("stability", stability);
    recorder->add_summary(summary);
    summary.write(output.directory + "/summary.json");

    if (output.print_performance)
      out << "  CPU seconds: set-up " << setup_cpu_time << ", time loop "
          << loop_cpu_time << "; LCP: " << system->total_pivots()
          << " pivots in total, largest LCP " << system->largest_lcp()
          << std::endl;
    recorder->report_files(out,
                           {"normal_force", "mean_velocity_x", "total_energy"},
                           "Block on a plane, " +
                             to_string(time_stepping.scheme));
    if (print_figures)
      std::cout << out.str();
    else
      {
        std::istringstream lines(out.str());
        std::string        line;
        while (std::getline(lines, line))
          if (line.rfind("Block on a plane", 0) == 0 ||
              line.rfind("  Block:", 0) == 0 || line.rfind("  Body 2:", 0) == 0 ||
              line.rfind("  Check ", 0) == 0 || line.rfind("Results in", 0) == 0)
            std::cout << line << std::endl;
          else if (line.rfind("  Mass ", 0) == 0)
            std::cout << "  (figures of merit not printed: 'Print figures of "
                         "merit' is false)"
                      << std::endl;
      }
    AssertThrow(ok,
                ExcMessage("Verification: at least one bound of subsection "
                           "'Verification' does not hold (see above)."));
  }



  // @sect4{BlockOnPlaneProblem::run}
  void
  BlockOnPlaneProblem::run()
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
} // namespace BlockOnPlane



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
                     "/parameter_files/block_on_plane.prm";
      BlockOnPlane::BlockOnPlaneProblem problem(parameter_file);
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
