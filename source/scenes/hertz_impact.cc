#include <impactfe/bodies/geometry.h>
#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/scenes/hertz_impact.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace impactfe
{
  double
  HertzImpact::effective_modulus() const
  {
    double compliance = (1. - poissons_ratio * poissons_ratio) / youngs_modulus;
    if (std::isfinite(flat_youngs_modulus))
      compliance +=
        (1. - flat_poissons_ratio * flat_poissons_ratio) / flat_youngs_modulus;
    return 1. / compliance;
  }



  double
  HertzImpact::max_approach() const
  {
    return std::pow(15. * mass * velocity * velocity /
                      (16. * effective_modulus() * std::sqrt(radius)),
                    0.4);
  }



  double
  HertzImpact::force(const double approach) const
  {
    return 4. / 3. * effective_modulus() * std::sqrt(radius) *
           std::pow(std::max(approach, 0.), 1.5);
  }



  double
  HertzImpact::peak_force() const
  {
    return force(max_approach());
  }



  double
  HertzImpact::max_contact_radius() const
  {
    return std::sqrt(radius * max_approach());
  }



  // int_0^1 (1 - x^(5/2))^(-1/2) dx = (2/5) B(2/5, 1/2) with x^(5/2) = y.
  double
  HertzImpact::contact_duration() const
  {
    const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
    return 2. * 0.4 * beta * max_approach() / velocity;
  }



  void
  HertzBallParameters::declare_parameters(dealii::ParameterHandler &prm)
  {
    using dealii::Patterns::Double;
    using dealii::Patterns::Integer;
    prm.enter_subsection("Geometry");
    prm.declare_entry("Radius",
                      "0.01",
                      Double(),
                      "Radius R of the ball [m]. Must be > 0.");
    prm.declare_entry("Number of refinements",
                      "2",
                      Integer(0, 6),
                      "Global refinements of deal.II's 7-cell ball before "
                      "the grading: 7 * 8^n cells [-].");
    prm.declare_entry("Pole cell factor",
                      "0.3",
                      Double(),
                      "Size of the cells at the lowest point of the ball "
                      "relative to the uniform mesh's [-]; in (0, 1], 1: no "
                      "grading.");
    prm.declare_entry("Fine zone angle",
                      "0.15",
                      Double(),
                      "Polar angle from the lowest point of the cap whose "
                      "cells are smaller by the pole cell factor [rad]; "
                      "Hertz's contact radius a_max must fit in it. The "
                      "angle over the factor must be below 0.9 pi.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Impact velocity",
                      "5",
                      Double(),
                      "Downward velocity of the ball at t = 0 [m/s]. Must be "
                      "> 0.");
    prm.declare_entry("Initial gap",
                      "0",
                      Double(),
                      "Distance from the lowest point of the built-in ball "
                      "to the plane (or the block) at t = 0 [m]. Must be "
                      ">= 0.");
    prm.leave_subsection();
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum peak force error",
                      "-1",
                      Double(),
                      "Fail the run if |F_max - Hertz| / Hertz exceeds this "
                      "[-]. -1: no check.");
    prm.declare_entry("Maximum duration error",
                      "-1",
                      Double(),
                      "Fail the run if |t_c - Hertz| / Hertz exceeds this "
                      "[-]. -1: no check.");
    prm.leave_subsection();
  }



  void
  HertzBallParameters::parse_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    radius           = prm.get_double("Radius");
    n_refinements    = prm.get_integer("Number of refinements");
    pole_cell_factor = prm.get_double("Pole cell factor");
    fine_angle       = prm.get_double("Fine zone angle");
    prm.leave_subsection();
    require_positive(radius, "Geometry", "Radius");
    require_mesh_fits_in_memory(7. * std::pow(8., n_refinements),
                                3,
                                "Geometry",
                                "'Number of refinements'");
    AssertThrow(pole_cell_factor > 0. && pole_cell_factor <= 1.,
                dealii::ExcMessage(
                  "Geometry: 'Pole cell factor' must be in (0, 1], got " +
                  format_number(pole_cell_factor) + "."));
    AssertThrow(fine_angle > 0. && fine_angle / pole_cell_factor < 0.9 * M_PI,
                dealii::ExcMessage(
                  "Geometry: 'Fine zone angle' / 'Pole cell factor' must be "
                  "in (0, 0.9 pi) (the fine zone cannot take the whole "
                  "sphere), got " +
                  format_number(fine_angle) + " / " +
                  format_number(pole_cell_factor) + "."));
    prm.enter_subsection("Initial conditions");
    impact_velocity = prm.get_double("Impact velocity");
    initial_gap     = prm.get_double("Initial gap");
    prm.leave_subsection();
    AssertThrow(impact_velocity > 0.,
                dealii::ExcMessage("Initial conditions: 'Impact velocity' "
                                   "must be > 0, got " +
                                   format_number(impact_velocity) + "."));
    require_non_negative(initial_gap, "Initial conditions", "Initial gap");
    prm.enter_subsection("Verification");
    max_peak_force_error =
      get_verification_bound(prm, "Maximum peak force error");
    max_duration_error = get_verification_bound(prm, "Maximum duration error");
    prm.leave_subsection();
  }



  void
  HertzBallParameters::make_ball(dealii::Triangulation<3> &triangulation) const
  {
    Geometry::graded_ball(triangulation,
                          dealii::Point<3>(0., 0., radius + initial_gap),
                          radius,
                          n_refinements,
                          pole_cell_factor,
                          fine_angle);
  }



  double
  HertzBallParameters::pole_cell_size() const
  {
    return 0.5 * M_PI * std::pow(0.5, n_refinements) * pole_cell_factor *
           radius;
  }



  double
  HertzBallParameters::contact_duration(const double last_contact,
                                        const double end_time) const
  {
    if (last_contact < 0. || last_contact >= end_time)
      return -1.;
    return last_contact - initial_gap / impact_velocity;
  }



  void
  report_against_hertz(const HertzImpact &reference,
                       const double       peak_force,
                       const double       duration,
                       const double       approach,
                       std::ostream      &out,
                       JsonObject        &summary)
  {
    const auto line = [&](const std::string &what,
                          const double       measured,
                          const double       exact,
                          const std::string &unit) {
      out << "  " << what << ": " << measured << " " << unit << ", Hertz "
          << exact << " " << unit << ", relative error "
          << (measured - exact) / exact << std::endl;
    };
    line("Peak force", peak_force, reference.peak_force(), "N");
    const bool measured = duration >= 0.;
    if (measured)
      line("Contact duration", duration, reference.contact_duration(), "s");
    else
      out << "  Contact duration: not measured, "
          << (peak_force > 0. ? "the contact has not ended by the end of the "
                                "run (raise 'End time')" :
                                "no contact force in the run")
          << "; Hertz " << reference.contact_duration() << " s" << std::endl;
    line("Largest approach", approach, reference.max_approach(), "m");
    summary.add("hertz_peak_force", reference.peak_force())
      .add("hertz_contact_duration", reference.contact_duration())
      .add("hertz_max_approach", reference.max_approach())
      .add("hertz_max_contact_radius", reference.max_contact_radius())
      .add("contact_duration", measured ? duration : std::nan(""))
      .add("max_approach", approach)
      .add("peak_force_error",
           (peak_force - reference.peak_force()) / reference.peak_force())
      .add("contact_duration_error",
           measured ? (duration - reference.contact_duration()) /
                        reference.contact_duration() :
                      std::nan(""))
      .add("max_approach_error",
           (approach - reference.max_approach()) / reference.max_approach());
  }



  bool
  check_against_hertz(const HertzImpact &reference,
                      const double       peak_force,
                      const double       duration,
                      const double       max_peak_force_error,
                      const double       max_duration_error,
                      std::ostream      &out)
  {
    bool ok = print_check(out,
                          "Hertz peak force error",
                          std::abs(peak_force - reference.peak_force()) /
                            reference.peak_force(),
                          "<=",
                          max_peak_force_error);
    if (duration < 0. && max_duration_error >= 0.)
      {
        out << "  Check Hertz contact duration error <= " << max_duration_error
            << ": FAILED (not measured)" << std::endl;
        return false;
      }
    ok &= print_check(out,
                      "Hertz contact duration error",
                      std::abs(duration - reference.contact_duration()) /
                        reference.contact_duration(),
                      "<=",
                      max_duration_error);
    return ok;
  }
} // namespace impactfe
