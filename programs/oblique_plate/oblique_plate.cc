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
// The library's ObstacleImpactScene checks what must hold:
//  - the impulse of the contact forces equals the change of momentum, in
//    both directions;
//  - |P_T| <= mu P_N at every node and step, and a sliding node has
//    P_T = -mu P_N V_T / |V_T|;
//  - no node penetrates the plane (the modified theta-method enforces the
//    gap at the end of the step);
//  - the energy does not grow.
// This program adds the plate's geometry, its initial velocity, and the
// ratio of the tangential to the normal impulse.

#include <deal.II/base/parameter_handler.h>

#include <impactfe/bodies/geometry.h>
#include <impactfe/scenes/obstacle_impact_scene.h>
#include <impactfe/utilities/program.h>

namespace ObliquePlate
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The ObliquePlateProblem class}
  class ObliquePlateProblem : public ObstacleImpactScene<2>
  {
  public:
    ObliquePlateProblem()
      : ObstacleImpactScene<2>("oblique_plate",
                               "plate",
                               2,
                               "0, 0",
                               "0, 1",
                               "0.1")
    {}

  private:
    void
    declare_scene_parameters(ParameterHandler &prm) override;
    void
    parse_scene_parameters(ParameterHandler &prm) override;
    void
    make_built_in_mesh(Triangulation<2> &triangulation) const override;
    double
    out_of_plane_measure() const override
    {
      return thickness;
    }
    double
    length_scale() const override
    {
      return width;
    }
    Tensor<1, 2>
    initial_velocity() const override
    {
      return velocity;
    }
    std::string
    title() const override
    {
      return "Oblique impact of a plate";
    }
    std::vector<std::string>
    plot_columns() const override
    {
      return {"normal_force", "tangential_force", "sliding"};
    }
    void
    report_motion(std::ostream &out, JsonObject &summary) const override;

    // The data of the paper's Fig. 7 table.
    double       width = 0.08, side_height = 0.04, radius = 0.101;
    double       thickness = 0.01, initial_gap = 0.;
    unsigned int nx = 10, ny = 8;
    Tensor<1, 2> velocity;
  };



  // @sect3{Parameters}
  //
  // `Geometry` and `Initial conditions`; the rest is the library's.
  void
  ObliquePlateProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Width",
                      "0.08",
                      Patterns::Double(),
                      "Width of the plate [m]. Must be > 0.");
    prm.declare_entry("Side height",
                      "0.04",
                      Patterns::Double(),
                      "Height of the plate's vertical sides, above the ends "
                      "of the round side [m]. Must be > 0.");
    prm.declare_entry("Radius of the round side",
                      "0.101",
                      Patterns::Double(),
                      "Radius of the arc that forms the lower side [m]. Must "
                      "exceed half the width.");
    prm.declare_entry("Thickness",
                      "0.01",
                      Patterns::Double(),
                      "Out-of-plane thickness (plane stress) [m]. Must be > "
                      "0.");
    prm.declare_entry("Number of cells across",
                      "10",
                      Patterns::Integer(1),
                      "Q1 cells along the width [-].");
    prm.declare_entry("Number of cells up",
                      "8",
                      Patterns::Integer(1),
                      "Q1 cells along the height [-].");
    prm.declare_entry("Initial gap",
                      "0",
                      Patterns::Double(),
                      "Height of the lowest point of the round side above "
                      "the plane at t = 0 [m]. Must be >= 0.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Horizontal velocity",
                      "3",
                      Patterns::Double(),
                      "V_h, along x, at t = 0 [m/s].");
    prm.declare_entry("Vertical velocity",
                      "-5",
                      Patterns::Double(),
                      "V_v, along y, at t = 0 [m/s]. Must be < 0 for an "
                      "impact.");
    prm.leave_subsection();
  }



  void
  ObliquePlateProblem::parse_scene_parameters(ParameterHandler &prm)
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
                ExcMessage("Geometry: 'Radius of the round side' must exceed "
                           "half the width, got " +
                           format_number(radius) + "."));
    require_positive(thickness, "Geometry", "Thickness");
    require_non_negative(initial_gap, "Geometry", "Initial gap");
    prm.enter_subsection("Initial conditions");
    velocity[0] = prm.get_double("Horizontal velocity");
    velocity[1] = prm.get_double("Vertical velocity");
    prm.leave_subsection();
    AssertThrow(velocity[1] < 0.,
                ExcMessage("Initial conditions: 'Vertical velocity' must be < "
                           "0 (towards the plane), got " +
                           format_number(velocity[1]) + "."));
  }



  // @sect3{The mesh}
  //
  // 10 x 8 Q1 cells, 99 nodes, as in the paper; the lowest point of the
  // round side at height g0 above the plane y = 0. The 11 nodes of the
  // round side (boundary id 2) are the candidates.
  void
  ObliquePlateProblem::make_built_in_mesh(Triangulation<2> &tria) const
  {
    Geometry::plate_with_round_side(
      tria, Point<2>(0., initial_gap), width, side_height, radius, nx, ny);
  }



  // @sect3{The report}
  //
  // The mean velocity before and after, and the ratio of the impulses,
  // which Coulomb's law bounds by mu.
  void
  ObliquePlateProblem::report_motion(std::ostream &out,
                                     JsonObject   &summary) const
  {
    const ContactRunSummary &s     = run_summary();
    const double             m     = deformable_body().total_mass();
    const Tensor<1, 2>       p_end = system().momentum(0);
    out << "  Mass " << m << " kg; mean velocity at t = 0: " << velocity
        << " m/s, at the end: " << p_end / m << " m/s" << std::endl;
    out << "  Tangential / normal impulse = "
        << (s.normal_impulse > 0. ? s.tangential_impulse / s.normal_impulse :
                                    0.)
        << " (Coulomb bound mu = " << friction_coefficient() << ")"
        << std::endl;
    summary.add("final_velocity_x", p_end[0] / m)
      .add("final_velocity_y", p_end[1] / m);
  }
} // namespace ObliquePlate



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      ObliquePlate::ObliquePlateProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
