// Geometry::graded_ball, the mesh of the Hertz scenes, against the plain
// deal.II ball it is made from:
// - with a pole cell factor of 1 it is that ball (the map is the identity);
// - its boundary vertices lie on the sphere;
// - on the sphere, the polar angles of the vertices of the fine zone are
//   the plain ball's times the pole cell factor (the cells there are
//   smaller by that factor), and the map moves no vertex near the centre;
// - no cell is inverted (corner Jacobians > 0), and the volume is close to
//   the sphere's (a polyhedron inscribed in it: a little smaller);
// - a fine zone too large for the factor is refused with a message.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <impactfe/bodies/geometry.h>

#include <cmath>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;

namespace
{
  double
  polar_angle(const Point<3> &x, const Point<3> &center)
  {
    const Tensor<1, 3> d = x - center;
    return std::atan2(std::hypot(d[0], d[1]), -d[2]);
  }

  void
  check(const unsigned int n, const double gamma, const double fine_angle)
  {
    const Point<3>   center(0., 0., 2.);
    const double     radius = 1.5;
    Triangulation<3> plain, graded;
    GridGenerator::hyper_ball(plain, center, radius);
    plain.refine_global(n);
    Geometry::graded_ball(graded, center, radius, n, gamma, fine_angle);
    deallog << "n = " << n << ", pole cell factor " << gamma
            << ", fine zone angle " << fine_angle << ": "
            << graded.n_active_cells() << " cells, " << graded.n_vertices()
            << " vertices" << std::endl;
    AssertThrow(plain.n_vertices() == graded.n_vertices(), ExcInternalError());

    // Vertex by vertex (same numbering: the grading only moves vertices).
    const auto       &xp = plain.get_vertices();
    const auto       &xg = graded.get_vertices();
    std::vector<bool> on_boundary(xg.size(), false);
    for (const auto &face : graded.active_face_iterators())
      if (face->at_boundary())
        for (const unsigned int v : face->vertex_indices())
          on_boundary[face->vertex_index(v)] = true;
    double       off_sphere = 0., angle_error = 0., core_move = 0., moved = 0.;
    unsigned int in_fine_zone = 0;
    for (unsigned int v = 0; v < xg.size(); ++v)
      {
        moved = std::max(moved, xg[v].distance(xp[v]) / radius);
        if (xp[v].distance(center) < 0.45 * radius)
          core_move = std::max(core_move, xg[v].distance(xp[v]) / radius);
        if (!on_boundary[v])
          continue;
        off_sphere =
          std::max(off_sphere,
                   std::abs(xg[v].distance(center) - radius) / radius);
        const double alpha = polar_angle(xp[v], center);
        if (alpha <= fine_angle / gamma)
          {
            ++in_fine_zone;
            angle_error =
              std::max(angle_error,
                       std::abs(polar_angle(xg[v], center) - gamma * alpha));
          }
      }
    double       volume = 0., smallest_jacobian = 1e300;
    unsigned int n_contact_faces  = 0;
    bool         ids_below_centre = true;
    for (const auto &cell : graded.active_cell_iterators())
      {
        volume += cell->measure();
        smallest_jacobian =
          std::min(smallest_jacobian, Geometry::min_corner_jacobian(cell));
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary() && face->boundary_id() == 1)
            {
              ++n_contact_faces;
              ids_below_centre &= face->center()[2] < center[2];
            }
      }
    const double sphere = 4. / 3. * numbers::PI * std::pow(radius, 3);
    deallog << "  largest vertex move / R: "
            << (moved < 1e-12 ?
                  std::string("0") :
                  std::to_string(impactfe_tests::rounded(moved, 3)))
            << "; within 0.45 R of the centre: "
            << (core_move < 1e-12 ? "0 (< 1e-12)" : "MOVED") << std::endl;
    deallog << "  boundary vertices off the sphere: "
            << (off_sphere < 1e-12 ? "< 1e-12 R" : "TOO FAR") << std::endl;
    deallog << "  " << in_fine_zone
            << " vertices in the fine zone, polar angle = factor x plain "
               "ball's: "
            << (angle_error < 1e-12 ? "yes (< 1e-12 rad)" : "NO") << std::endl;
    deallog << "  corner Jacobians > 0: "
            << (smallest_jacobian > 0. ? "yes" : "NO")
            << "; volume / sphere's - 1 = "
            << impactfe_tests::rounded(volume / sphere - 1., 3) << std::endl;
    deallog << "  " << n_contact_faces
            << " boundary faces with id 1, all below "
            << "the centre: " << (ids_below_centre ? "yes" : "NO") << std::endl;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  check(2, 1., 0.3);
  check(2, 0.5, 0.3);
  check(3, 0.25, 0.15);
  for (const auto &[n, gamma] : {std::pair{1u, 0.05}, std::pair{3u, 0.2}})
    try
      {
        Triangulation<3> tria;
        Geometry::graded_ball(tria, Point<3>(), 1., n, gamma, 0.15);
        deallog << "fine zone 0.15 rad, factor " << gamma << ": accepted"
                << std::endl;
      }
    catch (const std::exception &e)
      {
        const std::string what = e.what();
        deallog << "fine zone 0.15 rad, factor " << gamma << ", n = " << n
                << ": refused, "
                << (what.find("whole sphere") != std::string::npos ?
                      "the zone is too large" :
                    what.find("inverted cell") != std::string::npos ?
                      "an inverted cell" :
                      "OTHER ERROR")
                << std::endl;
      }
}
