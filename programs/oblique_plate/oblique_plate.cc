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

#include <impactfe/scenes/obstacle_impact_scene.h>
#include <impactfe/scenes/round_sided_plate.h>
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
      return plate.thickness;
    }
    double
    length_scale() const override
    {
      return plate.width;
    }
    Tensor<1, 2>
    initial_velocity() const override
    {
      return Tensor<1, 2>({plate.horizontal_velocity, plate.vertical_velocity});
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

    // The data of the paper's Fig. 7 table (`Geometry`, `Initial
    // conditions`).
    RoundSidedPlate plate;
  };



  // @sect3{Parameters}
  //
  // `Geometry` and `Initial conditions`; the rest is the library's.
  void
  ObliquePlateProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    RoundSidedPlate::declare_parameters(
      prm, "Out-of-plane thickness (plane stress) [m]. Must be > 0.");
  }



  void
  ObliquePlateProblem::parse_scene_parameters(ParameterHandler &prm)
  {
    plate.parse_parameters(prm);
  }



  // @sect3{The mesh}
  //
  // 10 x 8 Q1 cells, 99 nodes, as in the paper; the lowest point of the
  // round side at height g0 above the plane y = 0. The 11 nodes of the
  // round side (boundary id 2) are the candidates.
  void
  ObliquePlateProblem::make_built_in_mesh(Triangulation<2> &tria) const
  {
    plate.make_mesh(tria);
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
    out << "  Mass " << m
        << " kg; mean velocity at t = 0: " << initial_velocity()
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
