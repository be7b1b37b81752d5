#ifndef impactfe_contact_contact_parameters_h
#define impactfe_contact_contact_parameters_h

#include <deal.II/base/parameter_handler.h>

#include <impactfe/lcp/exact_cone.h>

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
    /// dense Delassus matrix, the matrix-free active set method
    /// (lcp/active_set.h, frictionless and 2D problems; Lemke is the
    /// fallback), or the active set method from active_set_threshold
    /// candidates on.
    enum class Method
    {
      lemke,
      active_set,
      automatic
    };
    Method       method                = Method::automatic;
    unsigned int active_set_threshold  = 300;
    unsigned int active_set_iterations = 50;
    /// GMRES iterations of one linear solve after which the normal rows'
    /// preconditioner inverts them exactly at the contact states (0: from
    /// the first solve).
    unsigned int exact_normal_rows_after = 40;
    /// Active set products with the dense Schur complement of M~ on the
    /// contact DoFs where that is cheaper (dynamics/schur_complement.h).
    bool dense_schur_complement = true;
    /// Largest problem (candidates) that may fall back to Lemke's method
    /// when the active set method does not converge; larger ones stop the
    /// run with a message instead of a dense W of that size.
    unsigned int largest_lemke_fallback = 3000;
    /// Start Lemke from the previous step's active set.
    bool warm_start = true;
    /// Step whose LCP is written to the output directory (-1: none). A step
    /// whose LCP fails is always written.
    int dump_step = -1;
    /// 3D friction: the circular cone (to exact_cone_tolerance) or the
    /// polygonal one of n_facets facets.
    lcp::ConeModel friction_cone        = lcp::ConeModel::exact;
    unsigned int   n_facets             = 8;
    double         exact_cone_tolerance = 1e-10;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };
} // namespace impactfe

#endif
