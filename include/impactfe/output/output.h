#ifndef impactfe_output_output_h
#define impactfe_output_output_h

#include <deal.II/base/parameter_handler.h>

#include <deal.II/dofs/dof_handler.h>

#include <impactfe/dynamics/multibody_system.h>

#include <fstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /** Parameter subsection `Output`. */
  struct OutputParameters
  {
    std::string  directory         = "results";
    bool         vtu_output        = true;
    unsigned int output_interval   = 1;
    bool         plot              = true;
    bool         print_performance = true;
    /// Write each body's mesh (Gmsh) at the set-up.
    bool write_meshes = false;
    /// Times of the deformed shapes written to shapes.csv (2D).
    std::vector<double> shape_times;

    static void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &default_directory);
    void
    parse_parameters(ParameterHandler &prm);

    /// Throw if `Write meshes` is set, in a program that writes no mesh
    /// files; @p why says where its meshes come from.
    void
    refuse_mesh_output(const std::string &why) const;

    /**
     * Throw unless the run writes every shape snapshot asked for: the
     * program writes shapes (@p writes_shapes: the 2D programs) and each
     * time is reached by its @p n_steps steps of @p time_step. A time past
     * the end would be skipped without a word.
     */
    void
    check_shape_times(const bool         writes_shapes,
                      const unsigned int n_steps,
                      const double       time_step) const;
  };

  /** Create @p directory (and parents); throws with its name on failure. */
  void
  create_output_directory(const std::string &directory);

  /**
   * Remove from @p directory the files of an earlier run of a serial
   * program that describe that run as a whole: summary.json, history.png,
   * solution.pvd, shapes.csv, cells_final.csv (taylor_bar) and the VTU
   * files "<body>-NNNNN.vtu" of the
   * bodies @p body_names. Left there, they would stand beside this run's
   * files (a longer earlier run's last VTU files, its plot), and stay if
   * this run fails. Other files are not touched: LCP dumps of chosen steps,
   * meshes written on request, the user's own.
   *
   * A distributed program names its records in @p parallel_records: for
   * a name "solution" the files "solution_NNNN.pvtu" and the pieces
   * "solution_NNNN.R.vtu" that DataOut::write_vtu_with_pvtu_record()
   * writes (four or more digits N, the rank R in as many digits as the
   * number of ranks needs) go too, which an earlier run on more ranks or
   * with more steps would otherwise leave beside this run's.
   */
  void
  remove_previous_run_output(
    const std::string              &directory,
    const std::vector<std::string> &body_names,
    const std::vector<std::string> &parallel_records = {});



  /**
   * `history.csv`: a header line, then one row per time step. Rows are
   * complete lines, so a run that stops early leaves a valid file.
   */
  class HistoryWriter
  {
  public:
    HistoryWriter(const std::string              &file_name,
                  const std::vector<std::string> &columns);
    void
    add_row(const std::vector<double> &values);
    /// Flush and close the file; throws if a write failed (disk full).
    void
    close();
    const std::vector<std::string> &
    columns() const;

  private:
    std::string              file_name;
    std::ofstream            out;
    std::vector<std::string> column_names;
    /// The row being written, kept so that a row does not allocate.
    std::string line;
  };



  /**
   * A flat JSON object written in one go (`summary.json`): keys in the order
   * they were added, each at most once; values are numbers, strings, or
   * nested objects.
   */
  class JsonObject
  {
  public:
    JsonObject &
    add(const std::string &key, const double value);
    JsonObject &
    add(const std::string &key, const std::string &value);
    JsonObject &
    add(const std::string &key, const JsonObject &value);
    std::string
    str(const unsigned int indent = 0) const;
    void
    write(const std::string &file_name) const;

  private:
    /// Throws std::logic_error if @p key is there already.
    void
    check_new_key(const std::string &key) const;

    std::vector<std::pair<std::string, std::string>> entries;
    std::vector<JsonObject>                          nested;
  };



  /**
   * VTU files of every body on its deformed mesh (one file per body and
   * output step) with displacement, velocity, nodal contact force, and the
   * nodal gap and active flag, plus a `solution.pvd` record with one part
   * per body that ParaView opens as a time series.
   */
  template <int dim>
  class SolutionWriter
  {
  public:
    SolutionWriter(const std::string &directory);
    void
    write(const MultibodySystem<dim> &system, const unsigned int step);

  private:
    std::string                                                directory;
    std::vector<std::tuple<double, unsigned int, std::string>> records;
  };



  /**
   * `shapes.csv`: the deformed mesh (every cell edge of every body, 2D) at
   * chosen times, for figures of deformed shapes: rows
   * `time,body,x0,y0,x1,y1`. write_if_due() writes the state when its time
   * has reached the next requested time (within half a step).
   */
  template <int dim>
  class ShapeWriter
  {
  public:
    ShapeWriter(const std::string &file_name, const std::vector<double> &times);
    void
    write_if_due(const MultibodySystem<dim> &system, const double time_step);

  private:
    std::ofstream       out;
    std::vector<double> times;
    unsigned int        next = 0;
  };

  /** Parse a comma-separated list of times (seconds), e.g. "0, 2.1, 3.3". */
  std::vector<double>
  parse_time_list(const std::string &text, const std::string &entry_name);



  /**
   * Run tools/plot_history.py on @p history (if python3 with matplotlib is
   * there) to draw the columns @p columns, each beside `exact_<column>` when
   * the file has it. Returns the PNG name, or an empty string with the reason
   * in @p why_not.
   */
  std::string
  plot_history(const std::string              &history,
               const std::string              &png,
               const std::vector<std::string> &columns,
               const std::string              &title,
               std::string                    &why_not);



  /**
   * Near the end of a run's screen output (before its checks): "Results
   * in <Output directory>/: "
   * and @p files, then, if `Plot` is set, history.png drawn from the
   * columns @p columns of history.csv by plot_history() (or why there is
   * no plot). history.csv must be complete (closed) by then.
   */
  void
  report_output_files(std::ostream                   &out,
                      const OutputParameters         &output,
                      const std::string              &files,
                      const std::vector<std::string> &columns,
                      const std::string              &title);
} // namespace impactfe

#endif
