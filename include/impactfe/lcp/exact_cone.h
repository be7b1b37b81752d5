// The circular (exact) Coulomb cone in 3D, reached through polygonal cones
// whose facets are re-aligned with each contact's slip direction: every
// iterate is a Lemke solution of a facet LCP, verified as every other one,
// and the iteration stops when the circular cone's natural-map residual,
// relative to the impulses, is below a tolerance. See doc/lcp.md, "The exact
// cone".
#ifndef impactfe_lcp_exact_cone_h
#define impactfe_lcp_exact_cone_h

#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/interior_point.h>

#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// How the Coulomb cone of a 3D contact is modelled.
    enum class ConeModel
    {
      /// The polygonal cone of ContactOptions::n_facets facets, inscribed
      /// in the circular one (the facet form, one LCP).
      facets,
      /// The circular cone |P_T| <= mu P_N, to ExactConeOptions::tolerance.
      exact
    };

    /// "facets", "exact".
    std::string
    to_string(ConeModel model);

    /// From "facets" or "exact"; throws std::invalid_argument otherwise.
    ConeModel
    cone_model_from_string(const std::string &name);

    /// The order in which ExactConeSolver tries its two routes.
    enum class ExactConeRoute
    {
      /// Facet LCPs re-aligned with the slip directions only.
      facets,
      /// Facet LCPs; the interior point route where they fail or stop
      /// short of the tolerance. For a sequence of problems (time steps),
      /// whose facets and states warm-start the next LCPs.
      facets_then_interior_point,
      /// The interior point route; the facet LCPs where it stops short of
      /// the tolerance. For cold problems (problem files).
      interior_point_then_facets,
      /// The interior point route only (any dimension, with or without
      /// friction).
      interior_point
    };

    /// "facets", "facets-then-interior-point", "interior-point-then-facets",
    /// "interior-point".
    std::string
    to_string(ExactConeRoute route);

    /// From the names of to_string(ExactConeRoute); throws
    /// std::invalid_argument otherwise.
    ExactConeRoute
    exact_cone_route_from_string(const std::string &name);

    /// Options of ExactConeSolver.
    struct ExactConeOptions
    {
      /**
       * Target of the residual (ExactConeReport::residual): the natural-map
       * residual |P_c - proj_K(P_c - u~_c / W_cc)| of the circular-cone
       * problem, largest over the contacts, relative to the impulse scale
       * s_P = max(|P|, (|V_free| + |b_N|)/|W|). It is a
       * tolerance on the impulses; exact_cone_error(), which compares
       * impulses with velocities, is reported beside it.
       */
      double tolerance = 1e-10;
      /**
       * If > 0, converged also needs exact_cone_error() <= this (the
       * standard measure, for the problem as given; lcp-solve's
       * --tolerance sets both). The two measures scale differently: on
       * BoxesStack1 of Siconos' collection a residual of 2e-14 comes with
       * an exact-cone error of 2e-8.
       */
      double cone_error_tolerance = 0.;
      /// Facet LCPs solved at the most.
      unsigned int max_iterations = 30;
      /// Which route first; the interior point route is
      /// CoulombInteriorPointSolver.
      ExactConeRoute route = ExactConeRoute::facets_then_interior_point;
    };

    /// What the last ExactConeSolver::solve() did.
    struct ExactConeReport
    {
      /// Facet LCPs solved (1 if the first answer already met the
      /// tolerance, or if the problem has no friction).
      unsigned int iterations = 0;
      /// exact_cone_error() of the returned impulses (the standard measure).
      double cone_error = 0.;
      /// The residual of ExactConeOptions::tolerance (impulse units).
      double residual = 0.;
      /// Whether residual <= tolerance and, if it is set,
      /// cone_error <= cone_error_tolerance (the residual is 0 for a solved
      /// problem without friction in 3D, whose LCP cone is exact).
      bool converged = false;
      /// Whether the answer is the interior point route's, and that route's
      /// iterations (interior point, then semismooth Newton) if it was tried.
      bool         interior_point            = false;
      unsigned int interior_point_iterations = 0;
      unsigned int newton_iterations         = 0;
    };

    /**
     * The circular-cone problem of a ContactProblem with n_directions == 3.
     *
     * Each contact c has its own rotation alpha_c of the tangent frame
     * (t1, t2), so that the facet directions of its polygonal cone are at
     * the angles alpha_c + 2 pi j / k. One iteration solves the facet LCP
     * of the problem written in the rotated frames (W' = R^T W R,
     * V_free' = R^T V_free, so the LCP module is used unchanged, with its
     * routes and verification) and maps the impulses back. Then each
     * closed contact that slides, or sticks on the boundary of its polygon,
     * turns its nearest facet onto the direction of P_T - rho V_T, with
     * rho = 1/W_TT of the contact: the predictor of the projection onto the
     * circular cone (as in Alart-Curnier's method). For an isolated contact
     * it is the direction of the exact P_T, so one turn suffices. At a
     * fixed point a sliding contact has its P_T on the facet direction
     * opposite to V_T, |P_T| = mu P_N, and a sticking one lies in the
     * circular cone: the circular-cone solution. Where a contact slid at
     * the last two iterates, its turn is a secant step on the residual of
     * this fixed point (angle = target(angle)), which converges faster when
     * W_TT is anisotropic or the contacts are coupled.
     * Rotating the nearest facet keeps the facet indices of the previous
     * answer, which warm-starts the next Lemke solve (the z_i > 0 of the
     * previous LCP).
     *
     * The iteration stops when the residual <= tolerance (converged),
     * when no facet moves any more, or after max_iterations. If a later
     * facet LCP fails, the last verified answer is returned, marked not
     * converged; if the first fails, its failure is returned.
     *
     * Frictionless problems and 2D problems (whose cone is exact already)
     * take one solve. Storage is kept from one solve to the next.
     */
    class ExactConeSolver
    {
    public:
      /**
       * @p initial_angles (one per contact, or empty: zero) start the
       * rotations, e.g. the facet_angles() of the previous time step;
       * @p state_guess, if not empty, warm-starts the first facet LCP.
       */
      const ContactSolution &
      solve(const ContactProblem            &problem,
            const ContactOptions            &options,
            const ExactConeOptions          &cone_options,
            const std::vector<double>       &initial_angles = {},
            const std::vector<ContactState> &state_guess    = {});

      const ExactConeReport &
      report() const;

      /// The rotations alpha_c of the last solve, one per contact.
      const std::vector<double> &
      facet_angles() const;

    private:
      void
      try_interior_point(const ContactProblem   &problem,
                         const ContactProblem   &unit_problem,
                         const ExactConeOptions &cone_options);

      ContactSolver              facet_solver;
      CoulombInteriorPointSolver interior_point_solver;
      bool                       interior_point_tried = false;
      /// The problem with W of unit size, and in the turned frames.
      ContactProblem      unit;
      ContactProblem      rotated;
      ContactSolution     solution;
      ExactConeReport     last_report;
      std::vector<double> angles;
      std::vector<double> velocity;
      /// Newton's impulses at the facet answer's states, kept only if they
      /// meet both targets.
      std::vector<double> polished_impulses;
      std::vector<bool>   guess;
      /// Per contact: the angle and residual of the last iterate, for the
      /// secant step, and whether they are valid (it slid then).
      std::vector<double> last_angle;
      std::vector<double> last_residual;
      std::vector<bool>   has_residual;
    };

    /// What solve_exact_cone_by_groups() returns.
    struct GroupedExactConeSolution
    {
      /// P of the whole problem; lcp.status solved if every group was
      /// solved (otherwise the first failure), lcp.pivots summed.
      ContactSolution solution;
      /// iterations: the most any group took; cone_error: of the whole
      /// problem; residual: the largest of the groups'; converged: every
      /// group converged.
      ExactConeReport report;
      /// Facet LCPs solved over all groups.
      unsigned int total_iterations = 0;
      unsigned int n_groups         = 0;
      /// Groups whose answer is the interior point route's.
      unsigned int n_interior_point = 0;
    };

    /**
     * The exact-cone problem split into the groups of contacts that W does
     * not couple (independent_contact_groups()), each solved by an
     * ExactConeSolver: what `lcp-solve --cone exact` does.
     */
    GroupedExactConeSolution
    solve_exact_cone_by_groups(const ContactProblem   &problem,
                               const ContactOptions   &options,
                               const ExactConeOptions &cone_options);

    /**
     * @p problem with the tangent frame of each contact c turned by
     * @p angles[c] in its (t1, t2) plane: W' = R^T W R, V_free' = R^T V_free.
     */
    void
    rotate_tangent_frames(const ContactProblem      &problem,
                          const std::vector<double> &angles,
                          ContactProblem            &rotated);
  } // namespace lcp
} // namespace impactfe

#endif
