#ifndef impactfe_scenes_round_sided_plate_h
#define impactfe_scenes_round_sided_plate_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/tria.h>

namespace impactfe
{
  using namespace dealii;

  /**
   * The plate with a round side of the paper's section 6.3 (Kim and Kwak;
   * data of the paper's Fig. 7 table) and how it is thrown: the entries of
   * subsections `Geometry` (width, side height, radius of the round side,
   * thickness, cells, initial gap) and `Initial conditions` (horizontal and
   * vertical velocity), shared by `oblique_plate` (2D, plane stress) and
   * `oblique_plate_3d` (the plate extruded to its thickness).
   */
  struct RoundSidedPlate
  {
    double       width = 0.08, side_height = 0.04, radius = 0.101;
    double       thickness = 0.01, initial_gap = 0.;
    unsigned int nx = 10, ny = 8;
    /// V_h (along the width) and V_v (along the normal of the plane).
    double horizontal_velocity = 3., vertical_velocity = -5.;

    /** @p thickness_help says what the thickness is in the program. */
    static void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &thickness_help);
    /** Reads and checks the entries (one message per bad value). */
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * The 2D mesh, nx x ny Q1 cells, the lowest point of the round side at
     * (0, initial gap); boundary id 2 on the round side
     * (Geometry::plate_with_round_side()).
     */
    void
    make_mesh(Triangulation<2> &triangulation) const;
  };
} // namespace impactfe

#endif
