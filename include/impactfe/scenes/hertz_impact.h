#ifndef impactfe_scenes_hertz_impact_h
#define impactfe_scenes_hertz_impact_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/tria.h>

#include <impactfe/output/output.h>

#include <limits>
#include <ostream>

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



  /**
   * The ball of the Hertz scenes (hertz_impact, hertz_on_block) and its
   * entries: `Geometry` (Radius, Number of refinements, Pole cell factor,
   * Fine zone angle), `Initial conditions` (Impact velocity, Initial gap)
   * and `Verification` (Maximum peak force error, Maximum duration error).
   */
  struct HertzBallParameters
  {
    double       radius           = 0.01;
    unsigned int n_refinements    = 2;
    double       pole_cell_factor = 0.3, fine_angle = 0.15;
    double       impact_velocity = 5., initial_gap = 0.;
    /// -1: not checked.
    double max_peak_force_error = -1., max_duration_error = -1.;

    static void
    declare_parameters(dealii::ParameterHandler &prm);
    /** Throws a message naming the entry for a value out of range. */
    void
    parse_parameters(dealii::ParameterHandler &prm);

    /**
     * Geometry::graded_ball() with the lowest point at height initial_gap
     * above z = 0.
     */
    void
    make_ball(dealii::Triangulation<3> &triangulation) const;

    /** Side of the cells at the lowest point, (pi/2) 2^-n gamma R [m]. */
    double
    pole_cell_size() const;

    /**
     * From the touch (initial gap / v) to @p last_contact, the last step
     * with a contact force; -1 if there was none, or if the contact had
     * not ended at the run's end @p end_time (the duration is then not
     * known).
     */
    double
    contact_duration(const double last_contact, const double end_time) const;
  };



  /**
   * A run's peak force, contact duration and largest approach against
   * @p reference: one line each on @p out ("Peak force: F N, Hertz F_H N,
   * relative error e") and the entries hertz_*, contact_duration,
   * max_approach and *_error of summary.json. A @p duration < 0 is not
   * measured (no contact, or a contact that had not ended): the line says
   * why and summary.json has null for it and its error.
   */
  void
  report_against_hertz(const HertzImpact &reference,
                       const double       peak_force,
                       const double       duration,
                       const double       approach,
                       std::ostream      &out,
                       JsonObject        &summary);

  /**
   * The checks of `Verification/Maximum peak force error` and `Maximum
   * duration error` (-1: not checked), printed on @p out. Returns false if
   * one fails; a duration that was not measured fails its check.
   */
  bool
  check_against_hertz(const HertzImpact &reference,
                      const double       peak_force,
                      const double       duration,
                      const double       max_peak_force_error,
                      const double       max_duration_error,
                      std::ostream      &out);
} // namespace impactfe

#endif
