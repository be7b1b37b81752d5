// A primal-dual active set (semismooth Newton) solver for the contact
// problem of a step, on W given only as a product: for contact sets too large
// for a dense Delassus matrix and Lemke's O(n^3) pivoting (issue 14,
// doc/lcp.md "Large contact sets").
#ifndef impactfe_lcp_active_set_h
#define impactfe_lcp_active_set_h

#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/contact_state.h>

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// y = W x on the local unknowns (per contact [N, T...]); W is never
    /// formed (in the time loop: one solve pair with M~ per product).
    using DelassusProduct =
      std::function<void(const std::vector<double> &x, std::vector<double> &y)>;

    /// Tells a normal preconditioner the contact states whose rows it is
    /// to invert: per contact 0 (open), 1 (closed, sliding) or 2 (closed,
    /// sticking: its tangential rows are then the preconditioner's too),
    /// and (n_directions - 1 entries, in the contact frame's tangents) mu d
    /// if it slides in direction d (P_T = mu P_N d; the polygonal cone: the
    /// vertex's or the edge normal's part of P_T), else zero. Empty
    /// vectors: back to its own approximation.
    using NormalStateUpdate =
      std::function<void(const std::vector<unsigned char> &states,
                         const std::vector<double>        &slip)>;

    /// Options of ActiveSetSolver::solve().
    struct ActiveSetOptions
    {
      /// Active-set (Newton) iterations before giving up; past them, the
      /// method goes on, for at most min(n_contacts, max_front_iterations)
      /// more, only while a front moves: each state update changes some
      /// contacts, at most sqrt(n_contacts), none that the update before
      /// changed, and is not a damped cycle (or changes none while the 3D
      /// slip directions still converge, or is followed by the tight solve
      /// that confirms settled states).
      unsigned int max_iterations       = 50;
      unsigned int max_front_iterations = 1000;
      /// Relative residual of the linear solve (GMRES) at the final states,
      /// and of the solves while the states still change (inexact Newton).
      double linear_tolerance         = 1e-12;
      double inexact_linear_tolerance = 1e-6;
      /// The final answer's linear residual in impulse units (c_k |r_k| of
      /// every unknown k), relative to the largest impulse, that iterative
      /// refinement aims at: GMRES's linear_tolerance is relative to the
      /// right-hand side, which stiff normal rows can make far larger than
      /// the impulses (thin bodies).
      double refinement_tolerance = 1e-10;
      /// Refinement passes at most (each: one GMRES solve of the residual).
      unsigned int max_refinements = 4;
      /// 3D: the slip directions of the sliding contacts settle when they
      /// move by less than direction_tolerance in an iteration (and by less
      /// than inexact_direction_tolerance before the final, exact solves).
      double direction_tolerance         = 1e-10;
      double inexact_direction_tolerance = 1e-4;
      /// With a NormalStateUpdate: the normal preconditioner inverts the
      /// normal rows at the current states from the first solve on (true),
      /// or once a solve with its own approximation has taken more than
      /// exact_normal_rows_after GMRES iterations (0: from the first
      /// solve), at the end of a restart cycle. Each inversion is a
      /// factorisation, worth some 15 to 30 GMRES iterations at 10^4
      /// contacts in 3D.
      bool         exact_normal_rows       = false;
      unsigned int exact_normal_rows_after = 40;
      /// GMRES iterations per linear solve, and its restart length.
      unsigned int max_linear_iterations = 2000;
      unsigned int restart               = 120;
      /// Verification tolerance (verify_contact_velocities()).
      double tolerance = 1e-8;
      /// 3D: 0 for the circular cone; k >= 3 for the polygonal cone of the
      /// facet form (P_T in conv{mu P_N d_j}, d_j at the angles 2 pi j / k).
      unsigned int n_facets = 0;
    };

    /**
     * When a sequence of active set solves (one per contact problem: per
     * time step, and again when the candidates grow) starts with
     * the exact normal rows (ActiveSetOptions::exact_normal_rows). A
     * problem whose solve switched to them by itself is followed by
     * problems that start with them, none at first, and 1, 3, 7, ... each
     * time the first problem without them switches again: a scene that
     * needs them in every solve pays the GMRES iterations before the
     * switch only a logarithmic number of times, and one that needed them
     * once does not pay a factorisation per state change from then on. On
     * the 2D slab 1 m long at 30 001 contacts one solve needs them (656
     * GMRES iterations without, 132 with); held for the later steps they
     * cost 3.8 s per step against 3.2 s with this schedule (doc/lcp.md).
     */
    class ExactRowsSchedule
    {
    public:
      /// Whether the next problem starts with the exact rows.
      bool
      start_exact() const;
      /// After a problem: whether its solve used the exact rows.
      void
      finish(const bool used_exact_rows);

    private:
      unsigned int hold = 0, period = 0;
      bool         just_released = false;
    };



    /// What a solve did.
    struct ActiveSetReport
    {
      /// The contact states settled and (P, V) passed the verification.
      bool                converged             = false;
      unsigned int        iterations            = 0;
      unsigned int        linear_iterations     = 0;
      unsigned int        operator_applications = 0;
      ContactVerification verification;
      /// exact_cone_error() of the answer (the standard measure, issue 12).
      double cone_error = 0.;
      /// Refinement passes of the final solve, and its linear residual in
      /// impulse units relative to the largest impulse (ActiveSetOptions::
      /// refinement_tolerance).
      unsigned int refinements     = 0;
      double       linear_residual = 0.;
      /// Whether the normal preconditioner inverted the states' normal rows
      /// (ActiveSetOptions::exact_normal_rows).
      bool exact_normal_rows = false;
      /// Why it did not converge (empty if it did).
      std::string message;
    };

    /**
     * Frictionless (n_directions = 1), 2D and 3D Coulomb (n_directions 2, 3;
     * in 3D the circular cone) contact problems V = q + W P,
     * w_N = V_N + b_N (the conventions of ContactProblem), solved by a
     * primal-dual active set method, the semismooth Newton method of the
     * complementarity functions
     *   P_N = max(0, P_N - c_N w_N),
     *   P_T = proj_{|P_T| <= mu zeta}(P_T - c_T V_T), zeta = P_N - c_N w_N
     * (Hueber, Stadler and Wohlmuth, SIAM J. Sci. Comput. 30 (2008)).
     * Given the states (open, stick, slip) and the slip directions d, one
     * linear system fixes P: P = 0 on open contacts, w_N = 0 on closed
     * ones, V_T = 0 on sticking ones and P_T = mu P_N d on sliding ones; it
     * is solved by GMRES on products with W, right-preconditioned by
     * @p preconditioner (an approximation of W^{-1}, applied to vectors
     * that are zero outside the unknowns and restricted to them). The
     * states and d = xi / |xi|, xi = P_T - c_T V_T, are then updated from
     * (P, V) with c = @p penalty (per row, ~ 1 / W_jj), until they settle.
     * In 2D d is the sign that slip_positive / slip_negative name; in 3D
     * the directions settle by a fixed point (direction_tolerance) and a
     * sliding contact is reported as slip_positive.
     *
     * With the polygonal cone (3D, ActiveSetOptions::n_facets = k) the
     * projection is onto the polygon conv{mu zeta d_j}, which is piecewise
     * linear: a sliding contact is on a vertex j (P_T = mu P_N d_j: P_T is
     * eliminated) or on an edge j, between d_j and d_{j+1}, with outward
     * normal n_j and tangent t_j (P_T = alpha t_j + mu P_N cos(pi/k) n_j,
     * alpha an unknown whose equation is t_j . V_T = 0). Every equation is
     * then a velocity row and linear at fixed states: no slip directions
     * to settle. The states are the vertex or edge of the projection of
     * xi (the "feature"); the answer passes the polygonal cone's
     * verification (verify_contact_velocities() with n_facets = k), the
     * conditions of the facet LCP that Lemke's method solves.
     * A state changes only if its condition is violated by more than
     * 1e-10 of the scale, so rounding cannot make it cycle; a sliding
     * contact whose slip turns round sticks first; a set of states met
     * again makes only the most violated part of the changes (halved at
     * each repetition).
     *
     * The answer is accepted only if it passes verify_contact_velocities()
     * with V computed by a product with the final P; the last product the
     * solver makes is that one (none if every contact is open: P = 0). An
     * answer that fails it has its states updated again, at most twice per
     * solve, with a margin of 1e-2 of the verification's tolerance on its
     * impulse scale (at least ten times the answer's linear residual), and the
     * iteration goes on if any changes. Otherwise (no settling within
     * max_iterations and the front iterations, settled states that fail the
     * verification, a linear solve that stalls) converged is false and the
     * caller falls back to Lemke's method.
     */
    class ActiveSetSolver
    {
    public:
      /**
       * @p state_guess (one per contact, or empty: states from P = 0) and
       * @p impulse_guess (the start of the first linear solve, or empty)
       * warm-start the method.
       *
       * @p normal_preconditioner (optional) approximates W_NN^{-1} on the
       * normal rows (its output on the other rows is not read). A linear
       * solve in which at most 1 % of the closed contacts stick uses it
       * for the normal rows, and c for the velocity rows of the tangents:
       * the full preconditioner restricted to the normal rows is far from
       * W_NN^{-1} when the tangents are free (eigenvalues of the
       * preconditioned operator up to 3 against 1.1, doc/lcp.md).
       *
       * @p normal_state_update (optional) lets the normal preconditioner
       * invert the operator of the normal rows and the sticking tangents'
       * rows at the current states exactly (the closed contacts only, W_NN
       * + mu W_NT D with the slip directions D: doc/lcp.md, "Large
       * friction coefficients"); it is called before each linear solve
       * that uses the normal preconditioner. Once it is used
       * (ActiveSetOptions::exact_normal_rows), every linear solve uses it,
       * however many contacts stick.
       */
      const ActiveSetReport &
      solve(const DelassusProduct           &W,
            const DelassusProduct           &preconditioner,
            const std::vector<double>       &penalty,
            const unsigned int               n_directions,
            const std::vector<double>       &free_velocity,
            const std::vector<double>       &gap_term,
            const std::vector<double>       &mu,
            const std::vector<ContactState> &state_guess,
            const std::vector<double>       &impulse_guess,
            const ActiveSetOptions          &options               = {},
            const DelassusProduct           &normal_preconditioner = {},
            const NormalStateUpdate         &normal_state_update   = {});

      /// P, V = q + W P and the states of the last solve.
      const std::vector<double> &
      impulses() const;
      const std::vector<double> &
      velocities() const;
      const std::vector<ContactState> &
      states() const;
      const ActiveSetReport &
      report() const;

    private:
      ActiveSetReport           last_report;
      std::vector<double>       P, V, x, rhs, work, c, full_in, full_out;
      std::vector<ContactState> state, new_state;
      /// Per contact, the unit direction d of P_T of a sliding contact
      /// (P_T = mu P_N d; 2D: +-1), and its update.
      std::vector<double> direction, new_direction;
      /// 3D: beta = mu P_N / |xi| of the last iterate, per contact.
      std::vector<double> beta, new_beta;
      unsigned int        dimension = 1;
      /// The polygonal cone (0: circular); per contact, the feature of a
      /// sliding contact on it (2 j: vertex j, 2 j + 1: edge j; -1 else).
      unsigned int     n_facets = 0;
      std::vector<int> feature, new_feature;
      /// Per contact, the size of the violation that changes its state;
      /// hashes of the sets of states met; the contacts that change.
      std::vector<double>       violation;
      std::vector<std::size_t>  seen;
      std::vector<unsigned int> changed;
      unsigned int              cycles = 0;
      /// Per contact, the state update of solve() that last changed it
      /// (0: none), to tell a moving front (ActiveSetOptions::
      /// max_iterations).
      std::vector<unsigned int> last_update;
      /// Unknown k is local row unknowns[k]; position[row] is k or -1.
      std::vector<unsigned int> unknowns;
      std::vector<int>          position;
      /// The true residual rhs - K x of the last GMRES solve, and a copy of
      /// the right-hand side and x during a refinement.
      std::vector<double> residual, saved_rhs, saved_x, saved_work,
        saved_residual;
      /// GMRES storage: the Krylov basis (restart + 1 vectors), Hessenberg.
      std::vector<std::vector<double>> basis;
      /// Flexible GMRES: the preconditioned basis vectors Z v_j.
      std::vector<std::vector<double>> preconditioned;
      std::vector<double> hessenberg, givens_cos, givens_sin, g, y_small;
      /// The P of the last product W P, if work still holds that product:
      /// a product of the same P (after the slip directions moved, or to
      /// start a refinement) is then not made again. After GMRES's first
      /// cycle, if it was the last, work is W P by recurrence
      /// (product_from_recurrence): good for the next solve's residual, but
      /// not the product the caller's W made last, nor a measured residual,
      /// so refine() makes that one anew.
      std::vector<double> product_P;
      bool                product_valid           = false;
      bool                product_from_recurrence = false;
      /// GMRES: W P of its starting x, and W E z_j of each preconditioned
      /// basis vector z_j of the first cycle (full length), so that the
      /// cycle's W P and true residual need no product.
      std::vector<double>              start_product;
      std::vector<std::vector<double>> basis_products;

      void
      expand(const std::vector<double> &x_unknowns,
             const std::vector<double> &mu,
             std::vector<double>       &P_full) const;
      /// Whether local row @p row is the unknown alpha of a contact on an
      /// edge of the polygonal cone (its equation is t_j . V_T = 0); the
      /// edge's tangent.
      bool
      is_edge_row(const unsigned int row) const;
      void
      edge_tangent(const unsigned int a, double &t1, double &t2) const;
      /// Whether local row @p row is a tangential row of a sliding contact
      /// in 3D, and its Newton equation (active_set.cc).
      bool
      is_slip_row(const unsigned int row) const;
      double
      slip_row(const unsigned int         row,
               const std::vector<double> &P_full,
               const std::vector<double> &WP,
               const std::vector<double> &mu) const;
      double
      slip_rhs(const unsigned int row, const std::vector<double> &q) const;
      /// out = K in: the Newton system's operator on the unknowns (leaves
      /// P = E in and work = W P). With @p fresh, work comes from a product
      /// of W even if it holds W P by recurrence.
      void
      apply_newton_operator(const DelassusProduct     &W,
                            const std::vector<double> &mu,
                            const std::vector<double> &in,
                            std::vector<double>       &out,
                            const bool                 fresh = false);
      /// out = K x from P = E x and work = W P.
      void
      newton_rows(const std::vector<double> &mu,
                  std::vector<double>       &out) const;
      /// The right-hand side of the Newton system at the current states and
      /// directions.
      void
      assemble_rhs(const std::vector<double> &q, const std::vector<double> &b);
      /// Iterative refinement of the final solve (refinement_tolerance);
      /// returns the final impulse residual relative to the largest impulse
      /// and leaves P, V = q + W P of the refined x.
      double
      refine(const DelassusProduct     &W,
             const DelassusProduct     &preconditioner,
             const std::vector<double> &q,
             const std::vector<double> &b,
             const std::vector<double> &mu,
             const ActiveSetOptions    &options);
      /// The normal preconditioner of the current solve (or nullptr).
      const DelassusProduct     *normal_preconditioner   = nullptr;
      const NormalStateUpdate   *normal_state_update     = nullptr;
      bool                       exact_normal_rows       = false;
      unsigned int               exact_normal_rows_after = 40;
      std::vector<unsigned char> normal_states;
      std::vector<double>        normal_slip;
      unsigned int
      gmres(const DelassusProduct     &W,
            const DelassusProduct     &preconditioner,
            const std::vector<double> &mu,
            const double               tolerance,
            const unsigned int         max_iterations,
            const unsigned int         restart,
            bool                      &stalled);
    };

  } // namespace lcp
} // namespace impactfe

#endif
