// A corpus of hard contact problem files, generated deterministically: 280
// problems in 20 classes (10 kinds, 2D and 3D). Each one is written as a
// Siconos friction-contact file (dense, compressed-column and triplet storage
// in turn), read back, solved with the automatic form (every route of
// contact_routes.h), and checked here, independently of the solver, on the
// impulses P and velocities V = W P + q recomputed from the file's W, q, mu.
//
// W = H^T M^{-1} H as in a Lagrangian multibody model (ndof degrees of
// freedom, H the contact directions), q = H^T v + b (b_N >= 0): W is
// positive semidefinite and q^T u = b^T u >= 0 for every u in the cone with
// W u = 0, so the facet form is solvable (and processed by Lemke's method,
// see doc/lcp.md). The two "unsolvable" kinds have no solution by
// construction (two contacts pressing one degree of freedom from both sides
// with negative gap terms; a contact that no impulse can open), and must be
// reported as infeasible.
//
// The output lists, per class, how many problems were solved and verified,
// proven infeasible, or neither, and how many the time loop's path (route 1
// on W as it is, then the other routes on W scaled to unit size) answers as
// expected. Which route solved each problem is printed
// on stdout only (not compared): it depends on rounding.
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/problem_io.h>

#include <cstdio>
#include <iostream>
#include <map>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;

namespace
{
  struct Spec
  {
    std::string  name;
    unsigned int dim;
    bool         solvable;
  };

  /// Contact directions of random bodies: H is ndof x (dim n_c).
  DenseMatrix
  random_directions(lcp_test::Rng     &rng,
                    const unsigned int ndof,
                    const unsigned int rows)
  {
    DenseMatrix H(ndof, rows);
    for (unsigned int i = 0; i < ndof; ++i)
      for (unsigned int j = 0; j < rows; ++j)
        H(i, j) = rng.uniform(-1., 1.);
    return H;
  }

  /// W = H^T diag(inverse_mass) H (exactly symmetric), q = H^T v.
  ContactProblem
  lagrangian_problem(const DenseMatrix         &H,
                     const std::vector<double> &inverse_mass,
                     const std::vector<double> &v,
                     const unsigned int         dim,
                     const std::vector<double> &mu)
  {
    const unsigned int ndof = H.n_rows(), rows = H.n_cols();
    ContactProblem     p;
    p.n_directions = dim;
    p.n_contacts   = rows / dim;
    p.W            = DenseMatrix(rows, rows, 0.);
    for (unsigned int i = 0; i < rows; ++i)
      for (unsigned int j = 0; j <= i; ++j)
        {
          double s = 0.;
          for (unsigned int k = 0; k < ndof; ++k)
            s += H(k, i) * inverse_mass[k] * H(k, j);
          p.W(i, j) = p.W(j, i) = s;
        }
    p.free_velocity.assign(rows, 0.);
    for (unsigned int i = 0; i < rows; ++i)
      for (unsigned int k = 0; k < ndof; ++k)
        p.free_velocity[i] += H(k, i) * v[k];
    p.gap_term.assign(p.n_contacts, 0.);
    p.mu = mu;
    return p;
  }

  /// Contacts made grazing (q_N = 0) in a problem of the class "grazing".
  unsigned int
  n_grazing(const unsigned int n_contacts, const unsigned int ndof)
  {
    return std::min((n_contacts + 1) / 2, ndof - 1);
  }

