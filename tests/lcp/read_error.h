// The message with which read_problem() rejects a problem file given as text,
// or "no error": shared by the problem-file tests.
#ifndef impactfe_tests_lcp_read_error_h
#define impactfe_tests_lcp_read_error_h

#include <impactfe/lcp/problem_io.h>

#include <sstream>
#include <stdexcept>
#include <string>

namespace lcp_test
{
  inline std::string
  read_error(const std::string &text)
  {
    std::istringstream in(text);
    try
      {
        impactfe::lcp::read_problem(in, "bad.dat");
      }
    catch (const std::runtime_error &e)
      {
        return e.what();
      }
    return "no error";
  }
} // namespace lcp_test

#endif
