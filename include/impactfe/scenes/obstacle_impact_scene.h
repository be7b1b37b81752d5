#ifndef impactfe_scenes_obstacle_impact_scene_h
#define impactfe_scenes_obstacle_impact_scene_h

#include <impactfe/bodies/mesh_input.h>
#include <impactfe/contact/rigid_obstacle.h>
#include <impactfe/scenes/contact_scene.h>

#include <memory>
#include <string>

namespace impactfe
{
  /**
   * One deformable body, from a mesh file or the program's built-in
   * geometry, thrown with a uniform velocity at a rigid obstacle (plane,
   * ball or level set, with Coulomb friction): the scene of the paper's
   * cylinder (section 6.2) and oblique plate (section 6.3).
   *
   * Subsections `Mesh` (file and contact boundary id), `Obstacle` and
   * `Material` are read here; the program adds its geometry and initial
   * velocity, and what it checks beyond the common checks.
   */
  template <int dim>
  class ObstacleImpactScene : public ContactScene<dim>
  {
  public:
    /**
     * @p body_name names the body in files and messages. The defaults are
     * the program's: the contact boundary id of its built-in mesh, and its
     * obstacle plane and friction coefficient (comma-separated).
     */
    ObstacleImpactScene(const std::string &program_name,
                        const std::string &body_name,
                        const unsigned int default_contact_boundary_id,
                        const std::string &default_plane_point,
                        const std::string &default_plane_normal,
                        const std::string &default_friction);

  protected:
    // @sect4{What the program supplies}

    /** The program's subsections (Geometry, Initial conditions, ...). */
    virtual void
    declare_scene_parameters(ParameterHandler &prm) = 0;
    virtual void
    parse_scene_parameters(ParameterHandler &prm) = 0;
    /** The built-in mesh, used when `Mesh file` is empty. */
    virtual void
    make_built_in_mesh(Triangulation<dim> &triangulation) const = 0;
    /** Out-of-plane thickness (2D) or cross-section (1D) [m or m^2]. */
    virtual double
    out_of_plane_measure() const = 0;
    /** Length of the body, for the obstacle's finite differences [m]. */
    virtual double
    length_scale() const = 0;
    virtual Tensor<1, dim>
    initial_velocity() const = 0;
    /** Unit of time in the report (" s", or "" for scaled data). */
    virtual std::string
    time_unit() const;
    /**
     * Lines after the mesh line (mass, momentum, impulses, ...) and the
     * program's entries of summary.json.
     */
    virtual void
    report_motion(std::ostream &out, JsonObject &summary) const = 0;
    /** The program's own checks, after the common ones. */
    virtual bool
    report_checks(std::ostream &out, JsonObject &summary) const;

    // @sect4{What the scene offers the program}
    const ElasticBody<dim> &
    deformable_body() const;
    const RigidObstacle<dim> &
    obstacle() const;
    double
    friction_coefficient() const;

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
    bool
    report(std::ostream &out, JsonObject &summary) override;

    std::string        body_name;
    unsigned int       default_boundary_id;
    std::string        default_point, default_normal, default_mu;
    MeshParameters     mesh;
    ObstacleParameters obstacle_parameters;
    MaterialParameters material;
    std::unique_ptr<RigidObstacle<dim>> rigid_obstacle;
  };
} // namespace impactfe

#endif
