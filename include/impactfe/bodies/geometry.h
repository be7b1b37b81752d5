#ifndef impactfe_bodies_geometry_h
#define impactfe_bodies_geometry_h

#include <deal.II/base/point.h>

#include <deal.II/grid/tria.h>

namespace impactfe
{
  using namespace dealii;

  /**
   * Built-in 2D meshes of the paper's scenes. Boundary ids are documented
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
  } // namespace Geometry
} // namespace impactfe

#endif
