// The interior point route (CoulombInteriorPointSolver) against answers
// computed independently of it:
//
// 1. One contact, W = I, mu = 0.5: the closed forms of a sliding, a sticking
//    and a separating contact, in 3D and in 2D.
// 2. A rigid box on its four corners (W of rank 6 for 12 rows), thrown
//    down at 1 m/s and along the plane at 2 m/s in the direction s: the
//    rigid-body totals sum P_N = m, sum P_T = -mu m s, every corner sliding
//    at (2 - mu) s (see tests/lcp/exact_cone).
// 3. A stack of three rigid boxes (W of rank 18 for 36 rows: redundant
//    contacts at the ground and at both interfaces) thrown down and along
//    the ground: rigid-body mechanics gives, for the stack moving as one
//    body, the totals at each level k boxes below the top (k = 3 at the
//    ground): sum P_N = k m, sum P_T = -mu_ground k m s, no slip at the
//    interfaces (mu there is larger), the ground corners sliding at
//    (2 - mu_ground) s.
// 4. Random coupled problems: 3D (with frictionless contacts mixed in), 2D,
//    frictionless, and 3D with a non-symmetric W whose symmetric part is
//    positive definite: the same impulses as Lemke's method (the facet
//    route of ExactConeSolver in 3D, the 2D and frictionless LCPs) to 1e-7
//    of the impulse scale, and verified.
// 5. Problems without a solution are not reported as solved.
// 6. ExactConeSolver takes the interior point answer where its facet route
//    stops short; route names.
// 7. exact_cone_residual() on a hand-computed case.
// 8. solve_facet_form_by_interior_point(): random problems (3D with 8
//    facets, 2D, frictionless) give Lemke's impulses on the same form (to
//    1e-6), and z,
//    w solve the form as assemble_contact_lcp() writes it; no answer where
//    there is no solution.
// 9. A looser target (lcp-solve --tolerance 1e-4 or 1e-6, both measures)
//    still returns an answer that passes the 1e-8 verification: the Newton
//    steps go on past the target when the answer there fails it.
#include <impactfe/lcp/exact_cone.h>
#include <impactfe/lcp/interior_point.h>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using impactfe_tests::check;
using impactfe_tests::rounded;
using lcp_test::condensed;
using lcp_test::relative_difference;

namespace
{
  const double pi = std::acos(-1.);

  /// Solved, converged (natural-map residual <= 1e-10) and verified:
  /// Signorini and the circular cone, sliding contacts with P_T = -mu P_N
  /// V_T/|V_T|, to 1e-8.
  bool
  solved_and_verified(const ContactProblem             &p,
                      const CoulombInteriorPointSolver &solver)
  {
    if (solver.solution().lcp.status != Status::solved ||
        !solver.report().converged)
      return false;
    const ContactVerification v =
      verify_contact_solution(p, solver.solution().P, 1e-8);
    return v.ok && v.max_sliding_violation <= 1e-8;
  }

  void
  one_contact()
  {
    dealii::deallog << "1. One contact, W = I, mu = 0.5" << std::endl;
    for (const unsigned int dim : {3u, 2u})
      for (const double speed : {2., 0.45, 0.})
        for (const double normal : {-1., 0.5})
          {
            ContactProblem p;
            p.n_directions = dim;
            p.n_contacts   = 1;
            p.W            = DenseMatrix(dim, dim);
            for (unsigned int k = 0; k < dim; ++k)
              p.W(k, k) = 1.;
            const double phi = dim == 3 ? 0.7 : 0.; // V_T = speed (cos, sin)
            p.free_velocity  = {normal, speed * std::cos(phi)};
            if (dim == 3)
              p.free_velocity.push_back(speed * std::sin(phi));
            p.gap_term = {0.};
            p.mu       = {0.5};
            // Closed forms: separating if V_N >= 0; else P_N = -V_N and
            // P_T = -t V_T with t = min(|V_T|, mu P_N)/|V_T|.
            std::vector<double> exact(dim, 0.);
            if (normal < 0.)
              {
                exact[0]       = -normal;
                const double t = speed > 0. ? std::min(speed, 0.5) / speed : 0.;
                for (unsigned int k = 1; k < dim; ++k)
                  exact[k] = -t * p.free_velocity[k];
              }
            CoulombInteriorPointSolver solver;
            const ContactSolution     &s = solver.solve(p, {});
            std::ostringstream         name;
            name << dim << "D, |V_T| = " << speed << ", V_N = " << normal
                 << ": the closed form to 1e-9, verified";
            check(solved_and_verified(p, solver) &&
                    lcp_test::max_diff(s.P, exact) < 1e-9,
                  name.str(),
                  s.message);
          }
  }

