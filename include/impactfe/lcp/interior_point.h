// The Coulomb problem on the circular cone (2D and 3D; frictionless contacts
// too) by a primal-dual interior point method, then semismooth Newton: a
// route that needs no LCP, for the rank-deficient multibody problems on which
// the facet LCPs end in ray terminations. See doc/lcp.md, "The interior point
// route".
#ifndef impactfe_lcp_interior_point_h
#define impactfe_lcp_interior_point_h

#include <impactfe/lcp/contact_problem.h>

#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// Options of CoulombInteriorPointSolver.
    struct InteriorPointOptions
    {
      /// Target of exact_cone_residual() (impulse units, relative).
      double tolerance = 1e-10;
      /// Interior point iterations at the most.
      unsigned int max_iterations = 100;
      /// Semismooth Newton iterations at the most, after the interior point
      /// iteration, when its answer misses the tolerance.
      unsigned int max_newton_iterations = 20;
    };

    /// What the last CoulombInteriorPointSolver::solve() did.
    struct InteriorPointReport
    {
      unsigned int iterations        = 0;
      unsigned int newton_iterations = 0;
      /// exact_cone_residual() of the returned impulses.
      double residual = 0.;
      /// exact_cone_error() of the returned impulses (the standard measure).
      double cone_error = 0.;
      /// residual <= tolerance.
      bool converged = false;
      /// Why the interior point iteration stopped ("converged", "stalled",
      /// "iteration limit", "singular Newton matrix", "non-finite
      /// direction": a nearly singular Newton matrix gave a NaN; the last
      /// iterate is kept).
      std::string stop;
    };

    /**
     * The contact problem of a ContactProblem (n_directions 1, 2 or 3) with
     * the circular Coulomb cone K_c = {|P_T| <= mu_c P_N}, written as in De
     * Saxce's bipotential: with u = W P + q (q = V_free, b_N on the normal
     * rows) and u~_c = u_c + mu_c |u_T,c| e_N,
     *   K_c \ni P_c  \perp  u~_c \in K_c^*   for every contact c,
     * which is Signorini and Coulomb's law (sliding: P_T opposite to u_T on
     * the cone's boundary).
     *
     * With x_c = (P_N, P_T/mu_c) and y_c = (u~_N, mu_c u~_T) both cones are
     * the second-order cone L = {|x_T| <= x_0}, and the conditions read
     *   x, y in L,  x o y = 0 (Jordan product),
     *   y_N - |y_T| = (Q x + c)_N,  y_T = (Q x + c)_T,
     * with Q = E W E, c = E q, E = diag(1, mu_c, mu_c): a monotone
     * second-order cone complementarity problem (Q positive semidefinite)
     * but for the term |y_T| = mu_c |u_T,c|, which is local to the contact.
     * A contact without friction is a nonnegative orthant, P_T = 0.
     *
     * The primal-dual method (Nesterov-Todd scaling, Mehrotra's predictor
     * and corrector, an infeasible start at x = y = e) follows the central
     * path x o y = nu e; |y_T| is smoothed as sqrt(|y_T|^2 + nu^2) and its
     * derivative enters the Newton matrix Q + A G^2 (G the scaling, A the
     * identity with -y_T^T/|y_T| in the normal rows), which is nonsingular
     * whenever Q is positive semidefinite, also for the rank-deficient W of
     * redundant contacts (a box on four corners, granular packings) that
     * make the facet LCPs fail. Each iteration is one LU factorisation of
     * that matrix (LAPACK). The point it reaches is then refined by
     * semismooth Newton on the natural map of exact_cone_residual(), with
     * Levenberg-Marquardt steps (the Jacobian is singular with redundant
     * contacts) and a line search, when its residual misses the tolerance.
     *
     * The answer is returned as solved if it passes
     * verify_contact_solution() with the circular cone (Signorini, |P_T| <=
     * mu P_N, sliding contacts with P_T = -mu P_N V_T/|V_T|, all to 1e-8
     * relative), converged if exact_cone_residual() <= tolerance. W need
     * not be symmetric (some problem files' are not), only its symmetric
     * part positive semidefinite. Dense: for up to a few thousand unknowns.
     */
    class CoulombInteriorPointSolver
    {
    public:
      const ContactSolution &
      solve(const ContactProblem &problem, const InteriorPointOptions &options);

      const InteriorPointReport &
      report() const;

      /// The answer of the last solve().
      const ContactSolution &
      solution() const;

    private:
      ContactSolution     answer;
      InteriorPointReport last_report;
    };

    /**
     * The facet form of a contact problem (assemble_contact_lcp() with
     * FrictionForm::facets: per contact z = (P_N, beta_1..k, sigma),
     * P_T = sum_j beta_j d_j, k = options.n_facets in 3D and 2 in 2D, where
     * the polygon is the exact cone), or its frictionless LCP if
     * options.form is frictionless or there is no friction, by a primal-dual
     * interior point method (Mehrotra's predictor and corrector on
     * w = M z + q, z o w = nu e). The form's matrix is M = G^T W G + L, G
     * the map z -> P and L the local rows of sigma and mu P_N, so Newton's
     * matrix M + Z^-1 W_z is solved through (I + S W) u = G B^-1 g, with B =
     * L + Z^-1 W_z and S = G B^-1 G^T block diagonal: one LU of the order
     * of W (n_directions n_c), not of the form's ((k + 2) n_c). It needs no
     * pivots, so the degenerate facet LCPs of rank-deficient W, on which
     * Lemke's method can end in a ray (Siconos' KaplasTower: 13795 pivots
     * over the routes), do not stop it.
     *
     * The answer is solved only if its impulses pass
     * verify_contact_velocities() with the polygon (n_facets = k in 3D) to
     * 1e-8, with the velocity scale capped at 1e4 (|V_free| + |b_N|) as in
     * CoulombInteriorPointSolver; lcp.z and lcp.w are then the form's
     * variables (z_i > 0 warm-starts Lemke on the form), lcp.pivots = 0.
     */
    ContactSolution
    solve_facet_form_by_interior_point(const ContactProblem &problem,
                                       const ContactOptions &options,
                                       unsigned int max_iterations = 200);

    /**
     * The natural-map residual of the circular-cone problem in impulse
     * units: max over contacts of |P_c - proj_K(P_c - rho_c u~_c)|, with u =
     * W P + V_free (+ b_N), u~ = u + mu |u_T| e_N and rho_c = 1/W_cc (the
     * mean of the contact's diagonal of W), relative to the impulse scale
     * s_P = max(|P|, (|V_free| + |b_N|)/|W|) of verify_contact_solution()
     * (infinity norms). It is 0 exactly at a solution. Unlike
     * exact_cone_error() it does not compare impulses with velocities, whose
     * sizes can differ by orders of magnitude (a free velocity of 1 m/s
     * against impulses of a time step), so a tolerance on it is a tolerance
     * on the impulses. Infinite if P or the map has a NaN or an infinity.
     * @p u is work space.
     */
    double
    exact_cone_residual(const ContactProblem      &problem,
                        const std::vector<double> &P,
                        std::vector<double>       &u);
  } // namespace lcp
} // namespace impactfe

#endif
