#ifndef impactfe_output_scene_recorder_h
#define impactfe_output_scene_recorder_h

#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/output/output.h>

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace impactfe
{
  /**
   * Everything a contact program records during a run, in one place: the
   * ContactMonitor's checks, `history.csv` (the monitor's columns plus the
   * program's own), `contact_nodes.csv`, the VTU/PVD files and
   * `shapes.csv`, as the `Output` subsection asks.
   *
   * Use: construct after MultibodySystem::setup(), then record() after
   * every step (and once with an empty StepReport for t = 0), finish() at
   * the end.
   */
  template <int dim>
  class SceneRecorder
  {
  public:
    SceneRecorder(const MultibodySystem<dim>     &system,
                  const OutputParameters         &output,
                  const std::vector<std::string> &extra_columns = {});

    /**
     * Account for the step of @p report (not for the initial state,
     * report.step == 0) and write its outputs. @p extra_values go to the
     * program's extra history columns.
     */
    void
    record(const StepReport          &report,
           const std::vector<double> &extra_values = {});

    /** Close history.csv: it is complete and valid from here on. */
    void
    finish();

    const ContactMonitor<dim> &
    monitor() const;

    /** The common entries of summary.json (run, LCP, checks). */
    void
    add_summary(JsonObject &summary) const;

    /** "Results in ..." and the plot of @p columns, on @p out. */
    void
    report_files(std::ostream                   &out,
                 const std::vector<std::string> &columns,
                 const std::string              &title) const;

  private:
    const MultibodySystem<dim>       &system;
    OutputParameters                  output;
    ContactMonitor<dim>               contact_monitor;
    std::unique_ptr<HistoryWriter>    history;
    SolutionWriter<dim>               solution_writer;
    std::unique_ptr<ShapeWriter<dim>> shape_writer;
  };
} // namespace impactfe

#endif
