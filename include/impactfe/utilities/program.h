#ifndef impactfe_utilities_program_h
#define impactfe_utilities_program_h

#include <deal.II/base/parameter_handler.h>

#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace impactfe
{
  /** A number as a user wrote it: shortest round-trip-ish, no padding. */
  std::string
  format_number(const double value);

  /**
   * An input value in a range error: six digits where they give the value
   * back, more where they do not (1.0000001 must not read "1" beside
   * "must be in [0.5, 1]").
   */
  std::string
  format_input(const double value);

  /**
   * A figure of merit as a report prints it: three significant digits, and
   * values below @p round_off as "< round_off", so that the output does not
   * depend on the last bits.
   */
  std::string
  format_figure(const double value, const double round_off = 1e-12);

  /**
   * Append @p value to @p line as printf's "%.10g" would write it, then
   * @p separator: the CSV files' number format. std::to_chars, several
   * times faster than a stream, matters for files written at every step.
   */
  void
  append_csv_number(std::string &line,
                    const double value,
                    const char   separator);

  /**
   * An item of a list entry as a number: @p text must be a finite number
   * (subnormal ones included, which deal.II's string_to_double refuses as
   * "Can't convert"); otherwise throw with the message "<subsection>:
   * '<entry>' has '<text>', which is not a finite number.".
   */
  double
  parse_list_number(const std::string &text,
                    const std::string &subsection,
                    const std::string &entry);

  /**
   * Throw, with the message "<subsection>: '<entry>' must be > 0, got
   * <value>.", unless @p value is finite and > 0. For the checks that
   * parse_parameters() makes on the entries it has read.
   */
  void
  require_positive(const double       value,
                   const std::string &subsection,
                   const std::string &entry);

  /**
   * Throw, naming @p subsection and the entries, unless the parameter file
   * set each of @p entries of @p subsection. For entries declared with
   * deal.II's `has_to_be_set = true` (ParameterHandler::declare_entry()):
   * physical data whose default would be a placeholder (E = 1 Pa), so that
   * a file that leaves them out gives a message, not a silent wrong answer.
   * deal.II's own assert_that_entries_have_been_set() would name them in
   * mangled form (Material.Young_27s_20modulus) and could not skip the
   * subsection of a body that is not in the scene. Call it outside any
   * subsection (@p subsection is a top-level one).
   */
  void
  require_entries_set(const dealii::ParameterHandler &prm,
                      const std::string              &subsection,
                      const std::vector<std::string> &entries);

  /**
   * Throw unless the mass @p mass [kg] of @p what ("the plate", "the
   * bodies") is in [1e-100, 1e100] kg: momenta and energies are sums of
   * squares times masses, and outside that range they leave double
   * precision (a plate 1e-300 m thick gave an impulse balance of 0/0).
   */
  void
  require_representable_mass(const double mass, const std::string &what);

  /** The same for "must be >= 0". */
  void
  require_non_negative(const double       value,
                       const std::string &subsection,
                       const std::string &entry);

  /**
   * What @p error says, for a message of ours that carries it: a deal.II
   * exception's text without its source location and stack trace
   * (print_info()), another one's what(); blanks at both ends trimmed.
   */
  std::string
  exception_text(const std::exception &error);

  /**
   * Sends what is written to std::cerr to a stream while it lives: for
   * deal.II readers that print an inner error (muParser's, the ABAQUS
   * conversion's with its stack trace) to std::cerr before they throw,
   * so that the program's one message can say it instead.
   */
  class CerrCapture
  {
  public:
    explicit CerrCapture(std::ostream &into)
      : saved(std::cerr.rdbuf(into.rdbuf()))
    {}

    ~CerrCapture()
    {
      std::cerr.rdbuf(saved);
    }

    CerrCapture(const CerrCapture &) = delete;
    CerrCapture &
    operator=(const CerrCapture &) = delete;

  private:
    std::streambuf *saved;
  };

  /**
   * The statements of the .prm file @p file as ParameterHandler reads them:
   * comments from '#' removed, lines continued by a trailing backslash
   * joined, blanks at both ends trimmed, empty statements dropped. Each
   * comes with the number of its first line. An unreadable file gives none.
   */
  std::vector<std::pair<unsigned int, std::string>>
  parameter_file_statements(const std::filesystem::path &file);

  /**
   * The file that a statement "include <file>" names (relative to the
   * working directory, as deal.II opens it), or an empty string when
   * @p statement is not an include statement.
   */
  std::string
  included_file(const std::string &statement);

  /**
   * prm.parse_input(@p file), after checks whose failure deal.II would
   * report without the file's name, or not at all: the file must exist, be
   * a file (not a directory) and end in .prm, .json or .xml, and its
   * include statements must name files that exist and must not lead back
   * to a file that includes them (deal.II would recurse until the stack
   * overflows). deal.II's own parse errors name the file and line.
   */
  void
  read_parameter_file(dealii::ParameterHandler &prm, const std::string &file);

  /**
   * A bound of the subsection "Verification", which the caller has entered:
   * the entry @p entry read as a number that must be >= 0, or -1 for "no
   * check". Any other negative value would switch the check off without a
   * word; it is refused with "Verification: '<entry>' must be >= 0 or -1 (no
   * check), got <value>."
   */
  double
  get_verification_bound(dealii::ParameterHandler &prm,
                         const std::string        &entry);

  /**
   * A Coulomb friction coefficient: in [0, 1e6]. Above that the friction
   * rows of a contact problem (mu P_N against P_T) keep fewer digits than
   * the solvers' verification asks for (at mu = 1e14 a cold Lemke start
   * returned sliding nodes with no friction force).
   */
  void
  require_friction_coefficient(const double       value,
                               const std::string &subsection,
                               const std::string &entry);

  /**
   * Throw unless a mesh of @p n_cells cells in @p dim dimensions can fit in
   * this machine's physical memory and in deal.II's 32-bit indices. The
   * estimate is a lower bound measured on the programs (peak resident memory
   * per cell: 1 kB in 1D, 9 kB in 2D, 70 kB in 3D, of which half is counted),
   * so a run that fits is never refused; a run that cannot fit stops at once
   * with a message that names
   * @p entries of @p subsection, instead of swapping or being killed while
   * deal.II builds the mesh. A program that keeps more per cell (the
   * finite-strain programs: 22 kB per axisymmetric cell) passes its own
   * lower bound @p bytes_per_cell.
   */
  void
  require_mesh_fits_in_memory(const double       n_cells,
                              const unsigned int dim,
                              const std::string &subsection,
                              const std::string &entries,
                              const double       bytes_per_cell = 0.);

  /**
   * Print an exception caught in main() to stderr and return the exit code
   * 1. For deal.II exceptions only the message is printed (what went wrong
   * and which entry, value or step), not the library's source location.
   */
  int
  report_exception(const std::exception &exc);

  /**
   * Limit the threads of deal.II (TBB) and of the BLAS to @p n_threads
   * (0: no limit); the BLAS through set_blas_thread_limit(). The solves
   * with supernodal factors call the BLAS for supernodes wider than 32
   * columns, and CHOLMOD's factorisations always: the spinning OpenBLAS
   * workers doubled the process CPU of the plate's time loop (0.075 s to
   * 0.145 s).
   */
  void
  set_thread_limit(const unsigned int n_threads);

  /**
   * CPU seconds used so far by the calling thread (CLOCK_THREAD_CPUTIME_ID):
   * on a shared machine the wall clock would also count the time other
   * processes had the core. For timing phases inside one thread.
   */
  double
  thread_cpu_seconds();

  /**
   * Seconds of a monotonic wall clock (CLOCK_MONOTONIC), the clock for
   * per-step phase timing. It is read in user space (vDSO, 30 ns). The CPU
   * clocks are system calls: 1.3 us a read on this project's virtual
   * machine on 2026-11-28. Six CPU-clock reads per step made a 1D step (320
   * cells per bar) cost 17.7 us instead of 6.8 us.
   */
  double
  wall_seconds();

  /**
   * Accumulating stopwatch with nanosecond resolution, of the process's CPU
   * time (CLOCK_PROCESS_CPUTIME_ID) or of wall time (wall_seconds()): time
   * loops that take milliseconds are measured, not rounded to zero.
   */
  class Stopwatch
  {
  public:
    enum class Clock
    {
      process_cpu,
      wall
    };
    explicit Stopwatch(const Clock clock = Clock::process_cpu);
    void
    start();
    void
    stop();
    /** Accumulated seconds over all start/stop intervals. */
    double
    seconds() const;

  private:
    double
    now() const;

    Clock  clock;
    double accumulated = 0.;
    double started_at  = -1.;
  };

  /**
   * How many processes an MPI launcher started together with this one, and
   * this one's rank, as the launcher announces them in the environment:
   * Open MPI's mpirun (OMPI_COMM_WORLD_SIZE, OMPI_COMM_WORLD_RANK), the
   * PMI of MPICH's and Intel MPI's Hydra (PMI_SIZE, PMI_RANK). {1, 0} when
   * no launcher started it. Read without MPI_Init, which the serial
   * programs do not call.
   */
  struct LaunchedProcesses
  {
    unsigned int size = 1, rank = 0;
  };
  LaunchedProcesses
  launched_processes();

  /**
   * For the serial programs: started by an MPI launcher on several
   * processes, each would make the same run and write the same files at
   * the same time (`mpirun -np 2 cylinder_impact` made two identical runs
   * and printed everything twice). Rank 0 throws, naming @p program, the
   * count and @p alternative (where distributed runs are made); the other
   * ranks exit at once, before anything is written, with 0 (mpirun stops
   * every process at the first non-zero exit, which could cut rank 0's
   * message short; it returns rank 0's 1), so that the message appears
   * once and no process waits for another.
   */
  void
  require_one_process(const std::string &program,
                      const std::string &alternative);

  /**
   * What a simulation program's command line asks: `program [parameter
   * file]` runs (the file, or @p default_file without one), `--help` (or
   * `-h`) prints the usage and `--print-parameters` every entry with its
   * default and help text, in the parameter-file format. Another option or
   * a second argument throws with the usage.
   */
  struct CommandLine
  {
    enum class Action
    {
      run,
      help,
      print_parameters
    };
    Action      action = Action::run;
    std::string parameter_file;
  };
  CommandLine
  parse_command_line(const int          argc,
                     char              *argv[],
                     const std::string &program,
                     const std::string &default_file);

  /** The usage parse_command_line() prints for `--help`. */
  std::string
  command_line_usage(const std::string &program,
                     const std::string &default_file);

  /**
   * Carries out `--help` and `--print-parameters` of @p command_line on
   * the standard output of rank 0 (MPI_COMM_WORLD; the only process of a
   * serial run). @p declare_parameters declares every entry the program
   * reads. Returns whether the program is done, i.e. had no file to run.
   */
  bool
  answer_informational_option(
    const CommandLine                                     &command_line,
    const std::string                                     &program,
    const std::string                                     &default_file,
    const std::function<void(dealii::ParameterHandler &)> &declare_parameters);

  /** The same for an exception of unknown type. */
  int
  report_unknown_exception();

  /**
   * For `catch (...)` in main(): report the exception being handled (with
   * report_exception() if it is a std::exception) and return the exit
   * code 1.
   */
  int
  report_current_exception();
} // namespace impactfe

#endif
