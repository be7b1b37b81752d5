#ifndef impactfe_scenes_contact_scene_h
#define impactfe_scenes_contact_scene_h

#include <deal.II/base/parameter_handler.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_parameters.h>
#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/output/output.h>
#include <impactfe/output/scene_recorder.h>
#include <impactfe/time_integration/time_integrator.h>

#include <memory>
#include <ostream>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * The parameter subsections every scene reads, whatever its bodies:
   * `Discretization`, `Time stepping`, `Contact solver`, `Output` and the
   * common entries of `Verification`.
   */
  struct SceneParameters
  {
    DiscretizationParameters      discretization;
    TimeSteppingParameters        time_stepping;
    ContactSolverParameters       contact_solver;
    OutputParameters              output;
    ContactVerificationParameters verification;
    /// Top-level entry `Number of threads` (0: one per core).
    unsigned int n_threads = 1;

    /// @p distributed: contact_mpi's help texts (ContactSolverParameters).
    static void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &default_output_directory,
                       const bool         distributed = false);
    void
    parse_parameters(ParameterHandler &prm);
  };



  /**
   * The scene driver: parameters -> meshes and bodies -> contact set ->
   * stepper -> recorder, the time loop, the checks, `history.csv`,
   * `summary.json` and the timing breakdown, in one place.
   *
   * A program derives its scene from this class and supplies what is its
   * own: its parameter subsections, its meshes and materials, its contact
   * candidates, its initial state, and what it measures and reports beyond
   * the common checks. run() calls these in the order of a deal.II
   * tutorial program:
   *
   *   read the parameter file (declare_parameters(), parse_parameters())
   *   setup_system():    make_bodies(), the bodies' assembly, apply_loads(),
   *                      add_contacts(), set_initial_state(), the stepper's
   *                      set-up, prepare_run()
   *   output_results():  t = 0
   *   for each step:     do_time_step(), then output_results()
   *                      (history_values(), the recorder, measure_step())
   *   report_results():  report(), summary.json, files and plot
   *
   * Everything in the loop but the step itself is excluded from the loop's
   * CPU time, so that schemes can be compared by it.
   */
  template <int dim>
  class ContactScene
  {
  public:
    /**
     * @p program_name names summary.json's "program", the default output
     * directory `results/<program_name>` and the default parameter file
     * `parameter_files/<program_name>.prm`.
     */
    explicit ContactScene(const std::string &program_name);
    virtual ~ContactScene() = default;

    /**
     * Run on the parameter file named by the command line (argv[1]), or on
     * the program's default file. Throws ExcMessage naming the entry, value
     * or step on bad input, a failed LCP or a failed check.
     */
    void
    run(int argc, char *argv[]);

    /** Run on @p parameter_file. */
    void
    run(const std::string &parameter_file);

  protected:
    // @sect4{What a scene supplies}

    /** The scene's own subsections (Geometry, Material, ...). */
    virtual void
    declare_parameters(ParameterHandler &prm) = 0;
    virtual void
    parse_parameters(ParameterHandler &prm) = 0;

    /** Create the bodies with add_body() and fill their meshes. */
    virtual void
    make_bodies() = 0;

    /** Loads that need the assembled bodies (set_body_force()). */
    virtual void
    apply_loads()
    {}

    /**
     * Whether any candidate has friction: then each candidate has dim local
     * directions, else the normal one only.
     */
    virtual bool
    frictional() const = 0;

    /** Add the contact candidates (system().contacts(), system().bodies()). */
    virtual void
    add_contacts(ContactSet &contacts) = 0;

    /** Set u^0 and v^0 (zero unless set here). */
    virtual void
    set_initial_state(MechanicalState &state) = 0;

    /** Anything that needs the set-up system (reference solutions, ...). */
    virtual void
    prepare_run()
    {}

    /** Extra history.csv columns, and their values for the current state. */
    virtual std::vector<std::string>
    history_columns() const;
    virtual std::vector<double>
    history_values(const StepReport &report);

    /** Measurements of a step (report.step > 0), after the recorder's. */
    virtual void
    measure_step(const StepReport &report);

    /**
     * The screen report of the run on @p out and the scene's entries of
     * summary.json. Returns false if one of the scene's checks failed. The
     * driver then adds the common summary entries, the performance line and
     * the files.
     */
    virtual bool
    report(std::ostream &out, JsonObject &summary) = 0;

    /** Columns of history.png. */
    virtual std::vector<std::string>
    plot_columns() const = 0;

    /** A title for the plot and the report, e.g. "Oblique plate". */
    virtual std::string
    title() const = 0;

    /**
     * Print the complete report text (header, checks, files) to @p out. A
     * scene may filter it, e.g. to leave out round-off dependent figures.
     */
    virtual void
    print_report(const std::string &text, std::ostream &out) const;

    // @sect4{What the driver offers a scene}

    /** A new body; fill its triangulation() in make_bodies(). */
    ElasticBody<dim> &
    add_body(const std::string        &name,
             const MaterialParameters &material,
             const double              out_of_plane_measure);
    ElasticBody<dim> &
    body(const unsigned int b);
    const ElasticBody<dim> &
    body(const unsigned int b) const;
    unsigned int
    n_bodies() const;

    MultibodySystem<dim> &
    system();
    const MultibodySystem<dim> &
    system() const;
    const ContactMonitor<dim> &
    monitor() const;
    const ContactRunSummary &
    run_summary() const;

    /** The parameter file, e.g. for mesh files named relative to it. */
    const std::string &
    parameter_file() const;

    /**
     * "Scheme <name> (theta = 0.55)" or "(beta = .., gamma = ..)" for
     * Newmark, ", h = <h><unit>, <n> steps".
     */
    std::string
    scheme_description(const std::string &time_unit) const;

    /**
     * print_contact_summary() with the common bounds of `Verification`:
     * the checks every contact program prints.
     */
    bool
    print_contact_checks(std::ostream &out) const;

    SceneParameters parameters;
    std::string     program_name;

  private:
    void
    read_parameters(const std::string &file);
    void
    setup_system();
    void
    redistribute_mass();
    void
    check_initial_state() const;
    void
    output_results(const StepReport &report);
    void
    report_results();

    std::string                                    parameter_file_name;
    std::vector<std::unique_ptr<ElasticBody<dim>>> body_list;
    std::unique_ptr<MultibodySystem<dim>>          multibody_system;
    std::unique_ptr<SceneRecorder<dim>>            recorder;
    double       setup_cpu_seconds = 0., loop_cpu_seconds = 0.;
    unsigned int n_steps_taken = 0;
  };
} // namespace impactfe

#endif
