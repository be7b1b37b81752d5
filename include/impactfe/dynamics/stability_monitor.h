#ifndef impactfe_dynamics_stability_monitor_h
#define impactfe_dynamics_stability_monitor_h

#include <deal.II/base/parameter_handler.h>

#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/output/output.h>

#include <ostream>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * The bounds of a stability study, in the subsection `Verification`
   * beside the common ones (ContactVerificationParameters). A bound of -1
   * is not checked.
   */
  struct StabilityBounds
  {
    double final_phase_start        = -1.;
    double max_gap_drift            = -1.;
    double max_final_penetration    = -1.;
    double max_active_set_changes   = -1.;
    double max_reaction_error       = -1.;
    double max_stick_time_error     = -1.;
    double max_distance_error       = -1.;
    double max_final_velocity_error = -1.;
    double max_compression_error    = -1.;
    double min_restitution = -1., max_restitution = -1.;
    double max_energy_increase_in_round_offs = -1.;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };



  /**
   * The entry `Print figures of merit` of subsection `Output`: false prints
   * only the checks of a run whose figures depend on round-off
   * (chattering, friction-induced instabilities), so that a test compares
   * what is reproducible.
   */
  void
  declare_figures_entry(ParameterHandler &prm);
  bool
  parse_figures_entry(ParameterHandler &prm);

  /**
   * Print of the report @p text only its first line, the lines that start
   * with one of @p kept_prefixes, the checks and the files; a note stands
   * where the first figure was left out.
   */
  void
  print_checks_only(const std::string              &text,
                    std::ostream                   &out,
                    const std::vector<std::string> &kept_prefixes);



  /**
   * What a stability study measures in a run, beyond the ContactMonitor's
   * checks: the changes of the active set (chattering) and of the contact
   * states, and over a final phase of the run (at rest, or in a steady
   * regime) the drift of the mean gap, the largest penetration and the mean
   * reaction of the obstacle; and the round-off of the energy, eps (|u|.|K||u|
   * + |v|.|M||v| + |F|.|u|), against which a scheme that cannot increase
   * the energy is judged (Higham, Accuracy and Stability of Numerical
   * Algorithms, section 3.1).
   *
   * Candidates [0, n_obstacle_candidates) are the ones against the
   * obstacle whose gap and reaction are measured.
   *
   * Use: before_record() before the SceneRecorder records a state (its
   * result is the step's active-set changes), after_record() after it for
   * every step.
   */
  template <int dim>
  class StabilityMonitor
  {
  public:
    StabilityMonitor(const MultibodySystem<dim> &system,
                     const StabilityBounds      &bounds,
                     const double                end_time,
                     const unsigned int          n_obstacle_candidates);

    /** Active-set changes of the step just done; updates the round-off. */
    unsigned int
    before_record(const StepReport &report);

    /**
     * Measure the step (report.step > 0). @p measured_value is a scene
     * quantity whose mean over the final phase is wanted (e.g. the sinking
     * of a block's top).
     */
    void
    after_record(const StepReport          &report,
                 const ContactMonitor<dim> &monitor,
                 const double               measured_value);

    /** Total normal force of the obstacle on the bodies in the last step. */
    double
    obstacle_reaction() const;

    double
    final_phase_start() const;
    /** Mean of after_record()'s measured value over the final phase. */
    double
    final_phase_mean() const;
    /** The energy round-off relative to the energy scale of @p s. */
    double
    relative_energy_round_off(const ContactRunSummary &s) const;

    /**
     * Print the energy round-off, the active-set changes, the final phase
     * and the mean reaction against @p normal_load, with their checks, and
     * add the figures to @p stability. A negative @p normal_load pulls the
     * bodies off the obstacle: the gap drift is then not checked. Returns
     * false if a check failed.
     */
    bool
    report(std::ostream            &out,
           const ContactRunSummary &s,
           const double             normal_load,
           JsonObject              &stability) const;

  private:
    const MultibodySystem<dim> &system;
    StabilityBounds             bounds;
    double                      phase_start;
    double                      time_step;
    unsigned int                n_obstacle;

    std::vector<bool>         previous_active;
    std::vector<ContactState> previous_states;
    std::vector<double>       gaps;
    unsigned int              final_phase_steps = 0, final_contact_steps = 0;
    unsigned long long active_set_changes = 0, final_active_set_changes = 0,
                       final_state_changes = 0;
    double mean_gap_at_phase_start = 0., mean_gap = 0., final_penetration = 0.;
    double reaction_sum = 0., measured_sum = 0.;
    /// Largest eps (|u|.|K||u| + |v|.|M||v| + |F|.|u|) of the run.
    double energy_round_off = 0.;
  };
} // namespace impactfe

#endif
