// The LCP solvers of a time loop allocate no memory once they have seen
// problems of the largest size (issue 11: "LCP without per-step allocation").
//
// A time loop solves one contact problem per step; ContactSolver and
// LemkeSolver keep their storage (the LCP matrix of the form, the Lemke
// basis and its inverse, the Klarbring blocks, the block pivoting systems,
// the solution) from one solve to the next. Here every allocation of the
// program is counted (tests/allocation_counter.h replaces malloc and its
// relatives), over sequences of problems like those of a run: the same
// Delassus operator W = A A^T + 0.1 I (positive definite, as H^T M~^{-1} H),
// free velocities that change from step to step, and the states of the
// previous solve as the guess of the next, as MultibodySystem does.
//
// Storage is only ever grown, never given back. Per scenario:
//  - a solve after which memory_consumption() has not grown must have
//    allocated nothing (on every path: forms, cold and warm Lemke, block
//    pivoting, messages);
//  - the sequence solved a second time with the same solver (its storage
//    now large enough) allocates nothing at all.
// Each solution must also equal, bit for bit, the one of the one-shot
// solve_contact_problem() / solve_lemke() with the same input and guess:
// reusing storage changes no number. That includes the block pivoting's
// factors, which a solve reuses when the states and W are those of the
// last factorisation (at least once in scenario 2): the one-shot solve
// factorises afresh.
//
// Scenarios (each path of the time loop):
//  1. frictionless, 40 contacts, Lemke warm-started from the states;
//  2. 2D Coulomb (mu = 0.3), 30 contacts, block pivoting on the states;
//  3. 2D Coulomb in the Klarbring form, cold Lemke (no guess);
//  4. 3D Coulomb, 12 contacts, facet form k = 8, with the states as guess
//     (3D states say only open / closed: the guessed basis is rejected and
//     cold Lemke solves, the fallback path);
//  5. LemkeSolver alone on random P-matrix LCPs, cold and warm.
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/lemke.h>

#include "../tests.h"

#include "../allocation_counter.h"
#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using dealii::deallog;
using impactfe::ContactState;
using namespace impactfe_tests;