  // Rows (n = z, t1 = x, t2 = y) of the relative velocity at a corner r
  // (from the centre of the upper body, r_lower from the lower one's)
  // between an upper body (dofs at u) and a lower one (dofs at l, or none
  // for the ground), omega x r = (wy rz - wz ry, wz rx - wx rz, wx ry - wy
  // rx).
  void
  add_corner_rows(std::vector<std::vector<double>> &G,
                  const unsigned int                n_dofs,
                  const int                         u,
                  const int                         l,
                  const double                      rx,
                  const double                      ry,
                  const double                      rz_upper,
                  const double                      rz_lower)
  {
    for (unsigned int direction = 0; direction < 3; ++direction)
      {
        std::vector<double> row(n_dofs, 0.);
        for (const int body : {u, l})
          {
            if (body < 0)
              continue;
            const double sign = body == u ? 1. : -1.;
            const double rz   = body == u ? rz_upper : rz_lower;
            double      *g    = &row[6 * body];
            if (direction == 0) // z: v_z + wx ry - wy rx
              {
                g[2] += sign;
                g[3] += sign * ry;
                g[4] -= sign * rx;
              }
            else if (direction == 1) // x: v_x + wy rz - wz ry
              {
                g[0] += sign;
                g[4] += sign * rz;
                g[5] -= sign * ry;
              }
            else // y: v_y + wz rx - wx rz
              {
                g[1] += sign;
                g[5] += sign * rx;
                g[3] -= sign * rz;
              }
          }
        G.push_back(row);
      }
  }

  void
  boxes(const unsigned int n_boxes)
  {
    dealii::deallog << (n_boxes == 1 ? "2. A rigid box on its four corners" :
                                       "3. A stack of three rigid boxes")
                    << std::endl;
    const double m = 2., a = 0.5, b = 0.4, c = 0.1, mu_ground = 0.3,
                 mu_interface  = 0.6;
    const unsigned int  n_dofs = 6 * n_boxes;
    std::vector<double> m_diag, v;
    for (unsigned int box = 0; box < n_boxes; ++box)
      for (const double x : {m,
                             m,
                             m,
                             m / 3. * (b * b + c * c),
                             m / 3. * (a * a + c * c),
                             m / 3. * (a * a + b * b)})
        m_diag.push_back(x);
    std::vector<std::vector<double>> G;
    std::vector<double>              mu;
    for (unsigned int box = 0; box < n_boxes; ++box)
      for (const double rx : {-a, a})
        for (const double ry : {-b, b})
          {
            add_corner_rows(G, n_dofs, box, int(box) - 1, rx, ry, -c, c);
            mu.push_back(box == 0 ? mu_ground : mu_interface);
          }
    for (const double phi : {0., 0.3, pi / 5., 1.1, -2.4})
      {
        const double sx = std::cos(phi), sy = std::sin(phi);
        v.clear();
        for (unsigned int box = 0; box < n_boxes; ++box)
          for (const double x : {2. * sx, 2. * sy, -1., 0., 0., 0.})
            v.push_back(x);
        const ContactProblem       p = condensed(G, m_diag, v, mu);
        CoulombInteriorPointSolver solver;
        const ContactSolution     &s           = solver.solve(p, {});
        double                     total_error = 0., slip_error = 0.;
        if (s.lcp.status == Status::solved)
          {
            std::vector<double> V;
            p.W.vmult(V, s.P);
            for (unsigned int level = 0; level < n_boxes; ++level)
              {
                const double k      = n_boxes - level; // boxes above + 1
                double       sum[3] = {0., 0., 0.};
                for (unsigned int q = 4 * level; q < 4 * level + 4; ++q)
                  {
                    for (unsigned int d = 0; d < 3; ++d)
                      sum[d] += s.P[3 * q + d];
                    const double slip = level == 0 ? 2. - mu_ground : 0.;
                    slip_error        = std::max(
                      {slip_error,
                              std::abs(V[3 * q] + p.free_velocity[3 * q]),
                              std::abs(V[3 * q + 1] + p.free_velocity[3 * q + 1] -
                                slip * sx),
                              std::abs(V[3 * q + 2] + p.free_velocity[3 * q + 2] -
                                slip * sy)});
                  }
                total_error =
                  std::max({total_error,
                            std::abs(sum[0] - k * m),
                            std::abs(sum[1] + mu_ground * k * m * sx),
                            std::abs(sum[2] + mu_ground * k * m * sy)});
              }
          }
        std::ostringstream name;
        name << "direction " << phi
             << ": the rigid-body totals at every level to 1e-8, the "
                "velocities to 1e-8, verified";
        check(solved_and_verified(p, solver) && total_error < 1e-8 &&
                slip_error < 1e-8,
              name.str(),
              s.message);
      }
  }

