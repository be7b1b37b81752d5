// The time step of a distributed body against rigid obstacles: the
// theta-schemes of the serial code (TimeIntegrator::theta_step_rule()),
// the mass/stiffness solves by AMG-preconditioned CG on Trilinos matrices,
// and the contact problem replicated on every rank and solved by the
// active set method with its products through distributed solves (issue
// 14, doc/parallel.md).
#ifndef impactfe_parallel_distributed_dynamics_h
#define impactfe_parallel_distributed_dynamics_h

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <impactfe/contact/contact_parameters.h>
#include <impactfe/lcp/active_set.h>
#include <impactfe/parallel/distributed_contact.h>
#include <impactfe/parallel/substructured_solver.h>
#include <impactfe/time_integration/time_integrator.h>

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  namespace distributed
  {
    /// What one step did.
    struct DistributedStepReport
    {
      double time = 0.;
      /// The step's length, in steps h (k for a free-flight step), and
      /// the coefficient of the loads' impulse over it (its length in
      /// seconds: the loads are constant).
      unsigned int n_substeps       = 1;
      double       load_coefficient = 0.;
      unsigned int lcp_size         = 0;
      unsigned int active_contacts  = 0;
      /// Sum over the contacts of P_N, and |sum of P_T| (as vectors) [N s].
      double normal_impulse = 0., tangential_impulse = 0.;
      /// Per body (DistributedContact::n_bodies()), the contact impulse on
      /// it in global coordinates: P on side A, -P on side B [N s].
      std::vector<std::array<double, 3>> body_impulse;
      /// Per body, the part of the last step's impulse that acts in this
      /// one, (1 - w)/w times it with w =
      /// TimeIntegrator::contact_force_weight(): with massless contact
      /// nodes (mass redistribution) and with Newmark. The step changes a
      /// body's momentum by body_impulse + carried_impulse (+ the loads').
      std::vector<std::array<double, 3>> carried_impulse;
      bool                               fallback = false;
    };

    /// Counts and worst values over the run.
    struct DistributedRunStatistics
    {
      unsigned int contact_problems = 0, active_set_iterations = 0,
                   products = 0, cg_iterations = 0, solves = 0, fallbacks = 0,
                   free_flight_steps = 0, lcp_resolves = 0, largest_lcp = 0;
      /// The worst verification violations of the accepted answers
      /// (relative, verify_contact_velocities()).
      double largest_signorini = 0., largest_cone = 0., largest_sliding = 0.;
      std::string last_fallback_reason;
      /// Keep the worst of @p check's violations.
      void
      record(const lcp::ContactVerification &check);
      /// Wall seconds in the solves with M~ (this rank).
      double solve_seconds = 0.;
      /// Wall seconds in the contact problems, their products W x (and
      /// the solves these make with the direct and AMG solvers) included
      /// (this rank).
      double contact_problem_seconds = 0.;
      /// The substructured solver: the groups of contact DoFs that its
      /// dense contact Schur complement does not couple (one per body
      /// with contacts, DenseSchurComplement::n_groups()).
      unsigned int contact_schur_groups = 0;
      /// The substructured solver's contact operator: "dense", "sparse"
      /// (SubstructuredSolver::ContactOperator), empty with the others.
      std::string contact_operator;
      /// The sparse operator's preconditioner: "Schur complement" (by
      /// solves with M~ pinned on the contact DoFs) or "contact block".
      std::string contact_preconditioner;
    };

    /**
     * Parameter subsection `Parallel solver`: how the solves with M~ are
     * made.
     */
    struct ParallelSolverParameters
    {
      enum class Solver
      {
        /// MUMPS (through Trilinos' Amesos), M~ factorised once.
        direct,
        /// CG preconditioned by ML's AMG, set up once.
        amg_cg,
        /// A sparse Cholesky factor per rank and a dense interface
        /// problem (SubstructuredSolver), factorised once; the contact
        /// problem's products are then dense.
        substructured
      };
      Solver solver = Solver::substructured;
      /// The substructured solver's contact operator (never factors_only).
      SubstructuredSolver::ContactOperator contact_operator =
        SubstructuredSolver::ContactOperator::automatic;
      /// With the sparse contact operator, the contact problem's
      /// preconditioner H^T X H: X = M~'s block on the contact DoFs, or
      /// their Schur complement S_C applied by a solve with M~ pinned on
      /// them; automatic: S_C in 3D with friction.
      enum class ContactPreconditioner
      {
        automatic,
        contact_block,
        schur_complement
      };
      ContactPreconditioner contact_preconditioner =
        ContactPreconditioner::automatic;
      /// Relative residual of each CG solve with M~.
      double       tolerance      = 1e-12;
      unsigned int max_iterations = 1000;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The step of schemes.md at the velocity level,
     *   M~ v^{i+1} = F~ + H P,  w_N = V_N^{i+1} + b_N >= 0 _|_ P_N >= 0,
     * and Coulomb's law, with M~, F~ and b_N from the serial TimeIntegrator
     * (its ThetaStepRule, or Newmark's NewmarkStepRule, whose a^0 solves
     * M a^0 = F - K u^0 - C v^0 by CG at the first step). W = H^T M~^{-1} H is
     * never formed: each product is one solve with M~, by MUMPS's
     * distributed factorisation of M~ (made once) or by CG with ML's AMG
     * (set up once), `Parallel solver/Solver`; or, with the substructured
     * solver, a dense product with the Schur complement of M~ on the
     * contact DoFs, which its factorisation gives. The candidates that can
     * touch (free normal velocity closing the gap, or active in the last step)
     * enter the contact problem; the active set method solves it,
     * preconditioned by H^T M~ H (the contact nodes' block of M~, one
     * distributed product), and its answer is verified. If it does not
     * converge, W of the candidates is built by products (n_c n_d solves) and
     * Lemke's method solves the problem (reported as a fallback), if its
     * LCP is within `Largest Lemke fallback` (ContactSolverParameters::
     * lemke_fallback_allowed()). `Method = lemke` always takes that
     * route (for small scenes and tests). With `Free-flight step factor`
     * k > 1, a step after one without impulses is tried with k h and its
     * own operators (try_free_flight_step()). With massless contact nodes
     * (DistributedElasticBody::redistribute_mass()) the step is the serial
     * one's (TimeIntegrator::set_massless_contact_nodes()): the last
     * impulse's carry in F~, the slip velocity's carry, and a massless
     * node's velocity (u^{i+1} - u^i) / h.
     */
    template <int dim>
    class DistributedImpactSolver
    {
    public:
      DistributedImpactSolver(const DistributedElasticBody<dim> &body,
                              const DistributedContact<dim>     &contact,
                              const TimeSteppingParameters      &time,
                              const ContactSolverParameters     &solver,
                              const ParallelSolverParameters    &linear_solver);

      /// The step matrices and the AMG preconditioner.
      void
      setup();

      /**
       * The contact's candidates were replaced (a contact search during the
       * run); @p previous[c] is new candidate c's index in the old list, or
       * numbers::invalid_unsigned_int: the successors keep their
       * predecessors' contact state and impulse. Their nodes must be among
       * the set-up's candidates' nodes or
       * DistributedContact::potential_contact_nodes() (the substructured
       * solver's factors are kept). What the last impulse carries into
       * the next step (mass redistribution, Newmark) is kept on the DoFs
       * and per body, so it does not depend on the candidates.
       */
      void
      candidates_changed(const std::vector<unsigned int> &previous);

      /// A uniform velocity on the cells with material id @p part (all
      /// cells by default), leaving the other DoFs as they are.
      void
      set_initial_velocity(
        const Tensor<1, dim>    &velocity,
        const types::material_id part = numbers::invalid_material_id);

      /**
       * One step: h, or k h (`Free-flight step factor`) after a step
       * without impulses if no contact can act in it and at most
       * @p max_substeps steps h remain.
       */
      const DistributedStepReport &
      do_time_step(const unsigned int max_substeps = 1);

      double
      time() const;
      const DistributedVector &
      displacement() const;
      const DistributedVector &
      velocity() const;
      /// Per candidate (replicated): whether it carries an impulse.
      const std::vector<bool> &
      active_set() const;
      /// H P of the last step on the DoFs (zero before the first and after
      /// a step without impulses); times the scheme's force_per_impulse()
      /// it is the nodal contact force. Collective.
      void
      contact_impulse_field(DistributedVector &field) const;
      const DistributedRunStatistics &
      statistics() const;
      const TimeIntegrator &
      integrator() const;

      /// 1/2 v.M v + 1/2 u.K u - f.u (f constant: its potential).
      double
      energy() const;

      /// The directory of the contact problems written for replay (`Dump
      /// LCP of step`, and those of failed steps).
      void
      set_dump_directory(const std::string &directory);

    private:
      const DistributedElasticBody<dim> &body;
      const DistributedContact<dim>     &contact;
      const ContactSolverParameters      solver_parameters;
      const ParallelSolverParameters     linear_parameters;

      /// A scheme with its step size, and what its steps solve with: M~,
      /// the velocity term of F~, and the solver of `Parallel solver`.
      struct StepOperators
      {
        std::unique_ptr<TimeIntegrator> scheme;
        /// The scheme's numbers: a theta-scheme's, or Newmark's.
        ThetaStepRule                     rule;
        NewmarkStepRule                   newmark_rule;
        DistributedMatrix                 step_matrix, velocity_matrix;
        double                            displacement_factor = 0.;
        TrilinosWrappers::PreconditionAMG amg;
        SolverControl                     direct_control;
        std::unique_ptr<TrilinosWrappers::SolverDirect> direct_solver;
        std::unique_ptr<SubstructuredSolver>            substructured_solver;
      };
      /// The step h; and with `Free-flight step factor` k > 1 the same
      /// scheme with k h, tried after a step without impulses.
      StepOperators                  fine;
      std::unique_ptr<StepOperators> coarse;
      unsigned int                   free_flight_factor     = 1;
      bool                           last_step_had_impulses = true;
      /// Newmark: the acceleration (a^0 made at the first step) and the
      /// step's prediction u~, v~.
      const bool        newmark;
      bool              acceleration_ready = false;
      DistributedVector acceleration, predicted_displacement,
        predicted_velocity;
      /// The contact DoFs of the substructured solver (each node's once),
      /// and each node's first slot among them (by its first DoF).
      std::vector<types::global_dof_index>            contact_dofs;
      std::map<types::global_dof_index, unsigned int> slot_of_node;
      /// With the sparse contact operator: M~'s block on the contact DoFs
      /// (compressed rows, on every rank), for the preconditioner H^T M~ H
      /// with no distributed product.
      std::vector<unsigned int> contact_block_start, contact_block_column;
      std::vector<double>       contact_block_value;
      /// With the sparse contact operator and its Schur complement
      /// preconditioner: the solver of M~ with the contact DoFs pinned
      /// (their rows and columns zero but a positive diagonal), the contact
      /// DoFs this rank owns (index in contact_dofs, offset in the vectors),
      /// and the preconditioner's vectors.
      std::unique_ptr<SubstructuredSolver>               pinned_solver;
      std::vector<std::pair<unsigned int, unsigned int>> owned_contact_dofs;
      DistributedVector                                  schur_in, schur_out;
      /// Mass redistribution: the offsets in this rank's part of the
      /// vectors of the massless DoFs it owns; every candidate (for the
      /// last impulse's carry, H P^i).
      std::vector<unsigned int> owned_massless_offsets;
      std::vector<unsigned int> all_candidates;
      /// Per candidate and node, the positions of its DoFs in the
      /// substructured solver's contact Schur complement (each node's DoFs
      /// once); and that product's vectors.
      std::vector<std::array<std::array<unsigned int, dim>,
                             DistributedContact<dim>::max_nodes>>
        contact_slots;
      /// H on the contact DoFs as rows (candidate c, direction k) of
      /// (slot, node weight x frame component) pairs, from contact_slots:
      /// the products' H x and H^T y walk these arrays instead of the
      /// candidates' records (which are ten times larger).
      std::vector<unsigned int> h_row_start, h_slot;
      std::vector<double>       h_value;
      unsigned int              n_contact_dofs = 0;
      std::vector<double>       dense_in, dense_out, contact_dof_values;
      /// v_free and correction (M~^{-1} H P) are not used (nor sized)
      /// with the substructured solver.
      DistributedVector u, v, u_old, v_old, v_free, rhs, correction,
        impulse_force, work;
      /// F~ relative to the body's translation (as FreeRhsOperator): the
      /// component of each owned DoF, one reference DoF per component
      /// (invalid: none; a damped body takes off none), the arguments
      /// less the translation, and the translation t of the last F~.
      std::vector<unsigned char>             owned_components;
      std::array<types::global_dof_index, 3> reference_dofs;
      DistributedVector     shifted_velocity, shifted_displacement;
      std::array<double, 3> free_translation = {{0., 0., 0.}};
      /// Takes t and s off @p x and @p y into the shifted vectors (t in
      /// free_translation); returns false (nothing done) for a damped body.
      bool
      take_off_translation(const DistributedVector &x,
                           const DistributedVector &y);
      /// x += t on the owned DoFs / on the contact DoFs' values.
      void
      add_translation(DistributedVector &x) const;
      void
      add_translation(std::vector<double> &contact_values) const;
      /// The last step's impulse as it acted: H P on the DoFs (with
      /// massless nodes, whose rows carry it) and per body in global
      /// coordinates; they outlive a contact search.
      DistributedVector                  last_impulse_field;
      std::vector<std::array<double, 3>> last_body_impulses;
      double                             current_time = 0.;
      DistributedStepReport              report;
      DistributedRunStatistics           stats;

      std::vector<bool>         active, in_lcp;
      std::vector<unsigned int> lcp_candidates;
      std::vector<double>       gap_terms, gap_work, normal_velocity,
        local_free_velocity, local_impulses, last_impulses, start_velocity;
      std::vector<ContactState> last_states;
      std::vector<double> lcp_q, lcp_b, lcp_mu, lcp_penalty, lcp_guess, lcp_P,
        lcp_correction;
      std::vector<ContactState> lcp_state_guess;
      lcp::ActiveSetSolver      active_set_solver;

      /// The matrices and the solver of @p level.
      void
      setup_operators(StepOperators &level);
      /// ML's AMG on M~ with the rigid translations as near null space.
      void
      setup_amg(StepOperators &level);
      /// The contact DoFs and each candidate's slots among them.
      void
      setup_contact_slots();
      /// Each candidate's slots among the contact DoFs, and the rows of H
      /// on them (h_row_start, h_slot, h_value).
      void
      find_contact_slots();
      /// The substructured solver of the level's M~.
      void
      setup_substructured_solver(StepOperators &level);
      /// Newmark: M a^0 = F - K u - C v (CG with Jacobi on M).
      void
      compute_initial_acceleration();
      /// x = M~^{-1} b with @p level's M~ (CG: counts the iterations).
      void
      solve_step_matrix(const StepOperators     &level,
                        const DistributedVector &b,
                        DistributedVector       &x);
      /**
       * After a step without impulses, try one of k h: if no candidate's
       * free velocity closes its gap under the Signorini condition of k h
       * (the test that puts candidates into the contact problem), no
       * contact acts in it and it is kept; otherwise nothing has changed,
       * and the step is made with h. As the serial
       * MultibodySystem::do_time_step().
       */
      bool
      try_free_flight_step();
      /// The free velocity of @p level's step (its local components, and
      /// v_free unless substructured) and the gap terms of its scheme.
      void
      start_step(const StepOperators &level);
      /// u and the time after @p level's step (v_old = v^i, v = v^{i+1}).
      void
      advance_displacement(const StepOperators &level);
      /// y = W x on lcp_candidates; correction = M~^{-1} H x.
      void
      delassus_product(const std::vector<double> &x, std::vector<double> &y);
      /// y = H^T S_C^{-1} H x (W x) or, with @p use_schur, H^T S_C H x,
      /// with the substructured solver's dense contact Schur complement S_C
      /// (no solve, no communication).
      /// @p on_dofs = H x on the contact DoFs (contact_slots) for the
      /// impulses @p x of lcp_candidates.
      void
      impulses_on_contact_dofs(const std::vector<double> &x,
                               std::vector<double>       &on_dofs) const;
      /// Per candidate and direction, the frame's components of
      /// @p on_dofs (values on the contact DoFs).
      void
      local_components(const std::vector<double> &on_dofs,
                       std::vector<double>       &local) const;
      /// Candidate @p c's component @p direction of @p on_dofs: the sum
      /// over its nodes of weight * frame[direction] . value.
      double
      frame_component(const unsigned int         c,
                      const unsigned int         direction,
                      const std::vector<double> &on_dofs) const;
      /// The substructured path's products on the contact DoFs: y = W x
      /// for lcp_candidates (S_C^{-1} dense, or partial substitutions with
      /// the sparse contact operator), or with @p use_schur the
      /// preconditioner: H^T S_C H (the dense operator's S_C, or by pinned
      /// solves) or H^T M~ H (the contact block).
      void
      contact_dof_product(const std::vector<double> &x,
                          std::vector<double>       &y,
                          const bool                 use_schur);
      /// Whether the substructured solver forms S_C densely.
      bool
      dense_contact_operator() const;
      /// contact_block_*: M~'s rows of the contact DoFs this rank owns,
      /// restricted to the contact DoFs, gathered on every rank.
      void
      setup_contact_block();
      /// y = S_C x on the contact DoFs (replicated vectors): b = M~ x with
      /// b_C = 0, z = the pinned solve of b, y = (M~ (x - z))_C.
      void
      schur_complement_product(const std::vector<double> &x,
                               std::vector<double>       &y);
      /// Per body, the impulses of @p local (per candidate and
      /// direction) in global coordinates, times @p factor.
      std::vector<std::array<double, 3>>
      body_impulses(const std::vector<double> &local,
                    const double               factor) const;
      /// Solve the contact problem of lcp_candidates into lcp_P; whether
      /// it took the active set route (else: Lemke, fallback or chosen).
      void
      solve_contact_problem();
      void
      solve_by_lemke();
      /// W of lcp_candidates column by column (n n_d solves, or products on
      /// the contact DoFs with the substructured solver), symmetrised, with
      /// the step's free velocity, gap terms and friction coefficients.
      /// Collective.
      void
      build_contact_problem(lcp::ContactProblem &problem);
      /// Rank 0 writes the step's contact problem to @p file for replay
      /// with lcp-solve, forming W first unless @p built is given.
      /// Collective; throws on every rank if the file cannot be written.
      void
      write_contact_problem(const std::string         &file,
                            const lcp::ContactProblem *built);
      /// The end of the message of a failed step: where its problem was
      /// written, or why it was not (W is formed for the file only up to
      /// 4000 rows, or when `Dump LCP of step` names the step). Collective.
      std::string
      write_unsolved_problem(const lcp::ContactProblem *built);
      /// `Dump LCP of step` writes lcp_step_<n>.dat here, a failed step
      /// lcp_failure_step_<n>.dat; n counts steps h, a free-flight step k.
      std::string  dump_directory = ".";
      unsigned int step_number    = 0;
    };
  } // namespace distributed
} // namespace impactfe

#endif
