// Solving a contact problem by several routes, so that a solvable problem is
// not given up after the first form that fails, and telling an unsolvable
// problem (proven: its LCP is infeasible) from one we failed on.
//
// The routes, in order, each tried only if the previous ones did not give a
// verified solution (see doc/lcp.md, "Solvable means solved"):
//  1. the requested form (automatic: frictionless / Klarbring / facets);
//  2. the facet form (k = 2 in 2D, n_facets in 3D), cold Lemke. For a
//     positive semidefinite W it is copositive, and Lemke's method processes
//     it whenever q^T u >= 0 for every u in the polygonal cone with W u = 0
//     (e.g. q = H^T v + b with b_N >= 0 for W = H^T M^{-1} H);
//  3. the same form by the interior point method of interior_point.h (no
//     pivots: degenerate forms do not stop it). Its point warm-starts
//     Lemke (no cold start) for the exact basic solution; where that fails
//     a point that passes the contact verification (to 1e-8) is taken, on
//     forms of more than 4000 rows at once, on smaller ones after routes 4
//     and 5 did not find an exact one;
//  4. the same with a pivot tolerance 100 times smaller (near a singular
//     basis the default one hides true positive entries: false rays);
//  5. the same with another covering vector;
//  6. the facet form of W + eps ||W|| I (positive definite: Lemke always
//     processes it), then Lemke on the original facet form warm-started from
//     that solution's basis, reduced to linearly independent columns where
//     the basis is singular (redundant contacts);
// and, if none gave a verified solution, a feasibility test: the LCP of the
// linear program "z >= 0, M z + q >= 0" (skew-symmetric, copositive-plus) is
// solved by Lemke's method; a ray there proves that the facet form has no
// solution (Status::infeasible).
#ifndef impactfe_lcp_contact_routes_h
#define impactfe_lcp_contact_routes_h

#include <impactfe/lcp/contact_problem.h>

