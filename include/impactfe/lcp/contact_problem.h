// The condensed contact problem of one time step and its LCP forms:
// frictionless, 2D Klarbring (size 3 n_c) and faceted Coulomb cone (size
// (k + 2) n_c). See doc/lcp.md and the spec (schemes.md) for the equations.
#ifndef impactfe_lcp_contact_problem_h
#define impactfe_lcp_contact_problem_h

#include <impactfe/lcp/contact_state.h>
#include <impactfe/lcp/dense_matrix.h>
#include <impactfe/lcp/lemke.h>

#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /**
     * V = free_velocity + W P in the local frames of the contacts, ordered per
     * contact as [N, T1, (T2)]. Signorini: w_N = V_N + b_N >= 0, P_N >= 0,
     * w_N P_N = 0 (P_N >= 0 pushes apart). Coulomb: |P_T| <= mu P_N, and
     * P_T = -mu P_N V_T/|V_T| when V_T != 0.
     */
    struct ContactProblem
    {
      /// 1 (normal only), 2 (2D: n, t) or 3 (3D: n, t1, t2).
      unsigned int n_directions = 1;
      unsigned int n_contacts   = 0;
      /// Delassus operator, (n_contacts n_directions)^2.
      DenseMatrix W;
      /// Local relative velocities without impulse, same ordering as W.
      std::vector<double> free_velocity;
      /// b_N per contact (e.g. g/h): w_N = V_N + b_N.
      std::vector<double> gap_term;
      /// Friction coefficient per contact (ignored when n_directions == 1).
      std::vector<double> mu;
    };

    /// The LCP form of the contact problem.
    enum class FrictionForm
    {
      /// Normal block only (n_c unknowns); tangential impulses are zero.
      frictionless,
      /// 2D only: z = (P_N, lambda1, lambda2), needs W_TT invertible.
      klarbring,
      /// Polygonal Coulomb cone with k facets: z = (P_N, beta, sigma).
      facets,
      /// frictionless if n_directions == 1 or all mu == 0; klarbring in 2D
      /// (facets with k = 2 if W_TT is singular); facets in 3D.
      automatic
    };

    /// "frictionless", "klarbring", "facets", "automatic".
    std::string
    to_string(FrictionForm form);


    /// Options of solve_contact_problem().
    struct ContactOptions
    {
      FrictionForm form = FrictionForm::automatic;
      /// Facets of the polygonal cone in 3D (>= 3); in 2D k is always 2.
      unsigned int n_facets = 8;
      /// W_TT counts as singular if an LU pivot is below this times max|W_TT|.
      double singularity_tolerance = 1e-10;
      /// Block principal pivoting on contact states (2D friction with a
      /// state guess): at most this many linear solves before Lemke's method
      /// takes over.
      unsigned int max_block_pivoting_iterations = 25;
      LemkeOptions lemke;
    };

    /// An assembled LCP w = M z + q and how to map z back to impulses.
    struct ContactLCP
    {
      DenseMatrix         M;
      std::vector<double> q;
      FrictionForm        form     = FrictionForm::frictionless;
      unsigned int        n_facets = 0;
      /// W_TT^{-1} (Klarbring form only).
      DenseMatrix W_TT_inverse;
      /// Unit tangent directions of the facet form, per facet j the (d-1)
      /// components of d_j (same for all contacts).
      std::vector<std::vector<double>> directions;
      /// Why the form is what it is (e.g. the fallback from Klarbring).
      std::string message;
    };

    /// Throws std::invalid_argument if the sizes are inconsistent, data are
    /// not finite or a friction coefficient is negative.
    void
    check_contact_problem(const ContactProblem &problem);

    /// Assemble the LCP in the requested form (automatic resolved as above).
    ContactLCP
    assemble_contact_lcp(const ContactProblem &problem,
                         const ContactOptions &options = {});

    /// Local impulses P (ordering of W) from an LCP solution z.
    std::vector<double>
    impulses_from_lcp(const ContactProblem      &problem,
                      const ContactLCP          &lcp,
                      const std::vector<double> &z);

    /// Result of solve_contact_problem().
    struct ContactSolution
    {
      /// Local impulses, ordering of W; empty unless lcp.status == solved.
      std::vector<double> P;
      /// The LCP result (z in the variables of the form used).
      Result       lcp;
      FrictionForm form     = FrictionForm::frictionless;
      unsigned int n_facets = 0;
      /// The state of every contact at P (see contact_states()); the guess
      /// for the next time step. Empty unless solved.
      std::vector<ContactState> states;
      /// Linear solves of the block pivoting method (0 if it was not used).
      unsigned int block_pivoting_iterations = 0;
      /// Of these, the solves that reused the factors of the solver's last
      /// factorisation (the same states and W to the last bit, as in a time
      /// loop whose contacts keep their states): one right-hand side solved.
      unsigned int block_pivoting_reused_factors = 0;
      std::string  message;
    };

    /**
     * Assemble and solve with Lemke's method. With @p guess (in the LCP
     * variables of the form that will be used, e.g. z_i > 0 of the previous
     * step's lcp.z) the warm-started solver is used.
     */
    ContactSolution
    solve_contact_problem(const ContactProblem    &problem,
                          const ContactOptions    &options = {},
                          const std::vector<bool> *guess   = nullptr);

    /**
     * Solve with a guess of the contact states, e.g. the states of the
     * previous time step (ContactSolution::states); @p state_guess has one
     * entry per contact.
     *
     * 2D with friction: block principal pivoting on the contact states. For
     * given states the impulses solve one linear system taken directly from W
     * (rows V_N + b_N = 0 of the closed contacts and V_T = 0 of the sticking
     * ones; unknowns P_N of the closed and P_T of the sticking contacts,
     * P_T = -+mu P_N for the sliding ones): no W_TT^{-1}, no LCP matrix. The
     * point is written in the variables of the facet form with k = 2
     * (z = (P_N, beta, sigma)) and accepted only if it passes the same
     * verify() as a Lemke solution of that form (residual computed with W,
     * without forming M). Otherwise the states of the violating contacts are
     * changed (open contact penetrating: stick; P_N < 0: open; |P_T| > mu P_N:
     * slip; sliding against its velocity: stick), all at once, and the
     * system is solved again. After max_block_pivoting_iterations solves, a
     * repeated set of states or a singular system, Lemke's method solves the
     * problem in the requested form, warm-started from @p state_guess
     * (guess_from_states()). The block pivoting result has
     * lcp.start_path == StartPath::block_pivoting and lcp.pivots == 0.
     *
     * Frictionless and 3D problems: Lemke's method warm-started from the
     * guess mapped by guess_from_states().
     */
    ContactSolution
    solve_contact_problem(const ContactProblem            &problem,
                          const ContactOptions            &options,
                          const std::vector<ContactState> &state_guess);

    /**
     * The states at the impulses @p P (V = V_free + W P), with the scales of
     * verify_contact_solution(): open if P_N <= tol s_P; otherwise, in 2D
     * with friction, slip_positive / slip_negative if V_T > tol s_V / V_T <
     * -tol s_V, stick if not; frictionless and 3D: stick (closed).
     */
    std::vector<ContactState>
    contact_states(const ContactProblem      &problem,
                   const std::vector<double> &P,
                   double                     tolerance = 1e-8);

    /**
     * The LCP guess ("z_i > 0 expected") of @p lcp that corresponds to the
     * contact states: P_N for closed contacts; Klarbring: lambda_1 for
     * slip_positive, lambda_2 for slip_negative; facets: sigma for open and
     * sliding contacts and, in 2D, the facet opposite to the sliding
     * velocity.
     */
    std::vector<bool>
    guess_from_states(const ContactLCP                &lcp,
                      const std::vector<ContactState> &states);

    /// Signorini and Coulomb checked on (P, V = V_free + W P) directly.
    struct ContactVerification
    {
      /// max over contacts of -P_N, -w_N and |P_N w_N|, relative (see below).
      double max_signorini_violation = 0.;
      /// max over contacts of (|P_T| - mu P_N)^+, relative to s_P.
      double max_cone_violation = 0.;
      /// max over sliding contacts of |P_T + mu P_N V_T/|V_T||, relative to
      /// s_P: the deviation from the exact Coulomb law (a faceted cone in
      /// 3D does not reach zero here).
      double       max_sliding_violation = 0.;
      unsigned int n_separated           = 0;
      unsigned int n_sticking            = 0;
      unsigned int n_sliding             = 0;
      bool         ok                    = false;
    };

    /**
     * Velocities are measured relative to s_V = ||V_free||+||b_N||+||W|| ||P||,
     * impulses relative to s_P = max(||P||, (||V_free|| + ||b_N||)/||W||)
     * (all norms infinity norms). A contact is separated if P_N <= tol ||P||,
     * sticking if |V_T| <= tol s_V, sliding otherwise. ok if all violations
     * are <= tol.
     */
    ContactVerification
    verify_contact_solution(const ContactProblem      &problem,
                            const std::vector<double> &P,
                            double                     tolerance = 1e-8);

    /**
     * The checks of verify_contact_solution() for impulses @p P and
     * velocities @p V = q + W P computed elsewhere (without forming W), with
     * @p norm_W in place of ||W||_inf in the scales. The matrix-free caller
     * (the active set solver) passes ||W P||_inf / ||P||_inf, a lower bound
     * of ||W||_inf: the velocity scale s_V is then smaller and the velocity
     * checks stricter; the impulse scale is ||P||_inf unless P is nearly 0.
     *
     * In 3D with @p n_facets = k > 0 the cone is the polygonal one of the
     * facet form, P_T in conv{mu P_N d_j}, d_j at the angles 2 pi j / k in
     * the (t1, t2) plane: the cone check is max_j n_j . P_T <= mu P_N
     * cos(pi / k) (n_j the edges' outward normals), and a sliding contact
     * must maximise the dissipation over the polygon, -V_T . P_T = mu P_N
     * max_j (-V_T . d_j) (P_T in the normal cone's preimage of -V_T).
     */
    ContactVerification
    verify_contact_velocities(const unsigned int         n_directions,
                              const std::vector<double> &free_velocity,
                              const std::vector<double> &gap_term,
                              const std::vector<double> &mu,
                              const std::vector<double> &P,
                              const std::vector<double> &V,
                              const double               norm_W,
                              const double               tolerance = 1e-8,
                              const unsigned int         n_facets  = 0);

    /**
     * The exact-cone error of @p P, a standard measure of the friction
     * contact literature (as used by FCLib-based comparisons): with
     * u = V_free + W P (+ b_N on the normal rows) and, per contact,
     * u~ = u + mu |u_T| e_N,
     *   error = sqrt(sum_c |P_c - proj_K(P_c - u~_c)|^2)
     *           / max(|q|, |P|, |u|),
     * q = V_free (+ b_N), Euclidean norms, proj_K the projection on the
     * circular cone |P_T| <= mu P_N. It is 0 exactly at a solution of the
     * circular-cone problem; a polygonal-cone answer in 3D leaves the error
     * of its facets.
     */
    double
    exact_cone_error(const ContactProblem      &problem,
                     const std::vector<double> &P);

    /**
     * The same measure from @p q (V_free, b_N added to the normal rows) and
     * @p u = q + W P, for solvers that have W P but not W
     * (ActiveSetSolver); @p n_directions numbers per contact.
     */
    double
    exact_cone_error(const unsigned int         n_directions,
                     const std::vector<double> &q,
                     const std::vector<double> &u,
                     const std::vector<double> &P,
                     const std::vector<double> &mu);



    /**
     * The contact problems of a run, one per time step, solved with storage
     * kept from one solve to the next: the LCP matrix of the form, the Lemke
     * basis and its inverse, the blocks of the Klarbring form, the systems of
     * the block pivoting and the ContactSolution itself. Once problems of the
     * largest size have been solved, a solve on any of the usual paths (the
     * three forms, cold or warm Lemke, block pivoting) allocates no memory;
     * tests/lcp/allocations counts it. Only the fallback routes after a
     * failed solve (contact_routes.h) allocate.
     *
     * solve_contact_problem() is this class used once: the same solution,
     * bit for bit.
     */
    class ContactSolver
    {
    public:
      ContactSolver();
      ~ContactSolver();
      ContactSolver(ContactSolver &&) noexcept;
      ContactSolver &
      operator=(ContactSolver &&) noexcept;

      /// As solve_contact_problem(problem, options, guess). The reference
      /// stays valid until the next solve.
      const ContactSolution &
      solve(const ContactProblem    &problem,
            const ContactOptions    &options = {},
            const std::vector<bool> *guess   = nullptr);

      /// As solve_contact_problem(problem, options, state_guess).
      const ContactSolution &
      solve(const ContactProblem            &problem,
            const ContactOptions            &options,
            const std::vector<ContactState> &state_guess);

      /// The solution of the last solve.
      const ContactSolution &
      solution() const;

      /// Bytes of heap storage held (capacities). A solve on the usual
      /// paths allocates only if this grows.
      std::size_t
      memory_consumption() const;

      struct Workspace;

    private:
      std::unique_ptr<Workspace> workspace;
    };
  } // namespace lcp
} // namespace impactfe

#endif
