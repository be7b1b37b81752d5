#ifndef impactfe_contact_contact_parameters_h
#define impactfe_contact_contact_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <impactfe/lcp/exact_cone.h>

#include <cstddef>
#include <functional>
#include <string>

namespace impactfe
{
  using namespace dealii;

  /**
   * Parameter subsection `Contact solver`: how each step's LCP is solved and
   * what is kept for replay with lcp-solve.
   */
  struct ContactSolverParameters
  {
    /// How each step's contact problem is solved: Lemke's method on the
    /// dense Delassus matrix, the active set method (lcp/active_set.h,
    /// W as a product; Lemke is the fallback), or automatic: the active
    /// set method from active_set_threshold candidates on, and in 3D with
    /// friction wherever W x is a dense product
    /// (MultibodySystem::use_active_set()).
    enum class Method
    {
      lemke,
      active_set,
      automatic
    };
    Method       method                = Method::automatic;
    unsigned int active_set_threshold  = 300;
    unsigned int active_set_iterations = 50;
    /// Iterations past active_set_iterations while a front moves
    /// (lcp::ActiveSetOptions::max_front_iterations).
    unsigned int active_set_front_iterations = 1000;
    /// GMRES iterations of one linear solve after which the normal rows'
    /// preconditioner inverts them exactly at the contact states (0: from
    /// the first solve).
    unsigned int exact_normal_rows_after = 40;
    /// Contacts whose states may differ from those at which the exact
    /// normal rows were last factorised before they are factorised again.
    unsigned int exact_normal_rows_state_lag = 16;
    /// Active set products with the dense Schur complement of M~ on the
    /// contact DoFs where that is cheaper (dynamics/schur_complement.h).
    bool dense_schur_complement = true;
    /// Largest problem that may fall back to Lemke's method when the
    /// active set method does not converge, in candidates of a 2D
    /// frictional problem: the fallback's LCPs may have at most
    /// 3 largest_lemke_fallback unknowns (lemke_fallback_allowed()). Larger
    /// ones stop the run with a message instead of a dense W and a
    /// pivoting of that size.
    unsigned int largest_lemke_fallback = 3000;
    /// Start Lemke from the previous step's active set.
    bool warm_start = true;
    /// Step whose LCP is written to the output directory (-1: none). A step
    /// that fails is written too (MultibodySystem::write_unsolved_problem()).
    int dump_step = -1;
    /// 3D friction: the circular cone (to exact_cone_tolerance) or the
    /// polygonal one of n_facets facets.
    lcp::ConeModel friction_cone        = lcp::ConeModel::exact;
    unsigned int   n_facets             = 8;
    double         exact_cone_tolerance = 1e-10;

    /// Unknowns of the LCP that Lemke's method solves for @p n_candidates
    /// contacts with @p n_directions directions (1: frictionless): per
    /// candidate 1 (frictionless), 3 (2D, Klarbring's form) or
    /// n_facets + 2 (3D, the facet form; the exact cone solves a sequence
    /// of such LCPs).
    std::size_t
    lemke_lcp_size(const std::size_t  n_candidates,
                   const unsigned int n_directions) const;

    /// How many such LCPs a fallback solves at least: 2 for the exact
    /// cone in 3D (facet LCPs re-aligned with the slips), else 1.
    unsigned int
    lemke_lcps_per_problem(const unsigned int n_directions) const;

    /// Whether those LCPs' unknowns, summed, are within 'Largest Lemke
    /// fallback'.
    bool
    lemke_fallback_allowed(const std::size_t  n_candidates,
                           const unsigned int n_directions) const;

    /// The end of the message of a refused fallback: the LCP's size and
    /// the limit.
    std::string
    lemke_fallback_limit_text(const std::size_t  n_candidates,
                              const unsigned int n_directions) const;

    /**
     * The end of the message of step @p step that was not solved: its
     * problem, of @p rows rows, written by @p write to
     * <@p directory>/lcp_failure_step_<n>.dat (always when W is already
     * formed, @p w_formed; otherwise up to 4000 rows, or when 'Dump LCP of
     * step' names the step), or why it was not written. An error of the
     * write is told, not thrown: the failure's own message comes first.
     */
    std::string
    write_unsolved_problem(
      const std::string                              &directory,
      const unsigned int                              step,
      const std::size_t                               rows,
      const bool                                      w_formed,
      const std::function<void(const std::string &)> &write) const;

    /// @p distributed: the help of contact_mpi, which declares the same
    /// entries and says which of them it ignores.
    static void
    declare_parameters(ParameterHandler &prm, const bool distributed = false);
    void
    parse_parameters(ParameterHandler &prm);
  };
} // namespace impactfe

#endif
