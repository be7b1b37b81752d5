#ifndef impactfe_scenes_two_bars_exact_h
#define impactfe_scenes_two_bars_exact_h

namespace impactfe
{
  /**
   * The exact solution of the impact of two identical elastic bars
   * (Carpenter, Taylor and Katona 1991; Vola, Pratt, Jean and Raous,
   * section 6.1): bar 1 moves at v0 towards bar 2, at rest, across the gap
   * g0. During t0 <= t < t0 + 2L/c (t0 = g0/v0, c = sqrt(E/rho)) the
   * interface moves at v0/2 and carries the force rho c v0 A/2; afterwards
   * bar 1 rests and bar 2 moves at v0. Piecewise constant in time at the
   * contact nodes. The one definition used by the programs (two_bars_1d,
   * two_bars_2d) and the tests; the Python benchmarks implement the same
   * formulas (benchmarks/peers/two_bars_exact.py).
   */
  struct TwoBarsExactSolution
  {
    TwoBarsExactSolution() = default;
    /**
     * @p wave_speed: c of the bars, @p area: the cross-section A (in 2D the
     * height times the thickness).
     */
    TwoBarsExactSolution(const double impact_velocity,
                         const double initial_gap,
                         const double bar_length,
                         const double wave_speed,
                         const double density,
                         const double area);

    /**
     * Bar 1 at v0 hitting a rigid wall across the gap g0 instead: during
     * t0 <= t < t0 + 2L/c the contact face rests and carries rho c v0 A;
     * afterwards bar 1 moves back at -v0. It is the two bars' solution at
     * 2 v0 seen from the frame moving at v0 (the symmetric impact), with
     * the same error scales (the velocity jump v0 and the force).
     */
    static TwoBarsExactSolution
    against_rigid_wall(const double impact_velocity,
                       const double initial_gap,
                       const double bar_length,
                       const double wave_speed,
                       const double density,
                       const double area);
    /** Velocity of bar 1's contact node (lab frame). */
    double
    contact_velocity(const double t) const;
    /** Velocity of bar 2's contact node. */
    double
    target_velocity(const double t) const;
    /** Total contact force, positive in compression. */
    double
    normal_force(const double t) const;

    double v0 = 0., t_contact = 0., duration = 0., contact_force = 0.;
    /// The jump of the contact velocity at the touch: v0/2 (bars), v0
    /// (wall); the scale of err_v.
    double velocity_jump = 0.;
    bool   rigid_wall    = false;
  };



  /**
   * The errors of a two-bar run against the exact solution, as defined in
   * doc/two_bars_1d.md and used by every benchmark: with the interface
   * velocity jump v0/2 and the contact force rho c v0 A/2 as scales (v0
   * and rho c v0 A against a rigid wall),
   *   err_v = mean over steps of |v_c(t_i) - v_c^ex(t_i)| / (v0/2),
   *   err_f = mean over steps of |F(t_i) - F^ex(t_i)| / (rho c v0 A/2),
   * at the end time t_i of every step (not at t = 0).
   */
  class TwoBarsErrors
  {
  public:
    explicit TwoBarsErrors(const TwoBarsExactSolution &exact);

    /**
     * Account for the state at the end of a step that covers @p n_steps
     * steps of the parameter file's h (a free-flight step: its end values
     * count for each of them).
     */
    void
    add(const double       t,
        const double       contact_velocity,
        const double       normal_force,
        const unsigned int n_steps = 1);

    double
    err_v() const;
    double
    err_f() const;
    unsigned int
    n_steps() const;

  private:
    TwoBarsExactSolution exact;
    double               sum_v = 0., sum_f = 0.;
    unsigned int         n = 0;
  };
} // namespace impactfe

#endif
