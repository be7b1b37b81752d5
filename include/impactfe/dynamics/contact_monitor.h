#ifndef impactfe_dynamics_contact_monitor_h
#define impactfe_dynamics_contact_monitor_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/lcp/contact_state.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;



  /**
   * What the checks of a whole run found. All quantities are measured, not
   * assumed; the tolerances they are compared with are the program's.
   */
  struct ContactRunSummary
  {
    /// max over bodies and components of |p(T) - p(0) - impulses| divided
    /// by the largest |p| of that body during the run.
    double impulse_balance_error   = 0.;
    bool   impulse_balance_checked = true;
    /// max over steps and candidates of -g (0 if no node ever penetrated).
    double max_penetration = 0.;
    /// max over steps of ContactSet::largest_slide_off(): how far a node
    /// between bodies slid off the other body's contact boundary, as a
    /// fraction of its length (small sliding keeps the pairs of t = 0).
    double largest_slide_off = 0.;
    /// max over steps and nodes of (|P_T| - mu P_N) / max P_N (<= 0 holds).
    double coulomb_excess = 0.;
    /// Sliding nodes whose P_T is not opposite to V_T, or is below mu P_N.
    unsigned int wrong_slip_count = 0;
    /// Whether the bodies carry external loads: the energy then includes
    /// their potential (minus their work since t = 0).
    bool with_loads = false;
    /// The energy E^0 at t = 0 if it is > 0; otherwise (a scene that starts
    /// at rest and undeformed) the largest kinetic plus elastic energy of
    /// the run. The energy figures below are relative to it.
    double energy_scale            = 0.;
    bool   energy_scale_is_initial = true;
    /// max over steps of (E^{i+1} - E^i) / energy_scale.
    double max_energy_increase = 0.;
    /// E(T) / E^0, or 1 + (E(T) - E^0) / energy_scale if E^0 is not > 0.
    double energy_ratio = 1.;
    /// First and last step end times with a non-zero contact force (-1:
    /// never).
    double first_contact = -1., last_contact = -1.;
    double peak_normal_force = 0.;
    /// Time integrals of the total normal and tangential force magnitudes.
    double normal_impulse = 0., tangential_impulse = 0.;
    /// Changes of candidate states (open/stick/slip) summed over the run,
    /// and the number of steps.
    unsigned long long state_changes = 0;
    unsigned int       n_steps       = 0;
    /// Of these steps, those made with k h (`Free-flight step factor`).
    unsigned int free_flight_steps = 0;
    /// 3D with `Friction cone = exact`: the contact problems solved, how
    /// many missed the exact-cone tolerance, and that tolerance.
    unsigned int exact_cone_solves        = 0;
    unsigned int exact_cone_not_converged = 0;
    double       exact_cone_tolerance     = 0.;
    /// Contact problems solved by the active set method, its iterations,
    /// and the solves that fell back to Lemke's method.
    unsigned int       active_set_solves                 = 0;
    unsigned long long active_set_iterations             = 0;
    unsigned int       active_set_fallbacks              = 0;
    bool               active_set_dense_schur_complement = false;
    /// Whether the normal rows were inverted at the contact states.
    bool active_set_exact_normal_rows = false;
  };



  /**
   * Parameter subsection `Verification` of the 2D/3D programs: optional
   * bounds on the run's checks. A bound of -1 is not checked. The program
   * prints each check with OK or FAILED and exits with code 1 if one fails,
   * so that tests and regression runs can use them.
   */
  struct ContactVerificationParameters
  {
    double max_impulse_balance_error = -1.;
    double max_penetration           = -1.;
    double max_coulomb_excess        = -1.;
    double max_energy_increase       = -1.;
    double min_energy_ratio          = -1.;
    double max_energy_ratio          = -1.;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };

  /**
   * Print `Check <what> <relation> <bound>: OK` or `...: FAILED (<value>)`
   * (nothing if the bound is negative: -1, "no check", the only negative
   * value get_verification_bound() accepts) and return false if it failed.
   */
  bool
  print_check(std::ostream      &out,
              const std::string &what,
              const double       value,
              const std::string &relation,
              const double       bound);

  /**
   * Print `Check <what> is a number: FAILED (<value>)` for each figure of
   * @p figures that is not finite (a state that overflowed or underflowed:
   * 0/0 of a momentum scale that is zero) and return false if there was
   * one. Such a run fails whatever its bounds: nothing they check holds.
   */
  bool
  check_figures_are_numbers(
    std::ostream                                      &out,
    const std::vector<std::pair<std::string, double>> &figures);

  /**
   * Print the run's contact summary (contact interval, peak force,
   * impulses, impulse balance, penetration, Coulomb, energy, state changes)
   * and the checks of @p bounds. Returns false if a check failed; a sliding
   * node with a wrong friction force always fails.
   */
  bool
  print_contact_summary(std::ostream                        &out,
                        const ContactRunSummary             &summary,
                        const ContactVerificationParameters &bounds,
                        const bool                           frictional);

  /**
   * Only the checks of print_contact_summary(): one line per bound that is
   * set. Returns false if one failed.
   */
  bool
  check_contact_bounds(std::ostream                        &out,
                       const ContactRunSummary             &summary,
                       const ContactVerificationParameters &bounds,
                       const bool                           frictional);



  /**
   * Watches a MultibodySystem during a run: the history columns every 2D
   * and 3D program writes (total contact force and momentum of the bodies,
   * per body when there are several; energies; gap; stick and slip counts),
   * an optional per-node file (`contact_nodes.csv`), and the physical
   * checks of the run:
   *  - impulse balance: p(T) - p(0) equals the sum of the contact and
   *    external impulses of every step, for each body and component (the
   *    scheme's own rule for the impulse of a step, see
   *    TimeIntegrator::contact_force_weight());
   *  - Signorini: the largest penetration max(-g) over steps and nodes;
   *  - Coulomb: |P_T| <= mu P_N at every node and step, and a sliding node
   *    (|V_T^{i+1}| > 0) has P_T = -mu P_N V_T / |V_T|;
   *  - energy: the largest increase of the total energy in a step,
   *    relative to the initial energy (see total_energy()).
   *
   * Call record() after every MultibodySystem::do_time_step().
   */
  template <int dim>
  class ContactMonitor
  {
  public:
    /**
     * @p system must be set up. If @p node_file is not empty, one row per
     * step and candidate goes there.
     */
    ContactMonitor(const MultibodySystem<dim> &system,
                   const std::string          &node_file = "");

    /** Column names of history_values(). */
    std::vector<std::string>
    history_columns() const;
    /** The row of the current state (after record(), or the initial one). */
    std::vector<double>
    history_values(const StepReport &report) const;

    /** Account for the step just done. */
    void
    record(const StepReport &report);

    /** Close the node file; throws if a write failed (disk full). */
    void
    close_node_file();

    /**
     * State of candidate @p c after the last step; a sliding candidate
     * slips along +t1 or -t1 (frictionless: slip_positive).
     */
    ContactState
    state(const unsigned int c) const;

    const ContactRunSummary &
    summary() const;

    /**
     * Kinetic plus elastic energy minus the work of the external loads
     * since t = 0. The loads are constant, so their potential is -F.u and
     * this is the energy that the dissipative schemes do not increase.
     */
    double
    total_energy() const;

    /** Total contact force on all bodies, and total momentum. */
    Tensor<1, dim>
    total_contact_force() const;
    Tensor<1, dim>
    total_momentum() const;

  private:
    const MultibodySystem<dim>    &system;
    std::unique_ptr<std::ofstream> node_output;
    std::string                    node_file_name;
    /// The row of contact_nodes.csv being written (reused).
    std::string node_line;

    ContactRunSummary run;
    double            initial_energy = 0., last_energy = 0.;
    /// F.u at t = 0, and the largest absolute energy increase in a step
    /// and kinetic plus elastic energy so far.
    double initial_load_term = 0., largest_increase = 0.,
           largest_stored_energy = 0.;
    std::vector<Tensor<1, dim>> initial_momentum, external_force,
      previous_contact_force, accumulated_impulse;
    std::vector<double>       largest_momentum;
    std::vector<ContactState> states;
    std::vector<double>       gaps, local_velocity;
    double                    velocity_scale = 0., impulse_scale = 0.,
           largest_inverse_nodal_mass = 0.;
  };
} // namespace impactfe

#endif
