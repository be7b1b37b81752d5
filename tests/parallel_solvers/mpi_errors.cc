// Errors in distributed runs (impactfe/utilities/mpi_errors.h): an
// exception met on one rank only is thrown on every rank with that rank's
// message, so that no rank waits in a collective for one that stopped.
// Each rank records what it caught; rank 0 writes whether all agree.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>

#include <impactfe/utilities/mpi_errors.h>

#include <string>

#include "../tests.h"

using namespace dealii;

namespace
{
  // What on_every_rank() / on_rank_zero() made of @p action on this rank:
  // the message it threw, or "" if it did not throw.
  template <typename Run>
  std::string
  caught(const Run &run)
  {
    try
      {
        run();
      }
    catch (const std::exception &e)
      {
        return impactfe::exception_message(e);
      }
    return "";
  }

  // The same string on every rank?
  bool
  same_on_all_ranks(const MPI_Comm comm, const std::string &text)
  {
    const std::string root_text = Utilities::MPI::broadcast(comm, text, 0);
    return Utilities::MPI::min(root_text == text ? 1 : 0, comm) == 1;
  }
} // namespace



int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const unsigned int rank = Utilities::MPI::this_mpi_process(comm);
  if (rank == 0)
    impactfe_tests::initlog();
  const auto report = [&](const std::string &name,
                          const std::string &message,
                          const std::string &expected) {
    const bool agree = same_on_all_ranks(comm, message);
    if (rank == 0)
      {
        deallog << name << ": \"" << message << "\"" << std::endl;
        impactfe_tests::check(agree && message == expected,
                              name + ": every rank threw the expected message");
      }
  };

  // 1. Only rank 1 fails (an inverted cell that rank 1 owns).
  report("1. on_every_rank, rank 1 throws",
         caught([&]() {
           impactfe::on_every_rank(comm, [&]() {
             AssertThrow(rank != 1, ExcMessage("cell 7 of rank 1 is inverted"));
           });
         }),
         "cell 7 of rank 1 is inverted");

  // 2. Both fail: the lowest rank's message.
  report("2. on_every_rank, every rank throws",
         caught([&]() {
           impactfe::on_every_rank(comm, [&]() {
             throw std::runtime_error("rank " + std::to_string(rank));
           });
         }),
         "rank 0");

  // 3. None fails: nothing thrown, and the ranks go on together.
  report("3. on_every_rank, no rank throws",
         caught([&]() { impactfe::on_every_rank(comm, []() {}); }),
         "");

  // 4. Rank 0 cannot write a file: every rank stops.
  report("4. on_rank_zero, rank 0 throws",
         caught([&]() {
           impactfe::on_rank_zero(comm, [&]() {
             AssertThrow(false, ExcMessage("Cannot write history.csv"));
           });
         }),
         "Cannot write history.csv");

  // 5. The action runs on rank 0 only.
  unsigned int runs = 0;
  impactfe::on_rank_zero(comm, [&]() { ++runs; });
  const unsigned int total = Utilities::MPI::sum(runs, comm);
  if (rank == 0)
    impactfe_tests::check(total == 1 && runs == 1,
                          "5. on_rank_zero runs its action on rank 0 only");
  return 0;
}
