/* ---------------------------------------------------------------------
 *
 * block_sliding_3d: an elastic block sliding on a rigid plane under
 * gravity, with Coulomb friction, in any direction of the plane: it
 * decelerates at mu g along its slip direction and sticks at v0/(mu g),
 * whatever the direction, with the exact (circular) cone.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A box of Q1 hexahedra (length along x, height along y, width along z)
// rests on the rigid plane y = 0 under gravity g and is launched along the
// plane with the speed v0 in the direction s = (cos phi, 0, sin phi). A
// rigid block would decelerate at d = mu g along s, stick at t* = v0/d
// after sliding v0^2/(2d), and never leave the direction s. The deformable
// block's mean velocity (its momentum over its mass) is compared with
// that: the stick time (the first time the mean velocity along s reaches
// 0), the distance slid by the centre of mass, and the largest angle
// between the mean sliding velocity and s while it slides.
//
// The contact frames (n, t1, t2) of the plane y = 0 are (y, z, x) for
// every node, so the slip direction phi meets the facets of a polygonal
// cone at the angle phi: with `Friction cone = facets` the deceleration
// and the direction depend on phi, with `exact` they do not (tests
// `tests/block_sliding_3d/`).
//
// The library does the rest: `ObstacleImpactScene<3>` (mesh, plane,
// material, candidates, the common checks) and `RigidBlockTracker<3>`
// (the stick time and the sliding reference), as for the 2D block of
// `block_on_plane`.

#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>

#include <impactfe/scenes/obstacle_impact_scene.h>
#include <impactfe/scenes/rigid_block.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <memory>

namespace BlockSliding3D
{
  using namespace dealii;
  using namespace impactfe;

  // @sect3{The BlockSliding3DProblem class}
  class BlockSliding3DProblem : public ObstacleImpactScene<3>
  {
  public:
    BlockSliding3DProblem()
      : ObstacleImpactScene<3>("block_sliding_3d",
                               "block",
                               2,
                               "0, 0, 0",
                               "0, 1, 0",
                               "0.5")
    {}

  private:
    void
    declare_scene_parameters(ParameterHandler &prm) override;
    void
    parse_scene_parameters(ParameterHandler &prm) override;
    void
    make_built_in_mesh(Triangulation<3> &triangulation) const override;
    double
    out_of_plane_measure() const override
    {
      return 1.;
    }
    double
    length_scale() const override
    {
      return box.length;
    }
    Tensor<1, 3>
    initial_velocity() const override
    {
      return box.speed * direction();
    }
    std::string
    title() const override
    {
      return "Block sliding on a plane in 3D";
    }
    std::vector<std::string>
    plot_columns() const override
    {
      return {"normal_force", "tangential_force", "sliding"};
    }
    void
    apply_loads() override;
    void
    prepare_run() override;
    void
    measure_step(const StepReport &report) override;
    void
    report_motion(std::ostream &out, JsonObject &summary) const override;
    bool
    report_checks(std::ostream &out, JsonObject &summary) const override;

    /// s = (cos phi, 0, sin phi).
    Tensor<1, 3>
    direction() const
    {
      return Tensor<1, 3>({std::cos(box.phi), 0., std::sin(box.phi)});
    }

    SlidingBoxParameters box;

    /// The block's momentum over its mass, or its mean displacement.
    MassWeightedMean<3>                   block_mean;
    std::unique_ptr<RigidBlockTracker<3>> tracker;
    double                                largest_turn = 0.;
  };



  // @sect3{Parameters}
  void
  BlockSliding3DProblem::declare_scene_parameters(ParameterHandler &prm)
  {
    SlidingBoxParameters::declare_parameters(prm);
  }



  void
  BlockSliding3DProblem::parse_scene_parameters(ParameterHandler &prm)
  {
    box.parse_parameters(prm);
  }



  // @sect3{The mesh and the loads}
  //
  // The box on the plane, centred on the origin in x and z; colorized, so
  // that its lower face y = 0 has boundary id 2 (the candidates). Gravity
  // is the body force rho g (0, -1, 0).
  void
  BlockSliding3DProblem::make_built_in_mesh(Triangulation<3> &tria) const
  {
    GridGenerator::subdivided_hyper_rectangle(
      tria,
      {box.nx, box.ny, box.nz},
      Point<3>(-0.5 * box.length, 0., -0.5 * box.width),
      Point<3>(0.5 * box.length, box.height, 0.5 * box.width),
      true);
  }



  void
  BlockSliding3DProblem::apply_loads()
  {
    body(0).set_body_force(
      Tensor<1, 3>({0., -body(0).material().density * box.gravity, 0.}));
  }



  // @sect3{What a step measures}
  //
  // The mean velocity (MassWeightedMean: M e_d . v / m for the three axes)
  // feeds the rigid-block tracker, and its angle with s while the block
  // slides is followed.
  void
  BlockSliding3DProblem::prepare_run()
  {
    block_mean.reinit(deformable_body());
    tracker = std::make_unique<RigidBlockTracker<3>>(
      Tensor<1, 3>({0., 1., 0.}),
      direction(),
      parameters.time_stepping.time_step);
    tracker->start(initial_velocity());
  }



  void
  BlockSliding3DProblem::measure_step(const StepReport &)
  {
    const Tensor<1, 3> v = block_mean(system().state().velocity.block(0));
    bool               on_plane = false;
    for (const bool a : system().active_set())
      on_plane |= a;
    tracker->record(system().state().time, v, on_plane);
    // The direction of sliding, while the block slides faster than 1 % of
    // v0 (near the stop the mean velocity is the elastic vibration's).
    const double along  = v * direction();
    const double across = v[2] * std::cos(box.phi) - v[0] * std::sin(box.phi);
    if (std::hypot(along, across) > 0.01 * box.speed)
      largest_turn =
        std::max(largest_turn, std::abs(std::atan2(across, along)));
  }



  // @sect3{The report}
  void
  BlockSliding3DProblem::report_motion(std::ostream &out,
                                       JsonObject   &summary) const
  {
    const Tensor<1, 3> v = block_mean(system().state().velocity.block(0));
    out << "  Mass " << block_mean.mass() << " kg; launched at " << box.speed
        << " m/s in the direction phi = " << box.phi << " rad" << std::endl
        << "  Largest angle between the mean sliding velocity and the "
           "launch direction: "
        << format_figure(largest_turn, 1e-6) << " rad" << std::endl
        << "  Mean velocity at the end: " << format_figure(v.norm(), 1e-6)
        << " m/s" << std::endl;
    summary.add("direction", box.phi)
      .add("largest_turn", largest_turn)
      .add("final_speed", v.norm());
  }



  bool
  BlockSliding3DProblem::report_checks(std::ostream &out,
                                       JsonObject   &summary) const
  {
    const RigidSliding rigid(box.speed,
                             0.,
                             box.gravity,
                             friction_coefficient(),
                             parameters.time_stepping.end_time);
    const Tensor<1, 3> u = block_mean(system().state().displacement.block(0));
    JsonObject         sliding;
    const bool         ok =
      tracker->report_sliding(out,
                              rigid,
                              u * direction(),
                              block_mean(system().state().velocity.block(0)) *
                                direction(),
                              parameters.time_stepping.end_time,
                              box.bounds,
                              sliding);
    summary.add("sliding", sliding);
    return ok;
  }
} // namespace BlockSliding3D



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      BlockSliding3D::BlockSliding3DProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
