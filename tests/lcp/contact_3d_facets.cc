// 3D contact with the polygonal Coulomb cone: how the result depends on the
// number of facets k.
//
// One contact, W = I (a unit point mass), V_free = (-1, v_T), mu = 0.5, so
// P_N = 1. With W = I the facet LCP is the optimality system of
//   P_T = argmin { (v_T + P_T) . Q : Q in the polygon }  <=>
//   P_T = projection of -v_T onto the regular k-gon with vertices
//         mu P_N (cos 2 pi j/k, sin 2 pi j/k)  (inscribed in the exact disc).
// The projection is computed here independently (nearest point on the edges),
// and the exact Coulomb answer is P_T = -mu P_N v_T/|v_T| (sliding, |v_T| >
// mu) resp. P_T = -v_T (sticking). Reported per k: |P_T| / (mu P_N) and the
// angle between P_T and the exact direction, both closed-form for the
// polygon: for a sliding direction phi inside the facet between the
// vertices at 0 and 2 pi/k the projection lies on that edge.
#include <impactfe/lcp/contact_problem.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

namespace
{
  // nearest point of the regular k-gon (circumradius R, vertex at angle 0)
  std::vector<double>
  project_on_polygon(const std::vector<double> &x,
                     const unsigned int         k,
                     const double               R)
  {
    const double pi = std::acos(-1.);
    // inside?
    bool inside = true;
    for (unsigned int j = 0; j < k; ++j)
      {
        const double a = 2. * pi * (j + 0.5) / k;
        if (std::cos(a) * x[0] + std::sin(a) * x[1] > R * std::cos(pi / k))
          inside = false;
      }
    if (inside)
      return x;
    std::vector<double> best;
    double              dbest = 1e300;
    for (unsigned int j = 0; j < k; ++j)
      {
        const double a0 = 2. * pi * j / k, a1 = 2. * pi * (j + 1) / k;
        const double p0[2] = {R * std::cos(a0), R * std::sin(a0)};
        const double e[2]  = {R * std::cos(a1) - p0[0],
                              R * std::sin(a1) - p0[1]};
        double       t     = ((x[0] - p0[0]) * e[0] + (x[1] - p0[1]) * e[1]) /
                   (e[0] * e[0] + e[1] * e[1]);
        t                 = std::min(1., std::max(0., t));
        const double y[2] = {p0[0] + t * e[0], p0[1] + t * e[1]};
        const double dd   = std::hypot(x[0] - y[0], x[1] - y[1]);
        if (dd < dbest)
          {
            dbest = dd;
            best  = {y[0], y[1]};
          }
      }
    return best;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  const double mu = 0.5, pi = std::acos(-1.);

  for (const double speed : {2.0, 0.2})
    {
      const double phi = 0.3; // direction of v_T, radians
      dealii::deallog << (speed > mu ? "sliding" : "sticking")
                      << ", |v_T| = " << speed << ", direction 0.3 rad"
                      << std::endl;
      double previous_angle = 1e300;
      for (const unsigned int k : {3u, 4u, 6u, 8u, 16u, 32u, 64u})
        {
          ContactProblem p;
          p.n_directions  = 3;
          p.n_contacts    = 1;
          p.W             = lcp_test::matrix({{1, 0, 0}, {0, 1, 0}, {0, 0, 1}});
          p.free_velocity = {-1., speed * std::cos(phi), speed * std::sin(phi)};
          p.gap_term      = {0.};
          p.mu            = {mu};
          ContactOptions o;
          o.n_facets              = k;
          const ContactSolution s = solve_contact_problem(p, o);

          const std::vector<double> expected =
            project_on_polygon({-p.free_velocity[1], -p.free_velocity[2]},
                               k,
                               mu * 1.);
          const std::vector<double> PT = {s.P[1], s.P[2]};
          const double ratio = std::hypot(PT[0], PT[1]) / (mu * s.P[0]);
          // angle between P_T and the exact Coulomb direction -v_T
          const double angle =
            std::abs(std::atan2(PT[1], PT[0]) -
                     std::atan2(-std::sin(phi), -std::cos(phi)));
          const double angle_deg = std::min(angle, 2 * pi - angle) * 180. / pi;
          dealii::deallog << "k = " << k << ": form " << to_string(s.form)
                          << ", P_N = " << impactfe_tests::rounded(s.P[0])
                          << ", |P_T|/(mu P_N) = "
                          << impactfe_tests::rounded(ratio)
                          << ", angle to -v_T = "
                          << impactfe_tests::rounded(angle_deg, 6, 1e-8)
                          << " deg" << std::endl;
          bool ok = s.form == FrictionForm::facets && s.n_facets == k &&
                    s.lcp.status == Status::solved &&
                    std::abs(s.P[0] - 1.) < 1e-12 &&
                    lcp_test::max_diff(PT, expected) < 1e-12;
          if (speed > mu)
            {
              // |P_T| <= mu P_N always (inscribed polygon); the angle error
              // is at most pi/k and does not grow with k
              ok = ok && ratio <= 1. + 1e-12 && angle_deg <= 180. / k + 1e-9 &&
                   angle_deg <= previous_angle + 1e-9;
              previous_angle = angle_deg;
            }
          else
            ok = ok &&
                 lcp_test::max_diff(PT,
                                    {-p.free_velocity[1],
                                     -p.free_velocity[2]}) < 1e-12 &&
                 verify_contact_solution(p, s.P).ok;
          impactfe_tests::check(ok,
                                "k = " + std::to_string(k) +
                                  " matches the projection on the polygon");
        }
    }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
