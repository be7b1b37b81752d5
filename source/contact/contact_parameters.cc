#include <deal.II/base/exceptions.h>

#include <impactfe/contact/contact_parameters.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <string>

namespace impactfe
{
  void
  ContactSolverParameters::declare_parameters(ParameterHandler &prm,
                                              const bool        distributed)
  {
    // contact_mpi reads the serial programs' files, so it declares every
    // entry; its help says which of them it does not use.
    const std::string serial_only =
      distributed ? " Serial programs only: contact_mpi reads it and ignores "
                    "it." :
                    "";
    prm.enter_subsection("Contact solver");
    prm.declare_entry(
      "Method",
      "automatic",
      Patterns::Selection("lemke|active set|automatic"),
      "How each step's contact problem is solved. 'lemke': Lemke's method "
      "on the dense Delassus matrix W (its columns cost one solve each, "
      "the pivoting O(n^3)). 'active set': a primal-dual active set "
      "(semismooth Newton) method whose linear systems are solved by "
      "GMRES with products W x = H^T M~^{-1} H x (one solve pair each), "
      "so W is never formed; frictionless, 2D, and 3D problems with the "
      "exact or the polygonal cone; its answer passes the same "
      "verification, and when it does not converge the step falls back to "
      "Lemke's method and says so (doc/lcp.md, 'Large contact sets'). "
      "'automatic': the active set method when at least 'Active set "
      "threshold' candidates can touch in a step, Lemke's method below; "
      "in 3D with friction the active set method at every size where its "
      "products are dense (see 'Dense Schur complement'), since Lemke's "
      "facet LCPs are the dearer ones there (doc/lcp.md, 'Which method "
      "automatic takes')." +
        std::string(distributed ?
                      " In contact_mpi 'automatic' is the active set method "
                      "at every size." :
                      ""));
    prm.declare_entry("Active set threshold",
                      "300",
                      Patterns::Integer(1),
                      "With 'Method = automatic': the number of contact "
                      "candidates in a step's problem from which the active "
                      "set method is used (in 3D with friction and dense "
                      "products: from one) [-]." +
                        serial_only);
    prm.declare_entry(
      "Dense Schur complement",
      "true",
      Patterns::Bool(),
      "With the active set method, when every candidate is against a "
      "rigid obstacle: compute the Schur complement S of M~ on the contact "
      "DoFs and its inverse as dense matrices, from one factorisation that "
      "eliminates those DoFs last, so that W x and the preconditioner are "
      "dense products instead of sparse solve pairs. Used only where that "
      "is the cheaper product (|C|^2 < 4 nnz(L), at most 1 GiB; typically "
      "3D) (doc/lcp.md, 'Large contact sets')." +
        serial_only);
    prm.declare_entry("Active set iterations",
                      "50",
                      Patterns::Integer(1),
                      "Active set (Newton) iterations of one contact solve "
                      "before it falls back to Lemke's method, unless a "
                      "front moves (Active set front iterations) [-].");
    prm.declare_entry(
      "Active set front iterations",
      "1000",
      Patterns::Integer(0),
      "Iterations of one contact solve allowed past 'Active set "
      "iterations' while a lift-off or stick-slip front moves: each "
      "iteration changes some contacts, but at most sqrt(contacts), and "
      "none that the iteration before changed. At most one per contact in "
      "any case; 0: none, the first limit is a hard one [-].");
    prm.declare_entry(
      "Exact normal rows after",
      "40",
      Patterns::Integer(0),
      "With the active set method and friction, in the linear solves in "
      "which (nearly) every closed contact slides: the GMRES iterations of "
      "one solve after which the preconditioner of the normal rows, "
      "W_NN^{-1} on all candidates, is replaced by the exact inverse of "
      "those rows at the current contact states (the closed contacts only, "
      "W_NN + mu W_NT D with the slip directions D) [-]. Later contact "
      "problems start with them on a schedule: none at first, 1, 3, 7, ... "
      "each time the first problem after such a hold switches again "
      "(lcp::ExactRowsSchedule). A change of the states then costs one "
      "sparse LU factorisation of the size of M~ (see 'Exact normal rows "
      "state lag'); it pays for large friction coefficients and many open "
      "candidates (doc/lcp.md, 'Large friction coefficients'). 0: from the "
      "first solve, in every problem." +
        serial_only);
    prm.declare_entry(
      "Exact normal rows state lag",
      "16",
      Patterns::Integer(0),
      "With the exact normal rows: how many contacts of a body may differ "
      "from the states those rows were last factorised at (a changed state, "
      "or a skew mu d that moved by more than 0.05) before they are "
      "factorised again [-]. In between, the preconditioner is exact for the states "
      "it was factorised at, which costs the linear solves a few GMRES "
      "iterations, far less than a factorisation at every change: on the "
      "2D slab 1 m long at 30 001 contacts, 16 took a fifth off the run "
      "(doc/lcp.md). 0: a factorisation at every change of the states." +
        serial_only);
    prm.declare_entry(
      "Largest Lemke fallback",
      "3000",
      Patterns::Integer(0),
      "The largest problem that falls back to Lemke's method when the "
      "active set method does not converge, in candidates of a 2D "
      "frictional problem [-]: the fallback's LCP may have at most 3 times "
      "this many unknowns (a 2D frictional candidate has 3, a frictionless "
      "one 1, a 3D one 'Number of facets' + 2, counted twice with the "
      "exact cone, which solves at least two such LCPs). A larger problem "
      "stops the run with a message naming the step: its dense W and "
      "Lemke's pivoting would take gigabytes and minutes to hours (3000 "
      "frictional 2D contacts: 3 min per step; 3D, exact cone, 8 facets: "
      "441 contacts 68 s, 1024 contacts more than 20 min).");
    prm.declare_entry("Warm start",
                      "true",
                      Patterns::Bool(),
                      "Start Lemke's method from the previous step's active "
                      "set (falls back to a cold start when that fails). The "
                      "answers are the same; only the pivot count changes." +
                        std::string(
                          distributed ?
                            " In contact_mpi: the active set method starts "
                            "from the last step's states and impulses; its "
                            "Lemke solves start cold." :
                            ""));
    prm.declare_entry("Dump LCP of step",
                      "-1",
                      Patterns::Integer(-1),
                      "Write the LCP of this step (1 = first step) to "
                      "<Output directory>/lcp_step_<n>.dat in the Siconos "
                      "text format, for replay with lcp-solve. -1: none. "
                      "A step that fails writes its problem to "
                      "lcp_failure_step_<n>.dat: always after Lemke's "
                      "method, and after the active set method if its W "
                      "has at most 4000 rows or this entry names the "
                      "step. Steps count h: a free-flight step k h "
                      "('Free-flight step factor') solves no contact "
                      "problem, and a step inside it writes nothing.");
    prm.declare_entry(
      "Friction cone",
      "exact",
      Patterns::Selection("exact|facets"),
      "3D friction only (in 2D the cone is exact): 'exact', the circular "
      "Coulomb cone |P_T| <= mu P_N (the active set method solves it "
      "directly; Lemke's method by facet LCPs re-aligned with the slip "
      "directions until the exact-cone error is below 'Exact cone "
      "tolerance', doc/lcp.md); 'facets', the polygonal cone of 'Number of "
      "facets' facets inscribed in it (Lemke: one LCP per step).");
    prm.declare_entry(
      "Number of facets",
      "8",
      Patterns::Integer(),
      "k [-], even, in [4, 256]: facets of the polygonal cone in "
      "3D, for both cone models (the exact one re-aligns "
      "them).");
    prm.declare_entry("Exact cone tolerance",
                      "1e-10",
                      Patterns::Double(),
                      "With 'Friction cone = exact': the residual of the "
                      "circular cone to reach in every contact problem [-], "
                      "relative to the largest impulse (doc/lcp.md, 'The "
                      "exact cone'). Must be > 0. A problem that does not "
                      "reach it is counted and reported (summary.json: "
                      "lcp.cone_not_converged) and fails the run's check" +
                        std::string(distributed ?
                                      "; contact_mpi stops at that step." :
                                      "."));
    prm.leave_subsection();
  }



