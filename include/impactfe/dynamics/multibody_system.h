#ifndef impactfe_dynamics_multibody_system_h
#define impactfe_dynamics_multibody_system_h

#include <deal.II/base/tensor.h>

#include <deal.II/lac/block_vector.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/contact/contact_set.h>
#include <impactfe/dynamics/schur_complement.h>
#include <impactfe/dynamics/sparse_cholesky.h>
#include <impactfe/lcp/active_set.h>
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/dense_matrix.h>
#include <impactfe/lcp/lemke.h>
#include <impactfe/time_integration/time_integrator.h>

#include <array>
#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /** What one time step did: forces, the LCP, the active set. */
  struct StepReport
  {
    unsigned int step = 0;
    double       time = 0.;
    /// Sum over candidates of the normal contact force, positive in
    /// compression: impulse / step for the theta-schemes; the force at the
    /// end of the step for Newmark (r^{i+1}) and with massless contact
    /// nodes (P / (h theta): the step's impulse is then
    /// h (theta F^{i+1} + (1 - theta) F^i)).
    double normal_force = 0.;
    /// Magnitude of the sum of the tangential contact forces.
    double       tangential_force = 0.;
    unsigned int active_contacts  = 0;
    /// Rows of the LCP solved this step (0 if no candidate could touch).
    unsigned int lcp_size   = 0;
    unsigned int lcp_pivots = 0;
    /// How many times the candidate set had to grow within the step.
    unsigned int lcp_resolves = 0;
    /// The step's length, and how many steps of the parameter file's h it
    /// covers (k for a free-flight step, 1 otherwise).
    double       time_step  = 0.;
    unsigned int n_substeps = 1;
    /// Active set iterations of the step's contact solves (0 if Lemke's
    /// method solved them), and whether one fell back to Lemke's method.
    unsigned int active_set_iterations = 0;
    bool         active_set_fallback   = false;
    /// The velocity update's stored columns M~^{-1} H_j, one per non-zero
    /// impulse, summed instead of a solve pair (0 if it made a solve, added
    /// the active set method's M~^{-1} H P, or had nothing to add).
    unsigned int stored_columns_summed = 0;
  };



  /**
   * Where the time of a run goes (wall seconds, accumulated since setup();
   * only measured after MultibodySystem::enable_cost_breakdown()). Wall,
   * not CPU, time: a CPU clock is too dear to be read several times per
   * step (see wall_seconds()).
   */
  struct CostBreakdown
  {
    /// Building and factorising M~ (once, in setup()).
    double factorization = 0.;
    /// Solves for the Delassus columns M~^{-1} H_j and W = H^T M~^{-1} H,
    /// done when a candidate first enters an LCP; or the active set
    /// method's Schur complement on the contact DoFs (once).
    double delassus = 0.;
    /// Right-hand side and solve of the free velocity, local velocities and
    /// gap terms.
    double free_velocity = 0.;
    /// Candidate selection, assembly and solution of the LCPs.
    double lcp = 0.;
    /// Velocity correction (one solve), contact forces, completion of the
    /// step and the step report.
    double update = 0.;
    /// Candidates whose Delassus columns have been computed.
    unsigned int delassus_candidates = 0;
  };



  /** Thrown when a step's LCP is not solved; the message names the step. */
  struct ContactSolverFailure : public ExceptionBase
  {
    ContactSolverFailure(const std::string &message)
      : text(message)
    {}
    void
    print_info(std::ostream &out) const override
    {
      out << text << std::endl;
    }
    const char *
    what() const noexcept override
    {
      return text.c_str();
    }
    std::string text;
  };



  /**
   * Bodies, contact candidates and a time scheme, advanced step by step.
   *
   * Each step (see ../shared/spec/schemes.md, "Condensation"):
   *  1. v_free = M~^{-1} F~ (one solve with the factorisation of M~, made
   *     once in setup());
   *  2. the local free velocities V_free = H^T v_free and the scheme's gap
   *     terms b_N;
   *  3. the LCP on the candidates that can touch in this step (w_N free < 0,
   *     plus those active in the previous step; the set grows if an excluded
   *     candidate would be pushed into penetration), with the Delassus
   *     operator W = H^T M~^{-1} H;
   *  4. v^{i+1} = v_free + M~^{-1} (H P): a sum of stored columns
   *     M~^{-1} H_j when they are stored and that is cheaper, else one
   *     more solve;
   *  5. the scheme completes u^{i+1} (and a^{i+1}).
   *
   * The columns of W belonging to a candidate are computed (dim solves with
   * the factorisation) the first time the candidate enters an LCP, and
   * kept. The vectors M~^{-1} H_j themselves are kept only within a memory
   * budget (set_column_storage_budget()), so memory is O(n_dofs +
   * n_columns^2) instead of O(n_dofs n_columns), and candidates that never
   * come close to touching cost nothing (doc/performance.md).
   */
  template <int dim>
  class MultibodySystem
  {
  public:
    /**
     * @p contact_directions: local directions per contact candidate, 1 for
     * a frictionless scene (normal only) or dim with friction.
     */
    MultibodySystem(const TimeSteppingParameters  &time_stepping,
                    const ContactSolverParameters &solver_parameters,
                    const unsigned int             contact_directions = 1);

    /** Register a body (set up already). Returns its index. */
    unsigned int
    add_body(const ElasticBody<dim> &body);

    const std::vector<const ElasticBody<dim> *> &
    bodies() const;

    /** Add candidates here before setup(). */
    ContactSet &
    contacts();
    const ContactSet &
    contacts() const;

    /** Where failing (and requested) LCPs are written. */
    void
    set_dump_directory(const std::string &directory);

    /**
     * Build the operators, factorise M~, compute W and, for Newmark, the
     * initial acceleration. Call after bodies, candidates and the initial
     * state (state().displacement, state().velocity) are set.
     */
    void
    setup();

    /** Zero state with the block layout of the bodies (before setup()). */
    MechanicalState &
    state();
    const MechanicalState &
    state() const;

    /**
     * Advance by one step. Throws ContactSolverFailure if the LCP fails.
     *
     * With `Free-flight step factor` k > 1 and @p max_substeps >= k, a step
     * after one without contact impulses is first tried with k h: if its
     * free velocities close no gap (V_N + b_N >= 0 for every candidate, with
     * the gap term of k h), no contact acts during it and it is kept
     * (StepReport::n_substeps = k). Otherwise the same step is made with h:
     * the state is not touched until a step is kept.
     */
    StepReport
    do_time_step(const unsigned int max_substeps = 1);

    const TimeIntegrator &
    integrator() const;

    /** 1/2 v^T M v, per body or in total. */
    double
    kinetic_energy() const;
    double
    kinetic_energy(const unsigned int body) const;
    /** 1/2 u^T K u. */
    double
    elastic_energy() const;
    double
    elastic_energy(const unsigned int body) const;
    /** Total linear momentum of one body. */
    Tensor<1, dim>
    momentum(const unsigned int body) const;
    /** Total contact force of the last step on one body (global axes). */
    Tensor<1, dim>
    contact_force(const unsigned int body) const;
    /** Nodal contact forces of the last step (H P times force/impulse). */
    const BlockVector<double> &
    nodal_contact_force() const;
    /** Local impulses of the last step, per candidate [N, T...]. */
    const std::vector<double> &
    impulses() const;
    /** Candidates with P_N > 0 in the last step. */
    const std::vector<bool> &
    active_set() const;
    /**
     * The Delassus operator W (n_columns x n_columns). Completes the
     * columns not computed yet (one solve each).
     */
    const lcp::DenseMatrix &
    delassus_operator() const;
    /**
     * Memory [bytes] for stored columns M~^{-1} H_j (default 64 MiB; 0
     * stores none and always corrects the velocity with a solve). Call
     * before setup().
     */
    void
    set_column_storage_budget(const std::size_t bytes);
    /** Measure where the CPU time goes (a few clock reads per step). */
    void
    enable_cost_breakdown(const bool enable = true);
    const CostBreakdown &
    cost_breakdown() const;
    /**
     * Bytes held by the step's contact problem and its solver (capacities).
     * Storage is never given back, so the LCP part of a step allocates only
     * when this grows (tests/dynamics/step_allocations).
     */
    std::size_t
    lcp_memory_consumption() const;
    /** Total pivots, largest LCP, failures so far. */
    unsigned long long
    total_pivots() const;
    unsigned int
    largest_lcp() const;

    /// The exact-cone solves of the run (3D friction with `Friction cone =
    /// exact`): how many, the facet LCPs they took, their largest
    /// residual (ExactConeReport), and how many missed the tolerance.
    struct ExactConeStatistics
    {
      unsigned int       solves           = 0;
      unsigned long long facet_lcps       = 0;
      unsigned int       most_facet_lcps  = 0;
      double             largest_residual = 0.;
      unsigned int       not_converged    = 0;
    };
    const ExactConeStatistics &
    exact_cone_statistics() const;

    /// The contact LCPs of the run on Lemke's route (not the exact cone's,
    /// not the active set method's): how many, how each was answered
    /// (lcp::StartPath: cold Lemke, the guessed basis as it was, Lemke from
    /// it, cold Lemke after a rejected guess, or block pivoting), and the
    /// block pivoting's attempts, the attempts it gave up (Lemke then
    /// answered), its linear solves and the solves that reused the factors
    /// of the one before.
    struct LcpStatistics
    {
      unsigned int solves = 0;
      /// Indexed by lcp::StartPath.
      std::array<unsigned int, 5> by_path{};
      unsigned int                block_pivoting_attempts       = 0;
      unsigned int                block_pivoting_gave_up        = 0;
      unsigned long long          block_pivoting_linear_solves  = 0;
      unsigned long long          block_pivoting_reused_factors = 0;
    };
    const LcpStatistics &
    lcp_statistics() const;

    /// The active set solves of the run (`Method = active set` or
    /// `automatic`): how many, their iterations, GMRES iterations and
    /// products with W (one solve pair each), the largest verification
    /// violation, and the fallbacks to Lemke's method with the last reason.
    struct ActiveSetStatistics
    {
      unsigned int       solves                = 0;
      unsigned long long iterations            = 0;
      unsigned int       most_iterations       = 0;
      unsigned long long linear_iterations     = 0;
      unsigned long long operator_applications = 0;
      double             largest_violation     = 0.;
      /// The largest exact_cone_error() of the verified answers.
      double largest_cone_error = 0.;
      /// Refinement passes of the final solves, and the largest final
      /// linear residual (impulse units, relative to the largest impulse).
      unsigned long long refinements             = 0;
      double             largest_linear_residual = 0.;
      unsigned int       fallbacks               = 0;
      /// Factorisations of the normal rows' operator at the contact states
      /// (update_normal_states()), and how many of them found it singular
      /// (W_NN^{-1} was used instead).
      unsigned int state_factorizations    = 0;
      unsigned int singular_state_matrices = 0;
      /// Whether the products used the dense Schur complements.
      bool        dense_schur_complement = false;
      std::string last_fallback_reason;
    };
    const ActiveSetStatistics &
    active_set_statistics() const;
    /// The `Contact solver` parameters the system was made with.
    const ContactSolverParameters &
    contact_solver_parameters() const;

  private:
    TimeSteppingParameters                time_stepping;
    ContactSolverParameters               solver_parameters;
    std::vector<const ElasticBody<dim> *> body_list;
    ContactSet                            contact_set;
    std::unique_ptr<TimeIntegrator>       scheme;
    std::string                           dump_directory = ".";
    /// The scheme with k h, its F~ and factorised step matrices (only if
    /// the free-flight step factor k > 1).
    std::unique_ptr<TimeIntegrator>                    coarse_scheme;
    FreeRhsOperator                                    coarse_free_rhs_operator;
    std::vector<std::unique_ptr<SparseMatrix<double>>> coarse_step_matrices;
    std::vector<std::unique_ptr<SparseCholesky>>       coarse_step_solvers;
    /// Whether the last step applied contact impulses (a free-flight step
    /// follows only a step without them).
    bool last_step_had_impulses = true;

    MechanicalOperators operators;
    /// Counts the changes of the state (a step changes the contact forces
    /// with it). The monitor, the history and the scene ask for the
    /// energies, momenta and contact forces several times per step; they
    /// are computed once per state.
    unsigned long state_version = 0;
    struct BodyIntegrals
    {
      double         kinetic_energy = 0., elastic_energy = 0.;
      Tensor<1, dim> momentum, contact_force;
    };
    mutable unsigned long              integrals_version = ~0ul;
    mutable std::vector<BodyIntegrals> integrals;
    const BodyIntegrals &
    body_integrals(const unsigned int body) const;
    /// F~ of the scheme from M, C, K and the load, combined once.
    FreeRhsOperator free_rhs_operator;
    /// The translation free_rhs_operator took off the last F~.
    FreeRhsOperator::Translations free_velocity_translation;
    /// Step matrices M~ per body and their factorisations.
    std::vector<std::unique_ptr<SparseMatrix<double>>> step_matrices;
    std::vector<std::unique_ptr<SparseCholesky>>       step_solvers;
    /// Flops of one solve with all step matrices (4 per factor entry).
    double solve_cost = 0.;
    /// Stored columns M~^{-1} H_j (slots allocated in setup()) and, per
    /// column of H, its slot or -1.
    std::size_t                              column_storage_budget = 64 << 20;
    mutable std::vector<BlockVector<double>> stored_columns;
    mutable std::vector<int>                 stored_column_slot;
    mutable unsigned int                     n_stored_columns = 0;
    /// W, filled column block by column block as candidates enter an LCP.
    mutable lcp::DenseMatrix    delassus;
    mutable std::vector<bool>   delassus_ready;
    mutable BlockVector<double> column_work;
    mutable CostBreakdown       costs;
    bool                        measure_costs = false;
    /// Uniform unit fields e_d per component, for momenta and net forces.
    std::array<BlockVector<double>, dim> unit_fields;
    /// M e_d: the momentum of a body is then one dot product.
    std::array<BlockVector<double>, dim> mass_unit_fields;

    MechanicalState current, next;
    unsigned int    step_number = 0;

    // Work space of a step, kept to avoid allocation in the time loop.
    /// Per body: the DoFs without mass (ElasticBody::redistribute_mass()).
    std::vector<std::vector<types::global_dof_index>> massless_dofs;
    /// Per body: (H P) of the last step at massless_dofs.
    std::vector<std::vector<double>> massless_impulses;
    BlockVector<double>              free_velocity;
    BlockVector<double>              contact_force_field;
    BlockVector<double>              impulse_response;
    std::vector<double>              local_free_velocity;
    /// H^T v^i, for the slip of massless nodes.
    std::vector<double> start_local_velocity;
    std::vector<double> gap_terms;
    std::vector<double> local_impulses;
    std::vector<bool>   active;
    std::vector<bool>   in_lcp;
    /// State of each candidate at the last LCP solve (warm start).
    std::vector<ContactState> last_contact_states;
    std::vector<unsigned int> lcp_candidates;
    lcp::ContactProblem       problem;
    /// The LCP solver and its storage, reused from step to step.
    lcp::ContactSolver        contact_solver;
    std::vector<ContactState> state_guess;
    /// The exact cone: its solver, the facet rotation of each candidate at
    /// its last solve (the next step starts from it), and the statistics.
    lcp::ExactConeSolver exact_cone_solver;
    std::vector<double>  facet_angles;
    std::vector<double>  facet_angle_guess;
    ExactConeStatistics  cone_statistics;
    LcpStatistics        lcp_path_statistics;
    unsigned int         last_lcp_size = 0;
    /// The active set method: its solver; its preconditioners (set up by
    /// setup_schur_preconditioner() at the first use): the Schur complement
    /// of M~ on the contact DoFs C of the rigid-obstacle candidates (the
    /// inverse of W on all of them) and the one on their normal components
    /// alone, in the contact frames (the inverse of W_NN: for the normal
    /// rows when most closed contacts slide, and for frictionless contact),
    /// per body; with friction, the frames and normal slots that the
    /// normal ones are factorised from when a solve first asks for them
    /// (ensure_normal_schur_complements()), and the CPU seconds that took
    /// in this step (a set-up cost, not the contact problem's); their work
    /// vectors; the step matrices as a list;
    /// M~^{-1} H P of its last product (the velocity correction, valid if
    /// impulse_velocity_ready); the previous step's impulses (its warm
    /// start); the problem data on the candidates.
    lcp::ActiveSetSolver                              active_set_solver;
    std::vector<std::vector<types::global_dof_index>> schur_contact_dofs;
    std::vector<SparseSchurComplement>                schur_complements;
    std::vector<SparseSchurComplement>                normal_schur_complements;
    /// Per candidate against a rigid obstacle, its node's DoFs, the slots of
    /// its frame's rotated unknowns in the normal ones (normal first).
    std::vector<std::array<types::global_dof_index, 3>> frame_slots;
    /// With friction, per candidate: its frame's index among its body's
    /// normal frames (or invalid), its tangents' coordinates in that frame
    /// ([k][l]: tangent k + 1 on rotated unknown l + 1); per body the
    /// states (open, slide, stick; the skews) of the active set iteration;
    /// whether the active set method has used the exact normal rows, and
    /// when its problems start with them.
    std::vector<unsigned int>                         normal_frame_index;
    std::vector<std::array<std::array<double, 2>, 2>> normal_frame_tangents;
    std::vector<std::vector<unsigned char>>           normal_state;
    std::vector<std::vector<std::array<double, 3>>>   normal_skew;
    bool                                              exact_normal_rows = false;
    lcp::ExactRowsSchedule                            exact_rows_schedule;
    std::vector<std::vector<SparseSchurComplement::NodeFrame>> normal_frames;
    std::vector<std::vector<types::global_dof_index>>          normal_dofs;
    bool   schur_preconditioner_ready = false;
    bool   normal_schur_pending       = false;
    double normal_schur_seconds       = 0.;
    /// Or, when they are the cheaper products, the dense Schur complements
    /// S and S^{-1} of each body on C (then W = H^T S^{-1} H exactly), with
    /// their work vectors.
    std::vector<DenseSchurComplement> dense_schur;
    mutable std::vector<double>       dense_in, dense_out;
    mutable BlockVector<double> schur_nodal, schur_product, schur_interior;
    std::vector<const SparseMatrix<double> *> step_matrix_list;
    BlockVector<double>                       impulse_velocity;
    bool                                      impulse_velocity_ready = false;
    std::vector<double>                       last_impulses;
    std::vector<double> lcp_free_velocity, lcp_gap_terms, lcp_mu,
      lcp_impulse_guess, lcp_penalty;
    void
    setup_schur_preconditioner();
    /// Factorise the normal Schur complements if they are pending; whether
    /// they exist (the rotation may not fit the matrices' patterns).
    bool
    ensure_normal_schur_complements();
    /// The active set method's contact states (lcp::NormalStateUpdate):
    /// refactorise the operator of its rows with them if a contact's state
    /// changed or a slip moved by more than 0.05 (units of mu) since the
    /// last factorisation; empty: back to the normal Schur complements.
    void
    update_normal_states(const std::vector<unsigned char> &states,
                         const std::vector<double>        &slip);
    /// y = H^T S H x (or, if @p normal, the normal rows' S_N x_N) on the
    /// LCP candidates' rows; rows of candidates between two bodies get
    /// c_j x_j.
    void
    schur_preconditioner_product(const std::vector<double> &x,
                                 std::vector<double>       &y,
                                 const bool                 normal) const;
    /// target += H x for x on the LCP candidates' directions; y = H^T v.
    void
    add_lcp_columns(const std::vector<double> &x,
                    BlockVector<double>       &target) const;
    void
    lcp_column_dots(const BlockVector<double> &v, std::vector<double> &y) const;
    /// y = H^T S^{-1} H x, or H^T S H x if @p use_schur, with dense_schur.
    void
                        dense_schur_product(const std::vector<double> &x,
                                            std::vector<double>       &y,
                                            const bool                 use_schur) const;
    ActiveSetStatistics active_set_stats;
    /// Whether the step's problem on @p n candidates goes to the active set
    /// method.
    bool
    use_active_set(const unsigned int n) const;
    /// Whether the active set method's products W x are to be dense ones
    /// (dense_schur): dense_products_pay_off() at set-up.
    bool dense_contact_products = false;
    bool
    dense_products_pay_off() const;
    /**
     * Solve the problem on lcp_candidates by the active set method; fills
     * local_impulses, impulse_velocity and the contact states. False (and
     * counted as a fallback) if it did not converge.
     */
    bool
    solve_contact_active_set(StepReport &report);

    unsigned long long pivot_count  = 0;
    unsigned int       lcp_max_size = 0;

    BlockVector<double>
    make_block_vector() const;
    void
    solve_step_matrix(BlockVector<double> &rhs_and_solution) const;
    /// M~ = M + c_C C + c_K K of @p level_scheme for every body, factorised.
    void
    factorize_step_matrices(
      const TimeIntegrator                               &level_scheme,
      std::vector<std::unique_ptr<SparseMatrix<double>>> &matrices,
      std::vector<std::unique_ptr<SparseCholesky>>       &solvers) const;
    /**
     * The step with k h if no contact can act during it (see
     * do_time_step()): true and @p report filled if it was kept.
     */
    bool
    try_free_flight_step(StepReport &report);
    /// v^{i+1} set in next.velocity: complete the step with @p level_scheme.
    void
    complete_and_advance(const TimeIntegrator &level_scheme, const double time);
    /**
     * Compute the W columns of the candidates in @p candidates that do not
     * have them yet, with blocks of right-hand sides.
     */
    void
    ensure_delassus_columns(const std::vector<unsigned int> &candidates) const;
    /**
     * Solve the LCP on lcp_candidates; fills local_impulses. The result is
     * the solver's own, valid until the next solve.
     */
    const lcp::Result &
    solve_contact_lcp();
    /** The condensed contact problem on the current candidate set. */
    void
    build_contact_problem(lcp::ContactProblem &problem) const;
    /**
     * Write the contact problem on lcp_candidates to @p file_name (the
     * frictional-contact text format of Siconos numerics). Unless
     * @p problem_built (Lemke's solve has built it), W's missing columns
     * are formed and the problem is built first.
     */
    void
    dump_lcp(const std::string &file_name, const bool problem_built);
    /**
     * Write the problem of a step that was not solved to
     * <dump directory>/lcp_failure_step_<n>.dat: always when W is already
     * formed (@p w_formed), otherwise if it has at most 4000 rows or the
     * step is the one 'Dump LCP of step' names. Returns the sentence for
     * the failure message: where it went, or why not.
     */
    std::string
    write_unsolved_problem(const bool w_formed);
  };
} // namespace impactfe

#endif