  /// A random body's contact problem: 3D (n_directions 3), 2D or
  /// frictionless (1); with @p skew > 0, W + skew (B - B^T).
  ContactProblem
  random_problem(lcp_test::Rng     &rng,
                 const unsigned int n_directions,
                 const unsigned int nc,
                 const double       skew)
  {
    const unsigned int               n_dofs = 2 * n_directions * nc + 3;
    std::vector<std::vector<double>> G(n_directions * nc,
                                       std::vector<double>(n_dofs));
    for (auto &row : G)
      for (double &g : row)
        g = rng.uniform(-1., 1.);
    std::vector<double> m_diag(n_dofs), v(n_dofs), mu(nc);
    for (double &x : m_diag)
      x = rng.uniform(0.5, 2.);
    for (double &x : v)
      x = rng.uniform(-1., 1.);
    for (double &x : mu) // a quarter of the contacts without friction
      x = rng.uniform() < 0.25 ? 0. : rng.uniform(0.1, 0.6);
    ContactProblem p = condensed(G, m_diag, v, mu, n_directions);
    for (double &b : p.gap_term)
      b = rng.uniform(-0.2, 0.2);
    const std::size_t n = p.W.n_rows();
    for (std::size_t i = 0; i < n && skew > 0.; ++i)
      for (std::size_t j = 0; j < i; ++j)
        {
          const double x = skew * rng.uniform(-1., 1.);
          p.W(i, j) += x;
          p.W(j, i) -= x;
        }
    return p;
  }

  void
  random_problems()
  {
    dealii::deallog << "4. Random problems against Lemke's method" << std::endl;
    lcp_test::Rng rng(20261127);
    struct Kind
    {
      const char  *name;
      unsigned int n_directions;
      double       skew;
    };
    for (const Kind kind : {Kind{"3D", 3, 0.},
                            Kind{"2D", 2, 0.},
                            Kind{"frictionless", 1, 0.},
                            Kind{"3D, non-symmetric W", 3, 0.3}})
      {
        unsigned int agree = 0, n = 0;
        double       largest = 0.;
        std::string  detail;
        for (unsigned int trial = 0; trial < 25; ++trial)
          {
            const unsigned int   nc = 2 + rng.integer(9);
            const ContactProblem p =
              random_problem(rng, kind.n_directions, nc, kind.skew);
            ExactConeOptions lemke;
            lemke.route = ExactConeRoute::facets;
            ExactConeSolver        facets;
            const ContactSolution &reference = facets.solve(p, {}, lemke);
            if (reference.lcp.status != Status::solved ||
                !facets.report().converged)
              continue; // Lemke's answer is the reference; count the rest
            ++n;
            CoulombInteriorPointSolver solver;
            const ContactSolution     &s = solver.solve(p, {});
            const double               difference =
              s.lcp.status == Status::solved ?
                              relative_difference(p, s.P, reference.P) :
                              1.;
            largest = std::max(largest, difference);
            if (solved_and_verified(p, solver) && difference < 1e-7)
              ++agree;
            else if (detail.empty())
              detail = s.message;
          }
        std::ostringstream name;
        name << kind.name << ": " << agree << " of " << n
             << " random problems verified and equal to Lemke's answer to "
                "1e-7";
        check(agree == n && n >= 20, name.str(), detail);
      }
  }

