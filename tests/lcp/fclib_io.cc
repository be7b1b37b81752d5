// FCLib HDF5 files (read_fclib_file, write_fclib_local_file), the exact-cone
// error, and the solve by independent groups of contacts:
//  1. exact round trips of local problems in the three matrix storages;
//  2. global problems (M v = H r + f, u = H^T v + w) written here with the
//     HDF5 C library, M in triplets with both triangles and by rows with one
//     triangle: W = H^T M^{-1} H and q = H^T M^{-1} f + w against the same
//     products computed with the tests' own Gaussian elimination;
//  3. one clear error per kind of bad file;
//  4. the exact-cone error on a hand-computed case;
//  5. three independent problems interleaved in one: the groups are found,
//     and solving them separately gives the whole problem's impulses; a
//     600-contact chain solved by rounds of candidates gives them too;
//  6. the same rank-deficient 3D problem with W and q scaled by 1e-8 .. 1e6:
//     always solved, the same impulses (LMGC90's PerioBox file, W ~ 1e-5,
//     ended in rays and a false "infeasible" before W was scaled).
#include <impactfe/lcp/contact_routes.h>
#include <impactfe/lcp/fclib_io.h>
#include <impactfe/lcp/problem_io.h>

#include <hdf5.h>

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "../tests.h"

#include "lcp_test_tools.h"

using namespace impactfe::lcp;
using dealii::deallog;
using impactfe_tests::check;

