#ifndef impactfe_utilities_program_h
#define impactfe_utilities_program_h

#include <exception>
#include <string>

namespace impactfe
{
  /** A number as a user wrote it: shortest round-trip-ish, no padding. */
  std::string
  format_number(const double value);

  /**
   * Print an exception caught in main() to stderr and return the exit code
   * 1. For deal.II exceptions only the message is printed (what went wrong
   * and which entry, value or step), not the library's source location.
   */
  int
  report_exception(const std::exception &exc);

  /** The same for an exception of unknown type. */
  int
  report_unknown_exception();
} // namespace impactfe

#endif
