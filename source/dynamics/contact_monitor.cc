#include <deal.II/base/exceptions.h>

#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace impactfe
{
  namespace
  {
    const char *axis_name[3] = {"x", "y", "z"};
  }



  template <int dim>
  ContactMonitor<dim>::ContactMonitor(const MultibodySystem<dim> &system,
                                      const std::string          &node_file)
    : system(system)
  {
    const auto        &bodies   = system.bodies();
    const unsigned int n_bodies = bodies.size();
    initial_momentum.resize(n_bodies);
    external_force.resize(n_bodies);
    previous_contact_force.assign(n_bodies, Tensor<1, dim>());
    accumulated_impulse.assign(n_bodies, Tensor<1, dim>());
    largest_momentum.assign(n_bodies, 0.);
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        initial_momentum[b] = system.momentum(b);
        largest_momentum[b] = initial_momentum[b].norm();
        // Resultant of the (constant) external load: e_d . F.
        Vector<double> unit(bodies[b]->n_dofs());
        for (unsigned int d = 0; d < dim; ++d)
          {
            Tensor<1, dim> e;
            e[d] = 1.;
            bodies[b]->fill_uniform(unit, e);
            external_force[b][d] = unit * bodies[b]->external_force();
          }
        // Mass-proportional damping acts on rigid motion: its impulse is
        // not a contact or external impulse, so the balance is not checked.
        if (bodies[b]->material().rayleigh_mass > 0.)
          run.impulse_balance_checked = false;
        initial_load_term +=
          bodies[b]->external_force() * system.state().displacement.block(b);
        run.with_loads |= bodies[b]->external_force().linfty_norm() > 0.;
      }
    initial_energy        = total_energy();
    last_energy           = initial_energy;
    largest_stored_energy = system.kinetic_energy() + system.elastic_energy();
    run.energy_scale      = initial_energy;
    run.energy_scale_is_initial = initial_energy > 0.;
    states.assign(system.contacts().n_candidates(), ContactState::open);
    // 1 / (smallest nodal mass of a contact node): an impulse P changes the
    // velocity of its node by about P times this. (Not the diagonal of W,
    // which would make the system compute every Delassus column.)
    double smallest_nodal_mass = std::numeric_limits<double>::max();
    for (const ContactCandidate &c : system.contacts().candidates())
      {
        const ElasticBody<dim>     &body = *bodies[c.body_a];
        const SparseMatrix<double> &M    = body.mass_matrix();
        const auto                  row  = body.vertex_dof(c.vertex_a, 0);
        double                      mass = 0.;
        for (auto entry = M.begin(row); entry != M.end(row); ++entry)
          mass += std::abs(entry->value());
        // A massless node (mass redistribution) moves with the body
        // around it, whose velocities are in the scale anyway.
        if (mass > 0.)
          smallest_nodal_mass = std::min(smallest_nodal_mass, mass);
      }
    if (smallest_nodal_mass < std::numeric_limits<double>::max())
      largest_inverse_nodal_mass = 1. / smallest_nodal_mass;

    if (!node_file.empty())
      {
        node_file_name = node_file;
        node_output    = std::make_unique<std::ofstream>(node_file);
        AssertThrow(*node_output,
                    ExcMessage("Output: cannot write " + node_file));
        *node_output << "time,candidate";
        for (unsigned int d = 0; d < dim; ++d)
          *node_output << "," << axis_name[d];
        *node_output << ",normal_force,tangential_force,gap,normal_velocity,"
                        "tangential_velocity,state\n";
        *node_output << std::setprecision(10);
      }
  }



  template <int dim>
  std::vector<std::string>
  ContactMonitor<dim>::history_columns() const
  {
    std::vector<std::string> columns = {"time",
                                        "normal_force",
                                        "tangential_force"};
    for (unsigned int d = 0; d < dim; ++d)
      columns.push_back(std::string("force_") + axis_name[d]);
    for (unsigned int d = 0; d < dim; ++d)
      columns.push_back(std::string("momentum_") + axis_name[d]);
    for (const std::string name : {"kinetic_energy",
                                   "elastic_energy",
                                   "min_gap",
                                   "active_contacts",
                                   "sticking",
                                   "sliding",
                                   "lcp_size",
                                   "lcp_pivots"})
      columns.push_back(name);
    if (system.bodies().size() > 1)
      for (const auto *body : system.bodies())
        {
          for (unsigned int d = 0; d < dim; ++d)
            columns.push_back(body->name() + "_force_" + axis_name[d]);
          for (unsigned int d = 0; d < dim; ++d)
            columns.push_back(body->name() + "_momentum_" + axis_name[d]);
        }
    return columns;
  }



  template <int dim>
  double
  ContactMonitor<dim>::total_energy() const
  {
    double load_term = -initial_load_term;
    for (unsigned int b = 0; b < system.bodies().size(); ++b)
      load_term += system.bodies()[b]->external_force() *
                   system.state().displacement.block(b);
    return system.kinetic_energy() + system.elastic_energy() - load_term;
  }



  template <int dim>
  Tensor<1, dim>
  ContactMonitor<dim>::total_contact_force() const
  {
    Tensor<1, dim> f;
    for (unsigned int b = 0; b < system.bodies().size(); ++b)
      f += system.contact_force(b);
    return f;
  }

  template <int dim>
  Tensor<1, dim>
  ContactMonitor<dim>::total_momentum() const
  {
    Tensor<1, dim> p;
    for (unsigned int b = 0; b < system.bodies().size(); ++b)
      p += system.momentum(b);
    return p;
  }



  template <int dim>
  std::vector<double>
  ContactMonitor<dim>::history_values(const StepReport &report) const
  {
    std::vector<double>  values = {system.state().time,
                                   report.normal_force,
                                   report.tangential_force};
    const Tensor<1, dim> f = total_contact_force(), p = total_momentum();
    for (unsigned int d = 0; d < dim; ++d)
      values.push_back(f[d]);
    for (unsigned int d = 0; d < dim; ++d)
      values.push_back(p[d]);
    std::vector<double> g;
    system.contacts().gaps(system.state().displacement, g);
    unsigned int sticking = 0, sliding = 0;
    for (const ContactState s : states)
      {
        sticking += s == ContactState::stick ? 1 : 0;
        sliding += is_sliding(s) ? 1 : 0;
      }
    values.push_back(system.kinetic_energy());
    values.push_back(system.elastic_energy());
    values.push_back(g.empty() ? 0. : *std::min_element(g.begin(), g.end()));
    values.push_back(report.active_contacts);
    values.push_back(sticking);
    values.push_back(sliding);
    values.push_back(report.lcp_size);
    values.push_back(report.lcp_pivots);
    if (system.bodies().size() > 1)
      for (unsigned int b = 0; b < system.bodies().size(); ++b)
        {
          const Tensor<1, dim> fb = system.contact_force(b),
                               pb = system.momentum(b);
          for (unsigned int d = 0; d < dim; ++d)
            values.push_back(fb[d]);
          for (unsigned int d = 0; d < dim; ++d)
            values.push_back(pb[d]);
        }
    return values;
  }



  // @sect3{The checks of one step}
  template <int dim>
  void
  ContactMonitor<dim>::record(const StepReport &report)
  {
    const TimeIntegrator &scheme   = system.integrator();
    const double          h        = report.time_step;
    const double          w        = scheme.contact_force_weight();
    const ContactSet     &contacts = system.contacts();
    const unsigned int    nd       = contacts.n_directions();
    const double          t        = system.state().time;
    ++run.n_steps;
    if (report.n_substeps > 1)
      ++run.free_flight_steps;
    run.exact_cone_solves        = system.exact_cone_statistics().solves;
    run.exact_cone_not_converged = system.exact_cone_statistics().not_converged;
    run.exact_cone_tolerance =
      system.contact_solver_parameters().exact_cone_tolerance;
    run.active_set_solves     = system.active_set_statistics().solves;
    run.active_set_iterations = system.active_set_statistics().iterations;
    run.active_set_fallbacks  = system.active_set_statistics().fallbacks;
    run.active_set_dense_schur_complement =
      system.active_set_statistics().dense_schur_complement;
    run.active_set_exact_normal_rows =
      system.active_set_statistics().state_factorizations > 0;

    // Impulse balance, body by body.
    for (unsigned int b = 0; b < system.bodies().size(); ++b)
      {
        const Tensor<1, dim> f = system.contact_force(b);
        accumulated_impulse[b] +=
          h * (w * f + (1. - w) * previous_contact_force[b]) +
          h * external_force[b];
        previous_contact_force[b] = f;
        const Tensor<1, dim> p    = system.momentum(b);
        largest_momentum[b]       = std::max(largest_momentum[b], p.norm());
        const double scale =
          std::max(largest_momentum[b], std::numeric_limits<double>::min());
        const Tensor<1, dim> residual =
          p - initial_momentum[b] - accumulated_impulse[b];
        for (unsigned int d = 0; d < dim; ++d)
          run.impulse_balance_error =
            std::max(run.impulse_balance_error, std::abs(residual[d]) / scale);
      }

    // Signorini.
    contacts.gaps(system.state().displacement, gaps);
    for (const double g : gaps)
      run.max_penetration = std::max(run.max_penetration, -g);
    run.largest_slide_off =
      std::max(run.largest_slide_off,
               contacts.largest_slide_off(system.state().displacement));

    // Coulomb, with V_T^{i+1} from the new velocity.
    contacts.local_velocities(system.state().velocity, local_velocity);
    const std::vector<double> &P            = system.impulses();
    const double               force_factor = scheme.force_per_impulse();
    for (unsigned int c = 0; c < contacts.n_candidates(); ++c)
      {
        impulse_scale = std::max(impulse_scale, P[c * nd]);
        for (unsigned int k = 0; k < nd; ++k)
          velocity_scale =
            std::max(velocity_scale, std::abs(local_velocity[c * nd + k]));
      }
    // A node is sliding if |V_T| is more than round-off of the velocities
    // of the run: those of the contact nodes, of the bodies, and the
    // velocity that the largest impulse gives a contact node. (The contact
    // nodes of a body resting on a plane never move: their velocities alone
    // would be a scale of round-off itself, and every sticking node would
    // count as sliding.)
    velocity_scale                  = std::max({velocity_scale,
                                                system.state().velocity.linfty_norm(),
                                                largest_inverse_nodal_mass * impulse_scale});
    const double impulse_tolerance  = 1e-9 * impulse_scale;
    const double velocity_tolerance = 1e-8 * velocity_scale;
    // A sliding node has |P_T| = mu P_N on the circular cone; on the
    // polygonal one (3D, `Friction cone = facets`) only cos(pi/k) of it
    // where it slides along an edge.
    const ContactSolverParameters &solver = system.contact_solver_parameters();
    const double                   sliding_share =
      nd == 3 && solver.friction_cone == lcp::ConeModel::facets ?
                          std::cos(std::acos(-1.) / solver.n_facets) :
                          1.;
    for (unsigned int c = 0; c < contacts.n_candidates(); ++c)
      {
        const double mu  = contacts.candidate(c).friction_coefficient;
        const double p_n = P[c * nd];
        double       p_t = 0., v_t = 0., p_dot_v = 0.;
        for (unsigned int k = 1; k < nd; ++k)
          {
            p_t += P[c * nd + k] * P[c * nd + k];
            v_t += local_velocity[c * nd + k] * local_velocity[c * nd + k];
            p_dot_v += P[c * nd + k] * local_velocity[c * nd + k];
          }
        p_t = std::sqrt(p_t);
        v_t = std::sqrt(v_t);
        if (impulse_scale > 0.)
          run.coulomb_excess =
            std::max(run.coulomb_excess, (p_t - mu * p_n) / impulse_scale);

        ContactState s = ContactState::open;
        if (p_n > impulse_tolerance)
          {
            // Frictionless candidates carry no tangential unknown: they
            // slide freely.
            const bool backwards = nd > 1 && local_velocity[c * nd + 1] < 0.;
            s                    = (nd == 1 || v_t > velocity_tolerance) ?
                                     (backwards ? ContactState::slip_negative :
                                                  ContactState::slip_positive) :
                                     ContactState::stick;
            if (nd > 1 && is_sliding(s) &&
                (p_dot_v > impulse_tolerance * v_t ||
                 p_t < sliding_share * mu * p_n - impulse_tolerance))
              ++run.wrong_slip_count;
          }
        if (contact_mode(s) != contact_mode(states[c]))
          ++run.state_changes;
        states[c] = s;

        if (node_output)
          {
            // Signed tangential values in 2D (along t = n turned by +90
            // degrees); magnitudes in 3D.
            const double signed_p_t = nd == 2 ? P[c * nd + 1] : p_t;
            const double signed_v_t =
              nd == 2 ? local_velocity[c * nd + 1] : v_t;
            node_line.clear();
            append_csv_number(node_line, t, ',');
            append_csv_number(node_line, c, ',');
            for (unsigned int d = 0; d < dim; ++d)
              append_csv_number(node_line,
                                contacts.candidate(c).position[d],
                                ',');
            for (const double x : {force_factor * p_n,
                                   force_factor * signed_p_t,
                                   gaps[c],
                                   local_velocity[c * nd],
                                   signed_v_t})
              append_csv_number(node_line, x, ',');
            append_csv_number(node_line, contact_mode(s), '\n');
            node_output->write(node_line.data(), node_line.size());
            AssertThrow(*node_output,
                        ExcMessage("Output: writing " + node_file_name +
                                   " failed (disk full or an I/O error)."));
          }
      }

    // Energy, relative to the initial energy, or to the largest kinetic
    // plus elastic energy so far when the scene starts at rest.
    const double energy = total_energy();
    largest_increase    = std::max(largest_increase, energy - last_energy);
    largest_stored_energy =
      std::max(largest_stored_energy,
               system.kinetic_energy() + system.elastic_energy());
    if (!run.energy_scale_is_initial)
      run.energy_scale = largest_stored_energy;
    if (run.energy_scale > 0.)
      {
        run.max_energy_increase = largest_increase / run.energy_scale;
        run.energy_ratio        = run.energy_scale_is_initial ?
                                    energy / initial_energy :
                                    1. + (energy - initial_energy) / run.energy_scale;
      }
    last_energy = energy;

    // Forces.
    if (report.normal_force > 0.)
      {
        if (run.first_contact < 0.)
          run.first_contact = t;
        run.last_contact = t;
      }
    run.peak_normal_force =
      std::max(run.peak_normal_force, report.normal_force);
    run.normal_impulse += h * report.normal_force;
    run.tangential_impulse += h * report.tangential_force;
  }



  template <int dim>
  ContactState
  ContactMonitor<dim>::state(const unsigned int c) const
  {
    return states[c];
  }

  template <int dim>
  const ContactRunSummary &
  ContactMonitor<dim>::summary() const
  {
    return run;
  }

  void
  ContactVerificationParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    prm.declare_entry("Maximum impulse balance error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if |p(T) - p(0) - sum of impulses| / max "
                      "|p| exceeds this for a body and component [-]. -1: no "
                      "check.");
    prm.declare_entry("Maximum penetration",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if a node's gap goes below minus this "
                      "[m]. -1: no check.");
    prm.declare_entry("Maximum Coulomb excess",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if (|P_T| - mu P_N) / max P_N exceeds "
                      "this at a node [-]. -1: no check.");
    prm.declare_entry("Maximum energy increase",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the energy (kinetic plus elastic, "
                      "minus the work of the loads if there are any) grows "
                      "by more than this fraction of the initial energy in "
                      "one step [-]; a scene that starts at rest takes the "
                      "largest kinetic plus elastic energy instead. -1: no "
                      "check.");
    prm.declare_entry("Minimum energy ratio",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if final/initial energy is below this "
                      "[-] (a scene that starts at rest: 1 + (final - "
                      "initial) / largest kinetic plus elastic energy). -1: "
                      "no check.");
    prm.declare_entry("Maximum energy ratio",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if final/initial energy exceeds this "
                      "[-] (a scene that starts at rest: 1 + (final - "
                      "initial) / largest kinetic plus elastic energy). -1: "
                      "no check.");
    prm.leave_subsection();
  }



  void
  ContactVerificationParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    max_impulse_balance_error =
      get_verification_bound(prm, "Maximum impulse balance error");
    max_penetration    = get_verification_bound(prm, "Maximum penetration");
    max_coulomb_excess = get_verification_bound(prm, "Maximum Coulomb excess");
    max_energy_increase =
      get_verification_bound(prm, "Maximum energy increase");
    min_energy_ratio = get_verification_bound(prm, "Minimum energy ratio");
    max_energy_ratio = get_verification_bound(prm, "Maximum energy ratio");
    prm.leave_subsection();
  }



  bool
  print_check(std::ostream      &out,
              const std::string &what,
              const double       value,
              const std::string &relation,
              const double       bound)
  {
    if (bound < 0.)
      return true;
    const bool ok = relation == "<=" ? value <= bound : value >= bound;
    // The bound as the user wrote it (up to 12 digits), e.g. 1.000000001.
    std::ostringstream bound_text;
    bound_text << std::setprecision(12) << bound;
    out << "  Check " << what << " " << relation << " " << bound_text.str()
        << ": " << (ok ? "OK" : "FAILED");
    // The value, which the summary may have printed rounded ("< 1e-12").
    if (!ok)
      {
        std::ostringstream value_text; // out's precision stays the caller's
        value_text << std::setprecision(3) << value;
        out << " (" << value_text.str() << ")";
      }
    out << std::endl;
    return ok;
  }



  bool
  check_figures_are_numbers(
    std::ostream                                      &out,
    const std::vector<std::pair<std::string, double>> &figures)
  {
    bool ok = true;
    for (const auto &[what, value] : figures)
      if (!std::isfinite(value))
        {
          out << "  Check " << what << " is a number: FAILED (" << value << ")"
              << std::endl;
          ok = false;
        }
    return ok;
  }



  bool
  print_contact_summary(std::ostream                        &out,
                        const ContactRunSummary             &s,
                        const ContactVerificationParameters &bounds,
                        const bool                           frictional)
  {
    // Quantities at round-off level are printed as such, so that the
    // output does not depend on the last bits.
    const auto small = [](const double x) {
      std::ostringstream text;
      if (std::abs(x) < 1e-12)
        text << "< 1e-12";
      else
        text << std::setprecision(3) << x;
      return text.str();
    };
    if (s.first_contact < 0.)
      out << "  No contact force during the run" << std::endl;
    else
      out << "  Contact force > 0 from t = " << s.first_contact
          << " to t = " << s.last_contact << ", peak total normal force "
          << s.peak_normal_force << std::endl;
    out << "  Normal impulse " << s.normal_impulse;
    if (frictional)
      out << ", tangential impulse " << s.tangential_impulse;
    out << std::endl;
    if (s.impulse_balance_checked)
      out << "  Impulse balance: max |p(T) - p(0) - impulses| / max |p| = "
          << small(s.impulse_balance_error) << std::endl;
    else
      out << "  Impulse balance: not checked (mass-proportional damping acts "
             "on the momentum)"
          << std::endl;
    out << "  Signorini: largest penetration " << small(s.max_penetration)
        << std::endl;
    // the pairs of t = 0 hold a node past the end of the other body's
    // contact boundary on that boundary extended: never silently
    std::ostringstream slide; // two digits: a warning, not a result
    slide << std::setprecision(2) << s.largest_slide_off;
    if (s.largest_slide_off > 0.01)
      out << "  Warning: nodes slid off the other body's contact boundary "
             "by up to "
          << slide.str()
          << " of its length; the pairs of t = 0 hold them on that boundary "
             "extended (small sliding)."
          << std::endl;
    if (frictional)
      out << "  Coulomb: max (|P_T| - mu P_N) / max P_N = "
          << small(s.coulomb_excess) << ", sliding nodes with a wrong "
          << "friction force: " << s.wrong_slip_count << std::endl;
    // Without loads the energy is kinetic plus elastic and the line reads
    // as it always did.
    const std::string reference = s.energy_scale_is_initial ?
                                    "the initial energy" :
                                    "the largest kinetic + elastic energy";
    if (s.with_loads)
      out << "  Energy (kinetic + elastic - work of the loads): ";
    else
      out << "  Energy: ";
    if (s.energy_scale_is_initial)
      out << "final / initial = " << s.energy_ratio;
    else
      out << "0 at t = 0; (final - initial) / (" << reference
          << ") = " << small(s.energy_ratio - 1.);
    out << ", largest increase in a step = " << small(s.max_energy_increase)
        << " of " << reference << std::endl;
    out << "  Contact state changes (open/stick/slip): " << s.state_changes
        << " in " << s.n_steps << " steps" << std::endl;
    if (s.free_flight_steps > 0)
      out << "  Free-flight steps (k h, no contact possible): "
          << s.free_flight_steps << " of the " << s.n_steps << std::endl;
    if (s.active_set_solves > 0)
      out << "  Active set method: " << s.active_set_solves
          << " contact problems, "
          << s.active_set_solves - s.active_set_fallbacks
          << " solved and verified, " << s.active_set_fallbacks
          << " fell back to Lemke's method"
          << (s.active_set_dense_schur_complement ?
                "; W x by the dense Schur complement of M~" :
                "")
          << (s.active_set_exact_normal_rows ?
                "; normal rows preconditioned exactly at the contact states" :
                "")
          << std::endl;
    bool ok = true;
    if (s.exact_cone_solves > 0)
      {
        out << "  Exact cone: " << s.exact_cone_solves << " contact problems, "
            << s.exact_cone_not_converged << " of them above the tolerance "
            << s.exact_cone_tolerance << " of the circular cone's residual"
            << std::endl;
        ok = print_check(out,
                         "problems above the exact-cone tolerance",
                         s.exact_cone_not_converged,
                         "<=",
                         0.);
      }
    return check_contact_bounds(out, s, bounds, frictional) && ok;
  }



  bool
  check_contact_bounds(std::ostream                        &out,
                       const ContactRunSummary             &s,
                       const ContactVerificationParameters &bounds,
                       const bool                           frictional)
  {
    std::vector<std::pair<std::string, double>> figures = {
      {"penetration", s.max_penetration},
      {"energy increase in a step", s.max_energy_increase},
      {"energy ratio", s.energy_ratio}};
    if (s.impulse_balance_checked)
      figures.emplace_back("impulse balance error", s.impulse_balance_error);
    if (frictional)
      figures.emplace_back("Coulomb excess", s.coulomb_excess);
    bool ok = check_figures_are_numbers(out, figures);
    if (s.impulse_balance_checked)
      ok &= print_check(out,
                        "impulse balance error",
                        s.impulse_balance_error,
                        "<=",
                        bounds.max_impulse_balance_error);
    ok &= print_check(
      out, "penetration", s.max_penetration, "<=", bounds.max_penetration);
    if (frictional)
      {
        ok &= print_check(out,
                          "Coulomb excess",
                          s.coulomb_excess,
                          "<=",
                          bounds.max_coulomb_excess);
        if (s.wrong_slip_count > 0)
          {
            out << "  Check sliding nodes have P_T = -mu P_N V_T/|V_T|: "
                   "FAILED"
                << std::endl;
            ok = false;
          }
      }
    ok &= print_check(out,
                      "energy increase in a step",
                      s.max_energy_increase,
                      "<=",
                      bounds.max_energy_increase);
    ok &= print_check(
      out, "energy ratio", s.energy_ratio, ">=", bounds.min_energy_ratio);
    ok &= print_check(
      out, "energy ratio", s.energy_ratio, "<=", bounds.max_energy_ratio);
    return ok;
  }



  template <int dim>
  void
  ContactMonitor<dim>::close_node_file()
  {
    if (!node_output)
      return;
    node_output->close();
    AssertThrow(!node_output->fail(),
                ExcMessage("Output: writing " + node_file_name +
                           " failed (disk full or an I/O error)."));
    node_output.reset();
  }



  template class ContactMonitor<1>;
  template class ContactMonitor<2>;
  template class ContactMonitor<3>;
} // namespace impactfe
