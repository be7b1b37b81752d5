/* ---------------------------------------------------------------------
 * hertz_impact: an elastic ball (Q1 hexahedra, graded towards the point
 * of contact) dropped slowly on a rigid frictionless plane or ball,
 * against Hertz's theory of impact: contact duration, peak force and
 * largest approach.
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A ball of radius R moves down at v onto the rigid plane z = 0 (or onto a
// rigid ball of radius R2 touching it there: then R below stands for
// Hertz's effective radius R R2 / (R + R2)). Hertz's quasi-static theory
// (Johnson, Contact Mechanics, section 11.4; impactfe::HertzImpact)
// predicts the largest approach delta_max, the peak force F_max and the
// contact duration t_c from R, the mass, E* = E/(1 - nu^2) and v. It holds when
// the contact radius a_max = sqrt(R delta_max) is small against R and the
// impact is slow against the waves (v much less than sqrt(E/rho)): then nearly
// all the kinetic energy goes into the local deformation near the contact and
// comes back.
//
// The ball must resolve a contact disc of radius a_max (0.08 R here): the
// mesh (Geometry::graded_ball) is deal.II's ball refined n times, graded
// towards its lowest point (cells smaller by `Pole cell factor`).
//
// The program reports the three Hertz figures beside the measured ones:
// - the peak of the total contact force;
// - the contact duration, from the touch (initial gap / v: the flight
//   before it is exact) to the end of the last step with a contact force
//   (resolution: one step);
// - the largest approach, the largest downward displacement of the centre
//   of mass after the touch (the ball's far side moves with its centre of
//   mass in a slow impact, as Hertz's theory assumes).
// `Verification` can bound the relative errors of the first two. The
// convergence is benchmarks/hertz_impact/run_hertz_study.py's.
//
// The rest (candidates on the lower half of the sphere, the time loop, the
// common checks, the files) is the library's ObstacleImpactScene<3>.

#include <deal.II/base/parameter_handler.h>

#include <impactfe/bodies/geometry.h>
#include <impactfe/scenes/hertz_impact.h>
#include <impactfe/scenes/obstacle_impact_scene.h>
#include <impactfe/scenes/rigid_block.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace HertzImpactProgram
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The HertzImpactProblem class}
  class HertzImpactProblem : public ObstacleImpactScene<3>
  {
  public:
    HertzImpactProblem()
      : ObstacleImpactScene<3>("hertz_impact",
                               "ball",
                               1,
                               "0, 0, 0",
                               "0, 0, 1",
                               "0")
    {}

  private:
    void
    declare_scene_parameters(ParameterHandler &prm) override;
    void
    parse_scene_parameters(ParameterHandler &prm) override;
    void
    make_built_in_mesh(Triangulation<3> &triangulation) const override;
    double
    out_of_plane_measure() const override
    {
      return 1.;
    }
    double
    length_scale() const override
    {
      return radius;
    }
    Tensor<1, 3>
    initial_velocity() const override
    {
      return Tensor<1, 3>({0., 0., -impact_velocity});
    }
    std::string
    title() const override
    {
      return "Hertz impact of a ball on a rigid obstacle";
    }
    std::vector<std::string>
    plot_columns() const override
    {
      return {"normal_force", "approach"};
    }
    std::vector<std::string>
    history_columns() const override
    {
      return {"approach"};
    }
    std::vector<double>
    history_values(const StepReport &report) override;
    void
    prepare_run() override;
    void
    measure_step(const StepReport &report) override;
    void
    report_motion(std::ostream &out, JsonObject &summary) const override;
    bool
    report_checks(std::ostream &out, JsonObject &summary) const override;

    /// Downward displacement of the centre of mass since the touch [m].
    double
    approach() const;
    /// From the touch to the end of the last step with a contact force [s].
    double
    measured_duration() const;
    HertzImpact
    hertz() const;

    // Geometry and initial conditions.
    double       radius           = 0.01;
    unsigned int n_refinements    = 2;
    double       pole_cell_factor = 0.3, fine_angle = 0.15;
    double       impact_velocity = 5., initial_gap = 0.;
    // Verification bounds (-1: not checked).
    double max_peak_force_error = -1., max_duration_error = -1.;

    MassWeightedMean<3> centre_of_mass;
    double              largest_approach = 0.;
  };



  // @sect3{Parameters}
  void
  HertzImpactProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Radius",
                      "0.01",
                      Patterns::Double(),
                      "Radius R of the ball [m]. Must be > 0.");
    prm.declare_entry("Number of refinements",
                      "2",
                      Patterns::Integer(0, 6),
                      "Global refinements of deal.II's 7-cell ball before "
                      "the grading: 7 * 8^n cells [-].");
    prm.declare_entry("Pole cell factor",
                      "0.3",
                      Patterns::Double(),
                      "Size of the cells at the lowest point of the ball "
                      "relative to the uniform mesh's [-]; in (0, 1], 1: no "
                      "grading.");
    prm.declare_entry("Fine zone angle",
                      "0.15",
                      Patterns::Double(),
                      "Polar angle from the lowest point of the cap whose "
                      "cells are smaller by the pole cell factor [rad]; "
                      "Hertz's contact radius a_max must fit in it. The "
                      "angle over the factor must be below 0.9 pi.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Impact velocity",
                      "5",
                      Patterns::Double(),
                      "Downward velocity of the ball at t = 0 [m/s]. Must be "
                      "> 0.");
    prm.declare_entry("Initial gap",
                      "0",
                      Patterns::Double(),
                      "Distance from the lowest point of the built-in ball "
                      "to the plane at t = 0 [m]. Must be >= 0.");
    prm.leave_subsection();
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum peak force error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if |F_max - Hertz| / Hertz exceeds this "
                      "[-]. -1: no check.");
    prm.declare_entry("Maximum duration error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if |t_c - Hertz| / Hertz exceeds this "
                      "[-]. -1: no check.");
    prm.leave_subsection();
  }



  void
  HertzImpactProblem::parse_scene_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    radius           = prm.get_double("Radius");
    n_refinements    = prm.get_integer("Number of refinements");
    pole_cell_factor = prm.get_double("Pole cell factor");
    fine_angle       = prm.get_double("Fine zone angle");
    prm.leave_subsection();
    require_positive(radius, "Geometry", "Radius");
    AssertThrow(pole_cell_factor > 0. && pole_cell_factor <= 1.,
                ExcMessage("Geometry: 'Pole cell factor' must be in (0, 1], "
                           "got " +
                           format_number(pole_cell_factor) + "."));
    AssertThrow(fine_angle > 0. &&
                  fine_angle / pole_cell_factor < 0.9 * numbers::PI,
                ExcMessage("Geometry: 'Fine zone angle' / 'Pole cell factor' "
                           "must be in (0, 0.9 pi) (the fine zone cannot "
                           "take the whole sphere), got " +
                           format_number(fine_angle) + " / " +
                           format_number(pole_cell_factor) + "."));
    prm.enter_subsection("Initial conditions");
    impact_velocity = prm.get_double("Impact velocity");
    initial_gap     = prm.get_double("Initial gap");
    prm.leave_subsection();
    AssertThrow(impact_velocity > 0.,
                ExcMessage("Initial conditions: 'Impact velocity' must be > "
                           "0, got " +
                           format_number(impact_velocity) + "."));
    require_non_negative(initial_gap, "Initial conditions", "Initial gap");
    prm.enter_subsection("Verification");
    max_peak_force_error = prm.get_double("Maximum peak force error");
    max_duration_error   = prm.get_double("Maximum duration error");
    prm.leave_subsection();
  }



  // @sect3{The mesh}
  //
  // The graded ball, its lowest point at height g0 above the plane z = 0.
  void
  HertzImpactProblem::make_built_in_mesh(Triangulation<3> &tria) const
  {
    Geometry::graded_ball(tria,
                          Point<3>(0., 0., radius + initial_gap),
                          radius,
                          n_refinements,
                          pole_cell_factor,
                          fine_angle);
  }



  // @sect3{Measurements}
  //
  // The approach: the centre of mass's drop beyond the initial gap.
  void
  HertzImpactProblem::prepare_run()
  {
    centre_of_mass.reinit(deformable_body());
  }



  double
  HertzImpactProblem::approach() const
  {
    return -centre_of_mass(system().state().displacement.block(0))[2] -
           initial_gap;
  }



  double
  HertzImpactProblem::measured_duration() const
  {
    const double last = run_summary().last_contact;
    return last >= 0. ? last - initial_gap / impact_velocity : 0.;
  }



  std::vector<double>
  HertzImpactProblem::history_values(const StepReport &)
  {
    return {approach()};
  }



  void
  HertzImpactProblem::measure_step(const StepReport &)
  {
    largest_approach = std::max(largest_approach, approach());
  }



  // Hertz's figures for the finite-element ball's mass (the Q1 ball is a
  // polyhedron inscribed in the sphere), with the effective radius.
  HertzImpact
  HertzImpactProblem::hertz() const
  {
    const MaterialParameters &material = deformable_body().material();
    const auto *ball = dynamic_cast<const BallObstacle<3> *>(&obstacle());
    HertzImpact reference;
    reference.radius         = ball == nullptr ? radius :
                                                 radius * ball->ball_radius() /
                                           (radius + ball->ball_radius());
    reference.mass           = deformable_body().total_mass();
    reference.youngs_modulus = material.youngs_modulus;
    reference.poissons_ratio = material.poissons_ratio;
    reference.velocity       = impact_velocity;
    return reference;
  }



  // @sect3{The report}
  void
  HertzImpactProblem::report_motion(std::ostream &out,
                                    JsonObject   &summary) const
  {
    const HertzImpact        reference = hertz();
    const ContactRunSummary &run       = run_summary();
    const double             duration  = measured_duration();
    const double sphere_mass = 4. / 3. * numbers::PI * std::pow(radius, 3) *
                               deformable_body().material().density;
    const double wave_speed =
      std::sqrt(deformable_body().material().youngs_modulus /
                deformable_body().material().density);
    out << "  Mass " << reference.mass << " kg (sphere: " << sphere_mass
        << "); v / sqrt(E/rho) = " << impact_velocity / wave_speed
        << ", a_max / R = " << reference.max_contact_radius() / radius
        << std::endl;
    const auto line = [&](const std::string &what,
                          const double       measured,
                          const double       exact,
                          const std::string &unit) {
      out << "  " << what << ": " << measured << " " << unit << ", Hertz "
          << exact << " " << unit << ", relative error "
          << (measured - exact) / exact << std::endl;
    };
    line("Peak force", run.peak_normal_force, reference.peak_force(), "N");
    line("Contact duration", duration, reference.contact_duration(), "s");
    line("Largest approach", largest_approach, reference.max_approach(), "m");
    summary.add("mass", reference.mass)
      .add("hertz_peak_force", reference.peak_force())
      .add("hertz_contact_duration", reference.contact_duration())
      .add("hertz_max_approach", reference.max_approach())
      .add("hertz_max_contact_radius", reference.max_contact_radius())
      .add("contact_duration", duration)
      .add("max_approach", largest_approach)
      .add("peak_force_error",
           (run.peak_normal_force - reference.peak_force()) /
             reference.peak_force())
      .add("contact_duration_error",
           (duration - reference.contact_duration()) /
             reference.contact_duration())
      .add("max_approach_error",
           (largest_approach - reference.max_approach()) /
             reference.max_approach());
  }



  bool
  HertzImpactProblem::report_checks(std::ostream &out, JsonObject &) const
  {
    const HertzImpact        reference = hertz();
    const ContactRunSummary &run       = run_summary();
    const double             duration  = measured_duration();
    bool                     ok =
      print_check(out,
                  "Hertz peak force error",
                  std::abs(run.peak_normal_force - reference.peak_force()) /
                    reference.peak_force(),
                  "<=",
                  max_peak_force_error);
    ok &= print_check(out,
                      "Hertz contact duration error",
                      std::abs(duration - reference.contact_duration()) /
                        reference.contact_duration(),
                      "<=",
                      max_duration_error);
    return ok;
  }
} // namespace HertzImpactProgram



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      HertzImpactProgram::HertzImpactProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
