#ifndef impactfe_scenes_rigid_block_h
#define impactfe_scenes_rigid_block_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <deal.II/grid/tria.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/stability_monitor.h>
#include <impactfe/output/output.h>

#include <array>
#include <ostream>

namespace impactfe
{
  using namespace dealii;

  /**
   * A rectangular block of Q1 cells in the frame of a plane (unit normal n,
   * tangent t = n turned by -90 degrees): its width along t, its height
   * along n and its cells, in one parameter subsection (e.g. `Geometry`,
   * `Body 2`).
   */
  struct BlockParameters
  {
    double       width = 0.1, height = 0.05;
    unsigned int n_across = 8, n_up = 4;

    /** @p what names the block in the help texts and messages. */
    static void
    declare_parameters(ParameterHandler &prm, const std::string &what);
    void
    parse_parameters(ParameterHandler &prm, const std::string &subsection);

    /**
     * The mesh, centred on @p origin along t, its lower side at
     * @p lower_side along n. With `colorize`, boundary ids 0 left, 1 right,
     * 2 lower side, 3 upper side.
     */
    void
    make_mesh(Triangulation<2>   &triangulation,
              const Point<2>     &origin,
              const Tensor<1, 2> &normal,
              const double        lower_side) const;
  };

  /**
   * Two comma-separated components of entry @p entry, e.g. "0, -9.81", of
   * the subsection @p subsection that @p prm is in (for the message).
   */
  Tensor<1, 2>
  get_vector(ParameterHandler  &prm,
             const std::string &subsection,
             const std::string &entry);

  /**
   * The entries of the sliding-block scenes (block_sliding_3d and
   * contact_mpi): subsection `Geometry` (a box of length x height x
   * width, in nx x ny x nz Q1 cells), `Initial conditions` (the speed v0
   * and the direction phi of the launch along the plane), `Loads` (g) and
   * the stability bounds of `Verification`.
   */
  struct SlidingBoxParameters
  {
    double          length = 0.1, height = 0.01, width = 0.1;
    unsigned int    nx = 4, ny = 1, nz = 4;
    double          speed = 1., phi = 0., gravity = 9.81;
    StabilityBounds bounds;

    static void
    declare_parameters(ParameterHandler &prm);
    /// Parses and checks (lengths and v0 > 0, g >= 0, phi finite).
    void
    parse_parameters(ParameterHandler &prm);
  };



  /**
   * The rigid-block model of sliding on a plane. Along the plane's tangent
   * t, with normal load N (pressing), tangential acceleration a_t of the
   * loads and initial velocity v0 = v(0).t: while sliding in the direction
   * s = sign(v0), dv/dt = a_t - s mu N/m. The block decelerates at
   * d = mu N/m - s a_t and sticks at t* = |v0|/d after sliding v0^2/(2d);
   * if d <= 0 (or t* is past the end time T) it never sticks and
   * v(T) = v0 - s d T.
   */
  struct RigidSliding
  {
    RigidSliding(const double v0,
                 const double a_t,
                 const double normal_load_per_mass,
                 const double mu,
                 const double end_time);

    bool
    sticks() const;
    /** Velocity along t at @p t (before sticking). */
    double
    velocity(const double t) const;

    double v0 = 0., deceleration = 0., stick_time = -1., distance = 0.;
  };



  /**
   * The mass-weighted mean of a nodal vector field of one body, (M e_d .
   * field) / m for each axis d: the mean velocity (momentum over mass) of a
   * velocity field, the displacement of the centre of mass of a
   * displacement field. M e_d is computed once, in reinit().
   */
  template <int dim>
  class MassWeightedMean
  {
  public:
    void
    reinit(const ElasticBody<dim> &body);

    Tensor<1, dim>
    operator()(const Vector<double> &field) const;

    /// The body's total mass m.
    double
    mass() const;

  private:
    std::array<Vector<double>, dim> weights;
    double                          total_mass = 0.;
  };



  /**
   * Follows the mean velocity of a deformable block on a plane (unit normal
   * n towards the block, tangent t) during a run, and compares it with
   * the rigid-block references: the apparent restitution of the first
   * impact (the mean normal velocity when the block leaves the plane over
   * the one before it touched), and the time at which the mean velocity
   * along t first reaches 0 against RigidSliding.
   */
  template <int dim>
  class RigidBlockTracker
  {
  public:
    RigidBlockTracker(const Tensor<1, dim> &normal,
                      const Tensor<1, dim> &tangent,
                      const double          time_step);

    /** The mean velocity at t = 0. */
    void
    start(const Tensor<1, dim> &mean_velocity);
    /**
     * The mean velocity at the end of the step ending at @p t, and whether
     * a node of the block touches the plane.
     */
    void
    record(const double          t,
           const Tensor<1, dim> &mean_velocity,
           const bool            on_plane);

    /**
     * Print the sliding reference against the measured stick time,
     * @p distance (slid by the centre of mass) and @p final_velocity
     * (along t, at the end time), with the checks of @p bounds.
     */
    bool
    report_sliding(std::ostream          &out,
                   const RigidSliding    &rigid,
                   const double           distance,
                   const double           final_velocity,
                   const double           end_time,
                   const StabilityBounds &bounds,
                   JsonObject            &stability) const;

    /** The first time the mean velocity along t reached 0 (-1: never). */
    double
    stop_time() const;

    /** Print the first impact's restitution (if there was an impact). */
    bool
    report_restitution(std::ostream          &out,
                       const StabilityBounds &bounds,
                       JsonObject            &stability) const;

  private:
    Tensor<1, dim> normal, tangent;
    double         time_step;
    double         velocity_before_impact = 0., velocity_after_impact = 0.;
    int            impact_phase                 = 0;
    double         previous_tangential_velocity = 0., first_stop_time = -1.;
  };
} // namespace impactfe

#endif
