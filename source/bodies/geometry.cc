#include <deal.II/base/exceptions.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/geometry.h>

#include <cmath>
#include <vector>

namespace impactfe
{
  namespace Geometry
  {
    // @sect3{The O-grid disc}
    // Ring level 0 is the boundary of the square core, walked counter-
    // clockwise from its lower right corner; point k of a ring sits, on the
    // circle, at the angle -pi/4 + (pi/2) k / n_core, and the rings in
    // between blend linearly from square to circle.
    void
    disc(Triangulation<2>  &triangulation,
         const Point<2>    &center,
         const double       radius,
         const unsigned int n_core,
         const unsigned int n_rings)
    {
      AssertThrow(radius > 0.,
                  ExcMessage("Geometry: the disc's radius must be > 0."));
      AssertThrow(n_core >= 2 && n_core % 2 == 0,
                  ExcMessage("Geometry: the number of core cells across the "
                             "disc must be even and >= 2, got " +
                             std::to_string(n_core) + "."));
      AssertThrow(n_rings >= 1,
                  ExcMessage("Geometry: the disc needs at least one ring."));
      const unsigned int n = n_core, m = n_rings, n_ring_points = 4 * n;
      const double       a = 0.37 * radius;

      std::vector<Point<2>> vertices;
      const auto core_index = [n](const unsigned int i, const unsigned int j) {
        return j * (n + 1) + i;
      };
      for (unsigned int j = 0; j <= n; ++j)
        for (unsigned int i = 0; i <= n; ++i)
          vertices.emplace_back(-a + 2. * a * i / n, -a + 2. * a * j / n);

      // Core index of point k of ring level 0.
      const auto square_point = [&](const unsigned int k) {
        if (k < n)
          return core_index(n, k);
        if (k < 2 * n)
          return core_index(n - (k - n), n);
        if (k < 3 * n)
          return core_index(0, n - (k - 2 * n));
        return core_index(k - 3 * n, 0);
      };
      const auto ring_index = [&](const unsigned int level,
                                  const unsigned int k) {
        const unsigned int kk = k % n_ring_points;
        return level == 0 ?
                 square_point(kk) :
                 (n + 1) * (n + 1) + (level - 1) * n_ring_points + kk;
      };
      for (unsigned int level = 1; level <= m; ++level)
        {
          const double s = double(level) / m;
          for (unsigned int k = 0; k < n_ring_points; ++k)
            {
              const double   angle = -M_PI / 4. + (M_PI / 2.) * k / n;
              const Point<2> on_circle(radius * std::cos(angle),
                                       radius * std::sin(angle));
              const Point<2> on_square = vertices[square_point(k)];
              vertices.push_back((1. - s) * on_square + s * on_circle);
            }
        }
      for (Point<2> &x : vertices)
        x += center;

      std::vector<CellData<2>> cells;
      for (unsigned int j = 0; j < n; ++j)
        for (unsigned int i = 0; i < n; ++i)
          {
            CellData<2> cell;
            cell.vertices = {core_index(i, j),
                             core_index(i + 1, j),
                             core_index(i, j + 1),
                             core_index(i + 1, j + 1)};
            cells.push_back(cell);
          }
      // Ring cells: local x radial (outwards), local y along the ring
      // (counter-clockwise), which gives a positive Jacobian.
      for (unsigned int level = 0; level < m; ++level)
        for (unsigned int k = 0; k < n_ring_points; ++k)
          {
            CellData<2> cell;
            cell.vertices = {ring_index(level, k),
                             ring_index(level + 1, k),
                             ring_index(level, k + 1),
                             ring_index(level + 1, k + 1)};
            cells.push_back(cell);
          }
      GridTools::consistently_order_cells(cells);
      triangulation.create_triangulation(vertices, cells, SubCellData());

      for (const auto &face : triangulation.active_face_iterators())
        if (face->at_boundary())
          face->set_boundary_id(face->center()[1] < center[1] ? 1 : 0);
    }



    // @sect3{The plate with a round side}
    void
    plate_with_round_side(Triangulation<2>  &triangulation,
                          const Point<2>    &lowest_point,
                          const double       width,
                          const double       side_height,
                          const double       radius,
                          const unsigned int nx,
                          const unsigned int ny)
    {
      AssertThrow(width > 0. && side_height > 0.,
                  ExcMessage("Geometry: the plate's width and height must be "
                             "> 0."));
      AssertThrow(2. * radius > width,
                  ExcMessage("Geometry: the radius of the round side must "
                             "exceed half the plate's width."));
      const double half    = 0.5 * width;
      const double sagitta = radius - std::sqrt(radius * radius - half * half);
      const double top     = sagitta + side_height;
      GridGenerator::subdivided_hyper_rectangle(triangulation,
                                                {nx, ny},
                                                Point<2>(-half, 0.),
                                                Point<2>(half, 1.),
                                                /*colorize=*/true);
      // Map the unit-height grid: row parameter eta in [0, 1] goes from the
      // arc y_b(x) = R - sqrt(R^2 - x^2) to the top.
      GridTools::transform(
        [&](const Point<2> &p) {
          const double x   = p[0];
          const double y_b = radius - std::sqrt(radius * radius - x * x);
          return Point<2>(lowest_point[0] + x,
                          lowest_point[1] + y_b + p[1] * (top - y_b));
        },
        triangulation);
    }
  } // namespace Geometry
} // namespace impactfe
