#include <impactfe/output/scene_recorder.h>

namespace impactfe
{
  template <int dim>
  SceneRecorder<dim>::SceneRecorder(
    const MultibodySystem<dim>     &system,
    const OutputParameters         &output,
    const std::vector<std::string> &extra_columns)
    : system(system)
    , output(output)
    , contact_monitor(system, output.directory + "/contact_nodes.csv")
    , solution_writer(output.directory)
  {
    std::vector<std::string> columns = contact_monitor.history_columns();
    columns.insert(columns.end(), extra_columns.begin(), extra_columns.end());
    history = std::make_unique<HistoryWriter>(output.directory + "/history.csv",
                                              columns);
    if (!output.shape_times.empty())
      shape_writer =
        std::make_unique<ShapeWriter<dim>>(output.directory + "/shapes.csv",
                                           output.shape_times);
  }



  template <int dim>
  void
  SceneRecorder<dim>::record(const StepReport          &report,
                             const std::vector<double> &extra_values)
  {
    if (report.step > 0)
      contact_monitor.record(report);
    std::vector<double> row = contact_monitor.history_values(report);
    row.insert(row.end(), extra_values.begin(), extra_values.end());
    history->add_row(row);
    if (output.vtu_output && report.step % output.output_interval == 0)
      solution_writer.write(system, report.step);
    if (shape_writer)
      shape_writer->write_if_due(system,
                                 report.step > 0 ?
                                   report.time_step :
                                   system.integrator().time_step());
  }



  template <int dim>
  void
  SceneRecorder<dim>::finish()
  {
    if (history)
      history->close();
    history.reset();
    contact_monitor.close_node_file();
  }



  template <int dim>
  const ContactMonitor<dim> &
  SceneRecorder<dim>::monitor() const
  {
    return contact_monitor;
  }



  template <int dim>
  void
  SceneRecorder<dim>::add_summary(JsonObject &summary) const
  {
    const ContactRunSummary &s = contact_monitor.summary();
    JsonObject               lcp;
    lcp.add("total_pivots", double(system.total_pivots()))
      .add("largest_lcp", double(system.largest_lcp()))
      // A failed LCP stops the run with its step named: a finished run
      // has none.
      .add("failures", 0.);
    // How the LCPs on Lemke's route were answered (lcp::StartPath).
    const auto &paths = system.lcp_statistics();
    if (paths.solves > 0)
      {
        const auto count = [&](const lcp::StartPath path) {
          return double(paths.by_path[static_cast<unsigned int>(path)]);
        };
        lcp.add("solves", double(paths.solves))
          .add("cold_lemke_solves", count(lcp::StartPath::cold))
          .add("guess_solved", count(lcp::StartPath::guess_solved))
          .add("guess_lemke_solves", count(lcp::StartPath::guess_lemke))
          .add("guess_rejected_cold_lemke_solves",
               count(lcp::StartPath::guess_fallback_cold))
          .add("block_pivoting_solves", count(lcp::StartPath::block_pivoting))
          .add("block_pivoting_gave_up", double(paths.block_pivoting_gave_up))
          .add("block_pivoting_linear_solves",
               double(paths.block_pivoting_linear_solves))
          .add("block_pivoting_reused_factors",
               double(paths.block_pivoting_reused_factors));
      }
    const auto &cone = system.exact_cone_statistics();
    if (cone.solves > 0)
      lcp.add("exact_cone_solves", double(cone.solves))
        .add("exact_cone_facet_lcps", double(cone.facet_lcps))
        .add("exact_cone_most_facet_lcps", double(cone.most_facet_lcps))
        .add("exact_cone_largest_residual", cone.largest_residual)
        .add("cone_not_converged", double(cone.not_converged));
    const auto &active_set = system.active_set_statistics();
    if (active_set.solves > 0)
      lcp.add("active_set_solves", double(active_set.solves))
        .add("active_set_iterations", double(active_set.iterations))
        .add("active_set_most_iterations", double(active_set.most_iterations))
        .add("active_set_gmres_iterations",
             double(active_set.linear_iterations))
        .add("active_set_products", double(active_set.operator_applications))
        .add("active_set_largest_violation", active_set.largest_violation)
        .add("active_set_largest_cone_error", active_set.largest_cone_error)
        .add("active_set_refinements", double(active_set.refinements))
        .add("active_set_largest_linear_residual",
             active_set.largest_linear_residual)
        .add("active_set_fallbacks", double(active_set.fallbacks))
        .add("active_set_state_factorizations",
             double(active_set.state_factorizations))
        .add("active_set_singular_state_matrices",
             double(active_set.singular_state_matrices))
        .add("active_set_dense_schur_complement",
             double(active_set.dense_schur_complement));
    JsonObject checks;
    checks.add("impulse_balance_error", s.impulse_balance_error)
      .add("max_penetration", s.max_penetration)
      .add("largest_slide_off", s.largest_slide_off)
      .add("coulomb_excess", s.coulomb_excess)
      .add("wrong_slip_count", double(s.wrong_slip_count))
      .add("max_energy_increase", s.max_energy_increase);
    summary.add("n_steps", double(s.n_steps))
      .add("contact_candidates", double(system.contacts().n_candidates()))
      .add("lcp", lcp)
      .add("first_contact", s.first_contact)
      .add("last_contact", s.last_contact)
      .add("peak_normal_force", s.peak_normal_force)
      .add("normal_impulse", s.normal_impulse)
      .add("tangential_impulse", s.tangential_impulse)
      .add("energy_ratio", s.energy_ratio)
      .add("state_changes", double(s.state_changes))
      .add("steps_taken", double(s.n_steps))
      .add("free_flight_steps", double(s.free_flight_steps))
      .add("checks", checks);
  }



  template <int dim>
  void
  SceneRecorder<dim>::report_files(std::ostream                   &out,
                                   const std::vector<std::string> &columns,
                                   const std::string              &title) const
  {
    std::string files = "history.csv, contact_nodes.csv, summary.json";
    if (output.vtu_output)
      files += ", solution.pvd (VTU files)";
    if (shape_writer)
      files += ", shapes.csv";
    report_output_files(out, output, files, columns, title);
  }



  template class SceneRecorder<1>;
  template class SceneRecorder<2>;
  template class SceneRecorder<3>;
} // namespace impactfe
