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
      return ball.radius;
    }
    Tensor<1, 3>
    initial_velocity() const override
    {
      return Tensor<1, 3>({0., 0., -ball.impact_velocity});
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

    // Geometry, initial conditions and the Verification bounds.
    HertzBallParameters ball;

    MassWeightedMean<3> centre_of_mass;
    double              largest_approach = 0.;
  };



  // @sect3{Parameters}
  // The ball's entries are the library's (HertzBallParameters), shared
  // with hertz_on_block.
  void
  HertzImpactProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    HertzBallParameters::declare_parameters(prm);
  }



  void
  HertzImpactProblem::parse_scene_parameters(ParameterHandler &prm)
  {
    ball.parse_parameters(prm);
  }



  // @sect3{The mesh}
  //
  // The graded ball, its lowest point at height g0 above the plane z = 0.
  void
  HertzImpactProblem::make_built_in_mesh(Triangulation<3> &tria) const
  {
    ball.make_ball(tria);
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
           ball.initial_gap;
  }



  double
  HertzImpactProblem::measured_duration() const
  {
    return ball.contact_duration(run_summary().last_contact,
                                 system().state().time);
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
    const auto               *obstacle_ball =
      dynamic_cast<const BallObstacle<3> *>(&obstacle());
    const double R = ball.radius;
    HertzImpact  reference;
    reference.radius =
      obstacle_ball == nullptr ?
        R :
        R * obstacle_ball->ball_radius() / (R + obstacle_ball->ball_radius());
    reference.mass           = deformable_body().total_mass();
    reference.youngs_modulus = material.youngs_modulus;
    reference.poissons_ratio = material.poissons_ratio;
    reference.velocity       = ball.impact_velocity;
    return reference;
  }



  // @sect3{The report}
  void
  HertzImpactProblem::report_motion(std::ostream &out,
                                    JsonObject   &summary) const
  {
    const HertzImpact        reference   = hertz();
    const ContactRunSummary &run         = run_summary();
    const double             duration    = measured_duration();
    const double             sphere_mass = 4. / 3. * numbers::PI *
                               std::pow(ball.radius, 3) *
                               deformable_body().material().density;
    const double wave_speed =
      std::sqrt(deformable_body().material().youngs_modulus /
                deformable_body().material().density);
    out << "  Mass " << reference.mass << " kg (sphere: " << sphere_mass
        << "); v / sqrt(E/rho) = " << ball.impact_velocity / wave_speed
        << ", a_max / R = " << reference.max_contact_radius() / ball.radius
        << std::endl;
    summary.add("mass", reference.mass);
    report_against_hertz(reference,
                         run.peak_normal_force,
                         duration,
                         largest_approach,
                         out,
                         summary);
  }



  bool
  HertzImpactProblem::report_checks(std::ostream &out, JsonObject &) const
  {
    return check_against_hertz(hertz(),
                               run_summary().peak_normal_force,
                               measured_duration(),
                               ball.max_peak_force_error,
                               ball.max_duration_error,
                               out);
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