  void
  no_solution()
  {
    dealii::deallog << "5. Problems without a solution" << std::endl;
    // Two opposite frictionless contacts (W of rank 1) both approaching:
    // u_1 + u_2 = -2 for every P, so they cannot both separate.
    ContactProblem p;
    p.n_directions  = 1;
    p.n_contacts    = 2;
    p.W             = lcp_test::matrix({{1., -1.}, {-1., 1.}});
    p.free_velocity = {-1., -1.};
    p.gap_term      = {0., 0.};
    p.mu            = {0., 0.};
    CoulombInteriorPointSolver solver;
    const ContactSolution     &s = solver.solve(p, {});
    check(s.lcp.status != Status::solved && s.P.empty(),
          "opposite contacts both approaching: not solved",
          s.message);
    // W = 0: nothing can stop an approaching contact.
    ContactProblem q;
    q.n_directions  = 3;
    q.n_contacts    = 1;
    q.W             = DenseMatrix(3, 3);
    q.free_velocity = {-1., 0.5, 0.};
    q.gap_term      = {0.};
    q.mu            = {0.5};
    check(solver.solve(q, {}).lcp.status != Status::solved,
          "W = 0, an approaching contact: not solved");
    // Bad data is refused with a message, as by the other solvers.
    q.mu = {-0.1};
    try
      {
        solver.solve(q, {});
        check(false, "mu < 0 is refused");
      }
    catch (const std::invalid_argument &e)
      {
        dealii::deallog << "mu < 0 is refused: " << e.what() << std::endl;
      }
  }

  void
  exact_cone_solver()
  {
    dealii::deallog << "6. ExactConeSolver's routes" << std::endl;
    lcp_test::Rng        rng(7);
    const ContactProblem p = random_problem(rng, 3, 8, 0.);
    // A facet route cut at one LCP stops short of the circular cone; the
    // interior point answer is taken.
    ExactConeOptions cut;
    cut.max_iterations = 1;
    ExactConeSolver solver;
    solver.solve(p, {}, cut);
    check(solver.report().interior_point && solver.report().converged,
          "facet route cut at one LCP: the interior point answer is taken, "
          "converged");
    ExactConeOptions facets_only = cut;
    facets_only.route            = ExactConeRoute::facets;
    solver.solve(p, {}, facets_only);
    check(!solver.report().interior_point && !solver.report().converged,
          "route facets: the same cut stays not converged");
    bool names = true;
    for (const ExactConeRoute route :
         {ExactConeRoute::facets,
          ExactConeRoute::facets_then_interior_point,
          ExactConeRoute::interior_point_then_facets,
          ExactConeRoute::interior_point})
      names = names && exact_cone_route_from_string(to_string(route)) == route;
    check(names, "route names");
    try
      {
        exact_cone_route_from_string("simplex");
        check(false, "an unknown route is refused");
      }
    catch (const std::invalid_argument &e)
      {
        dealii::deallog << "an unknown route is refused: " << e.what()
                        << std::endl;
      }
  }

