#include <impactfe/bodies/geometry.h>
#include <impactfe/scenes/round_sided_plate.h>
#include <impactfe/utilities/program.h>

namespace impactfe
{
  void
  RoundSidedPlate::declare_parameters(ParameterHandler  &prm,
                                      const std::string &thickness_help)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Width",
                      "0.08",
                      Patterns::Double(),
                      "Width of the plate [m]. Must be > 0.");
    prm.declare_entry("Side height",
                      "0.04",
                      Patterns::Double(),
                      "Height of the plate's vertical sides, above the ends "
                      "of the round side [m]. Must be > 0.");
    prm.declare_entry("Radius of the round side",
                      "0.101",
                      Patterns::Double(),
                      "Radius of the arc that forms the lower side [m]. Must "
                      "exceed half the width.");
    prm.declare_entry("Thickness", "0.01", Patterns::Double(), thickness_help);
    prm.declare_entry("Number of cells across",
                      "10",
                      Patterns::Integer(1),
                      "Q1 cells along the width [-].");
    prm.declare_entry("Number of cells up",
                      "8",
                      Patterns::Integer(1),
                      "Q1 cells along the height [-].");
    prm.declare_entry("Initial gap",
                      "0",
                      Patterns::Double(),
                      "Height of the lowest point of the round side above "
                      "the plane at t = 0 [m]. Must be >= 0.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Horizontal velocity",
                      "3",
                      Patterns::Double(),
                      "V_h, along x, at t = 0 [m/s].");
    prm.declare_entry("Vertical velocity",
                      "-5",
                      Patterns::Double(),
                      "V_v, along y, at t = 0 [m/s]. Must be < 0 (towards "
                      "the plane).");
    prm.leave_subsection();
  }



  void
  RoundSidedPlate::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    width       = prm.get_double("Width");
    side_height = prm.get_double("Side height");
    radius      = prm.get_double("Radius of the round side");
    thickness   = prm.get_double("Thickness");
    nx          = prm.get_integer("Number of cells across");
    ny          = prm.get_integer("Number of cells up");
    initial_gap = prm.get_double("Initial gap");
    prm.leave_subsection();
    require_mesh_fits_in_memory(double(nx) * ny,
                                2,
                                "Geometry",
                                "'Number of cells across' and 'Number of "
                                "cells up'");
    AssertThrow(width > 0. && side_height > 0.,
                ExcMessage("Geometry: 'Width' and 'Side height' must be > 0, "
                           "got " +
                           format_number(width) + " and " +
                           format_number(side_height) + "."));
    AssertThrow(2. * radius > width,
                ExcMessage("Geometry: 'Radius of the round side' must exceed "
                           "half the width, got " +
                           format_number(radius) + "."));
    require_positive(thickness, "Geometry", "Thickness");
    require_non_negative(initial_gap, "Geometry", "Initial gap");
    prm.enter_subsection("Initial conditions");
    horizontal_velocity = prm.get_double("Horizontal velocity");
    vertical_velocity   = prm.get_double("Vertical velocity");
    prm.leave_subsection();
    AssertThrow(vertical_velocity < 0.,
                ExcMessage("Initial conditions: 'Vertical velocity' must be < "
                           "0 (towards the plane), got " +
                           format_number(vertical_velocity) + "."));
  }



  void
  RoundSidedPlate::make_mesh(Triangulation<2> &triangulation) const
  {
    Geometry::plate_with_round_side(triangulation,
                                    Point<2>(0., initial_gap),
                                    width,
                                    side_height,
                                    radius,
                                    nx,
                                    ny);
  }
} // namespace impactfe
