/* ---------------------------------------------------------------------
 *
 * two_bars_1d: the impact of two identical elastic bars in 1D
 * (Vola, Pratt, Jean, Raous, section 6.1.1; Carpenter, Taylor and Katona
 * 1991), with the four time schemes of impactfe.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// Bar 1 moves at the impact velocity $v_0$ towards bar 2, at rest. When the
// gap closes at $t_0 = g_0 / v_0$, a compression wave runs into each bar at
// the speed $c = \sqrt{E/\rho}$. For identical bars the exact solution is
// known: during $t_0 \le t \le t_0 + 2L/c$ the interface moves at $v_0/2$
// and carries the stress $\rho c v_0 / 2$; afterwards bar 1 is at rest and
// bar 2 moves at $v_0$. All the energy passes from bar 1 to bar 2.
//
// The bars are discretised with P1 elements, each bar its own mesh. One
// contact candidate pairs bar 1's right end with bar 2's left end
// (node-to-node). Each time step, the library condenses the dynamics on
// that candidate and solves a one-row LCP with Lemke's method.
//
// The library's TwoBarsScene compares the computed contact velocity and
// contact force with the exact solution and prints the normalised errors
// @f[
//   \mathrm{err}_v = \frac{1}{N}\sum_i \frac{|v_c(t_i) -
//   v_c^{ex}(t_i)|}{v_0/2}, \qquad \mathrm{err}_f = \frac{1}{N}\sum_i
//   \frac{|F(t_i) - F^{ex}(t_i)|}{\rho c v_0 A/2},
// @f]
// with the checks of every contact program (impulse balance, Signorini,
// energy). This program supplies the two meshes and the candidate.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>

#include <impactfe/scenes/two_bars_scene.h>
#include <impactfe/utilities/program.h>

namespace TwoBars1D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The TwoBarsProblem class}
  class TwoBarsProblem : public TwoBarsScene<1>
  {
  public:
    TwoBarsProblem()
      : TwoBarsScene<1>("two_bars_1d")
    {}

  private:
    void
    declare_geometry(ParameterHandler &prm) override;
    void
    parse_geometry(ParameterHandler &prm) override;
    void
    make_bar_meshes(Triangulation<1> &bar_1,
                    Triangulation<1> &bar_2) const override;
    void
    add_bar_contacts(ContactSet &contacts) override;
    double
    out_of_plane_measure() const override
    {
      return area;
    }
    double
    cross_section() const override
    {
      return area;
    }
    std::string
    title() const override
    {
      return "Two elastic bars in 1D";
    }
    std::string
    header_details() const override
    {
      return ", " + std::to_string(n_cells) + " cells per bar";
    }
    void
    report_geometry(std::ostream &out, JsonObject &summary) const override;

    double       area    = 6.4516e-4;
    unsigned int n_cells = 20;
  };



  // @sect3{Parameters}
  //
  // The scene's subsection `Geometry`; `Material`, `Initial conditions`
  // and the rest are the library's.
  void
  TwoBarsProblem::declare_geometry(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Number of cells per bar",
                      "20",
                      Patterns::Integer(1),
                      "Number of P1 elements in each bar [-].");
    prm.declare_entry("Cross-section area",
                      "6.4516e-4",
                      Patterns::Double(),
                      "Cross-section area A of the bars [m^2]; scales masses, "
                      "forces and energies. Must be > 0.");
    prm.leave_subsection();
  }



  void
  TwoBarsProblem::parse_geometry(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    n_cells = prm.get_integer("Number of cells per bar");
    area    = prm.get_double("Cross-section area");
    prm.leave_subsection();
    require_positive(area, "Geometry", "Cross-section area");
    require_mesh_fits_in_memory(2. * n_cells,
                                1,
                                "Geometry",
                                "'Number of cells per bar'");
  }



  // @sect3{The meshes and the candidate}
  //
  // Bar 1 on $[-L-g_0, -g_0]$, bar 2 on $[0, L]$. With `colorize`, the left
  // end of each gets boundary id 0 and the right end id 1. The contact
  // normal points from bar 2 towards bar 1, i.e. along $-x$, so that the
  // gap is $g = (x_1 - x_2)\cdot n \ge 0$.
  void
  TwoBarsProblem::make_bar_meshes(Triangulation<1> &bar_1,
                                  Triangulation<1> &bar_2) const
  {
    const std::vector<unsigned int> cells{n_cells};
    GridGenerator::subdivided_hyper_rectangle(bar_1,
                                              cells,
                                              Point<1>(-bar_length -
                                                       initial_gap),
                                              Point<1>(-initial_gap),
                                              true);
    GridGenerator::subdivided_hyper_rectangle(
      bar_2, cells, Point<1>(0.), Point<1>(bar_length), true);
  }



  void
  TwoBarsProblem::add_bar_contacts(ContactSet &contacts)
  {
    contacts.add_node_to_node(system().bodies(),
                              /*body_a=*/0,
                              /*boundary_a=*/1,
                              /*body_b=*/1,
                              /*boundary_b=*/0,
                              Tensor<1, 1>({-1.}));
  }



  // @sect3{The report}
  // The Courant number of the mesh and the step, which sets how sharply a
  // scheme can resolve the wave fronts.
  void
  TwoBarsProblem::report_geometry(std::ostream &out, JsonObject &summary) const
  {
    const double courant = material().longitudinal_wave_speed<1>() *
                           parameters.time_stepping.time_step /
                           (bar_length / n_cells);
    out << "  Courant number c h / dx = " << courant << std::endl;
    // (courant_number is in summary.json already, with the scheme's keys)
    summary.add("cells_per_bar", double(n_cells));
  }
} // namespace TwoBars1D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      TwoBars1D::TwoBarsProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