  void
  residual_by_hand()
  {
    dealii::deallog << "7. exact_cone_residual() by hand" << std::endl;
    // One contact, W = 2 I (rho = 3 / trace W = 1/2), mu = 0.5; residual
    // max |P - proj_K(P - rho u~)| over s_P = max(|P|, |q|/|W|).
    ContactProblem p;
    p.n_directions = 3;
    p.n_contacts   = 1;
    p.W        = lcp_test::matrix({{2., 0., 0.}, {0., 2., 0.}, {0., 0., 2.}});
    p.gap_term = {0.};
    p.mu       = {0.5};
    std::vector<double> u;
    // q = (-1, 0, 0), P = (1, 0, 0): u = u~ = (1, 0, 0), P - u~/2 = (0.5,
    // 0, 0) inside K: residual 0.5 (s_P = 1); the answer (0.5, 0, 0): 0.
    p.free_velocity = {-1., 0., 0.};
    dealii::deallog << "sticking: "
                    << rounded(exact_cone_residual(p, {1., 0., 0.}, u))
                    << " (0.5 by hand), at the answer "
                    << rounded(exact_cone_residual(p, {0.5, 0., 0.}, u))
                    << " (0)" << std::endl;
    // q = (-1, 2, 0), P = (0.5, 0, 0): u = (0, 2, 0), u~ = (1, 2, 0),
    // P - u~/2 = (0, -1, 0), projected on the cone's surface: a = (mu 1 +
    // 0)/(1 + mu^2) = 0.4, proj = (0.4, -0.2, 0), residual |(0.1, 0.2, 0)|
    // = 0.2 (s_P = max(0.5, 2/2) = 1); the answer slides, P = (0.5,
    // -0.25, 0) (u = (0, 1.5, 0)): 0.
    p.free_velocity = {-1., 2., 0.};
    dealii::deallog << "sliding: "
                    << rounded(exact_cone_residual(p, {0.5, 0., 0.}, u))
                    << " (0.2 by hand), at the answer "
                    << rounded(exact_cone_residual(p, {0.5, -0.25, 0.}, u))
                    << " (0)" << std::endl;
  }
  void
  facet_form()
  {
    dealii::deallog << "8. The facet form by the interior point method"
                    << std::endl;
    lcp_test::Rng rng(20261128);
    for (const unsigned int n_directions : {3u, 2u, 1u})
      {
        unsigned int agree = 0, n = 0;
        std::string  detail;
        for (unsigned int trial = 0; trial < 20; ++trial)
          {
            const unsigned int   nc = 2 + rng.integer(9);
            const ContactProblem p  = random_problem(rng, n_directions, nc, 0.);
            ContactOptions       options;
            options.form     = FrictionForm::facets;
            options.n_facets = 8;
            if (n_directions == 1)
              options.form = FrictionForm::frictionless;
            const ContactSolution lemke = solve_contact_problem(p, options);
            if (lemke.lcp.status != Status::solved)
              continue;
            ++n;
            const ContactSolution s =
              solve_facet_form_by_interior_point(p, options);
            // z and w in the layout of the assembled form: w = M z + q,
            // z, w >= 0, z.w = 0, to 1e-8 of their scales.
            const ContactLCP    lcp = assemble_contact_lcp(p, options);
            std::vector<double> Mz;
            double              layout = 1.;
            if (s.lcp.status == Status::solved &&
                s.lcp.z.size() == lcp.q.size())
              {
                lcp.M.vmult(Mz, s.lcp.z);
                const double scale =
                  lcp_test::linfty(lcp.q) +
                  lcp.M.linfty_norm() * lcp_test::linfty(s.lcp.z);
                layout = 0.;
                for (std::size_t i = 0; i < Mz.size(); ++i)
                  layout =
                    std::max({layout,
                              std::abs(s.lcp.w[i] - Mz[i] - lcp.q[i]),
                              -s.lcp.z[i],
                              -s.lcp.w[i],
                              std::abs(s.lcp.z[i] * s.lcp.w[i]) / scale});
                layout /= scale;
              }
            // (1e-6: two solutions of the form to 1e-14 differ by up to 2e-7
            // where a contact sits at a corner of its polygon)
            if (s.lcp.status == Status::solved && layout < 1e-8 &&
                relative_difference(p, s.P, lemke.P) < 1e-6)
              ++agree;
            else if (detail.empty())
              {
                std::ostringstream m;
                m << s.message << ", layout " << layout << ", difference "
                  << relative_difference(p, s.P, lemke.P);
                detail = m.str();
              }
          }
        std::ostringstream name;
        name << (n_directions == 3 ? "3D, 8 facets" :
                 n_directions == 2 ? "2D" :
                                     "frictionless")
             << ": " << agree << " of " << n
             << " random problems: Lemke's impulses to 1e-6, z and w a "
                "solution of the assembled form to 1e-8";
        check(agree == n && n >= 15, name.str(), detail);
      }
    ContactProblem p;
    p.n_directions  = 1;
    p.n_contacts    = 2;
    p.W             = lcp_test::matrix({{1., -1.}, {-1., 1.}});
    p.free_velocity = {-1., -1.};
    p.gap_term      = {0., 0.};
    p.mu            = {0., 0.};
    check(solve_facet_form_by_interior_point(p, {}).lcp.status !=
            Status::solved,
          "opposite contacts both approaching: not solved");
  }

  void
  loose_tolerance()
  {
    dealii::deallog << "9. Targets looser than the verification" << std::endl;
    for (const double tolerance : {1e-4, 1e-6})
      {
        lcp_test::Rng rng(20261205);
        unsigned int  verified = 0, n = 0;
        std::string   detail;
        for (unsigned int trial = 0; trial < 20; ++trial)
          {
            const unsigned int   nc = 2 + rng.integer(19);
            const ContactProblem p  = random_problem(rng, 3, nc, 0.);
            ExactConeOptions     options;
            options.route                = ExactConeRoute::interior_point;
            options.tolerance            = tolerance;
            options.cone_error_tolerance = tolerance;
            ExactConeSolver        solver;
            const ContactSolution &s = solver.solve(p, {}, options);
            ++n;
            if (s.lcp.status == Status::solved &&
                verify_contact_solution(p, s.P, 1e-8).ok)
              ++verified;
            else if (detail.empty())
              detail = s.message;
          }
        std::ostringstream name;
        name << "tolerance " << tolerance << ": " << verified << " of " << n
             << " random 3D problems solved and verified to 1e-8";
        check(verified == n, name.str(), detail);
      }
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  one_contact();
  boxes(1);
  boxes(3);
  random_problems();
  no_solution();
  exact_cone_solver();
  residual_by_hand();
  facet_form();
  loose_tolerance();
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