  ContactProblem
  generate(const std::string &kind, const unsigned int dim, lcp_test::Rng &rng)
  {
    unsigned int nc   = 2 + rng.integer(6);
    unsigned int rows = dim * nc;
    unsigned int ndof = 1 + rng.integer(rows); // usually rank-deficient W
    std::vector<double> mu(nc, 0.3), inverse_mass(ndof, 1.), v(ndof);
    for (double &x : v)
      x = rng.uniform(-1., 1.);
    DenseMatrix         H = random_directions(rng, ndof, rows);
    std::vector<double> gap(nc, 0.);

    if (kind == "redundant")
      {
        // every second contact duplicates the one before it
        for (unsigned int c = 1; c < nc; c += 2)
          for (unsigned int a = 0; a < dim; ++a)
            for (unsigned int k = 0; k < ndof; ++k)
              H(k, c * dim + a) = H(k, (c - 1) * dim + a);
      }
    else if (kind == "nearly-singular")
      {
        // full-rank H whose last column is the first plus 1e-9 noise
        ndof = rows;
        H    = random_directions(rng, ndof, rows);
        inverse_mass.assign(ndof, 1.);
        v.resize(ndof);
        for (double &x : v)
          x = rng.uniform(-1., 1.);
        for (unsigned int k = 0; k < ndof; ++k)
          H(k, rows - 1) = H(k, 0) + 1e-9 * rng.uniform(-1., 1.);
      }
    else if (kind == "mu=0")
      mu.assign(nc, 0.);
    else if (kind == "large-mu")
      for (double &m : mu)
        m = rng.uniform() < 0.5 ? 5. : 100.;
    else if (kind == "mixed-mu-gaps")
      for (unsigned int c = 0; c < nc; ++c)
        {
          mu[c]  = rng.uniform() < 0.25 ? 0. : rng.uniform(0., 1.);
          gap[c] = rng.uniform() < 0.5 ? 0. : rng.uniform(0., 0.5);
        }
    else if (kind == "grazing")
      {
        // v orthogonal to the normals of the first half of the contacts
        // (Gram-Schmidt), so that their normal velocities vanish. At most
        // ndof - 1 of them: with ndof normals spanning every direction, v
        // would vanish and q be rounding noise, a problem whose exact
        // version is q = 0 and whose perturbed version need not have a
        // solution (two such problems were in this class before).
        std::vector<std::vector<double>> basis;
        for (unsigned int c = 0; c < n_grazing(nc, ndof); ++c)
          {
            std::vector<double> n(ndof);
            for (unsigned int k = 0; k < ndof; ++k)
              n[k] = H(k, c * dim);
            for (const auto &b : basis)
              {
                double s = 0.;
                for (unsigned int k = 0; k < ndof; ++k)
                  s += n[k] * b[k];
                for (unsigned int k = 0; k < ndof; ++k)
                  n[k] -= s * b[k];
              }
            double norm = 0.;
            for (const double x : n)
              norm += x * x;
            if (norm < 1e-20)
              continue;
            for (double &x : n)
              x /= std::sqrt(norm);
            basis.push_back(n);
          }
        for (const auto &b : basis)
          {
            double s = 0.;
            for (unsigned int k = 0; k < ndof; ++k)
              s += v[k] * b[k];
            for (unsigned int k = 0; k < ndof; ++k)
              v[k] -= s * b[k];
          }
      }
    else if (kind == "scales")
      {
        // masses over 8 decades, velocities over 6
        for (double &m : inverse_mass)
          m = std::pow(10., rng.uniform(-4., 4.));
        for (double &x : v)
          x *= std::pow(10., rng.uniform(-3., 3.));
      }
    else if (kind == "pinched" || kind == "stuck")
      ndof = std::max(ndof, 2u);

    if (kind == "pinched" || kind == "stuck")
      {
        H = random_directions(rng, ndof, rows);
        inverse_mass.assign(ndof, 1.);
        v.resize(ndof);
        for (double &x : v)
          x = rng.uniform(-1., 1.);
        for (unsigned int k = 0; k < ndof; ++k)
          for (unsigned int a = 0; a < dim; ++a)
            if (kind == "pinched") // contact 1 = contact 0 from the other side
              H(k, dim + a) = -H(k, a);
            else // contact 0 acts on nothing
              H(k, a) = 0.;
      }

    ContactProblem p = lagrangian_problem(H, inverse_mass, v, dim, mu);
    for (unsigned int c = 0; c < nc; ++c)
      p.free_velocity[c * dim] += gap[c];
    if (kind == "grazing")
      for (unsigned int c = 0; c < n_grazing(nc, ndof); ++c)
        p.free_velocity[c * dim] = 0.; // exactly, not to rounding
    if (kind == "pinched")
      {
        // V_N0 + V_N1 = q_N0 + q_N1 whatever P is: make it negative
        const double s = p.free_velocity[0] + p.free_velocity[dim];
        p.free_velocity[0] -= s + 0.25;
      }
    if (kind == "stuck")
      p.free_velocity[0] = -0.5;
    return p;
  }

