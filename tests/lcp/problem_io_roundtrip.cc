// Problem files in the Siconos numerics text formats: round trips, a file as
// found in Siconos' test collection (lcp_CPS_4.dat, dense, column-major, with
// a trailing comment), a sparse-block (storage 1) friction-contact file
// written by hand, the replay of a dumped contact problem (same status, same
// impulses; the gap term is folded into q) and clear errors on malformed
// input.
#include <impactfe/lcp/problem_io.h>

#include <sstream>

#include "../tests.h"

#include "lcp_test_tools.h"
#include "read_error.h"

using namespace impactfe::lcp;

using lcp_test::read_error;

int
main()
{
  impactfe_tests::initlog();
  lcp_test::Rng rng(99);

  // 1. LCP round trip, exact to the last bit
  {
    DenseMatrix         M(5, 5);
    std::vector<double> q(5);
    for (unsigned int i = 0; i < 5; ++i)
      {
        q[i] = rng.uniform(-1., 1.) * 1e-7;
        for (unsigned int j = 0; j < 5; ++j)
          M(i, j) = rng.uniform(-1., 1.) * std::pow(10., rng.uniform(-8., 8.));
      }
    std::stringstream s;
    write_lcp(s, M, q);
    const ProblemFile f = read_problem(s, "roundtrip");
    impactfe_tests::check(f.type == ProblemType::lcp &&
                            f.lcp.M.data() == M.data() && f.lcp.q == q,
                          "LCP round trip is exact");
  }

  // 2. The Siconos file lcp_CPS_4.dat: M is stored column-major; the
  //    solution (2, 2, 2, 92) is known (see lemke_classical.cc).
  {
    std::istringstream in(
      "4\n0\n4\n4\n4\t4\n11 0 10 1\n0 11 10 1\n10 10 21 1\n-1 -1 -1 0\n50 50 10 -6\n"
      "\nsome trailing comment\n");
    const ProblemFile f = read_problem(in, "lcp_CPS_4.dat");
    const Result      r = solve_lemke(f.lcp.M, f.lcp.q);
    dealii::deallog << "lcp_CPS_4.dat: M(0,3) = " << f.lcp.M(0, 3)
                    << ", M(3,0) = " << f.lcp.M(3, 0)
                    << ", z = " << lcp_test::str(r.z) << std::endl;
    impactfe_tests::check(f.type == ProblemType::lcp && f.lcp.M(0, 3) == -1 &&
                            f.lcp.M(3, 0) == 1 &&
                            lcp_test::max_diff(r.z, {2, 2, 2, 92}) < 1e-12,
                          "Siconos dense LCP file");
  }

  // 3. A friction-contact file with a sparse-block matrix: two 2D contacts,
  //    diagonal blocks [2 .5; .5 1] and [3 0; 0 1], one off-diagonal block
  //    (row 0, column 1) [0.1 0.2; 0.3 0.4] (values column-major).
  {
    std::istringstream in(
      "2\n2\n1\n4\n4\n"
      "3\n2\n2\n2\t4\t\n2\t4\t\n3\n3\n0\t2\t3\t\n0\t1\t1\t\n"
      "0\n2\n0.5\n0.5\n1\n"
      "1\n0.1\n0.3\n0.2\n0.4\n"
      "2\n3\n0\n0\n1\n"
      "-1 0.1 -1 0.2\n0.3 0.4\n");
    const ProblemFile     f        = read_problem(in, "sbm.dat");
    const ContactProblem &p        = f.contact;
    const DenseMatrix     expected = lcp_test::matrix(
      {{2, 0.5, 0.1, 0.2}, {0.5, 1, 0.3, 0.4}, {0, 0, 3, 0}, {0, 0, 0, 1}});
    impactfe_tests::check(f.type == ProblemType::friction_contact &&
                            p.n_directions == 2 && p.n_contacts == 2 &&
                            p.W.data() == expected.data() &&
                            p.free_velocity ==
                              std::vector<double>({-1, 0.1, -1, 0.2}) &&
                            p.mu == std::vector<double>({0.3, 0.4}) &&
                            p.gap_term == std::vector<double>({0, 0}),
                          "Siconos sparse-block friction-contact file");
  }

  // 4. Dump a contact problem with a gap term and replay it
  {
    ContactProblem p;
    p.n_directions  = 2;
    p.n_contacts    = 3;
    p.W             = lcp_test::matrix({{2, 0.5, 0.3, 0, 0, 0},
                                        {0.5, 1, 0, 0.1, 0, 0},
                                        {0.3, 0, 2, 0.2, 0.1, 0},
                                        {0, 0.1, 0.2, 1, 0, 0.1},
                                        {0, 0, 0.1, 0, 2, 0.4},
                                        {0, 0, 0, 0.1, 0.4, 1}});
    p.free_velocity = {-1, 0.3, -0.5, -2, 0.4, 0.1};
    p.gap_term      = {0.2, 0.1, 0.7};
    p.mu            = {0.3, 0.2, 0.5};
    std::stringstream s;
    write_friction_contact(s, p);
    const ProblemFile     f  = read_problem(s, "dump.dat");
    const ContactSolution s1 = solve_contact_problem(p);
    const ContactSolution s2 = solve_contact_problem(f.contact);
    dealii::deallog << "replay: " << to_string(s1.lcp.status) << " / "
                    << to_string(s2.lcp.status) << std::endl;
    impactfe_tests::check(
      s1.lcp.status == Status::solved && s2.lcp.status == s1.lcp.status &&
        lcp_test::max_diff(s1.P, s2.P) < 1e-12 &&
        verify_contact_solution(p, s2.P).ok,
      "dumped contact problem replays to the same impulses");
  }

  // 5. Errors name the file and what is wrong
  dealii::deallog << read_error("") << std::endl;
  dealii::deallog << read_error(
                       "3\n0\n3\n3\n3\t3\n1 0 0\n0 1 0\n0 0 1\n-1 -1\n")
                  << std::endl;
  dealii::deallog << read_error("2\n0\n2\n2\n2\t2\n1 x\n0 1\n-1 -1\n")
                  << std::endl;
  dealii::deallog << read_error("2\n2\n2\n4\n4\n") << std::endl;
  dealii::deallog << read_error("hello world\n") << std::endl;
  // a header whose matrix the file cannot hold, or this machine could not
  // store dense, is refused before the matrix is allocated (n = 20000 took
  // 3.2 GB before the reader found the entries missing); the second
  // message ends with this machine's memory, cut off here
  dealii::deallog << read_error("20000\n0\n20000\n20000\n20000 20000\n"
                                "1 0\n0 1\n")
                  << std::endl;
  {
    const std::string message =
      read_error("1000000\n2\n1000000\n1000000\n2\n1000000-by-1000000, "
                 "nzmax: 1 nnz: 1, 1-norm: 1\n");
    dealii::deallog << message.substr(0, message.find("this machine's"))
                    << "..." << std::endl;
  }
  // a sparse header whose q the file cannot hold (n = 40000 in 70 bytes
  // took 12.8 GB before q was found missing)
  dealii::deallog << read_error("40000\n2 40000 40000\ntriplet: "
                                "40000-by-40000, nzmax: 0 nnz: 0\n")
                  << std::endl;
  // sparse block storage with block (0, 0) twice: the second overwrote the
  // first (triplets add up)
  dealii::deallog << read_error("2\n1 2 2\n3\n2 2\n1 2\n1 2\n3\n3\n0 2 3\n"
                                "0 0 1\n0 2\n1 7\n2 2\n-1 -1\n")
                  << std::endl;
  // a negative friction coefficient is named with its contact
  dealii::deallog << read_error("2\n2\n0 4 4\n4 4\n2 0 1 0  0 1 0 0  1 0 2 "
                                "0  0 0 0 1\n-1 0.5 -1 -0.2\n-0.3 0.5\n")
                  << std::endl;
  // more numbers than the header announces (n = 2 but three entries of q;
  // one contact but two friction coefficients; a global problem, M, H, q,
  // b, mu, whose H would be read as q); text after the data is a comment
  // (see 1.), and one 0 or 1 after a contact problem the flag of Siconos'
  // older writers: no error
  dealii::deallog << read_error("2\n0\n2\n2\n2\t2\n1 0\n0 1\n-1 -1 -1\n")
                  << std::endl;
  dealii::deallog << read_error("2\n1\n0\n2\n2\n2\t2\n1 0\n0 1\n-1 0\n"
                                "0.3 0.3\n# mu\n")
                  << std::endl;
  dealii::deallog << read_error("2\n1\n0\n2\n2\n2\t2\n1 0\n0 1\n-1 0\n"
                                "0.3\n# 2 more lines\n")
                  << std::endl;
  dealii::deallog << read_error("2\n1\n0\n2\n2\n2\t2\n1 0\n0 1\n-1 0\n"
                                "0.3\n1\n")
                  << std::endl;
  dealii::deallog << read_error("2\n1\n0\n2\n2\n2\t2\n1 0\n0 1\n0\n2\n2\n"
                                "2\t2\n1 0\n0 1\n-1 0\n0 0\n0.3\n0\n")
                  << std::endl;
  {
    bool thrown = false;
    try
      {
        read_problem_file("/nonexistent/problem.dat");
      }
    catch (const std::runtime_error &e)
      {
        thrown = std::string(e.what()).find("/nonexistent/problem.dat") !=
                 std::string::npos;
      }
    impactfe_tests::check(thrown, "unreadable file reported with its name");
  }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
