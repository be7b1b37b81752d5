// The statistics of how a run's contact LCPs were answered
// (MultibodySystem::lcp_statistics(), the "lcp" object of summary.json):
// checked against counts made independently from the step reports.
//
// Scene: the elastic block of step_allocations (6 x 3 Q1 cells, plane
// strain) thrown down and sideways onto a rigid plane, theta-Euler, 150
// steps; it lands on a corner, rocks and slides. Three runs:
// - mu = 0.3, warm start: 2D friction, so every LCP is first tried by
//   block pivoting on the last states (Lemke answers if it gives up);
// - frictionless, warm start: Lemke from the guessed basis, no block
//   pivoting;
// - frictionless, cold: every LCP by Lemke from the all-slack basis.
// Checked: the LCP solves are those the step reports count (one per step
// with an LCP, plus one per growth of the candidate set); the paths add up
// to them; only the paths that may pivot (cold Lemke, Lemke from the
// guess, cold after a rejected guess) have pivots; the block pivoting's counts
// are consistent (every answer took at least one linear solve, the reused
// factors are some of those solves). No count is printed: they depend on
// rounding through the contact states.

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/multibody_system.h>

#include <memory>

#include "../tests.h"

#include "elastic_block.h"

using namespace impactfe;
using namespace impactfe_tests;

namespace
{
  void
  run(const double mu, const bool warm_start)
  {
    const std::unique_ptr<ElasticBody<2>> block_pointer = make_elastic_block();
    ElasticBody<2>                       &block         = *block_pointer;
    block.set_body_force(Tensor<1, 2>({0., -9.81 * 1000.})); // rho g

    ContactSolverParameters solver;
    solver.warm_start = warm_start;
    MultibodySystem<2> system(block_time_stepping(), solver, mu > 0. ? 2 : 1);
    throw_block_onto_plane(system, block, mu);
    system.setup();

    unsigned int       reported_solves = 0, steps_with_pivots = 0;
    unsigned long long reported_pivots = 0;
    for (unsigned int step = 0; step < 150; ++step)
      {
        const StepReport report = system.do_time_step();
        if (report.lcp_size > 0)
          reported_solves += 1 + report.lcp_resolves;
        reported_pivots += report.lcp_pivots;
        steps_with_pivots += report.lcp_pivots > 0 ? 1 : 0;
      }

    using Path        = lcp::StartPath;
    const auto &stats = system.lcp_statistics();
    const auto  count = [&](const Path path) {
      return stats.by_path[static_cast<unsigned int>(path)];
    };
    const unsigned int pivoting_solves = count(Path::cold) +
                                         count(Path::guess_lemke) +
                                         count(Path::guess_fallback_cold);
    const std::string name =
      (mu > 0. ? std::string("mu = 0.3") : std::string("frictionless")) +
      (warm_start ? ", warm" : ", cold");

    check(reported_solves >= 100 && stats.solves == reported_solves,
          name + ": LCP solves = those of the step reports (>= 100)",
          std::to_string(stats.solves) + " against " +
            std::to_string(reported_solves));
    check(count(Path::guess_solved) + pivoting_solves +
              count(Path::block_pivoting) ==
            stats.solves,
          name + ": the paths add up to the solves");
    check(reported_pivots == system.total_pivots() &&
            (reported_pivots == 0 || pivoting_solves > 0) &&
            steps_with_pivots <= pivoting_solves,
          name + ": pivots only on the paths that pivot");
    if (mu > 0.)
      {
        check(stats.block_pivoting_attempts == stats.solves,
              name + ": block pivoting tried on every LCP");
        check(count(Path::block_pivoting) > 0 &&
                count(Path::block_pivoting) + stats.block_pivoting_gave_up ==
                  stats.block_pivoting_attempts,
              name + ": block pivoting answers + give-ups = attempts");
        check(stats.block_pivoting_linear_solves >=
                  count(Path::block_pivoting) &&
                stats.block_pivoting_reused_factors <=
                  stats.block_pivoting_linear_solves,
              name + ": at least one linear solve per answer, reuses among "
                     "them");
      }
    else
      check(stats.block_pivoting_attempts == 0 &&
              stats.block_pivoting_linear_solves == 0 &&
              count(Path::block_pivoting) == 0,
            name + ": no block pivoting without friction");
    if (!warm_start)
      check(count(Path::cold) == stats.solves,
            name + ": every LCP by cold Lemke");
    else
      check(count(Path::cold) < stats.solves,
            name + ": the guess serves some LCPs");
  }
} // namespace



int
main()
{
  initlog();
  run(0.3, true);
  run(0., true);
  run(0., false);
  return n_failed_checks == 0 ? 0 : 1;
}
