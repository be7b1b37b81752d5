#ifndef impactfe_scenes_block_on_plane_scene_h
#define impactfe_scenes_block_on_plane_scene_h

#include <impactfe/contact/rigid_obstacle.h>
#include <impactfe/dynamics/stability_monitor.h>
#include <impactfe/scenes/contact_scene.h>
#include <impactfe/scenes/rigid_block.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  /**
   * One or two elastic blocks on a rigid plane (or inclined plane, ball,
   * level set) under gravity and a push, with Coulomb friction: the scene
   * of the stability study (programs/block_on_plane, tests/stability).
   *
   * Block 1 is built in the frame of the plane (its lower side parallel to
   * it, at the `Initial gap`); block 2 (`Body 2`, off by default), of its
   * own material (`Material of body 2`), lies above it and can fall on it
   * (node-to-segment candidates). Subsections `Geometry`, `Initial
   * conditions`, `Loads`, `Body 2`, `Obstacle`, the materials and the
   * stability bounds of `Verification` are read here. Each step the scene
   * feeds a StabilityMonitor (chattering, final phase, round-off) and a
   * RigidBlockTracker (first impact, stop time); a program reports them
   * against its references.
   */
  class BlockOnPlaneScene : public ContactScene<2>
  {
  public:
    explicit BlockOnPlaneScene(const std::string &program_name);

  protected:
    void
    declare_parameters(ParameterHandler &prm) override;
    void
    parse_parameters(ParameterHandler &prm) override;
    void
    make_bodies() override;
    void
    apply_loads() override;
    bool
    frictional() const override;
    void
    add_contacts(ContactSet &contacts) override;
    void
    set_initial_state(MechanicalState &state) override;
    void
    prepare_run() override;
    std::vector<std::string>
    history_columns() const override;
    std::vector<double>
    history_values(const StepReport &report) override;
    void
    measure_step(const StepReport &report) override;

    /** Mean velocity of block 1 (momentum / mass). */
    Tensor<1, 2>
    mean_velocity() const;
    /** Mean displacement of block 1. */
    Tensor<1, 2>
    mean_displacement() const;
    double
    top_sinking() const;
    double
    normal_load() const;

    // The block (body 1): `Geometry` and `Initial conditions`.
    BlockParameters block;
    double          thickness = 0.01, initial_gap = 0.;
    Tensor<1, 2>    velocity;
    // `Loads`: gravity on both blocks, the push on the first one.
    Tensor<1, 2> gravity, push;
    // `Body 2`: the optional second block, centred above the first. Its
    // lower nodes are node-to-segment candidates against the first
    // block's upper side.
    bool               body_2 = false;
    BlockParameters    block_2;
    double             gap_2 = 0.01, mu_2 = 0.;
    Tensor<1, 2>       velocity_2;
    ObstacleParameters obstacle_parameters;
    MaterialParameters material, material_2;
    StabilityBounds    bounds;
    bool               print_figures = true;

    std::unique_ptr<RigidObstacle<2>>    obstacle;
    std::unique_ptr<StabilityMonitor<2>> stability;
    // The plane's frame: unit normal n (towards the block) and tangent t
    // (n turned by -90 degrees: +x for a horizontal plane).
    Tensor<1, 2> normal, tangent;
    // Candidates [0, n_plane_candidates) are against the obstacle, the
    // others between the blocks.
    unsigned int              n_plane_candidates = 0;
    std::vector<unsigned int> top_vertices;
    // M e_x and M e_y of block 1, for its mean velocity and displacement.
    MassWeightedMean<2>                   block_mean;
    double                                mass_1 = 0., total_mass = 0.;
    std::unique_ptr<RigidBlockTracker<2>> tracker;
  };
} // namespace impactfe

#endif
