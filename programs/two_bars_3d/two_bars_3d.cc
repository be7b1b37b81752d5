/* ---------------------------------------------------------------------
 *
 * two_bars_3d: the impact of two identical elastic bars of square section,
 * meshed with Q1 hexahedra (the 1D bars of Vola, Pratt, Jean, Raous,
 * section 6.1, in three dimensions), node-to-node or node-to-face
 * contact, or one bar against a rigid wall.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// Two prisms of length L and square section H x H, bar 1 moving at v0
// along x onto bar 2 at rest. Each node of bar 1's end face is paired
// with the node of bar 2's end face on the same line along x, or with the
// closest point of bar 2's end faces (node-to-face: the meshes need not
// match).
//
// With Poisson's ratio 0, a state that is uniform over the section is an
// exact solution of the 3D discrete problem (nothing couples the axial
// motion to the lateral one), so the program must give the 1D program's
// err_v and err_f: the first check of a 3D body, its Q1 hexahedra, its
// node-to-node candidates and its frames against an independent program.
// With nu > 0 lateral inertia makes the bar dispersive, as in 2D.
//
// Everything but the meshes and the candidates is the library's
// TwoBarsScene: the same scene as two_bars_1d and two_bars_2d, with dim = 3.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>

#include <impactfe/scenes/two_bars_scene.h>
#include <impactfe/utilities/program.h>

namespace TwoBars3D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The TwoBarsProblem class}
  class TwoBarsProblem : public TwoBarsScene<3>
  {
  public:
    TwoBarsProblem()
      : TwoBarsScene<3>("two_bars_3d")
    {}

  private:
    void
    declare_geometry(ParameterHandler &prm) override;
    void
    parse_geometry(ParameterHandler &prm) override;
    void
    make_bar_meshes(Triangulation<3> &bar_1,
                    Triangulation<3> &bar_2) const override;
    void
    add_bar_contacts(ContactSet &contacts) override;
    // In 3D the matrices need no out-of-plane factor.
    double
    out_of_plane_measure() const override
    {
      return 1.;
    }
    double
    cross_section() const override
    {
      return side * side;
    }
    std::string
    title() const override
    {
      return "Two elastic bars in 3D (nu = " +
             format_number(material().poissons_ratio) + ")";
    }
    void
    report_geometry(std::ostream &out, JsonObject &summary) const override;

    double       side    = 0.0254;
    unsigned int n_along = 20, n_across = 2, n_across_2 = 2;
    bool         node_to_face = false;
  };



  // @sect3{Parameters}
  void
  TwoBarsProblem::declare_geometry(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Side of the section",
                      "0.0254",
                      Patterns::Double(),
                      "Side H of the square cross-section [m]. Must be > 0.");
    prm.declare_entry("Number of cells along",
                      "20",
                      Patterns::Integer(1),
                      "Q1 hexahedra along each bar [-].");
    prm.declare_entry("Number of cells across",
                      "2",
                      Patterns::Integer(1),
                      "Q1 hexahedra across each side of the section [-]. "
                      "Even, so that a node sits at the centre of the "
                      "contact face.");
    prm.declare_entry("Number of cells across bar 2",
                      "0",
                      Patterns::Integer(0),
                      "Q1 hexahedra across each side of bar 2's section; 0: "
                      "as bar 1's. A different number makes the interface "
                      "meshes non-matching (node-to-face) [-].");
    prm.declare_entry("Contact discretization",
                      "node-to-node",
                      Patterns::Selection("node-to-node|node-to-face"),
                      "node-to-node: pairs of facing nodes (matching "
                      "meshes); node-to-face: each node of bar 1's end "
                      "against the bilinear faces of bar 2's end.");
    prm.leave_subsection();
  }



  void
  TwoBarsProblem::parse_geometry(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    side         = prm.get_double("Side of the section");
    n_along      = prm.get_integer("Number of cells along");
    n_across     = prm.get_integer("Number of cells across");
    n_across_2   = prm.get_integer("Number of cells across bar 2");
    node_to_face = prm.get("Contact discretization") == "node-to-face";
    prm.leave_subsection();
    if (n_across_2 == 0)
      n_across_2 = n_across;
    require_mesh_fits_in_memory(double(n_along) *
                                  (double(n_across) * n_across +
                                   double(n_across_2) * n_across_2),
                                3,
                                "Geometry",
                                "'Number of cells along', 'Number of cells "
                                "across' and 'Number of cells across bar 2'");
    AssertThrow(n_across_2 == n_across || node_to_face,
                ExcMessage("Geometry: 'Number of cells across bar 2' = " +
                           std::to_string(n_across_2) +
                           " makes the interface meshes non-matching: set "
                           "'Contact discretization' to node-to-face."));
    AssertThrow(side > 0.,
                ExcMessage("Geometry: 'Side of the section' "
                           "must be > 0."));
    AssertThrow(n_across % 2 == 0,
                ExcMessage("Geometry: 'Number of cells across' must be even, "
                           "got " +
                           std::to_string(n_across) + "."));
  }



  // @sect3{The meshes and the candidates}
  //
  // Bar 1 on [-L - g0, -g0] x [0, H]^2, bar 2 on [0, L] x [0, H]^2; with
  // `colorize` the end faces have boundary ids 0 (x min) and 1 (x max).
  // The contact normal points from bar 2 towards bar 1 (along -x).
  void
  TwoBarsProblem::make_bar_meshes(Triangulation<3> &bar_1,
                                  Triangulation<3> &bar_2) const
  {
    const std::vector<unsigned int> cells{n_along, n_across, n_across};
    GridGenerator::subdivided_hyper_rectangle(
      bar_1,
      cells,
      Point<3>(-bar_length - initial_gap, 0., 0.),
      Point<3>(-initial_gap, side, side),
      /*colorize=*/true);
    GridGenerator::subdivided_hyper_rectangle(bar_2,
                                              {n_along, n_across_2, n_across_2},
                                              Point<3>(0., 0., 0.),
                                              Point<3>(bar_length, side, side),
                                              /*colorize=*/true);
  }



  void
  TwoBarsProblem::add_bar_contacts(ContactSet &contacts)
  {
    if (node_to_face)
      contacts.add_node_to_face(system().bodies(), 0, 1, 1, 0);
    else
      contacts.add_node_to_node(
        system().bodies(), 0, 1, 1, 0, Tensor<1, 3>({-1., 0., 0.}));
  }



  // @sect3{The report}
  void
  TwoBarsProblem::report_geometry(std::ostream &out, JsonObject &summary) const
  {
    out << "  Mesh: " << body(0).triangulation().n_active_cells()
        << (against_rigid_wall ?
              "" :
              " + " + std::to_string(body(1).triangulation().n_active_cells()))
        << " Q1 hexahedra, " << system().contacts().n_candidates()
        << (against_rigid_wall ? " node-to-plane" :
            node_to_face       ? " node-to-face" :
                                 " node-to-node")
        << " contact candidates" << std::endl;
    summary.add("poissons_ratio", material().poissons_ratio)
      .add("cells_per_bar", double(body(0).triangulation().n_active_cells()));
  }
} // namespace TwoBars3D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      TwoBars3D::TwoBarsProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
