#include <impactfe/dynamics/stability_monitor.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace impactfe
{
  void
  StabilityBounds::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    prm.declare_entry("Start of the final phase",
                      "-1",
                      Patterns::Double(),
                      "Time from which the run counts as its final phase "
                      "(at rest, or in a steady regime), where the gap "
                      "drift, the penetration, the active-set changes and "
                      "the mean reaction are measured [s]. -1: half the "
                      "end time.");
    prm.declare_entry("Maximum gap drift",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the mean gap of the plane's "
                      "contact nodes at the end differs from its value at "
                      "the start of the final phase by more than this "
                      "[m]. -1: no check.");
    prm.declare_entry("Maximum penetration in the final phase",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if a gap goes below minus this during "
                      "the final phase [m]. -1: no check.");
    prm.declare_entry("Maximum active-set changes per step",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the contact nodes change between "
                      "active and inactive more often than this per step "
                      "during the final phase (chattering) [1/step]. -1: "
                      "no check.");
    prm.declare_entry("Maximum reaction error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the mean plane reaction over the "
                      "final phase differs from the normal load (weight "
                      "of the blocks and push) by more than this fraction "
                      "[-]. -1: no check.");
    prm.declare_entry("Maximum stick time error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the time at which the block's mean "
                      "velocity along the plane reaches 0 differs from the "
                      "rigid-block value v0 / (mu N/m - a_t) by more than "
                      "this fraction [-]. -1: no check.");
    prm.declare_entry("Maximum sliding distance error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the distance slid by the block's "
                      "centre of mass differs from the rigid-block value "
                      "by more than this fraction [-]. -1: no check.");
    prm.declare_entry("Maximum final velocity error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if, for a block that never sticks, "
                      "the mean velocity along the plane at the end "
                      "differs from the rigid-block value v0 - d T by more "
                      "than this fraction [-]. -1: no check.");
    prm.declare_entry("Maximum static compression error",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the time-averaged sinking of the "
                      "block's top over the final phase differs from "
                      "rho g H^2 / (2 E) by more than this fraction "
                      "(Poisson's ratio 0, block at rest) [-]. -1: no "
                      "check.");
    prm.declare_entry("Maximum energy increase in round-offs",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the largest energy increase in a "
                      "step exceeds this many times the round-off of the "
                      "energy, eps (|u|.|K||u| + |v|.|M||v| + |F|.|u|) "
                      "(entry-wise absolute values, largest over the run) "
                      "[-]. The bound for schemes that cannot increase the "
                      "energy. -1: no check.");
    prm.declare_entry("Minimum restitution",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the apparent restitution of the "
                      "first impact (mean normal velocity after / before) "
                      "is below this [-]. -1: no check.");
    prm.declare_entry("Maximum restitution",
                      "-1",
                      Patterns::Double(),
                      "Fail the run if the apparent restitution of the "
                      "first impact exceeds this [-]. -1: no check.");
    prm.leave_subsection();
  }



  void
  StabilityBounds::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    final_phase_start = prm.get_double("Start of the final phase");
    max_gap_drift     = get_verification_bound(prm, "Maximum gap drift");
    max_final_penetration =
      get_verification_bound(prm, "Maximum penetration in the final phase");
    max_active_set_changes =
      get_verification_bound(prm, "Maximum active-set changes per step");
    max_reaction_error = get_verification_bound(prm, "Maximum reaction error");
    max_stick_time_error =
      get_verification_bound(prm, "Maximum stick time error");
    max_distance_error =
      get_verification_bound(prm, "Maximum sliding distance error");
    max_final_velocity_error =
      get_verification_bound(prm, "Maximum final velocity error");
    max_compression_error =
      get_verification_bound(prm, "Maximum static compression error");
    max_energy_increase_in_round_offs =
      get_verification_bound(prm, "Maximum energy increase in round-offs");
    min_restitution = get_verification_bound(prm, "Minimum restitution");
    max_restitution = get_verification_bound(prm, "Maximum restitution");
    prm.leave_subsection();
  }



  void
  declare_figures_entry(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Print figures of merit",
                      "true",
                      Patterns::Bool(),
                      "Print the figures of merit of the run. false prints "
                      "only the checks of 'Verification' and whether they "
                      "hold: for runs whose figures depend on round-off "
                      "(chattering, friction-induced instabilities), so "
                      "that a test compares what is reproducible.");
    prm.leave_subsection();
  }



  bool
  parse_figures_entry(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    const bool print = prm.get_bool("Print figures of merit");
    prm.leave_subsection();
    return print;
  }



  void
  print_checks_only(const std::string              &text,
                    std::ostream                   &out,
                    const std::vector<std::string> &kept_prefixes)
  {
    std::istringstream lines(text);
    std::string        line;
    bool               first = true, noted = false;
    while (std::getline(lines, line))
      {
        bool keep = first || line.rfind("  Check ", 0) == 0 ||
                    line.rfind("Results in", 0) == 0;
        for (const std::string &prefix : kept_prefixes)
          keep |= line.rfind(prefix, 0) == 0;
        first = false;
        if (keep)
          out << line << std::endl;
        else if (!noted)
          {
            out << "  (figures of merit not printed: 'Print figures of "
                   "merit' is false)"
                << std::endl;
            noted = true;
          }
      }
  }



  namespace
  {
    // sum_ij |A_ij| |x_i| |x_j|: the round-off of x.Ax is at most a small
    // multiple of eps times this (Higham, section 3.1), whatever cancels in
    // x.Ax itself.
    double
    absolute_quadratic_form(const SparseMatrix<double> &A,
                            const Vector<double>       &x)
    {
      double sum = 0.;
      for (unsigned int i = 0; i < A.m(); ++i)
        for (auto entry = A.begin(i); entry != A.end(i); ++entry)
          sum += std::abs(entry->value() * x(i) * x(entry->column()));
      return sum;
    }
  } // namespace



  template <int dim>
  StabilityMonitor<dim>::StabilityMonitor(
    const MultibodySystem<dim> &system,
    const StabilityBounds      &bounds,
    const double                end_time,
    const unsigned int          n_obstacle_candidates)
    : system(system)
    , bounds(bounds)
    , phase_start(bounds.final_phase_start < 0. ? 0.5 * end_time :
                                                  bounds.final_phase_start)
    , time_step(system.integrator().time_step())
    , n_obstacle(n_obstacle_candidates)
  {
    AssertThrow(phase_start < end_time,
                ExcMessage("Verification: 'Start of the final phase' (" +
                           format_number(phase_start) +
                           " s) must be before the end time."));
    previous_active.assign(system.contacts().n_candidates(), false);
    previous_states.assign(system.contacts().n_candidates(),
                           ContactState::open);
  }



  // The round-off of the energy: u.Ku sums terms of size |K| |u|^2 (u
  // includes the rigid motion) that cancel down to twice the strain energy.
  template <int dim>
  unsigned int
  StabilityMonitor<dim>::before_record(const StepReport &report)
  {
    unsigned int changes = 0;
    if (report.step > 0)
      {
        const std::vector<bool> &active = system.active_set();
        for (unsigned int c = 0; c < active.size(); ++c)
          changes += active[c] != previous_active[c] ? 1 : 0;
        previous_active = active;
      }
    double round_off = 0.;
    for (unsigned int b = 0; b < system.bodies().size(); ++b)
      {
        const ElasticBody<dim> &body = *system.bodies()[b];
        const Vector<double>   &u    = system.state().displacement.block(b),
                             &v      = system.state().velocity.block(b);
        round_off += absolute_quadratic_form(body.stiffness_matrix(), u) +
                     absolute_quadratic_form(body.mass_matrix(), v);
        for (unsigned int i = 0; i < u.size(); ++i)
          round_off += std::abs(body.external_force()(i) * u(i));
      }
    energy_round_off =
      std::max(energy_round_off,
               std::numeric_limits<double>::epsilon() * round_off);
    active_set_changes += changes;
    if (report.step > 0 &&
        system.state().time >= phase_start - 1e-9 * time_step)
      final_active_set_changes += changes;
    return changes;
  }



  template <int dim>
  void
  StabilityMonitor<dim>::after_record(const StepReport          &report,
                                      const ContactMonitor<dim> &monitor,
                                      const double               measured_value)
  {
    if (report.step == 0)
      return;
    const double t        = system.state().time;
    const bool   in_final = t >= phase_start - 1e-9 * time_step;

    system.contacts().gaps(system.state().displacement, gaps);
    mean_gap = 0.;
    for (unsigned int c = 0; c < n_obstacle; ++c)
      mean_gap += gaps[c] / n_obstacle;

    for (unsigned int c = 0; c < previous_states.size(); ++c)
      {
        const ContactState state = monitor.state(c);
        final_state_changes +=
          (in_final &&
           contact_mode(state) != contact_mode(previous_states[c])) ?
            1 :
            0;
        previous_states[c] = state;
      }
    if (in_final)
      {
        if (final_phase_steps == 0)
          mean_gap_at_phase_start = mean_gap;
        ++final_phase_steps;
        for (const double g : gaps)
          final_penetration = std::max(final_penetration, -g);
        reaction_sum += obstacle_reaction();
        final_contact_steps += obstacle_reaction() > 0. ? 1 : 0;
        measured_sum += measured_value;
      }
  }



  template <int dim>
  double
  StabilityMonitor<dim>::obstacle_reaction() const
  {
    const unsigned int nd = system.contacts().n_directions();
    double             P  = 0.;
    for (unsigned int c = 0; c < n_obstacle; ++c)
      P += system.impulses()[c * nd];
    return P * system.integrator().force_per_impulse();
  }



  template <int dim>
  double
  StabilityMonitor<dim>::final_phase_start() const
  {
    return phase_start;
  }



  template <int dim>
  double
  StabilityMonitor<dim>::final_phase_mean() const
  {
    return measured_sum / std::max(1u, final_phase_steps);
  }



  template <int dim>
  double
  StabilityMonitor<dim>::relative_energy_round_off(
    const ContactRunSummary &s) const
  {
    return s.energy_scale > 0. ? energy_round_off / s.energy_scale : 0.;
  }



  template <int dim>
  bool
  StabilityMonitor<dim>::report(std::ostream            &out,
                                const ContactRunSummary &s,
                                const double             normal_load,
                                JsonObject              &stability) const
  {
    // The energy's round-off, in units of the energy scale of the summary.
    const double round_off = relative_energy_round_off(s);
    const double increase_in_round_offs =
      round_off > 0. ? s.max_energy_increase / round_off : 0.;
    out << "  Round-off of the energy eps (|u|.|K||u| + |v|.|M||v| + "
           "|F|.|u|) = "
        << format_figure(round_off, 1e-300)
        << " of the same scale; largest increase "
        << "in a step = " << format_figure(increase_in_round_offs, 100.)
        << " round-offs" << std::endl;
    bool ok = print_check(out,
                          "energy increase in a step in round-offs",
                          increase_in_round_offs,
                          "<=",
                          bounds.max_energy_increase_in_round_offs);

    // The final phase.
    const double gap_drift = std::abs(mean_gap - mean_gap_at_phase_start);
    const double changes_per_step =
      double(active_set_changes) / std::max(1u, s.n_steps);
    const double final_changes_per_step =
      double(final_active_set_changes) / std::max(1u, final_phase_steps);
    out << "  Active-set changes: " << active_set_changes << " in the run ("
        << format_figure(changes_per_step) << " per step)" << std::endl;
    out << "  Final phase from t = " << phase_start << " s ("
        << final_phase_steps << " steps): gap drift "
        << format_figure(gap_drift) << " m, largest penetration "
        << format_figure(final_penetration) << " m, active-set changes "
        << final_active_set_changes << ", contact state changes "
        << final_state_changes << std::endl;
    // A load that pulls the bodies off the obstacle makes the gap grow:
    // that is flight, not drift.
    if (normal_load < 0.)
      out << "  Gap drift: not checked, the normal load "
          << format_figure(normal_load) << " N pulls the bodies off the "
          << "obstacle" << std::endl;
    else
      ok &=
        print_check(out, "gap drift", gap_drift, "<=", bounds.max_gap_drift);
    ok &= print_check(out,
                      "penetration in the final phase",
                      final_penetration,
                      "<=",
                      bounds.max_final_penetration);
    ok &= print_check(out,
                      "active-set changes per step in the final phase",
                      final_changes_per_step,
                      "<=",
                      bounds.max_active_set_changes);

    // Mean reaction against the normal load, if the bodies are on the
    // obstacle in the final phase.
    const double mean_reaction = reaction_sum / std::max(1u, final_phase_steps);
    double       reaction_error = -1.;
    if (normal_load > 0. && final_contact_steps > 0)
      {
        reaction_error = std::abs(mean_reaction - normal_load) / normal_load;
        out << "  Mean plane reaction in the final phase "
            << format_figure(mean_reaction) << " N, normal load "
            << format_figure(normal_load) << " N: relative error "
            << format_figure(reaction_error, 1e-9) << std::endl;
        ok &= print_check(out,
                          "reaction error",
                          reaction_error,
                          "<=",
                          bounds.max_reaction_error);
      }

    stability.add("max_penetration", s.max_penetration)
      .add("energy_change", s.energy_ratio - 1.)
      .add("max_energy_increase", s.max_energy_increase)
      .add("energy_round_off", round_off)
      .add("active_set_changes", double(active_set_changes))
      .add("active_set_changes_per_step", changes_per_step)
      .add("final_phase_start", phase_start)
      .add("final_active_set_changes_per_step", final_changes_per_step)
      .add("final_state_changes", double(final_state_changes))
      .add("gap_drift", gap_drift)
      .add("final_penetration", final_penetration)
      .add("reaction_error", reaction_error);
    return ok;
  }



  template class StabilityMonitor<1>;
  template class StabilityMonitor<2>;
  template class StabilityMonitor<3>;
} // namespace impactfe
