/* ---------------------------------------------------------------------
 *
 * oblique_plate_3d: the oblique plate of section 6.3 (Vola, Pratt, Jean,
 * Raous; Kim and Kwak 1996) as a 3D body, Q1 hexahedra, with the Coulomb
 * cone in 3D: exact (circular) or polygonal with k facets. The scene can be
 * turned about the plane's normal by an angle phi: with the exact cone the
 * answer must not depend on phi, with k facets it does.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// The 2D program `oblique_plate` models the plate in plane stress. Here the
// same plate is extruded to its thickness (`Number of layers` Q1 cells
// through it), centred on the plane z = 0 so that this plane is a plane of
// mirror symmetry, and thrown at the rigid plane y = 0 with the velocity
// (V_h, V_v, 0). Three things are measured:
//
// - Against the 2D plane-stress program: a thin plate with free faces is
//   in plane stress, so the impulses and the final mean velocity should be
//   those of `oblique_plate` to the accuracy of the plane-stress
//   assumption on this mesh (doc/oblique_plate_3d.md gives the numbers).
// - Direction independence: with `Turn about the normal` = phi the whole
//   scene (mesh and velocity) is turned by phi about the y axis. The
//   contact frames (n, t1, t2) are built from the normal alone, so they do
//   not turn with the scene: a polygonal cone meets the slip direction at
//   another angle. Turned back by -phi, the momentum change and the final
//   velocity must be those of phi = 0 with the exact cone; the program
//   prints them in the plate's own frame (x' along the plate, z' across).
// - Symmetry: the plate is symmetric about its mid-plane and slides along
//   it, so the friction impulse has no z' component with the exact cone. A
//   polygonal cone whose facets are not aligned with x' gives one.
//
// Everything else (time loop, LCP, exact cone, checks, files) is the
// library's: `ObstacleImpactScene<3>` with `Friction cone` of subsection
// `Contact solver`.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/scenes/obstacle_impact_scene.h>
#include <impactfe/scenes/round_sided_plate.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace ObliquePlate3D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The ObliquePlate3DProblem class}
  class ObliquePlate3DProblem : public ObstacleImpactScene<3>
  {
  public:
    ObliquePlate3DProblem()
      : ObstacleImpactScene<3>("oblique_plate_3d",
                               "plate",
                               2,
                               "0, 0, 0",
                               "0, 1, 0",
                               "0.1")
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
      return plate.width;
    }
    Tensor<1, 3>
    initial_velocity() const override
    {
      return to_scene_frame(
        Tensor<1, 3>({plate.horizontal_velocity, plate.vertical_velocity, 0.}));
    }
    std::string
    title() const override
    {
      return "Oblique impact of a plate in 3D";
    }
    std::vector<std::string>
    plot_columns() const override
    {
      return {"normal_force", "tangential_force", "sliding"};
    }
    void
    report_motion(std::ostream &out, JsonObject &summary) const override;

    /// A vector of the plate's frame turned by phi about the y axis.
    Tensor<1, 3>
    to_scene_frame(const Tensor<1, 3> &v) const;
    /// The inverse turn.
    Tensor<1, 3>
    to_plate_frame(const Tensor<1, 3> &v) const;

    // The 2D program's plate and velocity, and the 3D entries.
    RoundSidedPlate plate;
    unsigned int    n_layers = 1;
    double          turn     = 0.;
  };



  // @sect3{Parameters}
  //
  // The 2D program's `Geometry` and `Initial conditions` (RoundSidedPlate),
  // and two entries of 3D: the cells through the thickness and the turn of
  // the scene.
  void
  ObliquePlate3DProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    RoundSidedPlate::declare_parameters(
      prm, "Thickness of the plate, along z [m]. Must be > 0.");
    prm.enter_subsection("Geometry");
    prm.declare_entry("Number of layers",
                      "1",
                      Patterns::Integer(1),
                      "Q1 cells through the thickness [-].");
    prm.declare_entry("Turn about the normal",
                      "0",
                      Patterns::Double(),
                      "phi [rad]: the mesh and the velocity are turned by "
                      "phi about the plane's normal (the y axis). The "
                      "contact frames are not: with the exact cone the "
                      "results, turned back, do not depend on phi.");
    prm.leave_subsection();
  }



  void
  ObliquePlate3DProblem::parse_scene_parameters(ParameterHandler &prm)
  {
    plate.parse_parameters(prm);
    prm.enter_subsection("Geometry");
    n_layers = prm.get_integer("Number of layers");
    turn     = prm.get_double("Turn about the normal");
    prm.leave_subsection();
    require_mesh_fits_in_memory(double(plate.nx) * plate.ny * n_layers,
                                3,
                                "Geometry",
                                "'Number of cells across', 'Number of cells "
                                "up' and 'Number of layers'");
    AssertThrow(std::isfinite(turn),
                ExcMessage(
                  "Geometry: 'Turn about the normal' must be finite."));
  }



  // @sect3{The mesh}
  //
  // The 2D program's mesh (10 x 8 Q1 cells, the round side with boundary
  // id 2) extruded to the thickness: the lateral faces keep the boundary
  // ids of the 2D edges, so the candidates are the nodes of the round side
  // on every layer of nodes. The mid-plane is put on z = 0, then the whole
  // mesh is turned about the y axis.
  void
  ObliquePlate3DProblem::make_built_in_mesh(Triangulation<3> &tria) const
  {
    Triangulation<2> section;
    plate.make_mesh(section);
    GridGenerator::extrude_triangulation(section,
                                         n_layers + 1,
                                         plate.thickness,
                                         tria);
    GridTools::shift(Tensor<1, 3>({0., 0., -0.5 * plate.thickness}), tria);
    if (turn != 0.)
      GridTools::rotate(Tensor<1, 3>({0., 1., 0.}), turn, tria);
  }



  // A turn by phi about y: x' = x cos phi + z sin phi, z' = -x sin phi +
  // z cos phi (the sense of GridTools::rotate).
  Tensor<1, 3>
  ObliquePlate3DProblem::to_scene_frame(const Tensor<1, 3> &v) const
  {
    const double c = std::cos(turn), s = std::sin(turn);
    return Tensor<1, 3>({c * v[0] + s * v[2], v[1], -s * v[0] + c * v[2]});
  }



  Tensor<1, 3>
  ObliquePlate3DProblem::to_plate_frame(const Tensor<1, 3> &v) const
  {
    const double c = std::cos(turn), s = std::sin(turn);
    return Tensor<1, 3>({c * v[0] - s * v[2], v[1], s * v[0] + c * v[2]});
  }



  // @sect3{The report}
  //
  // In the plate's frame: the mean velocity at the end and the total
  // impulse (the change of momentum, which the impulse balance ties to the
  // contact impulses), split into normal (y), along the plate (x') and
  // across it (z'). The last is zero for the exact cone by symmetry.
  void
  ObliquePlate3DProblem::report_motion(std::ostream &out,
                                       JsonObject   &summary) const
  {
    const double       m = deformable_body().total_mass();
    const Tensor<1, 3> v0(
      {plate.horizontal_velocity, plate.vertical_velocity, 0.});
    const Tensor<1, 3> v_end   = to_plate_frame(system().momentum(0) / m);
    const Tensor<1, 3> impulse = m * (v_end - v0);
    const auto         rounded = [](const double x) {
      return std::abs(x) < 1e-12 ? 0. : x;
    };
    out << "  Mass " << m << " kg; turn about the normal " << turn
        << " rad; in the plate's frame (x' along it, y normal, z' across):"
        << std::endl
        << "  mean velocity at the end (" << rounded(v_end[0]) << ", "
        << rounded(v_end[1]) << ", " << rounded(v_end[2]) << ") m/s"
        << std::endl
        << "  total impulse: normal " << impulse[1] << ", along " << impulse[0]
        << ", across " << rounded(impulse[2] / m) * m << " N s" << std::endl
        << "  Tangential / normal impulse = "
        << std::hypot(impulse[0], impulse[2]) / impulse[1]
        << " (Coulomb bound mu = " << friction_coefficient() << ")"
        << std::endl;
    summary.add("turn", turn)
      .add("final_velocity_along", v_end[0])
      .add("final_velocity_normal", v_end[1])
      .add("final_velocity_across", v_end[2])
      .add("impulse_normal", impulse[1])
      .add("impulse_along", impulse[0])
      .add("impulse_across", impulse[2]);
  }
} // namespace ObliquePlate3D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      ObliquePlate3D::ObliquePlate3DProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
