// Cold vs warm Lemke on synthetic contact problems: a block-tridiagonal SPD
// Delassus operator W = B B' + 0.5 I (B block lower-bidiagonal with 2x2
// blocks, fixed seed), n_c contacts in 2D, a sequence of time steps whose
// free velocities drift slowly, so that consecutive active sets are close.
// Each step is solved cold and warm (guess: z_i > 0 of the previous step's
// warm solution); the table lists mean pivots and seconds per step.
//
//   lcp_scaling [max_n_c (2000)] [steps (5)] [max_n_c for Klarbring (1000)]
//
// Not a test: timings depend on the machine. Build it like lcp-solve (plain
// C++17, the sources in source/lcp/), e.g.
//   g++ -std=c++17 -O2 -Iinclude benchmarks/lcp/lcp_scaling.cc source/lcp/*.cc
//   -o lcp_scaling
#include <impactfe/lcp/contact_problem.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <vector>

using namespace impactfe::lcp;

namespace
{
  struct Rng
  {
    std::uint64_t s;
    double
    operator()()
    {
      s ^= s >> 12;
      s ^= s << 25;
      s ^= s >> 27;
      return static_cast<double>((s * 2685821657736338717ull) >> 11) /
             9007199254740992.0;
    }
  };

  DenseMatrix
  delassus(const unsigned int nc, Rng &rng)
  {
    const unsigned int m = 2 * nc;
    DenseMatrix        B(m, m, 0.);
    for (unsigned int c = 0; c < nc; ++c)
      for (unsigned int a = 0; a < 2; ++a)
        for (unsigned int b = 0; b < 2; ++b)
          {
            B(2 * c + a, 2 * c + b) = (a == b ? 1. : 0.) + 0.3 * (rng() - 0.5);
            if (c > 0)
              B(2 * c + a, 2 * (c - 1) + b) = 0.5 * (rng() - 0.5);
          }
    DenseMatrix W(m, m, 0.);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = (i >= 3 ? i - 3 : 0); j < std::min(m, i + 4); ++j)
        {
          double s = (i == j ? 0.5 : 0.);
          for (unsigned int k = 0; k < m; ++k)
            s += B(i, k) * B(j, k);
          W(i, j) = s;
        }
    return W;
  }

  void
  free_velocity(ContactProblem &p, const unsigned int step)
  {
    for (unsigned int c = 0; c < p.n_contacts; ++c)
      {
        // about 60 % of the contacts approach; the pattern drifts with the step
        p.free_velocity[2 * c]     = -0.2 + std::sin(0.37 * c + 0.02 * step);
        p.free_velocity[2 * c + 1] = 0.5 * std::cos(0.23 * c + 0.03 * step);
      }
  }

  double
  seconds_since(const std::chrono::steady_clock::time_point t0)
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
      .count();
  }
} // namespace

int
main(int argc, char **argv)
{
  const unsigned int max_nc   = argc > 1 ? std::atoi(argv[1]) : 2000;
  const unsigned int steps    = argc > 2 ? std::atoi(argv[2]) : 5;
  const unsigned int max_klar = argc > 3 ? std::atoi(argv[3]) : 1000;

  std::printf("%-13s %6s %6s | %9s %10s | %9s %10s | %s\n",
              "form",
              "n_c",
              "n",
              "cold piv",
              "cold s",
              "warm piv",
              "warm s",
              "warm paths (solved/lemke/fallback)");
  // the largest size of each form, for the RESULT line
  struct Largest
  {
    unsigned int contacts = 0;
    double       cold_s = 0., warm_s = 0.;
  };
  Largest      largest[2];
  unsigned int total_failures = 0;
  for (const FrictionForm form :
       {FrictionForm::frictionless, FrictionForm::klarbring})
    for (const unsigned int nc :
         {10u, 20u, 50u, 100u, 200u, 500u, 1000u, 2000u})
      {
        if (nc > max_nc || (form == FrictionForm::klarbring && nc > max_klar))
          continue;
        Rng            rng{12345};
        ContactProblem p;
        p.n_directions = 2;
        p.n_contacts   = nc;
        p.W            = delassus(nc, rng);
        p.free_velocity.assign(2 * nc, 0.);
        p.gap_term.assign(nc, 0.);
        p.mu.assign(nc, 0.3);
        ContactOptions o;
        o.form = form;

        double            cold_s = 0., warm_s = 0., cold_p = 0., warm_p = 0.;
        unsigned int      paths[4] = {0, 0, 0, 0}, n = 0, failures = 0;
        std::vector<bool> guess;
        for (unsigned int step = 0; step <= steps; ++step)
          {
            free_velocity(p, step);
            auto                  t0 = std::chrono::steady_clock::now();
            const ContactSolution c  = solve_contact_problem(p, o);
            const double          tc = seconds_since(t0);
            t0                       = std::chrono::steady_clock::now();
            const ContactSolution w =
              solve_contact_problem(p, o, guess.empty() ? nullptr : &guess);
            const double tw = seconds_since(t0);
            if (c.lcp.status != Status::solved ||
                w.lcp.status != Status::solved)
              ++failures;
            n = static_cast<unsigned int>(c.lcp.z.size());
            guess.assign(w.lcp.z.size(), false);
            for (std::size_t i = 0; i < w.lcp.z.size(); ++i)
              guess[i] = w.lcp.z[i] > 0.;
            if (step == 0)
              continue; // step 0 has no guess yet
            cold_s += tc;
            warm_s += tw;
            cold_p += c.lcp.pivots;
            warm_p += w.lcp.pivots;
            ++paths[static_cast<int>(w.lcp.start_path)];
          }
        std::printf(
          "%-13s %6u %6u | %9.1f %10.4f | %9.1f %10.4f | %u/%u/%u%s\n",
          to_string(form).c_str(),
          nc,
          n,
          cold_p / steps,
          cold_s / steps,
          warm_p / steps,
          warm_s / steps,
          paths[1],
          paths[2],
          paths[3],
          failures ? "  (FAILURES)" : "");
        std::fflush(stdout);
        Largest &l = largest[form == FrictionForm::frictionless ? 0 : 1];
        l          = {nc, cold_s / steps, warm_s / steps};
        total_failures += failures;
      }
  std::printf("RESULT frictionless_contacts=%u frictionless_cold_seconds=%g "
              "frictionless_warm_seconds=%g klarbring_contacts=%u "
              "klarbring_cold_seconds=%g klarbring_warm_seconds=%g "
              "failures=%u\n",
              largest[0].contacts,
              largest[0].cold_s,
              largest[0].warm_s,
              largest[1].contacts,
              largest[1].cold_s,
              largest[1].warm_s,
              total_failures);
  return total_failures == 0 ? 0 : 1;
}