namespace
{
  // W = H^T M^{-1} H of a random Lagrangian model: ndof degrees of freedom,
  // M diagonal with masses in [0.5, 2], H with 3 nonzeros per column.
  ContactProblem
  random_problem(lcp_test::Rng     &rng,
                 const unsigned int d,
                 const unsigned int n_contacts,
                 const unsigned int ndof)
  {
    const unsigned int m = d * n_contacts;
    DenseMatrix        H(ndof, m);
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int k = 0; k < 3; ++k)
        H(rng.integer(ndof), j) += rng.uniform(-1., 1.);
    std::vector<double> inverse_mass(ndof);
    for (double &v : inverse_mass)
      v = 1. / rng.uniform(0.5, 2.);
    ContactProblem p;
    p.n_directions = d;
    p.n_contacts   = n_contacts;
    p.W.reinit(m, m);
    for (unsigned int i = 0; i < m; ++i)
      for (unsigned int j = 0; j < m; ++j)
        for (unsigned int a = 0; a < ndof; ++a)
          p.W(i, j) += H(a, i) * inverse_mass[a] * H(a, j);
    p.free_velocity.resize(m);
    for (double &v : p.free_velocity)
      v = rng.uniform(-1., 1.);
    p.gap_term.resize(n_contacts);
    for (double &b : p.gap_term)
      b = rng.uniform(0., 0.3);
    p.mu.resize(n_contacts);
    for (double &mu : p.mu)
      mu = rng.uniform(0.1, 0.8);
    return p;
  }

  // Raw HDF5 writing, independent of the writer under test.
  class RawFile
  {
  public:
    explicit RawFile(const std::string &name)
      : file(H5Fcreate(name.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT))
    {}
    ~RawFile()
    {
      H5Fclose(file);
    }
    void
    group(const std::string &path)
    {
      H5Gclose(
        H5Gcreate2(file, path.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT));
    }
    void
    ints(const std::string &path, const std::vector<int> &v)
    {
      write(path, H5T_STD_I32LE, H5T_NATIVE_INT, v.size(), v.data());
    }
    void
    doubles(const std::string &path, const std::vector<double> &v)
    {
      write(path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, v.size(), v.data());
    }
    // A matrix group in one of FCLib's three forms from a dense matrix;
    // only entries (i, j) with keep(i, j) are stored.
    template <typename Keep>
    void
    matrix(const std::string &path,
           const DenseMatrix &A,
           const int          nz_kind,
           const Keep        &keep)
    {
      std::vector<int>    p, idx;
      std::vector<double> x;
      const int           rows = A.n_rows(), cols = A.n_cols();
      if (nz_kind >= 0)
        {
          for (int i = 0; i < rows; ++i)
            for (int j = 0; j < cols; ++j)
              if (A(i, j) != 0. && keep(i, j))
                {
                  idx.push_back(i);
                  p.push_back(j);
                  x.push_back(A(i, j));
                }
        }
      else
        {
          const bool by_columns = nz_kind == -1;
          p.push_back(0);
          for (int a = 0; a < (by_columns ? cols : rows); ++a)
            {
              for (int b = 0; b < (by_columns ? rows : cols); ++b)
                {
                  const int    i = by_columns ? b : a, j = by_columns ? a : b;
                  const double v = A(i, j);
                  if (v != 0. && keep(i, j))
                    {
                      idx.push_back(b);
                      x.push_back(v);
                    }
                }
              p.push_back(int(x.size()));
            }
        }
      group(path);
      ints(path + "/m", {rows});
      ints(path + "/n", {cols});
      ints(path + "/nz", {nz_kind >= 0 ? int(x.size()) : nz_kind});
      ints(path + "/nzmax", {int(x.size())});
      ints(path + "/p", p);
      ints(path + "/i", idx);
      doubles(path + "/x", x);
    }

  private:
    void
    write(const std::string &path,
          const hid_t        file_type,
          const hid_t        memory_type,
          const hsize_t      n,
          const void        *data)
    {
      const hid_t space = H5Screate_simple(1, &n, nullptr);
      const hid_t set   = H5Dcreate2(file,
                                   path.c_str(),
                                   file_type,
                                   space,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT,
                                   H5P_DEFAULT);
      H5Dwrite(set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data);
      H5Dclose(set);
      H5Sclose(space);
    }
    hid_t file;
  };

  const auto all = [](int, int) { return true; };

  // A local problem file with W from A, written raw, for the error cases.
  void
  write_local(const std::string         &name,
              const DenseMatrix         &W,
              const std::vector<double> &q,
              const std::vector<double> &mu,
              const int                  spacedim,
              const int                  nz_kind = -1)
  {
    RawFile f(name);
    f.group("/fclib_local");
    f.matrix("/fclib_local/W", W, nz_kind, all);
    f.group("/fclib_local/vectors");
    f.doubles("/fclib_local/vectors/q", q);
    f.doubles("/fclib_local/vectors/mu", mu);
    f.ints("/fclib_local/spacedim", {spacedim});
  }

  std::string
  read_error(const std::string &name)
  {
    try
      {
        read_fclib_file(name);
      }
    catch (const std::runtime_error &e)
      {
        return e.what();
      }
    return "no error";
  }

  double
  max_relative_difference(const std::vector<double> &a,
                          const std::vector<double> &b)
  {
    double d = 0., s = 0.;
    for (std::size_t k = 0; k < a.size(); ++k)
      {
        d = std::max(d, std::abs(a[k] - b[k]));
        s = std::max(s, std::abs(b[k]));
      }
    return a.size() == b.size() ? d / std::max(s, 1e-300) : 1e300;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng rng(1234);

  // 1. Round trips.
  for (const unsigned int d : {2u, 3u})
    for (const FclibStorage storage : {FclibStorage::compressed_column,
                                       FclibStorage::compressed_row,
                                       FclibStorage::triplet})
      {
        const ContactProblem p = random_problem(rng, d, 7, 2 * 7);
        FclibInfo            info;
        info.title       = "random " + std::to_string(d) + "D";
        info.description = "Lagrangian model, 7 contacts";
        info.math_info   = "W positive semidefinite";
        FclibSolution solution;
        solution.r.assign(d * 7, 0.25);
        solution.u = p.free_velocity;
        write_fclib_local_file("roundtrip.hdf5", p, info, &solution, storage);
        const FclibProblem r       = read_fclib_file("roundtrip.hdf5");
        bool               W_exact = r.contact.W.n_rows() == d * 7;
        for (unsigned int i = 0; W_exact && i < d * 7; ++i)
          for (unsigned int j = 0; j < d * 7; ++j)
            W_exact = W_exact && r.contact.W(i, j) == p.W(i, j);
        bool q_exact = r.contact.free_velocity.size() == d * 7;
        for (unsigned int k = 0; q_exact && k < d * 7; ++k)
          q_exact = r.contact.free_velocity[k] ==
                    p.free_velocity[k] + (k % d == 0 ? p.gap_term[k / d] : 0.);
        const std::string name =
          "round trip " + std::to_string(d) + "D " +
          (storage == FclibStorage::compressed_column ? "columns" :
           storage == FclibStorage::compressed_row    ? "rows" :
                                                        "triplets");
        check(W_exact && q_exact && r.contact.mu == p.mu &&
                r.contact.n_directions == d && r.contact.n_contacts == 7 &&
                !r.from_global &&
                r.contact.gap_term == std::vector<double>(7, 0.),
              name + ": W, q = free velocity + gap, mu exact");
        check(r.info.title == info.title &&
                r.info.description == info.description &&
                r.info.math_info == info.math_info &&
                r.solution.r == solution.r && r.solution.u == solution.u &&
                r.solution.v.empty() && r.guesses.empty(),
              name + ": info and solution");
        // read_problem_file() takes the HDF5 file as well
        const ProblemFile f = read_problem_file("roundtrip.hdf5");
        check(f.type == ProblemType::friction_contact &&
                f.contact.free_velocity == r.contact.free_velocity,
              name + ": read_problem_file");
      }

  // 2. Global problems. 9 degrees of freedom in three decoupled blocks
  // (sizes 2, 3, 4) with SPD blocks, 3 contacts in 3D (m = 9).
  {
    const int   n = 9, m = 9;
    DenseMatrix M(n, n), H(n, m);
    const int   blocks[4] = {0, 2, 5, 9};
    for (int b = 0; b < 3; ++b)
      for (int i = blocks[b]; i < blocks[b + 1]; ++i)
        {
          M(i, i) = 3. + rng.uniform();
          for (int j = blocks[b]; j < i; ++j)
            M(i, j) = M(j, i) = rng.uniform(-0.5, 0.5);
        }
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < m; ++j)
        if (rng.uniform() < 0.4)
          H(i, j) = rng.uniform(-1., 1.);
    std::vector<double> f(n), w(m), mu = {0.3, 0.5, 0.1};
    for (double &v : f)
      v = rng.uniform(-1., 1.);
    for (double &v : w)
      v = rng.uniform(-1., 1.);

    // reference: X = M^{-1} [H f] by the tests' Gaussian elimination
    std::vector<std::vector<double>> Mrows(n, std::vector<double>(n));
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        Mrows[i][j] = M(i, j);
    DenseMatrix         W_ref(m, m);
    std::vector<double> q_ref = w, x, column(n);
    for (int c = 0; c <= m; ++c)
      {
        for (int i = 0; i < n; ++i)
          column[i] = c < m ? H(i, c) : f[i];
        lcp_test::gauss_solve(Mrows, column, x);
        for (int a = 0; a < m; ++a)
          {
            double s = 0.;
            for (int i = 0; i < n; ++i)
              s += H(i, a) * x[i];
            if (c < m)
              W_ref(a, c) = s;
            else
              q_ref[a] += s;
          }
      }

    for (const int form : {0, 1})
      {
        {
          RawFile file("global.hdf5");
          file.group("/fclib_global");
          if (form == 0) // triplets, both triangles
            file.matrix("/fclib_global/M", M, 0, all);
          else // compressed rows, upper triangle only (as LMGC90 writes M)
            file.matrix("/fclib_global/M", M, -2, [](int i, int j) {
              return j >= i;
            });
          file.matrix("/fclib_global/H", H, -1, all);
          file.group("/fclib_global/vectors");
          file.doubles("/fclib_global/vectors/f", f);
          file.doubles("/fclib_global/vectors/w", w);
          file.doubles("/fclib_global/vectors/mu", mu);
          file.ints("/fclib_global/spacedim", {3});
          file.group("/guesses");
          file.ints("/guesses/number_of_guesses", {2});
          for (const char *g : {"/guesses/1", "/guesses/2"})
            {
              file.group(g);
              file.doubles(std::string(g) + "/r", std::vector<double>(m, 1.));
              file.doubles(std::string(g) + "/v", std::vector<double>(n, 2.));
            }
        }
        const FclibProblem  r = read_fclib_file("global.hdf5");
        std::vector<double> W_read, W_expected;
        for (int i = 0; i < m; ++i)
          for (int j = 0; j < m; ++j)
            {
              W_read.push_back(r.contact.W(i, j));
              W_expected.push_back(W_ref(i, j));
            }
        const double dW = max_relative_difference(W_read, W_expected);
        const double dq =
          max_relative_difference(r.contact.free_velocity, q_ref);
        check(r.from_global && r.n_global_dofs == 9 &&
                r.contact.n_contacts == 3 && r.contact.n_directions == 3 &&
                dW < 1e-13 && dq < 1e-13,
              std::string("global problem, M ") +
                (form == 0 ? "in triplets" : "by rows, upper triangle") +
                ": W = H^T M^-1 H and q = H^T M^-1 f + w",
              "dW " + std::to_string(dW) + " dq " + std::to_string(dq));
        check(r.guesses.size() == 2 && r.guesses[1].r.size() == 9 &&
                r.guesses[1].v.size() == 9 && r.guesses[1].u.empty() &&
                r.solution.r.empty(),
              "global problem: guesses read, no solution");
      }
  }

  // 3. Bad files.
  {
    const DenseMatrix   W2(4, 4, 1.);
    DenseMatrix         W3(4, 3, 1.);
    std::vector<double> q4(4, -1.), mu2 = {0.3, 0.3};
    std::ofstream("text.hdf5") << "2\n2\n0\n4\n4\n";
    deallog << read_error("text.hdf5") << std::endl;
    deallog << read_error("missing.hdf5") << std::endl;
    {
      RawFile f("empty.hdf5");
      f.group("/something_else");
    }
    deallog << read_error("empty.hdf5") << std::endl;
    {
      RawFile f("no_q.hdf5");
      f.group("/fclib_local");
      f.matrix("/fclib_local/W", W2, -1, all);
      f.group("/fclib_local/vectors");
      f.doubles("/fclib_local/vectors/mu", mu2);
      f.ints("/fclib_local/spacedim", {2});
    }
    deallog << read_error("no_q.hdf5") << std::endl;
    // a guess count without its groups (a count of 2e9 ran on for ever)
    {
      RawFile f("guesses_missing.hdf5");
      f.group("/fclib_local");
      f.matrix("/fclib_local/W", W2, -1, all);
      f.group("/fclib_local/vectors");
      f.doubles("/fclib_local/vectors/q", q4);
      f.doubles("/fclib_local/vectors/mu", mu2);
      f.ints("/fclib_local/spacedim", {2});
      f.group("/guesses");
      f.ints("/guesses/number_of_guesses", {2000000000});
    }
    deallog << read_error("guesses_missing.hdf5") << std::endl;
    write_local("negative_mu.hdf5", W2, q4, {0.3, -0.1}, 2);
    deallog << read_error("negative_mu.hdf5") << std::endl;
    write_local("short_mu.hdf5", W2, q4, {0.3}, 2);
    deallog << read_error("short_mu.hdf5") << std::endl;
    write_local("odd_size.hdf5", W2, q4, mu2, 3);
    deallog << read_error("odd_size.hdf5") << std::endl;
    write_local("spacedim.hdf5", W2, q4, mu2, 4);
    deallog << read_error("spacedim.hdf5") << std::endl;
    write_local("short_q.hdf5", W2, {1., 2.}, mu2, 2);
    deallog << read_error("short_q.hdf5") << std::endl;
    write_local("not_square.hdf5", W3, q4, mu2, 2);
    deallog << read_error("not_square.hdf5") << std::endl;
    write_local("bad_nz.hdf5", W2, q4, mu2, 2);
    {
      // overwrite nz with -3 and an index out of range in another file
      const hid_t file = H5Fopen("bad_nz.hdf5", H5F_ACC_RDWR, H5P_DEFAULT);
      const hid_t set  = H5Dopen2(file, "/fclib_local/W/nz", H5P_DEFAULT);
      const int   nz   = -3;
      H5Dwrite(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, &nz);
      H5Dclose(set);
      H5Fclose(file);
    }
    deallog << read_error("bad_nz.hdf5") << std::endl;
    write_local("bad_index.hdf5", W2, q4, mu2, 2);
    {
      const hid_t file = H5Fopen("bad_index.hdf5", H5F_ACC_RDWR, H5P_DEFAULT);
      const hid_t set  = H5Dopen2(file, "/fclib_local/W/i", H5P_DEFAULT);
      std::vector<int> i(16);
      H5Dread(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, i.data());
      i[5] = 7;
      H5Dwrite(set, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, i.data());
      H5Dclose(set);
      H5Fclose(file);
    }
    deallog << read_error("bad_index.hdf5") << std::endl;
    write_local("mixed.hdf5", W2, q4, mu2, 2);
    {
      RawFile f("mixed.hdf5");
      f.group("/fclib_local");
      f.matrix("/fclib_local/W", W2, -1, all);
      f.matrix("/fclib_local/V", W2, -1, all);
    }
    deallog << read_error("mixed.hdf5") << std::endl;
    for (const bool spd : {false, true})
      {
        DenseMatrix M(2, 2), H(2, 2, 1.);
        M(0, 0) = spd ? 1. : -1.;
        M(1, 1) = 1.;
        M(0, 1) = spd ? 0.5 : 0.;
        M(1, 0) = spd ? 0.25 : 0.;
        RawFile f(spd ? "unsymmetric_M.hdf5" : "indefinite_M.hdf5");
        f.group("/fclib_global");
        f.matrix("/fclib_global/M", M, 0, all);
        f.matrix("/fclib_global/H", H, -1, all);
        f.group("/fclib_global/vectors");
        f.doubles("/fclib_global/vectors/f", {0., 0.});
        f.doubles("/fclib_global/vectors/w", {0., 0.});
        f.doubles("/fclib_global/vectors/mu", {0.1});
        f.ints("/fclib_global/spacedim", {2});
      }
    deallog << read_error("indefinite_M.hdf5") << std::endl;
    deallog << read_error("unsymmetric_M.hdf5") << std::endl;
    // the writer: an unwritable path
    try
      {
        ContactProblem p = random_problem(rng, 2, 2, 4);
        write_fclib_local_file("no_such_directory/p.hdf5", p);
        deallog << "no error" << std::endl;
      }
    catch (const std::runtime_error &e)
      {
        deallog << e.what() << std::endl;
      }
  }

  // 4. The exact-cone error, by hand: W = I, q = (-1, 2, 0), mu = 1/2.
  // P = (1, -1/2, 0) solves the problem (sliding along +t1): error 0.
  // P = (1, -0.4, 0): u = (0, 1.6, 0), u~ = (0.8, 1.6, 0), x = P - u~ =
  // (0.2, -2, 0), projected onto the cone (0.96, -0.48, 0); |P - proj| =
  // sqrt(0.008), max(|q|, |P|, |u|) = sqrt(5): error 0.04.
  {
    ContactProblem p;
    p.n_directions = 3;
    p.n_contacts   = 1;
    p.W            = DenseMatrix(3, 3);
    p.W(0, 0) = p.W(1, 1) = p.W(2, 2) = 1.;
    p.free_velocity                   = {-1., 2., 0.};
    p.gap_term                        = {0.};
    p.mu                              = {0.5};
    const double e0                   = exact_cone_error(p, {1., -0.5, 0.});
    const double e1                   = exact_cone_error(p, {1., -0.4, 0.});
    check(e0 < 1e-15 && std::abs(e1 - 0.04) < 1e-14,
          "exact-cone error: 0 at the solution, 0.04 at the hand-computed "
          "point",
          std::to_string(e0) + " " + std::to_string(e1));
  }

  // 5. Three independent problems (2D, 4 + 5 + 6 contacts) interleaved.
  {
    const ContactProblem parts[3] = {random_problem(rng, 2, 4, 8),
                                     random_problem(rng, 2, 5, 10),
                                     random_problem(rng, 2, 6, 12)};
    // contact c of the whole problem is contact local[c] of part owner[c]
    std::vector<unsigned int> owner, local;
    unsigned int              counts[3] = {0, 0, 0};
    for (unsigned int c = 0; c < 15; ++c)
      {
        unsigned int k = c % 3;
        while (counts[k] == parts[k].n_contacts)
          k = (k + 1) % 3;
        owner.push_back(k);
        local.push_back(counts[k]++);
      }
    ContactProblem p;
    p.n_directions = 2;
    p.n_contacts   = 15;
    p.W.reinit(30, 30);
    p.free_velocity.resize(30);
    p.gap_term.resize(15);
    p.mu.resize(15);
    for (unsigned int a = 0; a < 15; ++a)
      {
        const ContactProblem &pa = parts[owner[a]];
        p.gap_term[a]            = pa.gap_term[local[a]];
        p.mu[a]                  = pa.mu[local[a]];
        for (unsigned int i = 0; i < 2; ++i)
          {
            p.free_velocity[2 * a + i] = pa.free_velocity[2 * local[a] + i];
            for (unsigned int b = 0; b < 15; ++b)
              if (owner[b] == owner[a])
                for (unsigned int j = 0; j < 2; ++j)
                  p.W(2 * a + i, 2 * b + j) =
                    pa.W(2 * local[a] + i, 2 * local[b] + j);
          }
      }
    const auto groups = independent_contact_groups(p);
    bool       right  = groups.size() == 3;
    for (const auto &g : groups)
      for (const unsigned int c : g)
        right = right && owner[c] == owner[g[0]];
    check(right, "independent groups: 3, each the contacts of one part");

    const GroupedContactSolution s     = solve_contact_problem_by_groups(p);
    const RoutedContactSolution  whole = solve_contact_problem_by_routes(p);
    const ContactVerification    v = verify_contact_solution(p, s.solution.P);
    check(s.solution.lcp.status == Status::solved && s.n_groups == 3 &&
            s.largest_group == 6 && s.solution.lcp.verification.ok && v.ok &&
            whole.solution.lcp.status == Status::solved &&
            max_relative_difference(s.solution.P, whole.solution.P) < 1e-9 &&
            exact_cone_error(p, s.solution.P) < 1e-12,
          "solved by groups: verified, the whole problem's P, exact-cone "
          "error < 1e-12");
    deallog << "  separated/sticking/sliding " << v.n_separated << '/'
            << v.n_sticking << '/' << v.n_sliding << std::endl;
  }

  // 5b. One group of 600 contacts (a chain, W block tridiagonal and
  // diagonally dominant): only the approaching contacts and those their
  // neighbours push in enter the LCPs, in rounds; the answer is the whole
  // problem's, which is computed here as one LCP too.
  {
    const unsigned int n = 600;
    ContactProblem     p;
    p.n_directions = 2;
    p.n_contacts   = n;
    p.W.reinit(2 * n, 2 * n);
    p.free_velocity.resize(2 * n);
    p.gap_term.assign(n, 0.);
    p.mu.assign(n, 0.3);
    for (unsigned int c = 0; c < n; ++c)
      {
        p.W(2 * c, 2 * c)         = 3.;
        p.W(2 * c + 1, 2 * c + 1) = 2.;
        p.W(2 * c, 2 * c + 1) = p.W(2 * c + 1, 2 * c) = 0.2;
        if (c + 1 < n)
          {
            const unsigned int a = 2 * c, b = 2 * (c + 1);
            p.W(a, b) = p.W(b, a) = -0.6;
            p.W(a + 1, b + 1) = p.W(b + 1, a + 1) = -0.4;
            p.W(a, b + 1) = p.W(b + 1, a) = p.W(a + 1, b) = p.W(b, a + 1) = 0.1;
          }
        p.free_velocity[2 * c] =
          rng.uniform() < 0.1 ? rng.uniform(-1., 0.) : rng.uniform(0., 0.3);
        p.free_velocity[2 * c + 1] = rng.uniform(-0.5, 0.5);
      }
    const GroupedContactSolution s     = solve_contact_problem_by_groups(p);
    const RoutedContactSolution  whole = solve_contact_problem_by_routes(p);
    const ContactVerification    v = verify_contact_solution(p, s.solution.P);
    check(s.solution.lcp.status == Status::solved && v.ok &&
            s.candidate_rounds > 1 && s.n_candidates < n &&
            exact_cone_error(p, s.solution.P) < 1e-12 &&
            whole.solution.lcp.status == Status::solved &&
            max_relative_difference(s.solution.P, whole.solution.P) < 1e-8,
          "600-contact chain by candidate rounds: verified, exact-cone error "
          "< 1e-12, the whole problem's P");
    deallog << "  candidates " << s.n_candidates << " of " << n << " after "
            << s.candidate_rounds << " rounds, " << s.n_groups << " groups"
            << std::endl;
  }

  // 6. Scale: a rank-deficient 3D problem (12 contacts, 20 degrees of
  // freedom) with W and q multiplied by s.
  {
    const ContactProblem base = random_problem(rng, 3, 12, 20);
    std::vector<double>  P_reference;
    bool                 all_solved = true, same = true;
    for (const double s : {1., 1e-8, 1e-5, 1e-2, 1e3, 1e6})
      {
        ContactProblem p = base;
        for (std::size_t i = 0; i < 36; ++i)
          for (std::size_t j = 0; j < 36; ++j)
            p.W(i, j) *= s;
        for (double &v : p.free_velocity)
          v *= s;
        for (double &b : p.gap_term)
          b *= s;
        const RoutedContactSolution r = solve_contact_problem_by_routes(p);
        all_solved = all_solved && r.solution.lcp.status == Status::solved;
        if (s == 1.)
          P_reference = r.solution.P;
        else
          same =
            same && max_relative_difference(r.solution.P, P_reference) < 1e-8;
      }
    check(all_solved && same,
          "W and q scaled by 1e-8 .. 1e6: solved, the same P");
  }

  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
