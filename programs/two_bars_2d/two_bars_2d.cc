/* ---------------------------------------------------------------------
 *
 * two_bars_2d: the impact of two identical elastic bars in 2D with
 * Poisson's ratio 0.45 (Vola, Pratt, Jean, Raous, section 6.1.2), plane
 * strain or plane stress, node-to-node or node-to-segment contact.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// The data of the 1D bars (Table 1 of the paper), but each bar is now a 2D
// strip of height H meshed with Q1 cells, and Poisson's ratio is 0.45. The
// bars meet along their end faces. With matching meshes, each node of bar
// 1's end is paired with the node of bar 2 at the same height
// (node-to-node); when bar 2's mesh is offset, each node of bar 1 is paired
// with the segment of bar 2's end it faces (node-to-segment).
//
// There is no exact solution in 2D: lateral inertia makes the bar
// dispersive, and the front of the compression wave runs at the
// dilatational speed of the model while the bulk of the pulse follows the
// long-wave bar speed. In plane stress the bar speed is sqrt(E/rho), as in
// 1D; in plane strain the bar cannot contract through its thickness and the
// speed is sqrt(E/((1 - nu^2) rho)). The contact time follows 2L over that
// bar speed.
//
// With nu = 0, however, a uniform state across the height is an exact
// solution of the 2D discrete problem: then the program must reproduce the
// 1D program's results, which a test checks. The library's TwoBarsScene
// prints the errors against the 1D exact solution in any case, so one sees
// how far nu = 0.45 moves the solution from the 1D one.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/mesh_input.h>
#include <impactfe/scenes/two_bars_scene.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace TwoBars2D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The TwoBarsProblem class}
  class TwoBarsProblem : public TwoBarsScene<2>
  {
  public:
    TwoBarsProblem()
      : TwoBarsScene<2>("two_bars_2d")
    {}

  private:
    void
    declare_geometry(ParameterHandler &prm) override;
    void
    parse_geometry(ParameterHandler &prm) override;
    void
    make_bar_meshes(Triangulation<2> &bar_1,
                    Triangulation<2> &bar_2) const override;
    void
    add_bar_contacts(ContactSet &contacts) override;
    types::boundary_id
    bar_1_contact_boundary() const override
    {
      return mesh_1.contact_boundary_id;
    }
    double
    out_of_plane_measure() const override
    {
      return thickness;
    }
    double
    cross_section() const override
    {
      return height * thickness;
    }
    std::string
    title() const override;
    void
    report_geometry(std::ostream &out, JsonObject &summary) const override;

    void
    make_bar(Triangulation<2>     &bar,
             const MeshParameters &mesh,
             const double          x_left,
             const double          row_offset) const;

    double         height = 0.0254, thickness = 0.0254;
    unsigned int   n_along = 20, n_across = 4;
    double         mesh_offset     = 0.;
    bool           node_to_segment = false;
    MeshParameters mesh_1, mesh_2;
  };



  // @sect3{Parameters}
  //
  // `Geometry` and one `Mesh` subsection per bar; `Material`, `Initial
  // conditions` and the rest are the library's.
  void
  TwoBarsProblem::declare_geometry(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Bar height",
                      "0.0254",
                      Patterns::Double(),
                      "Height H of each bar, in the plane [m]. Must be > 0.");
    prm.declare_entry("Thickness",
                      "0.0254",
                      Patterns::Double(),
                      "Out-of-plane thickness [m]; H times the thickness is "
                      "the cross-section of the 1D bars. Must be > 0.");
    prm.declare_entry("Number of cells along",
                      "20",
                      Patterns::Integer(1),
                      "Q1 cells along each bar [-].");
    prm.declare_entry("Number of cells across",
                      "4",
                      Patterns::Integer(1),
                      "Q1 cells across the height of each bar [-]. Even, so "
                      "that a node sits at the centre of the contact zone.");
    prm.declare_entry("Contact discretization",
                      "node-to-node",
                      Patterns::Selection("node-to-node|node-to-segment"),
                      "node-to-node: pairs of nodes at the same height "
                      "(matching meshes); node-to-segment: each node of bar "
                      "1's end against the facing segment of bar 2.");
    prm.declare_entry("Interface mesh offset",
                      "0",
                      Patterns::Double(),
                      "Shift of bar 2's inner rows of nodes, as a fraction of "
                      "a cell height, so that the meshes do not match at the "
                      "interface [-]. In [0, 1); non-zero needs "
                      "node-to-segment.");
    prm.leave_subsection();
    MeshParameters::declare_parameters(prm, "Mesh of bar 1", 1);
    MeshParameters::declare_parameters(prm, "Mesh of bar 2", 0);
  }



  void
  TwoBarsProblem::parse_geometry(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    height          = prm.get_double("Bar height");
    thickness       = prm.get_double("Thickness");
    n_along         = prm.get_integer("Number of cells along");
    n_across        = prm.get_integer("Number of cells across");
    node_to_segment = prm.get("Contact discretization") == "node-to-segment";
    mesh_offset     = prm.get_double("Interface mesh offset");
    prm.leave_subsection();
    AssertThrow(height > 0. && thickness > 0.,
                ExcMessage("Geometry: 'Bar height' and 'Thickness' must be > "
                           "0."));
    require_mesh_fits_in_memory(2. * n_along * n_across,
                                2,
                                "Geometry",
                                "'Number of cells along' and 'Number of cells "
                                "across'");
    AssertThrow(n_across % 2 == 0,
                ExcMessage("Geometry: 'Number of cells across' must be even, "
                           "got " +
                           std::to_string(n_across) + "."));
    AssertThrow(mesh_offset >= 0. && mesh_offset < 1.,
                ExcMessage("Geometry: 'Interface mesh offset' must be in [0, "
                           "1), got " +
                           format_number(mesh_offset) + "."));
    AssertThrow(mesh_offset == 0. || node_to_segment,
                ExcMessage("Geometry: an 'Interface mesh offset' of " +
                           format_number(mesh_offset) +
                           " makes the interface meshes non-matching: set "
                           "'Contact discretization' to node-to-segment."));
    mesh_1.parse_parameters(prm, "Mesh of bar 1");
    mesh_2.parse_parameters(prm, "Mesh of bar 2");
  }



  // @sect3{The meshes}
  //
  // A bar on [x_left, x_left + L] x [0, H] with `colorize`: boundary id 0
  // on the left end, 1 on the right end, 2 below, 3 above. The inner rows
  // of nodes may be shifted up by a fraction of a cell height (bar 2 with
  // an interface mesh offset), which keeps the outline and moves the nodes
  // of the end face off bar 1's.
  void
  TwoBarsProblem::make_bar(Triangulation<2>     &bar,
                           const MeshParameters &mesh,
                           const double          x_left,
                           const double          row_offset) const
  {
    if (mesh.from_file())
      {
        mesh.read(bar, parameter_file());
        return;
      }
    GridGenerator::subdivided_hyper_rectangle(bar,
                                              {n_along, n_across},
                                              Point<2>(x_left, 0.),
                                              Point<2>(x_left + bar_length,
                                                       height),
                                              /*colorize=*/true);
    if (row_offset > 0.)
      {
        const double dy = height / n_across;
        GridTools::transform(
          [&](const Point<2> &p) {
            const bool inner = p[1] > 0.5 * dy && p[1] < height - 0.5 * dy;
            return inner ? Point<2>(p[0], p[1] + row_offset * dy) : p;
          },
          bar);
      }
  }



  void
  TwoBarsProblem::make_bar_meshes(Triangulation<2> &bar_1,
                                  Triangulation<2> &bar_2) const
  {
    make_bar(bar_1, mesh_1, -bar_length - initial_gap, 0.);
    make_bar(bar_2, mesh_2, 0., mesh_offset);
  }



  // @sect3{The candidates}
  // The contact normal points from bar 2 towards bar 1 (along -x).
  // Frictionless: one local direction per candidate.
  void
  TwoBarsProblem::add_bar_contacts(ContactSet &contacts)
  {
    if (node_to_segment)
      contacts.add_node_to_segment(system().bodies(),
                                   0,
                                   mesh_1.contact_boundary_id,
                                   1,
                                   mesh_2.contact_boundary_id);
    else
      contacts.add_node_to_node(system().bodies(),
                                0,
                                mesh_1.contact_boundary_id,
                                1,
                                mesh_2.contact_boundary_id,
                                Tensor<1, 2>({-1., 0.}));
  }



  // @sect3{The report}
  std::string
  TwoBarsProblem::title() const
  {
    const bool strain = material().plane_model == PlaneModel::plane_strain;
    return std::string("Two elastic bars in 2D (") +
           (strain ? "plane strain" : "plane stress") +
           ", nu = " + format_number(material().poissons_ratio) + ")";
  }



  // The mesh, and the wave speeds that set the contact time.
  void
  TwoBarsProblem::report_geometry(std::ostream &out, JsonObject &summary) const
  {
    const MaterialParameters &m = material();
    const bool   strain         = m.plane_model == PlaneModel::plane_strain;
    const double nu             = m.poissons_ratio;
    const double bar_speed =
      std::sqrt(m.youngs_modulus / ((strain ? 1. - nu * nu : 1.) * m.density));
    out << "  Mesh: " << body(0).triangulation().n_active_cells()
        << (against_rigid_wall ?
              "" :
              " + " + std::to_string(body(1).triangulation().n_active_cells()))
        << " Q1 cells, " << system().contacts().n_candidates() << " "
        << (against_rigid_wall ? "node-to-plane" :
            node_to_segment    ? "node-to-segment" :
                                 "node-to-node")
        << " contact candidates" << std::endl;
    out << "  Wave speeds: bar (long waves) " << bar_speed
        << " m/s, dilatational " << m.longitudinal_wave_speed<2>()
        << " m/s; 2 L / bar speed = " << 2. * bar_length / bar_speed << " s"
        << std::endl;
    summary.add("poissons_ratio", nu)
      .add("plane_model", std::string(strain ? "plane strain" : "plane stress"))
      .add("bar_wave_speed", bar_speed);
  }
} // namespace TwoBars2D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      TwoBars2D::TwoBarsProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
