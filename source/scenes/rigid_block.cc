#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/scenes/rigid_block.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace impactfe
{
  // @sect3{The sliding block's entries}
  void
  SlidingBoxParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Length", "0.1", Patterns::Double(), "Along x [m].");
    prm.declare_entry("Height", "0.01", Patterns::Double(), "Along y [m].");
    prm.declare_entry("Width", "0.1", Patterns::Double(), "Along z [m].");
    prm.declare_entry("Number of cells along x",
                      "4",
                      Patterns::Integer(1),
                      "Q1 cells along the length [-].");
    prm.declare_entry("Number of cells up",
                      "1",
                      Patterns::Integer(1),
                      "Q1 cells along the height [-].");
    prm.declare_entry("Number of cells along z",
                      "4",
                      Patterns::Integer(1),
                      "Q1 cells along the width [-].");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Sliding speed",
                      "1",
                      Patterns::Double(),
                      "v0 [m/s], along the plane. Must be > 0.");
    prm.declare_entry("Sliding direction",
                      "0",
                      Patterns::Double(),
                      "phi [rad]: the block is launched along (cos phi, 0, "
                      "sin phi).");
    prm.leave_subsection();
    prm.enter_subsection("Loads");
    prm.declare_entry("Gravity",
                      "9.81",
                      Patterns::Double(),
                      "g [m/s^2], towards the plane (-y). Must be >= 0.");
    prm.leave_subsection();
    StabilityBounds::declare_parameters(prm);
  }



  void
  SlidingBoxParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    length = prm.get_double("Length");
    height = prm.get_double("Height");
    width  = prm.get_double("Width");
    nx     = prm.get_integer("Number of cells along x");
    ny     = prm.get_integer("Number of cells up");
    nz     = prm.get_integer("Number of cells along z");
    prm.leave_subsection();
    require_positive(length, "Geometry", "Length");
    require_positive(height, "Geometry", "Height");
    require_positive(width, "Geometry", "Width");
    require_mesh_fits_in_memory(double(nx) * ny * nz,
                                3,
                                "Geometry",
                                "'Number of cells along x', 'Number of cells "
                                "up' and 'Number of cells along z'");
    prm.enter_subsection("Initial conditions");
    speed = prm.get_double("Sliding speed");
    phi   = prm.get_double("Sliding direction");
    prm.leave_subsection();
    require_positive(speed, "Initial conditions", "Sliding speed");
    AssertThrow(std::isfinite(phi),
                ExcMessage(
                  "Initial conditions: 'Sliding direction' must be finite."));
    prm.enter_subsection("Loads");
    gravity = prm.get_double("Gravity");
    prm.leave_subsection();
    require_non_negative(gravity, "Loads", "Gravity");
    bounds.parse_parameters(prm);
  }



  void
  BlockParameters::declare_parameters(ParameterHandler  &prm,
                                      const std::string &what)
  {
    prm.declare_entry("Width",
                      "0.1",
                      Patterns::Double(),
                      "Width of the " + what +
                        ", along the plane [m]. Must be > 0.");
    prm.declare_entry("Height",
                      "0.05",
                      Patterns::Double(),
                      "Height of the " + what +
                        ", along the plane's normal [m]. Must be > 0.");
    prm.declare_entry("Number of cells across",
                      "8",
                      Patterns::Integer(1),
                      "Q1 cells along the width of the " + what +
                        " [-]; the lower side has one more node.");
    prm.declare_entry("Number of cells up",
                      "4",
                      Patterns::Integer(1),
                      "Q1 cells along the height of the " + what + " [-].");
  }



  void
  BlockParameters::parse_parameters(ParameterHandler  &prm,
                                    const std::string &subsection)
  {
    width    = prm.get_double("Width");
    height   = prm.get_double("Height");
    n_across = prm.get_integer("Number of cells across");
    n_up     = prm.get_integer("Number of cells up");
    AssertThrow(width > 0. && height > 0.,
                ExcMessage(subsection +
                           ": 'Width' and 'Height' must be > 0, "
                           "got " +
                           format_number(width) + " and " +
                           format_number(height) + "."));
    require_mesh_fits_in_memory(double(n_across) * n_up,
                                2,
                                subsection,
                                "'Number of cells across' and 'Number of "
                                "cells up'");
  }



  void
  BlockParameters::make_mesh(Triangulation<2>   &tria,
                             const Point<2>     &origin,
                             const Tensor<1, 2> &normal,
                             const double        lower_side) const
  {
    const Tensor<1, 2> tangent({normal[1], -normal[0]});
    GridGenerator::subdivided_hyper_rectangle(
      tria,
      {n_across, n_up},
      Point<2>(-0.5 * width, lower_side),
      Point<2>(0.5 * width, lower_side + height),
      /*colorize=*/true);
    GridTools::transform(
      [&](const Point<2> &q) {
        return origin + q[0] * tangent + q[1] * normal;
      },
      tria);
  }



  Tensor<1, 2>
  get_vector(ParameterHandler  &prm,
             const std::string &subsection,
             const std::string &entry)
  {
    const std::vector<std::string> parts =
      Utilities::split_string_list(prm.get(entry));
    AssertThrow(parts.size() == 2,
                ExcMessage(subsection + ": '" + entry +
                           "' needs 2 components, got '" + prm.get(entry) +
                           "'."));
    Tensor<1, 2> v;
    for (unsigned int d = 0; d < 2; ++d)
      v[d] = parse_list_number(parts[d], subsection, entry);
    return v;
  }



  RigidSliding::RigidSliding(const double v0,
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
  RigidSliding::sticks() const
  {
    return stick_time >= 0.;
  }



  double
  RigidSliding::velocity(const double t) const
  {
    const double s = v0 >= 0. ? 1. : -1.;
    return v0 - s * deceleration * t;
  }



  template <int dim>
  RigidBlockTracker<dim>::RigidBlockTracker(const Tensor<1, dim> &normal,
                                            const Tensor<1, dim> &tangent,
                                            const double          time_step)
    : normal(normal)
    , tangent(tangent)
    , time_step(time_step)
  {}



  template <int dim>
  void
  RigidBlockTracker<dim>::start(const Tensor<1, dim> &mean_velocity)
  {
    previous_tangential_velocity = mean_velocity * tangent;
    velocity_before_impact       = mean_velocity * normal;
  }



  template <int dim>
  void
  RigidBlockTracker<dim>::record(const double          t,
                                 const Tensor<1, dim> &mean_velocity,
                                 const bool            on_plane)
  {
    // First impact on the plane.
    const double v_n = mean_velocity * normal;
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
    const double v_t = mean_velocity * tangent;
    if (first_stop_time < 0. && previous_tangential_velocity != 0. &&
        v_t * previous_tangential_velocity <= 0.)
      first_stop_time = t - time_step +
                        time_step * previous_tangential_velocity /
                          (previous_tangential_velocity - v_t);
    previous_tangential_velocity = v_t;
  }



  // Relative errors of the measured times and distances have a floor of
  // 1e-4: below it they are set by the elastic vibrations at the instant of
  // sticking, not by the scheme.
  template <int dim>
  bool
  RigidBlockTracker<dim>::report_sliding(std::ostream          &out,
                                         const RigidSliding    &rigid,
                                         const double           distance,
                                         const double           final_velocity,
                                         const double           T,
                                         const StabilityBounds &bounds,
                                         JsonObject            &stability) const
  {
    double stick_error = -1., velocity_error = -1.;
    out << "  Rigid-block sliding: v0 = " << format_figure(rigid.v0)
        << " m/s, deceleration mu N/m - a_t = "
        << format_figure(rigid.deceleration) << " m/s^2" << std::endl;
    if (rigid.sticks())
      {
        out << "    sticks at t* = v0 / d = " << format_figure(rigid.stick_time)
            << " s; measured (mean velocity reaches 0): ";
        if (first_stop_time >= 0.)
          {
            stick_error =
              std::abs(first_stop_time - rigid.stick_time) / rigid.stick_time;
            out << format_figure(first_stop_time) << " s, relative error "
                << format_figure(stick_error, 1e-4);
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
        velocity_error = std::abs(final_velocity - rigid.velocity(T)) /
                         std::max(std::abs(rigid.velocity(T)), 1e-300);
        out << "    never sticks: velocity at T = " << T
            << " s: v0 - d T = " << format_figure(rigid.velocity(T))
            << " m/s, measured " << format_figure(final_velocity)
            << " m/s, relative error " << format_figure(velocity_error, 1e-6)
            << std::endl;
        if (first_stop_time >= 0.)
          out << "    but the mean velocity reached 0 at t = "
              << format_figure(first_stop_time) << " s" << std::endl;
      }
    const double distance_error = std::abs(distance - rigid.distance) /
                                  std::max(std::abs(rigid.distance), 1e-300);
    out << "    distance slid by the centre of mass: "
        << format_figure(rigid.distance) << " m, measured "
        << format_figure(distance) << " m, relative error "
        << format_figure(distance_error, 1e-4) << std::endl;
    bool ok = print_check(out,
                          "stick time error",
                          rigid.sticks() ? stick_error : 0.,
                          "<=",
                          rigid.sticks() ? bounds.max_stick_time_error : -1.);
    ok &= print_check(out,
                      "final velocity error",
                      rigid.sticks() ? 0. : velocity_error,
                      "<=",
                      rigid.sticks() ? -1. : bounds.max_final_velocity_error);
    ok &= print_check(out,
                      "sliding distance error",
                      distance_error,
                      "<=",
                      bounds.max_distance_error);
    stability.add("measured_stick_time", first_stop_time)
      .add("stick_time_error", stick_error)
      .add("distance_error", distance_error)
      .add("final_velocity_error", velocity_error);
    return ok;
  }



  template <int dim>
  bool
  RigidBlockTracker<dim>::report_restitution(std::ostream          &out,
                                             const StabilityBounds &bounds,
                                             JsonObject &stability) const
  {
    double restitution = -1.;
    bool   ok          = true;
    if (impact_phase > 0 && velocity_before_impact < 0.)
      {
        restitution = impact_phase == 2 ?
                        -velocity_after_impact / velocity_before_impact :
                        0.;
        out << "  First impact: mean normal velocity before "
            << format_figure(velocity_before_impact) << " m/s, ";
        if (impact_phase == 2)
          out << "after " << format_figure(velocity_after_impact) << " m/s";
        else
          out << "the block never leaves the plane";
        out << ": apparent restitution " << format_figure(restitution, 1e-6)
            << std::endl;
        ok &= print_check(
          out, "restitution", restitution, ">=", bounds.min_restitution);
        ok &= print_check(
          out, "restitution", restitution, "<=", bounds.max_restitution);
      }
    stability.add("restitution", restitution);
    return ok;
  }



  template <int dim>
  double
  RigidBlockTracker<dim>::stop_time() const
  {
    return first_stop_time;
  }



  template <int dim>
  void
  MassWeightedMean<dim>::reinit(const ElasticBody<dim> &body)
  {
    total_mass = body.total_mass();
    for (unsigned int d = 0; d < dim; ++d)
      {
        Vector<double> unit;
        Tensor<1, dim> e;
        e[d] = 1.;
        body.fill_uniform(unit, e);
        weights[d].reinit(unit.size());
        body.mass_matrix().vmult(weights[d], unit);
      }
  }



  template <int dim>
  Tensor<1, dim>
  MassWeightedMean<dim>::operator()(const Vector<double> &field) const
  {
    Tensor<1, dim> mean;
    for (unsigned int d = 0; d < dim; ++d)
      mean[d] = (weights[d] * field) / total_mass;
    return mean;
  }



  template <int dim>
  double
  MassWeightedMean<dim>::mass() const
  {
    return total_mass;
  }



  template class MassWeightedMean<2>;
  template class MassWeightedMean<3>;
  template class RigidBlockTracker<2>;
  template class RigidBlockTracker<3>;
} // namespace impactfe
