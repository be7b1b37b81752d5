#ifndef impactfe_scenes_two_bars_scene_h
#define impactfe_scenes_two_bars_scene_h

#include <impactfe/scenes/contact_scene.h>
#include <impactfe/scenes/two_bars_exact.h>

#include <memory>
#include <string>

namespace impactfe
{
  /**
   * Two identical elastic bars along x: bar 1 (body 0) moves at v0 towards
   * bar 2 (body 1), at rest (the paper's section 6.1). The scene measures
   * the contact velocity of bar 1's node at the centre of its contact face
   * and the total contact force against the 1D exact solution
   * (TwoBarsExactSolution, TwoBarsErrors), prints err_v and err_f with the
   * common checks, and writes them to summary.json; history.csv gets
   * `contact_velocity`, `target_contact_velocity` (bar 2's facing node),
   * `exact_contact_velocity` and `exact_normal_force`.
   *
   * With `Geometry/Target = rigid wall` bar 2 is replaced by the rigid
   * wall x = 0 (node-to-plane candidates on bar 1's end), against
   * TwoBarsExactSolution::against_rigid_wall().
   *
   * Subsections `Material` and `Initial conditions`, the entries `Bar
   * length`, `Initial gap` and `Target` of `Geometry`, and the entries
   * `Maximum err_v` and `Maximum err_f` of `Verification` are read here;
   * the program adds its geometry, meshes and contact candidates.
   */
  template <int dim>
  class TwoBarsScene : public ContactScene<dim>
  {
  public:
    explicit TwoBarsScene(const std::string &program_name);

  protected:
    // @sect4{What the program supplies}
    virtual void
    declare_geometry(ParameterHandler &prm) = 0;
    virtual void
    parse_geometry(ParameterHandler &prm) = 0;
    /** Bar 1 on [-L - g0, -g0] along x, bar 2 on [0, L]. */
    virtual void
    make_bar_meshes(Triangulation<dim> &bar_1,
                    Triangulation<dim> &bar_2) const = 0;
    /** The bars' node-to-node (or node-to-segment) candidates. */
    virtual void
    add_bar_contacts(ContactSet &contacts) = 0;
    /** The boundary id of bar 1's end facing bar 2 (or the wall). */
    virtual types::boundary_id
    bar_1_contact_boundary() const;
    /** Thickness (2D) or cross-section (1D) passed to the bodies. */
    virtual double
    out_of_plane_measure() const = 0;
    /** The cross-section A of the bars [m^2]. */
    virtual double
    cross_section() const = 0;
    /** Text after the header's step count (e.g. ", 20 cells per bar"). */
    virtual std::string
    header_details() const;
    /** Lines about the mesh and the waves, after the header. */
    virtual void
    report_geometry(std::ostream &out, JsonObject &summary) const = 0;

    const MaterialParameters &
    material() const;

    /// `Bar length` L and `Initial gap` g0 of subsection `Geometry`, read
    /// here for every dimension [m].
    double bar_length = 0.254, initial_gap = 0.;
    /// `Target = rigid wall`: no bar 2, the wall x = 0.
    bool against_rigid_wall = false;
    const TwoBarsExactSolution &
    exact_solution() const;

  private:
    void
    declare_parameters(ParameterHandler &prm) override;
    void
    parse_parameters(ParameterHandler &prm) override;
    void
    make_bodies() override;
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
    bool
    report(std::ostream &out, JsonObject &summary) override;
    std::vector<std::string>
    plot_columns() const override;

    MaterialParameters             bar_material;
    double                         impact_velocity = 5.13588;
    double                         max_err_v = -1., max_err_f = -1.;
    TwoBarsExactSolution           exact;
    std::unique_ptr<TwoBarsErrors> errors;
    /// x-velocity DoFs of bar 1's node at the centre of the contact face
    /// and of the node of bar 2 nearest to it.
    types::global_dof_index contact_dof_1 = 0, contact_dof_2 = 0;
  };
} // namespace impactfe

#endif
