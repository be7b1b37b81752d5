// Errors in distributed runs: an exception met on some ranks is thrown on
// every rank, with its message, so that no rank is left waiting in a
// collective operation for one that has stopped.
#ifndef impactfe_utilities_mpi_errors_h
#define impactfe_utilities_mpi_errors_h

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <impactfe/utilities/program.h>

#include <chrono>
#include <exception>
#include <iostream>
#include <sstream>
#include <string>
#include <thread>

namespace impactfe
{
  /**
   * The message of @p e as report_exception() prints it: for a deal.II
   * exception its text, not where it was thrown.
   */
  inline std::string
  exception_message(const std::exception &e)
  {
    const auto *deal_ii = dynamic_cast<const dealii::ExceptionBase *>(&e);
    if (deal_ii == nullptr)
      return e.what();
    std::ostringstream message;
    deal_ii->print_info(message);
    std::string text = message.str();
    text.erase(0, text.find_first_not_of(" \n"));
    text.erase(text.find_last_not_of(" \n") + 1);
    return text;
  }



  /**
   * Run @p action; the message of what it threw (exception_message()), or
   * an empty string.
   */
  template <typename Action>
  std::string
  failure_of(const Action &action)
  {
    try
      {
        action();
      }
    catch (const std::exception &e)
      {
        const std::string message = exception_message(e);
        return message.empty() ? "an error without a message" : message;
      }
    catch (...)
      {
        return "an exception of unknown type";
      }
    return "";
  }



  /**
   * Run @p action on rank 0 only (writing the files); an exception there
   * is thrown on every rank with its message. @p action must not
   * communicate. Without MPI, or on one process, @p action just runs.
   */
  template <typename Action>
  void
  on_rank_zero(const MPI_Comm comm, const Action &action)
  {
    if (!dealii::Utilities::MPI::job_supports_mpi() ||
        dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
      {
        action();
        return;
      }
    std::string error;
    if (dealii::Utilities::MPI::this_mpi_process(comm) == 0)
      error = failure_of(action);
    error = dealii::Utilities::MPI::broadcast(comm, error, 0);
    AssertThrow(error.empty(), dealii::ExcMessage(error));
  }



  /**
   * Run @p action on every rank; if it throws on some, the message of the
   * lowest of them is thrown on all (an inverted element is found only by
   * the rank that owns it). @p action must not communicate. On one
   * process @p action just runs.
   */
  template <typename Action>
  void
  on_every_rank(const MPI_Comm comm, const Action &action)
  {
    if (!dealii::Utilities::MPI::job_supports_mpi() ||
        dealii::Utilities::MPI::n_mpi_processes(comm) == 1)
      {
        action();
        return;
      }
    std::string        error   = failure_of(action);
    const unsigned int n_ranks = dealii::Utilities::MPI::n_mpi_processes(comm);
    const unsigned int first   = dealii::Utilities::MPI::min(
      error.empty() ? n_ranks : dealii::Utilities::MPI::this_mpi_process(comm),
      comm);
    if (first == n_ranks)
      return;
    error = dealii::Utilities::MPI::broadcast(comm, error, first);
    AssertThrow(false, dealii::ExcMessage(error));
  }



  /**
   * For `catch (...)` in the main() of a distributed program, where every
   * rank normally meets the error (on_rank_zero(), on_every_rank()): rank
   * 0 reports it (report_current_exception()), and all ranks meet at a
   * barrier before they exit with 1, since mpirun stops every process at
   * the first non-zero exit and would cut rank 0's message short. An error
   * met by some ranks only leaves the others elsewhere: after 10 s at the
   * barrier a rank other than 0 prints its own message and the job is
   * aborted (MPI_Abort). That is a best effort, not a guarantee: such a
   * rank may block before, while its objects are destroyed (a MUMPS
   * solver shuts down collectively).
   */
  inline int
  report_current_exception_on_rank_zero(const MPI_Comm comm)
  {
    if (!dealii::Utilities::MPI::job_supports_mpi())
      return report_current_exception();
    const unsigned int rank = dealii::Utilities::MPI::this_mpi_process(comm);
    const int          code = rank == 0 ? report_current_exception() : 1;
    MPI_Request        request;
    MPI_Ibarrier(comm, &request);
    int        done  = 0;
    const auto start = std::chrono::steady_clock::now();
    while (!done)
      {
        MPI_Test(&request, &done, MPI_STATUS_IGNORE);
        if (done)
          break;
        if (std::chrono::steady_clock::now() - start > std::chrono::seconds(10))
          {
            if (rank != 0)
              {
                std::cerr << "On MPI rank " << rank << ":" << std::endl;
                report_current_exception();
              }
            MPI_Abort(comm, code);
          }
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    return code;
  }
} // namespace impactfe

#endif
