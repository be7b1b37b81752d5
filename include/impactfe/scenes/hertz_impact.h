#ifndef impactfe_scenes_hertz_impact_h
#define impactfe_scenes_hertz_impact_h

#include <limits>

namespace impactfe
{
  /**
   * Hertz's quasi-static theory of the impact of an elastic sphere on a
   * flat elastic half-space (or a rigid one), the reference of the Hertz
   * scenes. Johnson, Contact Mechanics (1985), sections 4.2 and 11.4: the
   * approach delta of distant points of the two bodies gives the force
   *   F = (4/3) E* sqrt(R) delta^(3/2),
   *   1/E* = (1 - nu_1^2)/E_1 + (1 - nu_2^2)/E_2,
   * and energy conservation m v^2 / 2 = (8/15) E* sqrt(R) delta^(5/2) at
   * the largest approach gives
   *   delta_max = (15 m v^2 / (16 E* sqrt(R)))^(2/5),
   *   F_max = (4/3) E* sqrt(R) delta_max^(3/2),   a_max = sqrt(R delta_max),
   *   t_c = 2 (delta_max / v) int_0^1 dx / sqrt(1 - x^(5/2))
   *       = (4/5) B(2/5, 1/2) delta_max / v = 2.9432 delta_max / v.
   * The theory neglects the waves the impact sends through the bodies
   * (their energy is about 1.04 (v/c_0)^(3/5) of the impact energy, Hunter
   * 1957, c_0 = sqrt(E/rho)) and assumes a_max << R.
   */
  struct HertzImpact
  {
    /// Sphere: radius [m], mass [kg], Young's modulus [Pa], Poisson's ratio.
    double radius = 1., mass = 1., youngs_modulus = 1., poissons_ratio = 0.;
    /// The flat body's; infinite modulus: rigid.
    double flat_youngs_modulus = std::numeric_limits<double>::infinity(),
           flat_poissons_ratio = 0.;
    /// Approach velocity [m/s].
    double velocity = 1.;

    /** E* [Pa]. */
    double
    effective_modulus() const;
    /** delta_max [m]. */
    double
    max_approach() const;
    /** F_max [N]. */
    double
    peak_force() const;
    /** a_max [m]. */
    double
    max_contact_radius() const;
    /** t_c [s]. */
    double
    contact_duration() const;
    /** Hertz's force for an approach delta >= 0 [N]. */
    double
    force(const double approach) const;
  };
} // namespace impactfe

#endif
