/* ---------------------------------------------------------------------
 *
 * cylinder_impact: a frictionless elastic cylinder dropped on a rigid
 * plane (Vola, Pratt, Jean, Raous, section 6.2; Taylor and Papadopoulos
 * 1993), plane strain, theta-Euler by default.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A long elastic cylinder (plane strain) moves down at a uniform velocity
// onto a rigid, frictionless plane. The contact zone opens from a point,
// spreads, and closes again as the cylinder bounces off; stress waves run
// through the section meanwhile. There is no exact solution: the program
// reports what the paper plots (the total contact force against time, and
// the deformed shapes) and the checks that must hold whatever the mesh:
//  - the impulse of the contact force equals the change of momentum;
//  - no node penetrates the plane (theta-Euler and the modified
//    theta-method enforce the gap at the end of the step exactly);
//  - the energy does not grow (theta >= 1/2, no external work);
//  - the solution stays symmetric about the vertical axis (frictionless
//    contact, symmetric mesh and data).
//
// Only the nodes of the lower half of the circle are candidates, and only
// the normal direction is modelled (frictionless scene). Each step the LCP
// is restricted to the candidates that can touch during the step.
//
// The library's ObstacleImpactScene does the rest: the subsections `Mesh`,
// `Obstacle`, `Material`, `Discretization`, `Time stepping`, `Contact
// solver`, `Output` and `Verification`, the time loop, the common checks
// and the output files. This program adds the geometry, the initial
// velocity and the symmetry check.

#include <deal.II/base/parameter_handler.h>

#include <impactfe/bodies/geometry.h>
#include <impactfe/scenes/obstacle_impact_scene.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <map>

namespace CylinderImpact
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The CylinderImpactProblem class}
  class CylinderImpactProblem : public ObstacleImpactScene<2>
  {
  public:
    CylinderImpactProblem()
      : ObstacleImpactScene<2>("cylinder_impact",
                               "cylinder",
                               1,
                               "0, 0",
                               "0, 1",
                               "0")
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
      return radius;
    }
    Tensor<1, 2>
    initial_velocity() const override
    {
      return Tensor<1, 2>({0., -impact_velocity});
    }
    std::string
    time_unit() const override
    {
      return "";
    }
    std::string
    title() const override
    {
      return "Cylinder on a rigid plane";
    }
    std::vector<std::string>
    plot_columns() const override
    {
      return {"normal_force", "kinetic_energy"};
    }
    void
    prepare_run() override;
    void
    measure_step(const StepReport &report) override;
    void
    report_motion(std::ostream &out, JsonObject &summary) const override;
    bool
    report_checks(std::ostream &out, JsonObject &summary) const override;

    double
    asymmetry() const;

    // Geometry and initial conditions.
    double       radius = 10., thickness = 1.;
    unsigned int n_core = 12, n_rings = 9;
    double       impact_velocity = 1., initial_gap = 0.;
    double       max_symmetry_error = -1.;

    // Mirror pairs of vertices about the vertical axis, and the largest
    // asymmetry of the displacement so far.
    std::vector<std::pair<unsigned int, unsigned int>> mirror_pairs;
    double                                             symmetry_error = 0.;
  };



  // @sect3{Parameters}
  //
  // The scene's subsections `Geometry` and `Initial conditions`, and its
  // bound on the symmetry error in `Verification`.
  void
  CylinderImpactProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Radius",
                      "10",
                      Patterns::Double(),
                      "Radius R of the cylinder [m]. Must be > 0.");
    prm.declare_entry("Number of core cells",
                      "12",
                      Patterns::Integer(2),
                      "Cells across the square core of the O-grid mesh [-]; "
                      "even.");
    prm.declare_entry("Number of rings",
                      "9",
                      Patterns::Integer(1),
                      "Rings of cells between the core and the circle [-].");
    prm.declare_entry("Thickness",
                      "1",
                      Patterns::Double(),
                      "Out-of-plane length of the cylinder [m]; scales "
                      "masses, forces and energies. Must be > 0.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Impact velocity",
                      "1",
                      Patterns::Double(),
                      "Downward velocity of the cylinder at t = 0 [m/s]. "
                      "Must be > 0.");
    prm.declare_entry("Initial gap",
                      "0",
                      Patterns::Double(),
                      "Distance from the lowest point of the built-in "
                      "cylinder to the plane at t = 0 [m]. Must be >= 0. A "
                      "mesh file's nodes are not moved by it.");
    prm.leave_subsection();
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum symmetry error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if max |u(x) - mirrored u(-x)| / max |u| "
                      "exceeds this [-]. -1: no check.");
    prm.leave_subsection();
  }



  void
  CylinderImpactProblem::parse_scene_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    radius    = prm.get_double("Radius");
    n_core    = prm.get_integer("Number of core cells");
    n_rings   = prm.get_integer("Number of rings");
    thickness = prm.get_double("Thickness");
    prm.leave_subsection();
    require_positive(radius, "Geometry", "Radius");
    AssertThrow(n_core % 2 == 0,
                ExcMessage("Geometry: 'Number of core cells' must be even, "
                           "got " +
                           std::to_string(n_core) + "."));
    require_positive(thickness, "Geometry", "Thickness");
    require_mesh_fits_in_memory(double(n_core) * n_core + 4. * n_core * n_rings,
                                2,
                                "Geometry",
                                "'Number of core cells' and 'Number of rings'");
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
    max_symmetry_error = get_verification_bound(prm, "Maximum symmetry error");
    prm.leave_subsection();
  }



  // @sect3{The mesh}
  //
  // The built-in mesh is the O-grid disc of the library (576 cells and 601
  // vertices with 12 core cells and 9 rings, close to the paper's 576 cells
  // and 613 nodes), centred at height R + g0 above the plane y = 0. A mesh
  // file replaces it, with its own coordinates.
  void
  CylinderImpactProblem::make_built_in_mesh(Triangulation<2> &tria) const
  {
    Geometry::disc(
      tria, Point<2>(0., radius + initial_gap), radius, n_core, n_rings);
  }



  // @sect3{Symmetry}
  //
  // Vertex pairs (x, y) and (2 x_c - x, y), x_c being the mean abscissa of
  // the vertices, found by sorting the vertices by height. A mesh without
  // this symmetry (e.g. from a file) is not checked.
  void
  CylinderImpactProblem::prepare_run()
  {
    const auto &vertices = deformable_body().triangulation().get_vertices();
    double      x_c = 0., size = 0.;
    for (const auto &x : vertices)
      x_c += x[0] / vertices.size();
    for (const auto &x : vertices)
      size = std::max(size, std::abs(x[0] - x_c));
    const double tolerance = 1e-9 * size;
    const auto   key       = [&](const Point<2> &x) {
      return std::llround(x[1] / tolerance / 1e3);
    };
    std::multimap<long long, unsigned int> by_height;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      by_height.emplace(key(vertices[v]), v);
    mirror_pairs.clear();
    for (unsigned int v = 0; v < vertices.size(); ++v)
      {
        unsigned int partner = numbers::invalid_unsigned_int;
        for (long long k = key(vertices[v]) - 1; k <= key(vertices[v]) + 1; ++k)
          {
            const auto range = by_height.equal_range(k);
            for (auto it = range.first; it != range.second; ++it)
              {
                const Point<2> &y = vertices[it->second];
                if (std::abs(y[0] - (2. * x_c - vertices[v][0])) < tolerance &&
                    std::abs(y[1] - vertices[v][1]) < tolerance)
                  partner = it->second;
              }
          }
        if (partner == numbers::invalid_unsigned_int)
          {
            mirror_pairs.clear();
            AssertThrow(max_symmetry_error < 0.,
                        ExcMessage(
                          "Verification: 'Maximum symmetry error' = " +
                          format_input(max_symmetry_error) +
                          " asks for a symmetry check, but the mesh is not "
                          "symmetric about x = " +
                          format_input(x_c) + " (the vertex (" +
                          format_input(vertices[v][0]) + ", " +
                          format_input(vertices[v][1]) +
                          ") has no mirror vertex); set it to -1."));
            return;
          }
        if (v <= partner)
          mirror_pairs.emplace_back(v, partner);
      }
  }



  double
  CylinderImpactProblem::asymmetry() const
  {
    const Vector<double> &u          = system().state().displacement.block(0);
    const ElasticBody<2> &body       = deformable_body();
    double                difference = 0., size = 0.;
    for (const auto &[a, b] : mirror_pairs)
      {
        const double ax = body.nodal_value(u, a, 0),
                     ay = body.nodal_value(u, a, 1),
                     bx = body.nodal_value(u, b, 0),
                     by = body.nodal_value(u, b, 1);
        difference =
          std::max({difference, std::abs(ax + bx), std::abs(ay - by)});
        size = std::max({size, std::abs(ax), std::abs(ay)});
      }
    return size > 0. ? difference / size : 0.;
  }



  void
  CylinderImpactProblem::measure_step(const StepReport &)
  {
    if (!mirror_pairs.empty())
      symmetry_error = std::max(symmetry_error, asymmetry());
  }



  // @sect3{The report}
  //
  // The momentum before and after; the horizontal one is zero up to
  // round-off (symmetry) and printed as such.
  void
  CylinderImpactProblem::report_motion(std::ostream &out, JsonObject &) const
  {
    const double mass  = deformable_body().total_mass();
    Tensor<1, 2> p_end = system().momentum(0);
    for (unsigned int d = 0; d < 2; ++d)
      if (std::abs(p_end[d]) < 1e-9 * mass * impact_velocity)
        p_end[d] = 0.;
    out << "  Mass " << mass << ", momentum at t = 0: (0, "
        << -mass * impact_velocity << "), at the end: (" << p_end[0] << ", "
        << p_end[1] << ")" << std::endl;
  }



  bool
  CylinderImpactProblem::report_checks(std::ostream &out,
                                       JsonObject   &summary) const
  {
    if (mirror_pairs.empty())
      {
        out << "  Symmetry: not checked (the mesh is not symmetric)"
            << std::endl;
        return true;
      }
    summary.add("symmetry_error", symmetry_error);
    out << "  Symmetry: max |u(x) - mirrored u(-x)| / max |u| = "
        << (symmetry_error < 1e-12 ? std::string("< 1e-12") :
                                     format_number(symmetry_error))
        << std::endl;
    return print_check(
      out, "symmetry error", symmetry_error, "<=", max_symmetry_error);
  }
} // namespace CylinderImpact



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      CylinderImpact::CylinderImpactProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
