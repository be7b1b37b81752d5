// Heap allocations of MultibodySystem::do_time_step(), counted over a run
// (issue 11: "LCP without per-step allocation ... report the per-step
// allocation count in a test").
//
// Scene: an elastic block (plane strain, 6 x 3 Q1 cells) under gravity,
// thrown down and sideways onto a rigid plane, theta-Euler, 150 steps: it
// lands on one corner, rocks, and slides, so the candidate set and the
// contact states change.
// Run once with Coulomb friction (mu = 0.3: 2D LCPs, block pivoting on the
// contact states, Lemke as fallback) and once frictionless (normal
// directions only: Lemke warm-started from the active set).
//
// Every allocation of the program is counted (tests/allocation_counter.h)
// around each call of do_time_step(). A step may allocate when its storage
// has to grow: the first time a candidate enters an LCP (its Delassus
// columns are computed and stored) or when the contact problem or its
// solver need more room than ever before (lcp_memory_consumption() grows).
// Every other step, contact or not, must allocate nothing: not the free
// velocity solve, not the LCP, not the update. Growth must be rare (at most
// 15 of the 150 steps); how rare depends on the standard library's growth
// policy, so neither that number nor the counts are printed.

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/multibody_system.h>

#include <memory>

#include "../tests.h"

#include "../allocation_counter.h"
#include "elastic_block.h"

using namespace impactfe;
using namespace impactfe_tests;

namespace
{
  void
  run(const double mu)
  {
    const std::unique_ptr<ElasticBody<2>> block_pointer = make_elastic_block();
    ElasticBody<2>                       &block         = *block_pointer;
    block.set_body_force(Tensor<1, 2>({0., -9.81 * 1000.})); // rho g

    const TimeSteppingParameters time_stepping = block_time_stepping();
    ContactSolverParameters      solver;
    MultibodySystem<2>           system(time_stepping, solver, mu > 0. ? 2 : 1);
    throw_block_onto_plane(system, block, mu);
    system.enable_cost_breakdown();
    system.setup();

    unsigned int       n_contact_steps = 0, n_growing = 0, n_steady = 0;
    unsigned int       n_steady_contact = 0, largest_lcp = 0;
    unsigned int       candidates_with_columns = 0;
    std::size_t        lcp_storage        = system.lcp_memory_consumption();
    unsigned long long steady_allocations = 0;
    for (unsigned int step = 0; step < 150; ++step)
      {
        AllocationCount          count;
        const StepReport         report = system.do_time_step();
        const unsigned long long n      = count.count();

        const unsigned int new_columns =
          system.cost_breakdown().delassus_candidates;
        const std::size_t lcp_bytes = system.lcp_memory_consumption();
        const bool        grew =
          new_columns > candidates_with_columns || lcp_bytes > lcp_storage;
        candidates_with_columns = new_columns;
        lcp_storage             = lcp_bytes;
        largest_lcp             = std::max(largest_lcp, report.lcp_size);
        n_contact_steps += report.lcp_size > 0 ? 1 : 0;
        if (grew)
          ++n_growing;
        else
          {
            ++n_steady;
            n_steady_contact += report.lcp_size > 0 ? 1 : 0;
            steady_allocations += n;
          }
      }
    const std::string name = mu > 0. ? "mu = 0.3" : "frictionless";
    // the run exercises the contact path: most steps solve an LCP, and at
    // some step all 7 bottom nodes are in it (4 LCP rows per contact in the
    // facet form of the block pivoting, 1 when frictionless)
    check(n_contact_steps >= 100,
          name + ": at least 100 of the 150 steps solve an LCP",
          std::to_string(n_contact_steps));
    check(largest_lcp == 7 * (mu > 0. ? 4 : 1),
          name + ": the largest LCP holds all 7 bottom nodes",
          std::to_string(largest_lcp));
    // (how many steps grew the storage depends on the standard library's
    // growth policy: bounded here, not printed)
    check(n_growing <= 15 && n_steady_contact >= n_contact_steps - 15,
          name + ": at most 15 steps grew the storage",
          std::to_string(n_growing));
    check(steady_allocations == 0,
          name + ": allocations in the steps without growth = 0",
          "(" + std::to_string(steady_allocations) + " in " +
            std::to_string(n_steady) + " steps)");
  }
} // namespace



int
main()
{
  initlog();
  run(0.3);
  run(0.);
  return n_failed_checks == 0 ? 0 : 1;
}
