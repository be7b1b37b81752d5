#include <impactfe/scenes/obstacle_impact_scene.h>

namespace impactfe
{
  template <int dim>
  ObstacleImpactScene<dim>::ObstacleImpactScene(
    const std::string &program_name,
    const std::string &body_name,
    const unsigned int default_contact_boundary_id,
    const std::string &default_plane_point,
    const std::string &default_plane_normal,
    const std::string &default_friction)
    : ContactScene<dim>(program_name)
    , body_name(body_name)
    , default_boundary_id(default_contact_boundary_id)
    , default_point(default_plane_point)
    , default_normal(default_plane_normal)
    , default_mu(default_friction)
  {}



  template <int dim>
  void
  ObstacleImpactScene<dim>::declare_parameters(ParameterHandler &prm)
  {
    declare_scene_parameters(prm);
    MeshParameters::declare_parameters(prm, "Mesh", default_boundary_id);
    ObstacleParameters::declare_parameters(prm,
                                           default_point,
                                           default_normal,
                                           default_mu);
    MaterialParameters::declare_parameters(prm, dim);
  }



  template <int dim>
  void
  ObstacleImpactScene<dim>::parse_parameters(ParameterHandler &prm)
  {
    parse_scene_parameters(prm);
    mesh.parse_parameters(prm, "Mesh");
    obstacle_parameters.parse_parameters(prm, dim);
    material.parse_parameters(prm, dim);
  }



  template <int dim>
  void
  ObstacleImpactScene<dim>::make_bodies()
  {
    ElasticBody<dim> &body =
      this->add_body(body_name, material, out_of_plane_measure());
    if (mesh.from_file())
      mesh.read(body.triangulation(), this->parameter_file());
    else
      make_built_in_mesh(body.triangulation());
  }



  template <int dim>
  bool
  ObstacleImpactScene<dim>::frictional() const
  {
    return obstacle_parameters.friction_coefficient > 0.;
  }



  template <int dim>
  void
  ObstacleImpactScene<dim>::add_contacts(ContactSet &contacts)
  {
    rigid_obstacle = obstacle_parameters.create<dim>(length_scale());
    contacts.add_node_to_obstacle(this->system().bodies(),
                                  0,
                                  mesh.contact_boundary_id,
                                  *rigid_obstacle,
                                  obstacle_parameters.friction_coefficient);
  }



  template <int dim>
  void
  ObstacleImpactScene<dim>::set_initial_state(MechanicalState &state)
  {
    deformable_body().fill_uniform(state.velocity.block(0), initial_velocity());
  }



  template <int dim>
  std::string
  ObstacleImpactScene<dim>::time_unit() const
  {
    return " s";
  }



  template <int dim>
  bool
  ObstacleImpactScene<dim>::report_checks(std::ostream &, JsonObject &) const
  {
    return true;
  }



  // The header, the mesh, the program's lines, the common checks and the
  // program's checks.
  template <int dim>
  bool
  ObstacleImpactScene<dim>::report(std::ostream &out, JsonObject &summary)
  {
    const Triangulation<dim> &tria = deformable_body().triangulation();
    out << this->title() << ", " << this->scheme_description(time_unit())
        << std::endl;
    out << "  Mesh: " << tria.n_active_cells() << " Q1 cells, "
        << tria.n_vertices() << " nodes, "
        << this->system().contacts().n_candidates()
        << " contact candidates; obstacle: " << rigid_obstacle->description();
    if (frictional())
      out << ", mu = " << obstacle_parameters.friction_coefficient;
    out << std::endl;
    summary.add("cells", double(tria.n_active_cells()))
      .add("nodes", double(tria.n_vertices()));
    report_motion(out, summary);
    bool ok = this->print_contact_checks(out);
    ok &= report_checks(out, summary);
    return ok;
  }



  template <int dim>
  const ElasticBody<dim> &
  ObstacleImpactScene<dim>::deformable_body() const
  {
    return this->body(0);
  }



  template <int dim>
  const RigidObstacle<dim> &
  ObstacleImpactScene<dim>::obstacle() const
  {
    return *rigid_obstacle;
  }



  template <int dim>
  double
  ObstacleImpactScene<dim>::friction_coefficient() const
  {
    return obstacle_parameters.friction_coefficient;
  }



  template class ObstacleImpactScene<2>;
  template class ObstacleImpactScene<3>;
} // namespace impactfe
