#include <deal.II/base/exceptions.h>

#include <impactfe/contact/contact_parameters.h>

namespace impactfe
{
  void
  ContactSolverParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact solver");
    prm.declare_entry("Warm start",
                      "true",
                      Patterns::Bool(),
                      "Start Lemke's method from the previous step's active "
                      "set (falls back to a cold start when that fails). The "
                      "answers are the same; only the pivot count changes.");
    prm.declare_entry("Dump LCP of step",
                      "-1",
                      Patterns::Integer(-1),
                      "Write the LCP of this step (1 = first step) to "
                      "<Output directory>/lcp_step_<n>.dat in the Siconos "
                      "text format, for replay with lcp-solve. -1: none. "
                      "The LCP of a step that fails is always written.");
    prm.leave_subsection();
  }



  void
  ContactSolverParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Contact solver");
    warm_start = prm.get_bool("Warm start");
    dump_step  = prm.get_integer("Dump LCP of step");
    prm.leave_subsection();
  }
} // namespace impactfe