  /// Signorini and Coulomb on (P, V = W P + q), recomputed here. In 3D the
  /// facet form gives the maximal dissipation over the inscribed polygon
  /// with k facets: P_T . V_T <= -mu P_N |V_T| cos(pi / k) (up to tol).
  bool
  check_solution(const ContactProblem      &p,
                 const std::vector<double> &P,
                 const unsigned int         k,
                 std::string               &why)
  {
    const unsigned int d = p.n_directions, nc = p.n_contacts, m = d * nc;
    if (P.size() != m)
      {
        why = "wrong size";
        return false;
      }
    std::vector<double> V(m);
    double              pmax = 0., qmax = 0., wmax = 0.;
    for (unsigned int i = 0; i < m; ++i)
      {
        double s = p.free_velocity[i];
        for (unsigned int j = 0; j < m; ++j)
          s += p.W(i, j) * P[j];
        V[i] = s;
        pmax = std::max(pmax, std::abs(P[i]));
        qmax = std::max(qmax, std::abs(p.free_velocity[i]));
        for (unsigned int j = 0; j < m; ++j)
          wmax = std::max(wmax, std::abs(p.W(i, j)));
      }
    const double tol = 1e-9;
    const double sV  = qmax + m * wmax * pmax;
    const double sP  = std::max(pmax, wmax > 0. ? qmax / wmax : 0.);
    const double pi  = std::acos(-1.);
    for (unsigned int c = 0; c < nc; ++c)
      {
        const double PN = P[c * d], VN = V[c * d];
        double       PT2 = 0., VT2 = 0., PV = 0.;
        for (unsigned int a = 1; a < d; ++a)
          {
            PT2 += P[c * d + a] * P[c * d + a];
            VT2 += V[c * d + a] * V[c * d + a];
            PV += P[c * d + a] * V[c * d + a];
          }
        const double PT = std::sqrt(PT2), VT = std::sqrt(VT2),
                     mu = d > 1 ? p.mu[c] : 0.;
        char b[200];
        if (PN < -tol * sP || VN < -tol * sV ||
            std::abs(PN * VN) > tol * sP * sV)
          std::snprintf(
            b, sizeof(b), "contact %u: Signorini (P_N %g, V_N %g)", c, PN, VN);
        else if (PT > mu * PN + tol * sP)
          std::snprintf(b,
                        sizeof(b),
                        "contact %u: outside the cone (|P_T| %g, mu P_N %g)",
                        c,
                        PT,
                        mu * PN);
        else if (VT > tol * sV && PN > tol * sP &&
                 PV > -mu * PN * VT * (d == 2 ? 1. : std::cos(pi / k)) +
                        tol * sP * sV)
          std::snprintf(b,
                        sizeof(b),
                        "contact %u: sliding without maximal dissipation",
                        c);
        else
          continue;
        why = b;
        return false;
      }
    return true;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng rng(20261123);

  const std::vector<std::pair<std::string, bool>> kinds = {
    {"singular", true},
    {"redundant", true},
    {"nearly-singular", true},
    {"mu=0", true},
    {"large-mu", true},
    {"mixed-mu-gaps", true},
    {"grazing", true},
    {"scales", true},
    {"pinched", false},
    {"stuck", false}};
  const unsigned int  per_class  = 14;
  const MatrixStorage storages[] = {MatrixStorage::dense,
                                    MatrixStorage::compressed_column,
                                    MatrixStorage::triplet};

  unsigned int total = 0, total_ok = 0;
  std::map<std::string, unsigned int>
    route_share; // kind of route -> problems solved by it
  for (const unsigned int dim : {2u, 3u})
    for (const auto &kind : kinds)
      {
        unsigned int solved = 0, infeasible = 0, other = 0, wrong = 0;
        // The time loop's path: route 1 on W as it is, then the other
        // routes (continue_with_other_routes(), on W scaled to unit size).
        unsigned int time_loop_as_expected = 0;
        for (unsigned int i = 0; i < per_class; ++i, ++total)
          {
            const ContactProblem generated = generate(kind.first, dim, rng);
            const std::string    file = "corpus_" + std::to_string(dim) + "d_" +
                                     kind.first + "_" + std::to_string(i) +
                                     ".dat";
            write_friction_contact_file(file, generated, storages[total % 3]);
            const ProblemFile     f = read_problem_file(file);
            const ContactProblem &p = f.contact;

            const RoutedContactSolution r = solve_contact_problem_by_routes(p);
            {
              const ContactSolution t = solve_contact_problem(p);
              std::string           unused;
              if (kind.second ? (t.lcp.status == Status::solved &&
                                 check_solution(p, t.P, t.n_facets, unused)) :
                                t.lcp.status == Status::infeasible)
                ++time_loop_as_expected;
              else
                std::cout << file << " (time-loop path): " << t.message
                          << std::endl;
            }
            const Status status = r.solution.lcp.status;
            // a problem that is neither solved nor proven infeasible stays on
            // disk, to be looked at with lcp-solve
            if (status == Status::solved || status == Status::infeasible)
              std::remove(file.c_str());
            std::string why;
            if (status == Status::solved)
              {
                if (check_solution(p, r.solution.P, r.solution.n_facets, why))
                  {
                    ++solved;
                    ++route_share[std::to_string(dim) + "D " +
                                  r.attempts[r.successful_route].kind + " (" +
                                  r.attempts[r.successful_route].route.substr(
                                    0, 18) +
                                  ")"];
                  }
                else
                  {
                    ++wrong;
                    std::cout << file << ": solved but fails the check: " << why
                              << std::endl;
                  }
              }
            else if (status == Status::infeasible)
              ++infeasible;
            else
              {
                ++other;
                std::cout << file << ": " << r.solution.message << std::endl;
              }
          }
        // Never a wrong answer, never a solvable problem called infeasible,
        // every unsolvable one reported infeasible. (Solvable problems left
        // unsolved are counted in the line above: see doc/lcp.md.)
        const bool ok =
          (wrong == 0) &&
          (kind.second ? (infeasible == 0) : (infeasible == per_class));
        total_ok += (kind.second ? solved : infeasible);
        dealii::deallog << dim << "D " << kind.first << ": " << per_class
                        << " problems, " << solved << " solved and verified, "
                        << infeasible << " proven infeasible, " << other
                        << " neither, " << wrong << " wrong; time-loop path "
                        << time_loop_as_expected << " as expected" << std::endl;
        impactfe_tests::check(ok,
                              std::to_string(dim) + "D " + kind.first +
                                (kind.second ?
                                   ": no wrong answer, none called infeasible" :
                                   ": every problem reported infeasible"));
      }
  dealii::deallog << total << " problems, " << total_ok
                  << " answered as expected" << std::endl;
  for (const auto &s : route_share)
    std::cout << "solved by " << s.first << ": " << s.second << std::endl;
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
