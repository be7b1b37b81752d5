#include <deal.II/base/exceptions.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/geometry.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
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


    // @sect3{The graded ball}
    // In units of the radius, a point is (alpha, s): its polar angle from
    // the pole direction -z and its depth s = 1 - |p|. On the sphere the
    // polar angle is mapped by G with G(0) = 0, G(pi) = pi and the cell size
    // ratio G' = gamma (the pole cell factor) up to alpha_1 = beta / gamma,
    // so that a cap of half-angle beta (the fine zone) has cells gamma times
    // the uniform mesh's; G' then rises linearly to a constant c > 1 at
    // alpha_2 = (alpha_1 + pi) / 2 and keeps it to pi, c being what makes
    // G(pi) = pi: the cells away from the contact are larger than the
    // uniform mesh's by c. Depth follows the local size ratio near the
    // surface, s' = s (1 - w(s) (1 - G'(alpha))), and the angle blends to
    // the identity with depth, alpha' = alpha + w(s) (G(alpha) - alpha), w
    // falling smoothly from 1 at the surface to 0 at half the radius, so
    // that the map is the identity near the centre, keeps the sphere, and
    // scales (alpha, s) uniformly about the pole (cells keep their shape).
    namespace
    {
      double
      smooth_step(const double x)
      {
        const double y = std::min(1., std::max(0., x));
        return y * y * (3. - 2. * y);
      }



      struct PolarGrading
      {
        PolarGrading(const double gamma, const double fine_angle)
          : gamma(gamma)
          , alpha_1(fine_angle / gamma)
          , alpha_2(0.5 * (fine_angle / gamma + numbers::PI))
        {
          // gamma alpha_1 + (gamma + c)/2 (alpha_2 - alpha_1) + c (pi -
          // alpha_2) = pi.
          const double ramp = alpha_2 - alpha_1;
          c = (numbers::PI - gamma * alpha_1 - 0.5 * gamma * ramp) /
              (0.5 * ramp + numbers::PI - alpha_2);
        }

        /// G'(alpha).
        double
        size_ratio(const double alpha) const
        {
          if (alpha <= alpha_1)
            return gamma;
          if (alpha <= alpha_2)
            return gamma +
                   (c - gamma) * (alpha - alpha_1) / (alpha_2 - alpha_1);
          return c;
        }

        /// G(alpha).
        double
        operator()(const double alpha) const
        {
          if (alpha <= alpha_1)
            return gamma * alpha;
          const double ramp = std::min(alpha, alpha_2) - alpha_1;
          double       g    = gamma * alpha_1 + gamma * ramp +
                     0.5 * (c - gamma) * ramp * ramp / (alpha_2 - alpha_1);
          if (alpha > alpha_2)
            g += c * (alpha - alpha_2);
          return g;
        }

        double gamma, alpha_1, alpha_2, c;
      };
    } // namespace



    Point<3>
    ball_grading_map(const Point<3> &p,
                     const double    pole_cell_factor,
                     const double    fine_angle)
    {
      const double r = p.norm();
      if (r == 0.)
        return p;
      const PolarGrading grading(pole_cell_factor, fine_angle);
      const double       rho       = std::hypot(p[0], p[1]);
      const double       alpha     = std::atan2(rho, -p[2]);
      const double       depth     = 1. - r;
      const double       w         = 1. - smooth_step(depth / 0.5);
      const double       new_alpha = alpha + w * (grading(alpha) - alpha);
      const double       new_r =
        1. - depth * (1. - w * (1. - grading.size_ratio(alpha)));
      const double cx    = rho > 0. ? p[0] / rho : 1.,
                   cy    = rho > 0. ? p[1] / rho : 0.;
      const double sin_a = std::sin(new_alpha);
      return Point<3>(new_r * sin_a * cx,
                      new_r * sin_a * cy,
                      -new_r * std::cos(new_alpha));
    }



    namespace
    {
      // Cell sizes h, h g, h g^2, ... that fill @p length, the last one
      // taking what is left (merged into the one before if less than half
      // of it).
      std::vector<double>
      growing_steps(const double length, const double h, const double g)
      {
        std::vector<double> steps;
        double              filled = 0., next = h;
        while (filled + next < length)
          {
            steps.push_back(next);
            filled += next;
            next *= g;
          }
        const double rest = length - filled;
        if (!steps.empty() && rest < 0.5 * steps.back())
          steps.back() += rest;
        else
          steps.push_back(rest);
        return steps;
      }
    } // namespace



    void
    graded_block(Triangulation<3> &triangulation,
                 const double      half_width,
                 const double      depth,
                 const double      centre_cell_size,
                 const double      growth)
    {
      AssertThrow(half_width > 0. && depth > 0.,
                  ExcMessage("graded_block: the half width and the depth "
                             "must be > 0, got " +
                             std::to_string(half_width) + " and " +
                             std::to_string(depth) + "."));
      AssertThrow(centre_cell_size > 0. && centre_cell_size <= half_width &&
                    centre_cell_size <= depth,
                  ExcMessage("graded_block: the centre cell size must be in "
                             "(0, min(half width, depth)], got " +
                             std::to_string(centre_cell_size) + "."));
      AssertThrow(growth >= 1.,
                  ExcMessage("graded_block: the growth factor must be >= 1, "
                             "got " +
                             std::to_string(growth) + "."));
      const std::vector<double> half =
        growing_steps(half_width, centre_cell_size, growth);
      std::vector<double> across(half.rbegin(), half.rend());
      across.insert(across.end(), half.begin(), half.end());
      std::vector<double> down = growing_steps(depth, centre_cell_size, growth);
      std::reverse(down.begin(), down.end()); // from z = -d up to z = 0
      GridGenerator::subdivided_hyper_rectangle(
        triangulation,
        {across, across, down},
        Point<3>(-half_width, -half_width, -depth),
        Point<3>(half_width, half_width, 0.),
        /*colorize=*/true);
    }



    void
    graded_ball(Triangulation<3>  &triangulation,
                const Point<3>    &center,
                const double       radius,
                const unsigned int n_refinements,
                const double       pole_cell_factor,
                const double       fine_angle)
    {
      AssertThrow(radius > 0.,
                  ExcMessage("Geometry: the ball's radius must be > 0."));
      AssertThrow(pole_cell_factor > 0. && pole_cell_factor <= 1.,
                  ExcMessage("Geometry: the pole cell factor must be in (0, "
                             "1], got " +
                             std::to_string(pole_cell_factor) + "."));
      AssertThrow(fine_angle > 0. &&
                    fine_angle / pole_cell_factor < 0.9 * numbers::PI,
                  ExcMessage("Geometry: the fine zone's angle over the pole "
                             "cell factor must be in (0, 0.9 pi): the fine "
                             "zone would take the whole sphere; got " +
                             std::to_string(fine_angle) + " rad / " +
                             std::to_string(pole_cell_factor) + "."));
      // The unit ball, refined on its sphere (deal.II's manifolds), then
      // flat: the graded vertices define Q1 cells.
      GridGenerator::hyper_ball(triangulation, Point<3>(), 1.);
      triangulation.refine_global(n_refinements);
      triangulation.set_all_manifold_ids(numbers::flat_manifold_id);
      triangulation.reset_all_manifolds();
      GridTools::transform(
        [&](const Point<3> &p) {
          return Point<3>(center + radius * ball_grading_map(p,
                                                             pole_cell_factor,
                                                             fine_angle));
        },
        triangulation);
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          if (min_corner_jacobian(cell) <= 0.)
            {
              std::ostringstream where;
              where << std::setprecision(3) << cell->center();
              AssertThrow(false,
                          ExcMessage("Geometry: the graded ball has an "
                                     "inverted cell near (" +
                                     where.str() +
                                     "); use a larger pole cell factor or a "
                                     "smaller fine zone angle."));
            }
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary())
              face->set_boundary_id(face->center()[2] < center[2] ? 1 : 0);
        }
    }



    // The trilinear map's Jacobian determinant at the 8 corners of a hex:
    // at corner (i, j, k) it is the triple product of the three edges that
    // leave it, each oriented along its reference axis.
    double
    min_corner_jacobian(const Triangulation<3>::cell_iterator &cell)
    {
      double smallest = std::numeric_limits<double>::max();
      for (unsigned int v = 0; v < 8; ++v)
        {
          Tensor<2, 3> edges;
          for (unsigned int d = 0; d < 3; ++d)
            {
              const unsigned int neighbor = v ^ (1u << d);
              const double       sign     = (v & (1u << d)) ? -1. : 1.;
              const Tensor<1, 3> e =
                sign * (cell->vertex(neighbor) - cell->vertex(v));
              for (unsigned int c = 0; c < 3; ++c)
                edges[c][d] = e[c];
            }
          smallest = std::min(smallest, determinant(edges));
        }
      return smallest;
    }
  } // namespace Geometry
} // namespace impactfe