namespace
{
  /// W = A A^T + 0.1 I with A (m x m) uniform in [-1, 1) / sqrt(m).
  DenseMatrix
  delassus_like(const unsigned int m, lcp_test::Rng &rng)
  {
    DenseMatrix A(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        A(i, j) = rng.uniform(-1., 1.) / std::sqrt(double(m));
    DenseMatrix W(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        {
          double s = (i == j ? 0.1 : 0.);
          for (unsigned int k = 0; k < m; ++k)
            s += A(i, k) * A(j, k);
          W(i, j) = s;
        }
    return W;
  }

  /// The problems of a "run": W fixed, V_free and b_N changing per step.
  std::vector<ContactProblem>
  run_of_problems(const unsigned int  n_contacts,
                  const unsigned int  n_directions,
                  const double        mu,
                  const unsigned int  n_steps,
                  const std::uint64_t seed)
  {
    lcp_test::Rng      rng(seed);
    ContactProblem     base;
    const unsigned int m = n_contacts * n_directions;
    base.n_contacts      = n_contacts;
    base.n_directions    = n_directions;
    base.W               = delassus_like(m, rng);
    base.mu.assign(n_contacts, mu);
    std::vector<double> v0(m), dv(m), b0(n_contacts);
    for (unsigned int i = 0; i < m; ++i)
      {
        v0[i] = rng.uniform(-1., 0.5);
        dv[i] = rng.uniform(-0.2, 0.2);
      }
    for (unsigned int c = 0; c < n_contacts; ++c)
      b0[c] = rng.uniform(0., 0.2);
    std::vector<ContactProblem> run(n_steps, base);
    for (unsigned int s = 0; s < n_steps; ++s)
      {
        run[s].free_velocity.resize(m);
        run[s].gap_term.resize(n_contacts);
        for (unsigned int i = 0; i < m; ++i)
          run[s].free_velocity[i] = v0[i] + dv[i] * std::sin(0.7 * s + i);
        for (unsigned int c = 0; c < n_contacts; ++c)
          run[s].gap_term[c] = b0[c] * std::cos(0.3 * s + c);
      }
    return run;
  }

  bool
  same(const ContactSolution &a, const ContactSolution &b)
  {
    return a.P == b.P && a.states == b.states && a.lcp.z == b.lcp.z &&
           a.lcp.w == b.lcp.w && a.lcp.status == b.lcp.status &&
           a.lcp.pivots == b.lcp.pivots &&
           a.lcp.start_path == b.lcp.start_path && a.form == b.form &&
           a.block_pivoting_iterations == b.block_pivoting_iterations &&
           a.message == b.message;
  }

  enum class Guess
  {
    none,
    states
  };

  void
  check_run(const std::string                 &name,
            const std::vector<ContactProblem> &run,
            const ContactOptions              &options,
            const Guess                        guess_kind,
            const StartPath                    path)
  {
    ContactSolver                   solver;
    const std::vector<ContactState> open(run.front().n_contacts,
                                         ContactState::open);
    std::vector<ContactState>       guess                      = open;
    unsigned long long              allocations_without_growth = 0;
    unsigned int n_solved = 0, n_same = 0, n_block = 0, n_warm = 0,
                 n_fallback = 0, n_cold = 0, n_reused = 0;
    std::size_t largest = 0, bytes = solver.memory_consumption();
    for (std::size_t s = 0; s < run.size(); ++s)
      {
        AllocationCount        count;
        const ContactSolution &solution =
          guess_kind == Guess::states ? solver.solve(run[s], options, guess) :
                                        solver.solve(run[s], options);
        const unsigned long long n = count.count();
        if (solver.memory_consumption() == bytes)
          allocations_without_growth += n;
        bytes = solver.memory_consumption();

        // the one-shot solve with the same input
        const ContactSolution reference =
          guess_kind == Guess::states ?
            solve_contact_problem(run[s], options, guess) :
            solve_contact_problem(run[s], options);
        n_same += same(solution, reference) ? 1 : 0;
        n_solved += solution.lcp.status == Status::solved ? 1 : 0;
        n_block += solution.lcp.start_path == StartPath::block_pivoting ? 1 : 0;
        n_reused += solution.block_pivoting_reused_factors > 0 ? 1 : 0;
        n_warm += (solution.lcp.start_path == StartPath::guess_solved ||
                   solution.lcp.start_path == StartPath::guess_lemke) ?
                    1 :
                    0;
        n_fallback +=
          solution.lcp.start_path == StartPath::guess_fallback_cold ? 1 : 0;
        n_cold += solution.lcp.start_path == StartPath::cold ? 1 : 0;
        largest = std::max(largest, solution.lcp.z.size());
        if (solution.lcp.status == Status::solved)
          guess = solution.states;
      }
    deallog << name << ": " << run.size() << " solves, LCP size " << largest
            << std::endl;
    // the path the scenario is about was taken (how often is not printed:
    // it depends on the details of the pivoting rules)
    const unsigned int n_path = path == StartPath::block_pivoting ? n_block :
                                path == StartPath::guess_lemke    ? n_warm :
                                path == StartPath::guess_fallback_cold ?
                                                                 n_fallback :
                                                                 n_cold;
    check(n_path > 0,
          name + ": solved by " + to_string(path) + " at least once");
    check(n_solved == run.size(), name + ": every problem solved");
    if (path == StartPath::block_pivoting)
      check(n_reused > 0,
            name + ": the last factorisation's factors reused at least once");
    check(n_same == run.size(),
          name + ": each solution equals the one-shot solve bit for bit",
          std::to_string(n_same) + " of " + std::to_string(run.size()));
    check(allocations_without_growth == 0,
          name +
            ": allocations in the solves that did not grow the storage = 0",
          "(" + std::to_string(allocations_without_growth) + ")");

    // the same run again: the storage is large enough for every solve
    guess                         = open;
    unsigned long long second_run = 0;
    for (std::size_t s = 0; s < run.size(); ++s)
      {
        AllocationCount        count;
        const ContactSolution &solution =
          guess_kind == Guess::states ? solver.solve(run[s], options, guess) :
                                        solver.solve(run[s], options);
        second_run += count.count();
        if (solution.lcp.status == Status::solved)
          guess = solution.states;
      }
    check(second_run == 0,
          name + ": allocations in the second run of the same " +
            std::to_string(run.size()) + " solves = 0",
          "(" + std::to_string(second_run) + ")");
  }

  void
  check_lemke()
  {
    lcp_test::Rng       rng(7);
    const unsigned int  n = 60, n_problems = 20;
    const DenseMatrix   M = delassus_like(n, rng);
    LemkeSolver         solver;
    unsigned long long  later  = 0;
    std::size_t         bytes  = solver.memory_consumption();
    unsigned int        n_same = 0, n_solved = 0;
    std::vector<bool>   guess(n, false);
    std::vector<double> q(n);
    for (unsigned int s = 0; s < n_problems; ++s)
      {
        for (unsigned int i = 0; i < n; ++i)
          q[i] = std::sin(1.3 * s + 0.7 * i) - 0.3;
        const bool warm = (s % 2 == 1);
        Result     copy;
        {
          AllocationCount count;
          const Result   &r =
            warm ? solver.solve_warm(M, q, guess) : solver.solve(M, q);
          const unsigned long long allocations = count.count();
          if (solver.memory_consumption() == bytes)
            later += allocations;
          bytes = solver.memory_consumption();
          copy  = r; // (after counting: the copy allocates)
        }
        const Result reference =
          warm ? solve_lemke_warm(M, q, guess) : solve_lemke(M, q);
        n_same += (copy.z == reference.z && copy.w == reference.w &&
                   copy.pivots == reference.pivots &&
                   copy.message == reference.message) ?
                    1 :
                    0;
        n_solved += copy.status == Status::solved ? 1 : 0;
        for (unsigned int i = 0; i < n; ++i)
          guess[i] = copy.status == Status::solved && copy.z[i] > 0.;
      }
    deallog << "LemkeSolver: " << n_problems << " solves of size " << n
            << ", cold and warm alternating" << std::endl;
    check(n_solved == n_problems, "LemkeSolver: every problem solved");
    check(n_same == n_problems,
          "LemkeSolver: each result equals solve_lemke(_warm) bit for bit");
    check(later == 0,
          "LemkeSolver: allocations in the solves that did not grow the "
          "storage = 0",
          "(" + std::to_string(later) + ")");
  }
} // namespace



int
main()
{
  initlog();
  const unsigned int n_steps = 40;
  check_run("frictionless, warm",
            run_of_problems(40, 1, 0., n_steps, 1),
            {},
            Guess::states,
            StartPath::guess_lemke);
  check_run("2D Coulomb, block pivoting",
            run_of_problems(30, 2, 0.3, n_steps, 2),
            {},
            Guess::states,
            StartPath::block_pivoting);
  ContactOptions klarbring;
  klarbring.form = FrictionForm::klarbring;
  check_run("2D Coulomb, Klarbring form, cold",
            run_of_problems(30, 2, 0.3, n_steps, 3),
            klarbring,
            Guess::none,
            StartPath::cold);
  ContactOptions facets;
  facets.form     = FrictionForm::facets;
  facets.n_facets = 8;
  check_run("3D Coulomb, facet form k = 8, guessed states",
            run_of_problems(12, 3, 0.3, n_steps, 4),
            facets,
            Guess::states,
            StartPath::guess_fallback_cold);
  check_lemke();
  return n_failed_checks == 0 ? 0 : 1;
}