  void
  ContactSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact solver");
    const std::string method_name = prm.get("Method");
    method                        = method_name == "lemke" ? Method::lemke :
                                    method_name == "active set" ? Method::active_set :
                                                                  Method::automatic;
    active_set_threshold          = prm.get_integer("Active set threshold");
    active_set_iterations         = prm.get_integer("Active set iterations");
    active_set_front_iterations =
      prm.get_integer("Active set front iterations");
    exact_normal_rows_after = prm.get_integer("Exact normal rows after");
    exact_normal_rows_state_lag =
      prm.get_integer("Exact normal rows state lag");
    dense_schur_complement = prm.get_bool("Dense Schur complement");
    largest_lemke_fallback = prm.get_integer("Largest Lemke fallback");
    warm_start             = prm.get_bool("Warm start");
    dump_step              = prm.get_integer("Dump LCP of step");
    friction_cone = lcp::cone_model_from_string(prm.get("Friction cone"));
    const int k   = prm.get_integer("Number of facets");
    exact_cone_tolerance = prm.get_double("Exact cone tolerance");
    prm.leave_subsection();
    AssertThrow(k >= 4 && k <= 256 && k % 2 == 0,
                ExcMessage("Contact solver: 'Number of facets' must be even "
                           "and in [4, 256] ('Friction cone = exact' for the "
                           "circular cone), got " +
                           std::to_string(k) + "."));
    n_facets = static_cast<unsigned int>(k);
    AssertThrow(dump_step == -1 || dump_step >= 1,
                ExcMessage("Contact solver: 'Dump LCP of step' must be -1 "
                           "(none) or a step number >= 1 (the first step is "
                           "1), got " +
                           std::to_string(dump_step) + "."));
    AssertThrow(exact_cone_tolerance > 0. &&
                  std::isfinite(exact_cone_tolerance),
                ExcMessage("Contact solver: 'Exact cone tolerance' must be "
                           "> 0, got " +
                           format_number(exact_cone_tolerance) + "."));
  }


  std::string
  ContactSolverParameters::write_unsolved_problem(
    const std::string                              &directory,
    const unsigned int                              step,
    const std::size_t                               rows,
    const bool                                      w_formed,
    const std::function<void(const std::string &)> &write) const
  {
    // Beyond a few thousand rows W's columns (a solve pair each) and its
    // text (about 20 bytes per entry) would cost more than the failed run.
    constexpr std::size_t largest_written_rows = 4000;
    if (!w_formed && rows > largest_written_rows &&
        dump_step != static_cast<int>(step))
      return " Its W (" + std::to_string(rows) + " x " + std::to_string(rows) +
             ") was not written to a file: a failed step writes W up to " +
             std::to_string(largest_written_rows) +
             " rows; 'Dump LCP of step' = " + std::to_string(step) +
             " writes it whatever its size.";
    const std::string name =
      directory + "/lcp_failure_step_" + std::to_string(step) + ".dat";
    try
      {
        write(name);
      }
    catch (const std::exception &e)
      {
        return " The problem could not be written to " + name + ": " + e.what();
      }
    return " The problem was written to " + name + " (replay: lcp-solve " +
           name + ").";
  }



  std::size_t
  ContactSolverParameters::lemke_lcp_size(const std::size_t  n_candidates,
                                          const unsigned int n_directions) const
  {
    const std::size_t per_candidate =
      n_directions == 1 ? 1 : (n_directions == 2 ? 3 : n_facets + 2);
    return n_candidates * per_candidate;
  }



  unsigned int
  ContactSolverParameters::lemke_lcps_per_problem(
    const unsigned int n_directions) const
  {
    // the exact cone: at least the first facet LCP and one re-aligned
    // with its slips (2 in each run of doc/lcp.md's measurement)
    return n_directions == 3 && friction_cone == lcp::ConeModel::exact ? 2 : 1;
  }



  bool
  ContactSolverParameters::lemke_fallback_allowed(
    const std::size_t  n_candidates,
    const unsigned int n_directions) const
  {
    return lemke_lcps_per_problem(n_directions) *
             lemke_lcp_size(n_candidates, n_directions) <=
           3 * static_cast<std::size_t>(largest_lemke_fallback);
  }



  std::string
  ContactSolverParameters::lemke_fallback_limit_text(
    const std::size_t  n_candidates,
    const unsigned int n_directions) const
  {
    const std::size_t  size  = lemke_lcp_size(n_candidates, n_directions);
    const unsigned int count = lemke_lcps_per_problem(n_directions);
    return "its fallback, Lemke's method on the dense W, would pivot on " +
           (count == 1 ? "an LCP of " + std::to_string(size) + " unknowns" :
                         std::to_string(count) +
                           " facet LCPs of the exact cone or more, " +
                           std::to_string(size) + " unknowns each (" +
                           std::to_string(count * size) + " in all)") +
           ", more than the " +
           std::to_string(3 *
                          static_cast<std::size_t>(largest_lemke_fallback)) +
           " unknowns that 'Largest Lemke fallback' = " +
           std::to_string(largest_lemke_fallback) +
           " allows (3 per candidate of a 2D frictional problem)";
  }
} // namespace impactfe
