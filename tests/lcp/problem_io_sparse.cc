// Storage type 2 (CSparse text) of the Siconos numerics formats: compressed
// column (origin 2, and the older files without an origin line), compressed
// row (origin 3) and triplet (origin 1, duplicates summed). Exact round trips
// of our writer, files laid out as Siconos writes them (checked against the
// dense reading of the same matrix), and one clear error per kind of
// malformed input.
#include <impactfe/lcp/problem_io.h>

#include <sstream>

#include "../tests.h"

#include "lcp_test_tools.h"
#include "read_error.h"

using namespace impactfe::lcp;

namespace
{
  using lcp_test::read_error;

  ProblemFile
  read_text(const std::string &text)
  {
    std::istringstream in(text);
    return read_problem(in, "text");
  }

  // The same 2-contact 2D problem in four layouts. Dense: column-major.
  const std::string dense_file = "2\n2\n0\n4\n4\n4\t4\n"
                                 "2 0 0 -0.5\n0 3 0 0\n0 0 4 0\n-0.5 0 0 5\n"
                                 "-1 0.5 -2 0.1\n0.3 0.3\n";
  const std::string csc_body =
    "    col 0 : locations 0 to 1\n      0 : 2\n      3 : -0.5\n"
    "    col 1 : locations 2 to 2\n      1 : 3\n"
    "    col 2 : locations 3 to 3\n      2 : 4\n"
    "    col 3 : locations 4 to 5\n      0 : -0.5\n      3 : 5\n";
  const std::string header =
    "CSparse Version 3.1.9, May 4, 2016.  Copyright (c) Timothy A. Davis, 2006-2016\n";
  const std::string tail = "-1 0.5 -2 0.1\n0.3 0.3\n";
} // namespace

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng rng(2024);

  const ProblemFile reference = read_text(dense_file);

  // 1. Siconos' layouts, each compared with the dense reading.
  {
    const std::string csc = "2\n2\n2\n4\n4\n2\n" + header +
                            "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
                            csc_body + tail;
    const std::string csc_old = "2\n2\n2\n4\n4\n" + header +
                                "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
                                csc_body + tail;
    // compressed rows: the same text read as rows is the transpose; this
    // matrix is symmetric, so make it unsymmetric first
    const std::string csr =
      "2\n2\n2\n4\n4\n3\n" + header + "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
      "    col 0 : locations 0 to 1\n      0 : 2\n      3 : -0.25\n"
      "    col 1 : locations 2 to 2\n      1 : 3\n"
      "    col 2 : locations 3 to 3\n      2 : 4\n"
      "    col 3 : locations 4 to 5\n      0 : -0.5\n      3 : 5\n" +
      tail;
    const std::string triplet =
      "2\n2\n2\n4\n4\n1\n" + header + "triplet: 4-by-4, nzmax: 7 nnz: 7\n" +
      "    0 0 : 2\n    3 0 : -0.5\n    1 1 : 3\n    2 2 : 4\n"
      "    0 3 : -0.5\n    3 3 : 4.5\n    3 3 : 0.5\n" +
      tail;
    const ProblemFile f_csc = read_text(csc), f_old = read_text(csc_old),
                      f_csr = read_text(csr), f_trip = read_text(triplet);
    impactfe_tests::check(f_csc.contact.W.data() ==
                              reference.contact.W.data() &&
                            f_csc.contact.free_velocity ==
                              reference.contact.free_velocity &&
                            f_csc.contact.mu == reference.contact.mu,
                          "compressed column (origin 2) == dense");
    impactfe_tests::check(
      f_old.contact.W.data() == reference.contact.W.data(),
      "compressed column without origin line (older Siconos) == dense");
    impactfe_tests::check(f_trip.contact.W.data() == reference.contact.W.data(),
                          "triplet (origin 1, duplicates summed) == dense");
    impactfe_tests::check(f_csr.contact.W(0, 3) == -0.25 &&
                            f_csr.contact.W(3, 0) == -0.5 &&
                            f_csr.contact.W(1, 1) == 3.,
                          "compressed row (origin 3): 'col j' is row j");
  }

  // 2. Exact round trips through our writer, LCP and contact problems, with
  //    values over 16 decades and exact zeros.
  for (const MatrixStorage storage : {MatrixStorage::dense,
                                      MatrixStorage::compressed_column,
                                      MatrixStorage::triplet})
    {
      const unsigned int  n = 7;
      DenseMatrix         M(n, n, 0.);
      std::vector<double> q(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          q[i] = rng.uniform(-1., 1.);
          for (unsigned int j = 0; j < n; ++j)
            if (rng.uniform() < 0.4)
              M(i, j) =
                rng.uniform(-1., 1.) * std::pow(10., rng.uniform(-8., 8.));
        }
      std::stringstream s;
      write_lcp(s, M, q, storage);
      const ProblemFile f = read_problem(s, "roundtrip");

      ContactProblem p;
      p.n_directions = 3;
      p.n_contacts   = 3;
      p.W            = DenseMatrix(9, 9, 0.);
      for (unsigned int i = 0; i < 9; ++i)
        for (unsigned int j = 0; j < 9; ++j)
          if (rng.uniform() < 0.5)
            p.W(i, j) = rng.uniform(-1., 1.);
      p.free_velocity.resize(9);
      for (double &v : p.free_velocity)
        v = rng.uniform(-1., 1.);
      p.gap_term.assign(3, 0.);
      p.mu = {0., 0.3, 7.5};
      std::stringstream sc;
      write_friction_contact(sc, p, storage);
      const ProblemFile fc = read_problem(sc, "roundtrip");
      impactfe_tests::check(
        f.type == ProblemType::lcp && f.lcp.M.data() == M.data() &&
          f.lcp.q == q && fc.type == ProblemType::friction_contact &&
          fc.contact.W.data() == p.W.data() &&
          fc.contact.free_velocity == p.free_velocity && fc.contact.mu == p.mu,
        std::string("exact round trip, storage ") +
          (storage == MatrixStorage::dense   ? "dense" :
           storage == MatrixStorage::triplet ? "triplet" :
                                               "compressed column"));
    }

  // 3. Malformed sparse input: file, line and what is wrong.
  const std::string start = "2\n2\n2\n4\n4\n2\n" + header;
  dealii::deallog << read_error("2\n2\n2\n4\n4\n") << std::endl;
  dealii::deallog << read_error(start +
                                "4-by-3, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
                                csc_body + tail)
                  << std::endl;
  dealii::deallog
    << read_error(start + "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
                  "    col 0 : locations 0 to 1\n      0 : 2\n      4 : -0.5\n")
    << std::endl;
  dealii::deallog
    << read_error(start + "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
                  "    col 0 : locations 0 to 1\n      0 : 2\n      3 : -0.5\n"
                  "    col 1 : locations 1 to 2\n")
    << std::endl;
  dealii::deallog << read_error(start +
                                "4-by-4, nzmax: 6 nnz: 5, 1-norm: 5.5\n" +
                                csc_body + tail)
                  << std::endl;
  dealii::deallog << read_error(
                       start + "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
                       "    col 0 : locations 0 to 1\n      0 : 2\n  ...\n")
                  << std::endl;
  dealii::deallog << read_error("2\n2\n2\n4\n4\n1\n" + header +
                                "triplet: 4-by-4, nzmax: 2 nnz: 2\n" +
                                "    0 0 : 2\n    0 9 : 1\n")
                  << std::endl;
  dealii::deallog << read_error("2\n2\n2\n4\n4\n2\n(null)\n") << std::endl;
  dealii::deallog
    << read_error(
         start + "4-by-4, nzmax: 6 nnz: 6, 1-norm: 5.5\n" +
         "    col 0 : locations 0 to 1\n      0 : 2\n      3 : 1e999\n")
    << std::endl;
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