#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// One route tried by solve_contact_problem_by_routes().
    struct RouteAttempt
    {
      /// "requested", "copositive", "interior-point", "small-tolerance",
      /// "covering", "regularised" or "feasibility": which of the routes
      /// above.
      std::string  kind;
      std::string  route;
      Status       status = Status::numerical_failure;
      unsigned int pivots = 0;
      std::string  message;
    };

    /// What solve_contact_problem_by_routes() returns.
    struct RoutedContactSolution
    {
      /// The solution of the route that succeeded (or the last attempt).
      ContactSolution solution;
      /// Every route tried, in order.
      std::vector<RouteAttempt> attempts;
      /// Index into attempts of the successful route, -1 if none.
      int successful_route = -1;
    };

    /**
     * The LCP forms put W beside blocks of 1 and mu: a W far from unit size
     * makes Lemke's pivot tests compare numbers of different scales (false
     * rays). V / s = (W / s) P + V_free / s has the same impulses, so
     * @p scaled gets W, V_free and b_N divided by s = max |W|, and s is
     * returned; if max |W| is in [0.5, 2] (or W is zero) nothing is done and
     * 1 is returned.
     */
    double
    scale_to_unit_delassus(const ContactProblem &problem,
                           ContactProblem       &scaled);

    /**
     * Routes 1 to 6 above (route 1 is @p first_attempt if given), then (if all failed) the feasibility test. On
     * success solution.lcp.status == solved and solution.P the impulses; if
     * the facet form was proven infeasible, solution.lcp.status ==
     * Status::infeasible; otherwise the status of the last route. The
     * message lists every route and its outcome. Pivots are summed over the
     * routes.
     */
    RoutedContactSolution
    solve_contact_problem_by_routes(
      const ContactProblem  &problem,
      const ContactOptions  &options       = {},
      const ContactSolution *first_attempt = nullptr);

    /**
     * The contacts in groups that W does not couple: contacts a and b are in
     * one group if W has a nonzero entry between their rows, directly or
     * through other contacts (the connected components of the contact
     * graph; in a granular medium, the clusters of touching grains). Groups
     * are listed by their smallest contact, each sorted.
     */
    std::vector<std::vector<unsigned int>>
    independent_contact_groups(const ContactProblem &problem);

    /// The contacts @p contacts of @p problem (in that order) as a problem of
    /// their own, in @p sub.
    void
    restrict_contact_problem(const ContactProblem            &problem,
                             const std::vector<unsigned int> &contacts,
                             ContactProblem                  &sub);

    /// What solve_contact_problem_by_groups() returns.
    struct GroupedContactSolution
    {
      /**
       * P of the whole problem; lcp.status solved if every group was solved
       * (otherwise the status of the first group that was not), lcp.pivots
       * summed, lcp.verification.ok if every group's answer passed verify()
       * and lcp.verification.relative_error their largest; lcp.z the groups'
       * z one after the other (each in the variables of its own form), so
       * its size is the total size of the LCPs solved.
       */
      ContactSolution solution;
      /// Contacts in the LCPs solved (the candidates of the last round).
      unsigned int n_candidates = 0;
      /// Rounds of candidates: 1 if no contact left out was pushed in.
      unsigned int candidate_rounds = 0;
      /// Groups of the candidates in the last round.
      unsigned int n_groups = 0;
      /// Contacts of the largest group.
      unsigned int largest_group = 0;
    };

    /**
     * The contact problem reduced to the contacts that can touch and solved
     * group by group. In groups of independent_contact_groups() with more
     * than 500 contacts, candidates are the contacts that approach without
     * impulse (V_free,N + b_N < 0); the others get P = 0, and a contact that
     * the candidates' impulses push in (V_N + b_N < 0) becomes a candidate
     * for another round, until none does. The candidates are split by
     * independent_contact_groups(): the groups are independent problems,
     * each solved by solve_contact_problem_by_routes(). The impulses are a
     * solution of the whole problem (a contact left out is open with
     * V_N + b_N >= 0, which satisfies Signorini and Coulomb), at the cost of
     * the groups' LCPs instead of one LCP of the size of all contacts.
     */
    GroupedContactSolution
    solve_contact_problem_by_groups(const ContactProblem &problem,
                                    const ContactOptions &options = {});

    /**
     * For solve_contact_problem() with FrictionForm::automatic: @p failed is
     * its unsolved result (route 1, cold or warm); the other routes are
     * tried. Returns the routed solution, message "<failed message>; then
     * route 2 ...", pivots summed.
     */
    ContactSolution
    continue_with_other_routes(const ContactProblem  &problem,
                               const ContactOptions  &options,
                               const ContactSolution &failed);

    /**
     * Is there z >= 0 with M z + q >= 0? Lemke's method on the LCP of that
     * linear program (size 2n, M_LP = [0 -M^T; M 0], q_LP = (0, q)): M_LP is
     * skew-symmetric, hence copositive-plus, so a ray proves infeasibility
     * (Cottle-Pang-Stone 1992, Thm 4.4.13); otherwise a feasible z is found.
     * In floating point a ray is accepted as proof only if the x part of its
     * direction is a Farkas certificate to rounding: x >= 0, M^T x <= 0,
     * q^T x < 0. Returns the Lemke status on the LP (solved: feasible;
     * ray_termination: infeasible, certified; numerical_failure for a ray
     * whose certificate does not hold, and anything else: undecided).
     */
    Status
    lcp_feasibility(const DenseMatrix         &M,
                    const std::vector<double> &q,
                    const LemkeOptions        &options = {});

    /**
     * An LCP as lcp-solve solves it: Lemke cold, or (@p warm) from the
     * guess "z_i > 0 where q_i < 0"; a ray is reported as Status::infeasible
     * when lcp_feasibility() certifies that no z >= 0 has M z + q >= 0
     * (otherwise a ray says nothing about solvability unless M is
     * copositive-plus).
     */
    Result
    solve_lcp(const DenseMatrix         &M,
              const std::vector<double> &q,
              const bool                 warm,
              const LemkeOptions        &options = {});
  } // namespace lcp
} // namespace impactfe

#endif
