#include <impactfe/scenes/two_bars_scene.h>
#include <impactfe/utilities/program.h>

namespace impactfe
{
  template <int dim>
  TwoBarsScene<dim>::TwoBarsScene(const std::string &program_name)
    : ContactScene<dim>(program_name)
  {}



  template <int dim>
  void
  TwoBarsScene<dim>::declare_parameters(ParameterHandler &prm)
  {
    declare_geometry(prm);
    prm.enter_subsection("Geometry");
    prm.declare_entry("Bar length",
                      "0.254",
                      Patterns::Double(),
                      "Length L of each bar [m]. Must be > 0.");
    prm.declare_entry("Initial gap",
                      "0",
                      Patterns::Double(),
                      "Distance between the bars at t = 0 [m]. Must be >= 0.");
    prm.declare_entry("Target",
                      "bar",
                      Patterns::Selection("bar|rigid wall"),
                      "What bar 1 hits: 'bar', bar 2 (at rest on [0, L]), "
                      "or 'rigid wall', a rigid frictionless wall at x = 0.");
    prm.leave_subsection();
    MaterialParameters::declare_parameters(prm, dim);
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Impact velocity",
                      "5.13588",
                      Patterns::Double(),
                      "Velocity v0 of bar 1 towards bar 2 at t = 0 [m/s]. "
                      "Must be > 0.");
    prm.leave_subsection();
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum err_v",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if err_v against the 1D exact solution "
                      "exceeds this [-]. -1: no check.");
    prm.declare_entry("Maximum err_f",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if err_f against the 1D exact solution "
                      "exceeds this [-]. -1: no check.");
    prm.leave_subsection();
  }



  template <int dim>
  void
  TwoBarsScene<dim>::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    bar_length         = prm.get_double("Bar length");
    initial_gap        = prm.get_double("Initial gap");
    against_rigid_wall = prm.get("Target") == "rigid wall";
    prm.leave_subsection();
    require_positive(bar_length, "Geometry", "Bar length");
    require_non_negative(initial_gap, "Geometry", "Initial gap");
    parse_geometry(prm);
    bar_material.parse_parameters(prm, dim);
    prm.enter_subsection("Initial conditions");
    impact_velocity = prm.get_double("Impact velocity");
    prm.leave_subsection();
    AssertThrow(impact_velocity > 0.,
                ExcMessage("Initial conditions: 'Impact velocity' must be > "
                           "0, got " +
                           format_number(impact_velocity) + "."));
    prm.enter_subsection("Verification");
    max_err_v = get_verification_bound(prm, "Maximum err_v");
    max_err_f = get_verification_bound(prm, "Maximum err_f");
    prm.leave_subsection();
  }



  template <int dim>
  void
  TwoBarsScene<dim>::make_bodies()
  {
    ElasticBody<dim> &bar_1 =
      this->add_body("bar_1", bar_material, out_of_plane_measure());
    if (against_rigid_wall)
      {
        Triangulation<dim> unused_bar_2;
        make_bar_meshes(bar_1.triangulation(), unused_bar_2);
        return;
      }
    ElasticBody<dim> &bar_2 =
      this->add_body("bar_2", bar_material, out_of_plane_measure());
    make_bar_meshes(bar_1.triangulation(), bar_2.triangulation());
  }



  // Against the wall: node-to-plane candidates on bar 1's end, the normal
  // along -x (towards the bar).
  template <int dim>
  void
  TwoBarsScene<dim>::add_contacts(ContactSet &contacts)
  {
    if (!against_rigid_wall)
      {
        add_bar_contacts(contacts);
        return;
      }
    Tensor<1, dim> normal;
    normal[0] = -1.;
    contacts.add_node_to_plane(this->system().bodies(),
                               0,
                               bar_1_contact_boundary(),
                               Point<dim>(),
                               normal);
  }



  template <int dim>
  types::boundary_id
  TwoBarsScene<dim>::bar_1_contact_boundary() const
  {
    return 1;
  }



  template <int dim>
  bool
  TwoBarsScene<dim>::frictional() const
  {
    return false;
  }



  template <int dim>
  void
  TwoBarsScene<dim>::set_initial_state(MechanicalState &state)
  {
    Tensor<1, dim> v0;
    v0[0] = impact_velocity;
    this->body(0).fill_uniform(state.velocity.block(0), v0);
  }



  // The exact solution with the bar speed c = sqrt(E/rho), and the nodes
  // whose velocities are measured: the candidate nearest to the centre of
  // the candidates (bar 1's side), and bar 2's vertex nearest to it.
  template <int dim>
  void
  TwoBarsScene<dim>::prepare_run()
  {
    const double c =
      std::sqrt(bar_material.youngs_modulus / bar_material.density);
    exact  = against_rigid_wall ?
               TwoBarsExactSolution::against_rigid_wall(impact_velocity,
                                                       initial_gap,
                                                       bar_length,
                                                       c,
                                                       bar_material.density,
                                                       cross_section()) :
               TwoBarsExactSolution(impact_velocity,
                                   initial_gap,
                                   bar_length,
                                   c,
                                   bar_material.density,
                                   cross_section());
    errors = std::make_unique<TwoBarsErrors>(exact);

    const auto &candidates = this->system().contacts().candidates();
    AssertThrow(!candidates.empty(),
                ExcMessage("Contact: the bars have no contact candidate."));
    Point<dim> centre;
    for (const auto &c : candidates)
      for (unsigned int d = 0; d < dim; ++d)
        centre[d] += c.position[d] / candidates.size();
    const auto position = [](const ContactCandidate &c) {
      Point<dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = c.position[d];
      return p;
    };
    const ContactCandidate *nearest = &candidates[0];
    for (const auto &c : candidates)
      if (position(c).distance(centre) < position(*nearest).distance(centre))
        nearest = &c;
    contact_dof_1 = this->body(0).vertex_dof(nearest->vertex_a, 0);
    if (against_rigid_wall)
      return;

    const auto  &vertices_2 = this->body(1).triangulation().get_vertices();
    unsigned int facing     = 0;
    for (unsigned int v = 0; v < vertices_2.size(); ++v)
      if (vertices_2[v].distance(position(*nearest)) <
          vertices_2[facing].distance(position(*nearest)))
        facing = v;
    contact_dof_2 = this->body(1).vertex_dof(facing, 0);
  }



  template <int dim>
  std::vector<std::string>
  TwoBarsScene<dim>::history_columns() const
  {
    return {"contact_velocity",
            "target_contact_velocity",
            "exact_contact_velocity",
            "exact_normal_force"};
  }



  template <int dim>
  std::vector<double>
  TwoBarsScene<dim>::history_values(const StepReport &)
  {
    const MechanicalState &state = this->system().state();
    return {state.velocity.block(0)(contact_dof_1),
            against_rigid_wall ? 0. : state.velocity.block(1)(contact_dof_2),
            exact.contact_velocity(state.time),
            exact.normal_force(state.time)};
  }



  template <int dim>
  void
  TwoBarsScene<dim>::measure_step(const StepReport &report)
  {
    errors->add(report.time,
                this->system().state().velocity.block(0)(contact_dof_1),
                report.normal_force,
                report.n_substeps);
  }



  template <int dim>
  std::string
  TwoBarsScene<dim>::header_details() const
  {
    return "";
  }



  template <int dim>
  bool
  TwoBarsScene<dim>::report(std::ostream &out, JsonObject &summary)
  {
    out << this->title() << ", " << this->scheme_description(" s")
        << header_details() << std::endl;
    report_geometry(out, summary);
    if (against_rigid_wall)
      out << "  Target: a rigid frictionless wall at x = 0" << std::endl;
    out << "  Exact solution (1D): contact from t = " << exact.t_contact
        << " s to " << exact.t_contact + exact.duration << " s, contact force "
        << exact.contact_force << " N" << std::endl;
    out << "  Against it: err_v = " << errors->err_v()
        << ", err_f = " << errors->err_f() << std::endl;
    bool ok = this->print_contact_checks(out);
    ok &= print_check(out, "err_v", errors->err_v(), "<=", max_err_v);
    ok &= print_check(out, "err_f", errors->err_f(), "<=", max_err_f);
    summary.add("err_v", errors->err_v()).add("err_f", errors->err_f());
    return ok;
  }



  template <int dim>
  std::vector<std::string>
  TwoBarsScene<dim>::plot_columns() const
  {
    return {"contact_velocity", "normal_force"};
  }



  template <int dim>
  const MaterialParameters &
  TwoBarsScene<dim>::material() const
  {
    return bar_material;
  }



  template <int dim>
  const TwoBarsExactSolution &
  TwoBarsScene<dim>::exact_solution() const
  {
    return exact;
  }



  template class TwoBarsScene<1>;
  template class TwoBarsScene<2>;
  template class TwoBarsScene<3>;
} // namespace impactfe
