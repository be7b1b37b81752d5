#ifndef impactfe_bodies_geometry_h
#define impactfe_bodies_geometry_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

namespace impactfe
{
  using namespace dealii;

  /**
   * Built-in meshes of the scenes. Boundary ids are documented
   * per function; the candidates for contact are on one of them.
   */
  namespace Geometry
  {
    /**
     * A Q1 "O-grid" mesh of the disc of @p radius centred at @p center: a
     * square core of n_core x n_core cells (half-width 0.37 R) surrounded
     * by n_rings rings of 4 n_core cells that blend from the core's square
     * boundary to the circle (boundary vertices exactly on the circle, at
     * uniform angles). n_core must be even. Cells: n_core^2 + 4 n_core
     * n_rings; vertices: (n_core + 1)^2 + 4 n_core n_rings. The mesh is
     * symmetric about the vertical line through the centre.
     *
     * Boundary ids: 1 on the lower half of the circle (y < center y), 0 on
     * the upper half.
     */
    void
    disc(Triangulation<2>  &triangulation,
         const Point<2>    &center,
         const double       radius,
         const unsigned int n_core,
         const unsigned int n_rings);

    /**
     * A plate of @p width whose lower side is an arc of @p radius (bulging
     * downwards, through the lower corners) and whose vertical sides have
     * height @p side_height; the lowest point of the arc is at
     * @p lowest_point. nx x ny Q1 cells; vertical grid lines, the rows
     * blend linearly from the arc to the straight upper side.
     *
     * Boundary ids: 0 left, 1 right, 2 the round lower side, 3 top.
     */
    void
    plate_with_round_side(Triangulation<2>  &triangulation,
                          const Point<2>    &lowest_point,
                          const double       width,
                          const double       side_height,
                          const double       radius,
                          const unsigned int nx,
                          const unsigned int ny);

    /**
     * A Q1 mesh of the ball of @p radius centred at @p center, graded
     * towards its lowest point (the "south pole", direction -z): deal.II's
     * 7-cell ball refined @p n_refinements times on its sphere, then every
     * vertex moved by a smooth map of the ball onto itself: in the cap of
     * polar angle @p fine_angle [rad] around the pole the cells are
     * smaller than the uniform mesh's by @p pole_cell_factor, in every
     * direction (tangentially and in depth); beyond it they grow linearly
     * to a size c > 1 times the uniform mesh's, c being what the cell count
     * leaves. Boundary vertices stay on the sphere; the map is the identity
     * near the centre. The mesh has 7 * 8^n_refinements cells and no
     * hanging nodes, which is what a Hertz contact needs: cells much
     * smaller than the contact radius over the contact zone.
     * fine_angle / pole_cell_factor must be below 0.9 pi.
     *
     * Boundary ids: 1 on the lower half of the sphere (z < center z), 0 on
     * the upper half.
     */
    void
    graded_ball(Triangulation<3>  &triangulation,
                const Point<3>    &center,
                const double       radius,
                const unsigned int n_refinements,
                const double       pole_cell_factor,
                const double       fine_angle);

    /**
     * The box [-a, a]^2 x [-d, 0] (a = @p half_width, d = @p depth) of Q1
     * hexahedra graded towards the centre of its top face z = 0: the cells
     * there have sides @p centre_cell_size, and each next cell is larger by
     * @p growth, in x and y away from the axis and in z downwards; the last
     * cell of a row takes what is left (merged into its neighbour if less
     * than half of it). A tensor-product mesh, so it is conforming. Boundary
     * ids as deal.II's colorize: 0, 1 (x = -a, a), 2, 3 (y), 4 (bottom), 5
     * (top). Throws a message naming the argument if a size is not > 0, the
     * centre cells are larger than the box, or @p growth < 1.
     */
    void
    graded_block(Triangulation<3> &triangulation,
                 const double      half_width,
                 const double      depth,
                 const double      centre_cell_size,
                 const double      growth);

    /**
     * The map of graded_ball() on one point, relative to the centre and in
     * units of the radius (|p| <= 1): exposed so that tests can check that
     * it is one-to-one and keeps the sphere.
     */
    Point<3>
    ball_grading_map(const Point<3> &p,
                     const double    pole_cell_factor,
                     const double    fine_angle);

    /**
     * The smallest Jacobian determinant of a hexahedron's trilinear map at
     * its 8 corners [m^3]: <= 0 means the cell is inverted or degenerate.
     */
    double
    min_corner_jacobian(const Triangulation<3>::cell_iterator &cell);
  } // namespace Geometry
} // namespace impactfe

#endif
