#ifndef impactfe_time_integration_time_integrator_h
#define impactfe_time_integration_time_integrator_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/lac/block_vector.h>
#include <deal.II/lac/sparse_matrix.h>

#include <impactfe/time_integration/free_rhs_operator.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  class ContactSet;
  class JsonObject;

  /** The time schemes of ../shared/spec/schemes.md. */
  enum class Scheme
  {
    theta,
    theta_euler,
    modified_theta,
    newmark
  };

  std::string
  to_string(const Scheme scheme);

  /**
   * Parameter subsection `Time stepping`.
   */
  struct TimeSteppingParameters
  {
    Scheme scheme        = Scheme::theta_euler;
    double theta         = 0.55;
    double newmark_beta  = 0.25;
    double newmark_gamma = 0.5;
    double time_step     = 1e-3;
    double end_time      = 1.;
    /// `Theta rule = courant`: theta is set by apply_theta_rule() from the
    /// cell transit time of the mesh, theta = 1/2 + kappa dx / (c_p h).
    bool   theta_from_courant = false;
    double theta_damping      = 0.025;
    /// The entry `Theta` as read: the rule does not use it, and
    /// scheme_description() says so.
    double theta_entry = 0.55;
    /// The Courant number c_p h / dx apply_theta_rule() found (0: not set
    /// by the program).
    double courant_number = 0.;
    /// Steps without contact are made this many times longer (see the
    /// entry `Free-flight step factor` and MultibodySystem::do_time_step()).
    unsigned int free_flight_step_factor = 1;

    static void
    declare_parameters(ParameterHandler &prm);
    /** Parses and checks; throws with a message naming the entry. */
    void
    parse_parameters(ParameterHandler &prm);

    /** Number of steps to reach the end time (the last one may end past it
     * by less than a rounding error). */
    unsigned int
    n_steps() const;

    /**
     * With `Theta rule = courant`, sets theta = min(1, 1/2 + kappa / C),
     * C = h / @p cell_transit_time, from the shortest time dx / c_p a
     * P-wave takes to cross a cell of any body (the scene computes it, see
     * ElasticBody::cell_transit_time()). The theta-method's damping of a
     * mode of frequency omega is that of a stiffness-proportional damping of
     * coefficient (theta - 1/2) h for omega h << 1 (damping ratio (theta -
     * 1/2) omega h / 2); the rule makes it kappa dx / c_p at every h, a
     * mesh-scale viscosity that vanishes as the mesh is refined. With the
     * fixed rule it only records the Courant number.
     */
    void
    apply_theta_rule(const double cell_transit_time);

    /**
     * The parameters of the free-flight level: the step and the Courant
     * number are `Free-flight step factor` times larger, theta is that of
     * h (also under `Theta rule = courant`: see the measurement in the
     * function body).
     */
    TimeSteppingParameters
    free_flight_parameters() const;

    /**
     * "theta-euler (theta = 0.55)", "newmark (beta = 0.25, gamma = 0.5)" or
     * "modified-theta (theta = 0.52 from the Courant number 1.4; the entry
     * 'Theta' = 0.55 is not used)": the scheme as the programs print it.
     */
    std::string
    scheme_description() const;

    /** Adds scheme, theta, theta_rule, courant_number and time_step. */
    void
    add_to_summary(JsonObject &summary) const;
  };



  /**
   * The discrete mechanical operators of all bodies, M v' + C v + K u = F +
   * contact forces. The operators are block diagonal, one block per body
   * (bodies interact only through contact), so they are kept per body.
   */
  struct MechanicalOperators
  {
    std::vector<const SparseMatrix<double> *> mass;
    std::vector<const SparseMatrix<double> *> stiffness;
    /// Entries are nullptr for bodies without damping: C is skipped there.
    std::vector<const SparseMatrix<double> *> damping;
    /// External load, constant in time.
    BlockVector<double> external_force;
    /// The component of each DoF, per body (FreeRhsOperator: F~ relative
    /// to the rigid translation); empty vectors for none.
    std::vector<std::vector<unsigned char>> dof_components;
  };



  /**
   * The update and the gap term of the theta-schemes, as numbers (one
   * place for each scheme's formulas, used by the serial and the
   * distributed time loops):
   *   u^{i+1} = u^i + h (w v^{i+1} + (1 - w) v^i),
   *   b_N = g(u^i + a h v^i) / d + c V_N(v^i),
   * with w = new_velocity_weight, a = gap_prediction, d = gap_divisor,
   * c = gap_velocity.
   */
  struct ThetaStepRule
  {
    double new_velocity_weight = 1.;
    double gap_prediction      = 0.;
    double gap_divisor         = 1.;
    double gap_velocity        = 0.;
  };



  /**
   * Newmark's step as numbers, as ThetaStepRule for the theta-schemes (one
   * place for the formulas, used by NewmarkMethod and the distributed
   * time loop):
   *   u~ = u^i + h v^i + p a^i,  v~ = v^i + q a^i  (the prediction),
   *   b_N = c g(u~) - V_N(v~),
   *   a^{i+1} = (v^{i+1} - v~) / e,  u^{i+1} = u~ + f a^{i+1},
   * with p = predicted_displacement_acceleration = h^2 (1/2 - beta),
   * q = predicted_velocity_acceleration = h (1 - gamma), c = gap_factor =
   * gamma / (h beta), e = acceleration_divisor = h gamma and f =
   * displacement_acceleration = h^2 beta.
   */
  struct NewmarkStepRule
  {
    double time_step                           = 0.;
    double predicted_displacement_acceleration = 0.;
    double predicted_velocity_acceleration     = 0.;
    double gap_factor                          = 1.;
    double acceleration_divisor                = 1.;
    double displacement_acceleration           = 0.;
  };



  /** Displacement, velocity and (Newmark only) acceleration at one time. */
  struct MechanicalState
  {
    double              time = 0.;
    BlockVector<double> displacement;
    BlockVector<double> velocity;
    BlockVector<double> acceleration;
  };


  /**
   * Exchange two states without copying or allocating (the vectors' storage
   * is swapped); std::swap would move through a temporary, and moving a
   * deal.II BlockVector allocates.
   */
  inline void
  swap(MechanicalState &a, MechanicalState &b)
  {
    std::swap(a.time, b.time);
    a.displacement.swap(b.displacement);
    a.velocity.swap(b.velocity);
    a.acceleration.swap(b.acceleration);
  }



  /**
   * One time step of any scheme, written at the velocity level:
   *
   *   M~ v^{i+1} = F~ + H P,    w_N = V_N^{i+1} + b_N >= 0  _|_  P_N >= 0,
   *
   * with M~ = M + c_C C + c_K K fixed while h is fixed. A scheme supplies
   * c_C and c_K, the free right-hand side F~, the gap term b_N of its
   * discrete Signorini condition, and the update of u (and a) once v^{i+1}
   * is known. Everything else (Delassus operator, LCP, output) is shared.
   */
  class TimeIntegrator
  {
  public:
    explicit TimeIntegrator(const TimeSteppingParameters &parameters);
    virtual ~TimeIntegrator() = default;

    Scheme
    scheme() const;
    double
    time_step() const;

    /** c_C in M~ = M + c_C C + c_K K. */
    virtual double
    damping_coefficient() const = 0;
    /** c_K in M~ = M + c_C C + c_K K. */
    virtual double
    stiffness_coefficient() const = 0;

    /**
     * F~ of M~ v^{i+1} = F~ + H P is (M + a_C C + a_K K) x + b_K K y +
     * gamma f: the scheme's a_C, a_K, b_K and gamma. FreeRhsOperator
     * combines the matrices with them once.
     */
    virtual FreeRhsCoefficients
    free_rhs_coefficients() const = 0;

    /**
     * x and y of F~ for @p state: its velocity and displacement, unless the
     * scheme predicts them first (Newmark).
     */
    virtual std::pair<const BlockVector<double> *, const BlockVector<double> *>
    free_rhs_arguments(const MechanicalState &state) const;

    /**
     * F~ from the state at t_i, with the operator of the coefficients,
     * relative to the translation of FreeRhsOperator::apply(): the solve
     * with M~ is completed by op.add_translation(@p translation, v).
     */
    void
    free_rhs(const FreeRhsOperator         &op,
             const MechanicalState         &state,
             BlockVector<double>           &rhs,
             FreeRhsOperator::Translations &translation) const;

    /**
     * The theta-schemes' update and gap term (ThetaStepRule); Newmark,
     * whose step needs the acceleration, has none and throws.
     */
    virtual ThetaStepRule
    theta_step_rule() const;

    /** Newmark's prediction, gap term and update (NewmarkStepRule); the
     * theta-schemes have none and throw. */
    virtual NewmarkStepRule
    newmark_step_rule() const;

    /** b_N per contact candidate for the step from @p state (by default
     * from theta_step_rule()). */
    virtual void
    gap_term(const ContactSet      &contacts,
             const MechanicalState &state,
             std::vector<double>   &b) const;

    /** Given v^{i+1} in @p new_state, complete u^{i+1} (and a^{i+1}); by
     * default from theta_step_rule(). */
    virtual void
    complete_step(const MechanicalState &old_state,
                  MechanicalState       &new_state) const;

    /** The contact force that the impulse P of one step represents. */
    virtual double
    force_per_impulse() const;

    /**
     * How the step's contact impulse follows from the contact forces:
     * impulse = h (w F^{i+1} + (1 - w) F^i). The theta-schemes report
     * F = P / h, so w = 1; Newmark's r enters the velocity update with
     * weights gamma and 1 - gamma.
     */
    virtual double
    contact_force_weight() const;

    /** Whether the state needs a^0 (M a^0 = F - K u^0 - C v^0). */
    virtual bool
    needs_initial_acceleration() const;

    /**
     * The contact nodes carry no mass (mass redistribution). A
     * theta-scheme then balances a massless node at t^{i+1} instead of at
     * t^{i+theta}: same step matrix, and (1 - theta)/theta of the previous
     * step's contact impulse added to its rows of F~
     * (massless_impulse_carry()). Otherwise u at a free massless node would
     * alternate about its equilibrium by the factor -(1 - theta)/theta per step
     * (undamped at theta = 1/2). The contact force of a step is then P / (h
     * theta), and the impulse that changes the momentum h (theta F^{i+1} + (1 -
     * theta) F^i). Newmark refuses it (its a^0 needs M^{-1}).
     */
    void
    set_massless_contact_nodes(const bool massless);

    /** The factor of the previous impulse added at massless rows of F~. */
    double
    massless_impulse_carry() const;

    /**
     * With massless contact nodes, the factor c of V_T^i in the slip
     * velocity on which Coulomb's law is imposed, V_T^{i+1} + c V_T^i: the
     * step's mean slip velocity (u^{i+1} - u^i)/h over theta, the velocity
     * a massless node has (the theta-method's update u^{i+1} = u^i +
     * h (theta v^{i+1} + (1 - theta) v^i): c = (1 - theta)/theta; theta-Euler
     * moves u with v^{i+1} alone: c = 0). Without massless nodes, 0.
     */
    virtual double
    slip_velocity_carry() const;

  protected:
    const TimeSteppingParameters parameters;
    const double                 h;
    bool                         massless_contact_nodes = false;
    /// Work space of gap_term().
    mutable std::vector<double> rule_normal_velocity;
  };

  std::unique_ptr<TimeIntegrator>
  create_time_integrator(const TimeSteppingParameters &parameters);
} // namespace impactfe

#endif
