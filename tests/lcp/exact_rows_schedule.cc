// lcp::ExactRowsSchedule: which contact problems start with the exact
// normal rows, after solves that switched to them by themselves.
//
// Expected, from the schedule's definition (independent of the code): a
// problem that switches is followed by a hold of 0, 1, 3, 7, ... problems
// that start with the exact rows, the hold growing only when the first
// problem after a hold switches again. So a scene whose every solve needs
// them starts without them in problems 1, 2, 4, 8, 16, 32 and 64 of the
// first 100 (2^k), and one that needed them once starts with them never
// again.
#include <impactfe/lcp/active_set.h>

#include <string>
#include <vector>

#include "../tests.h"

using namespace impactfe::lcp;
using impactfe_tests::check;

int
main()
{
  impactfe_tests::initlog();

  // every solve that starts without the exact rows switches to them
  {
    ExactRowsSchedule         schedule;
    std::vector<unsigned int> without;
    for (unsigned int problem = 1; problem <= 100; ++problem)
      {
        const bool exact = schedule.start_exact();
        if (!exact)
          without.push_back(problem);
        schedule.finish(true);
      }
    std::string list;
    for (const unsigned int p : without)
      list += " " + std::to_string(p);
    dealii::deallog << "needed in every solve, problems started without:"
                    << list << std::endl;
    check(without == std::vector<unsigned int>{1, 2, 4, 8, 16, 32, 64},
          "needed in every solve: started without them 2^k times");
  }

  // needed once (problem 3), never again
  {
    ExactRowsSchedule schedule;
    unsigned int      with = 0;
    for (unsigned int problem = 1; problem <= 50; ++problem)
      {
        with += schedule.start_exact() ? 1 : 0;
        schedule.finish(problem == 3);
      }
    check(with == 0, "needed once: no problem starts with them");
  }

  // needed twice in a row (problems 5 and 6), then once much later (40):
  // problem 7 holds them, and the late switch starts a hold of 0 again
  {
    ExactRowsSchedule         schedule;
    std::vector<unsigned int> with;
    for (unsigned int problem = 1; problem <= 50; ++problem)
      {
        const bool exact = schedule.start_exact();
        if (exact)
          with.push_back(problem);
        schedule.finish(exact || problem == 5 || problem == 6 || problem == 40);
      }
    check(with == std::vector<unsigned int>{7},
          "needed in problems 5, 6 and 40: only problem 7 starts with them");
  }

  // never needed
  {
    ExactRowsSchedule schedule;
    bool              any = false;
    for (unsigned int problem = 1; problem <= 20; ++problem)
      {
        any = any || schedule.start_exact();
        schedule.finish(false);
      }
    check(!any, "never needed: never used");
  }
}
