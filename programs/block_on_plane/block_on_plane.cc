/* ---------------------------------------------------------------------
 *
 * block_on_plane: an elastic block on a rigid plane under gravity and a
 * push, with Coulomb friction, optionally with a second block falling on
 * it. The scene of the stability cases (tests/stability, doc/stability.md):
 * large time steps, resting contact, stick-slip, grazing incidence, many
 * simultaneous contacts, mass ratios, long runs of repeated impacts.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// A rectangular Q1 block of width $W$ and height $H$ lies (or falls) on a
// rigid obstacle, by default the plane $y = 0$. The block is built in the
// frame of the plane: its lower side is parallel to the plane, at the
// `Initial gap` above it, so that an inclined `Normal` gives a block on an
// inclined plane. Gravity and a constant push act as body forces; a second
// block (`Body 2`, off by default) of its own material can be placed above
// the first one and fall on it.
//
// Besides the checks of every contact program (impulse balance, Signorini,
// Coulomb, energy) this program measures what a stability study needs and
// compares it, where one exists, with an independent value:
//  - the energy $E = \tfrac12 v^T M v + \tfrac12 u^T K u - F^T u$, which
//    includes the work of the constant loads, so that a block falling under
//    gravity has a conserved energy;
//  - over a final phase of the run: the drift of the mean gap, the largest
//    penetration, the changes of the active set (chattering) and the mean
//    plane reaction against the normal load (the time average of the
//    reaction equals the load when the momentum is bounded);
//  - the rigid-block model of sliding: with initial velocity $v_0$ along
//    the plane, normal load $N$, tangential load $m a_t$ and friction
//    coefficient $\mu$, the block decelerates at $d = \mu N/m - a_t$ and
//    sticks at $t^* = v_0/d$ after sliding $v_0^2/(2d)$; if $d \le 0$ it
//    never sticks and $v(T) = v_0 - d T$;
//  - the static compression of a block of Poisson's ratio 0 resting on the
//    plane: its top sinks by $\rho g H^2/(2E)$ (the one-dimensional column,
//    which the Q1 solution reproduces at the nodes);
//  - the apparent restitution of the first impact: the block's mean normal
//    velocity when it leaves the plane over the one before it touched.
//
// The library does the time loop, the common checks and the files
// (ContactScene), the blocks, loads and candidates (BlockOnPlaneScene), and
// the chattering, final-phase and round-off measures of a stability study
// (StabilityMonitor). This program reports them against the rigid-block
// and static references.

#include <deal.II/base/parameter_handler.h>

#include <impactfe/scenes/block_on_plane_scene.h>
#include <impactfe/utilities/program.h>

#include <iostream>

namespace BlockOnPlane
{
  using namespace dealii;
  using namespace impactfe;


  // @sect3{The BlockOnPlaneProblem class}
  class BlockOnPlaneProblem : public BlockOnPlaneScene
  {
  public:
    BlockOnPlaneProblem()
      : BlockOnPlaneScene("block_on_plane")
    {}

  private:
    bool
    report(std::ostream &out, JsonObject &summary) override;
    bool
    report_compression(std::ostream &out, JsonObject &figures) const;
    std::string
    title() const override
    {
      return "Block on a plane";
    }
    std::vector<std::string>
    plot_columns() const override
    {
      return {"normal_force", "mean_velocity_x", "total_energy"};
    }
    // With 'Print figures of merit = false' only the header, the blocks
    // and the checks reach the screen.
    void
    print_report(const std::string &text, std::ostream &out) const override
    {
      if (print_figures)
        out << text;
      else
        print_checks_only(text, out, {"  Block:", "  Body 2:"});
    }
  };



  // @sect3{The report}
  //
  // The screen report (compared by the tests: figures with three
  // significant digits, no timings) and summary.json. Each figure is
  // printed beside its independent value where there is one, and the
  // bounds of `Verification` are checked.
  bool
  BlockOnPlaneProblem::report(std::ostream &out, JsonObject &summary)
  {
    const ContactRunSummary &s   = run_summary();
    const double             h   = parameters.time_stepping.time_step;
    const double             mu  = obstacle_parameters.friction_coefficient;
    const double             c_p = material.longitudinal_wave_speed<2>();
    const double             dx =
      std::min(block.width / block.n_across, block.height / block.n_up);
    const auto text = [](const Tensor<1, 2> &v) {
      return "(" + format_number(v[0]) + ", " + format_number(v[1]) + ")";
    };
    out << title() << ", " << scheme_description(" s") << std::endl;
    out << "  Block: " << block.width << " m x " << block.height << " m, "
        << block.n_across << " x " << block.n_up << " Q1 cells, "
        << n_plane_candidates
        << " contact nodes on the plane; obstacle: " << obstacle->description()
        << ", mu = " << mu << std::endl;
    if (body_2)
      out << "  Body 2: " << block_2.width << " m x " << block_2.height
          << " m, " << block_2.n_across << " x " << block_2.n_up
          << " Q1 cells, "
          << system().contacts().n_candidates() - n_plane_candidates
          << " contact nodes on block 1, mu = " << mu_2
          << "; mass ratio body 2 / body 1 = "
          << format_figure(body(1).total_mass() / mass_1) << std::endl;
    out << "  Mass " << format_figure(mass_1)
        << " kg; wave speed c = " << format_figure(c_p)
        << " m/s; Courant number c h / dx = " << format_figure(c_p * h / dx)
        << std::endl;
    out << "  Loads: gravity " << text(gravity) << " m/s^2, push " << text(push)
        << " N; initial velocity " << text(velocity) << " m/s" << std::endl;
    const Tensor<1, 2> v_end = mean_velocity();
    out << "  Mean velocity of the block at the end: ("
        << format_figure(v_end[0], 1e-9) << ", "
        << format_figure(v_end[1], 1e-9) << ") m/s" << std::endl;
    if (frictional() && s.normal_impulse > 0.)
      out << "  Tangential / normal impulse = "
          << format_figure(s.tangential_impulse / s.normal_impulse)
          << " (Coulomb bound mu = " << mu << ")" << std::endl;

    JsonObject stability_figures;
    stability_figures.add("courant_number", c_p * h / dx);
    bool ok = print_contact_checks(out);
    ok &= stability->report(out, s, normal_load(), stability_figures);
    ok &= report_compression(out, stability_figures);

    // Sliding against the rigid-block model: a single block that starts on
    // the plane with no normal velocity.
    // A load that pulls the block off the plane leaves no sliding to
    // compare with: the model's friction force mu N would change sign.
    const double a_t = (gravity + push / mass_1) * tangent;
    const bool   slides_on_plane =
      !body_2 && initial_gap == 0. && velocity * normal == 0. &&
      (velocity * tangent != 0. || a_t != 0.) &&
      obstacle_parameters.type == ObstacleParameters::Type::plane;
    if (slides_on_plane && normal_load() < 0.)
      out << "  Sliding against the rigid-block model: not checked, the "
          << "load pulls the block off the plane (normal load "
          << format_figure(normal_load()) << " N)" << std::endl;
    if (slides_on_plane && normal_load() >= 0.)
      ok &= tracker->report_sliding(out,
                                    RigidSliding(velocity * tangent,
                                                 a_t,
                                                 normal_load() / mass_1,
                                                 mu,
                                                 system().state().time),
                                    mean_displacement() * tangent,
                                    mean_velocity() * tangent,
                                    system().state().time,
                                    bounds,
                                    stability_figures);
    else
      stability_figures.add("measured_stick_time", tracker->stop_time())
        .add("stick_time_error", -1.)
        .add("distance_error", -1.)
        .add("final_velocity_error", -1.);
    ok &= tracker->report_restitution(out, bounds, stability_figures);
    stability_figures.add("checks_passed", ok ? 1. : 0.);
    summary.add("stability", stability_figures);
    return ok;
  }



  // Static compression: a single block of Poisson's ratio 0, at rest,
  // pressed by gravity normal to the plane sinks at its top by
  // rho g H^2 / (2 E).
  bool
  BlockOnPlaneProblem::report_compression(std::ostream &out,
                                          JsonObject   &figures) const
  {
    const double g_n   = -gravity * normal;
    double       error = -1.;
    bool         ok    = true;
    if (!body_2 && material.poissons_ratio == 0. && g_n > 0. &&
        std::abs(gravity * tangent) == 0. && push.norm() == 0. &&
        velocity.norm() == 0. &&
        obstacle_parameters.type == ObstacleParameters::Type::plane)
      {
        const double exact = material.density * g_n * block.height *
                             block.height / (2. * material.youngs_modulus);
        const double mean = stability->final_phase_mean();
        error             = std::abs(mean - exact) / exact;
        out << "  Static compression of the top: rho g H^2 / (2 E) = "
            << format_figure(exact) << " m, time average in the final phase "
            << format_figure(mean) << " m, at the end "
            << format_figure(top_sinking()) << " m: relative error "
            << format_figure(error, 1e-9) << std::endl;
        ok = print_check(out,
                         "static compression error",
                         error,
                         "<=",
                         bounds.max_compression_error);
      }
    figures.add("compression_error", error);
    return ok;
  }
} // namespace BlockOnPlane



// @sect3{The main function}
int
main(int argc, char *argv[])
{
  try
    {
      BlockOnPlane::BlockOnPlaneProblem().run(argc, argv);
    }
  catch (...)
    {
      return impactfe::report_current_exception();
    }
  return 0;
}
