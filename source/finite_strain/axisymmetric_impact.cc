#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q_eulerian.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>

#include <deal.II/numerics/data_out.h>

#include <impactfe/finite_strain/axisymmetric_impact.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <set>

namespace impactfe
{
  void
  AxisymmetricImpact::Settings::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Radius",
                      "3.2e-3",
                      Patterns::Double(),
                      "Initial radius r0 of the bar [m].");
    prm.declare_entry("Length",
                      "32.4e-3",
                      Patterns::Double(),
                      "Initial length L0 of the bar [m].");
    prm.declare_entry("Radial cells",
                      "5",
                      Patterns::Integer(1),
                      "Q1 cells across the radius.");
    prm.declare_entry("Axial cells",
                      "50",
                      Patterns::Integer(1),
                      "Q1 cells along the length.");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Impact velocity",
                      "227",
                      Patterns::Double(),
                      "Speed v0 of the bar towards the wall [m/s].");
    prm.leave_subsection();
    prm.enter_subsection("Time");
    prm.declare_entry("End time",
                      "80e-6",
                      Patterns::Double(),
                      "Simulated time [s].");
    prm.declare_entry("Time step", "2e-7", Patterns::Double(), "Step h [s].");
    prm.declare_entry("Theta",
                      "1",
                      Patterns::Double(),
                      "theta of the theta-method, in [0.5, 1].");
    prm.leave_subsection();
    prm.enter_subsection("Contact");
    prm.declare_entry("Bilateral contact",
                      "false",
                      Patterns::Bool(),
                      "true: a node stays tied to the wall, in both "
                      "directions, from the step after it first pushes on "
                      "it (the full-stick treatment common for the Taylor "
                      "bar); false: unilateral contact with Coulomb "
                      "friction.");
    prm.declare_entry("Friction coefficient",
                      "0",
                      Patterns::Double(),
                      "Coulomb coefficient mu at the wall (0: frictionless, "
                      "normal LCP rows only).");
    prm.leave_subsection();
    prm.enter_subsection("Discretisation");
    prm.declare_entry("F-bar",
                      "true",
                      Patterns::Bool(),
                      "Use F-bar (false: plain Q1, which locks under the "
                      "isochoric plastic flow).");
    prm.declare_entry("Newton tolerance",
                      "1e-9",
                      Patterns::Double(),
                      "Newton stops when the residual, relative to the "
                      "momentum max(M) v0, is below this.");
    prm.declare_entry("Maximum Newton iterations",
                      "25",
                      Patterns::Integer(1),
                      "A step that needs more stops the run with a message.");
    prm.leave_subsection();
  }



  void
  AxisymmetricImpact::Settings::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    radius   = prm.get_double("Radius");
    length   = prm.get_double("Length");
    n_radial = prm.get_integer("Radial cells");
    n_axial  = prm.get_integer("Axial cells");
    prm.leave_subsection();
    require_positive(radius, "Geometry", "Radius");
    require_positive(length, "Geometry", "Length");
    prm.enter_subsection("Initial conditions");
    speed = prm.get_double("Impact velocity");
    prm.leave_subsection();
    require_positive(speed, "Initial conditions", "Impact velocity");
    prm.enter_subsection("Time");
    end_time  = prm.get_double("End time");
    time_step = prm.get_double("Time step");
    theta     = prm.get_double("Theta");
    prm.leave_subsection();
    require_positive(end_time, "Time", "End time");
    require_positive(time_step, "Time", "Time step");
    prm.enter_subsection("Contact");
    friction_coefficient = prm.get_double("Friction coefficient");
    bilateral            = prm.get_bool("Bilateral contact");
    prm.leave_subsection();
    require_non_negative(friction_coefficient,
                         "Contact",
                         "Friction coefficient");
    prm.enter_subsection("Discretisation");
    f_bar                 = prm.get_bool("F-bar");
    newton_tolerance      = prm.get_double("Newton tolerance");
    max_newton_iterations = prm.get_integer("Maximum Newton iterations");
    prm.leave_subsection();
    require_positive(newton_tolerance, "Discretisation", "Newton tolerance");
  }



  unsigned int
  AxisymmetricImpact::Settings::n_steps() const
  {
    return static_cast<unsigned int>(std::llround(end_time / time_step));
  }



  AxisymmetricImpact::AxisymmetricImpact(const Settings             &settings,
                                         const MaterialParameters   &material,
                                         const PlasticityParameters &plasticity)
    : settings(settings)
    , material(material)
    , law(material, plasticity)
    , fe(FE_Q<2>(1), 2)
  {
    AssertThrow(settings.theta >= 0.5 && settings.theta <= 1.,
                ExcMessage("Time/Theta = " + format_number(settings.theta) +
                           " must be in [0.5, 1]."));
    AssertThrow(settings.time_step > 0.,
                ExcMessage(
                  "Time/Time step = " + format_number(settings.time_step) +
                  " must be > 0 [s]."));
    AssertThrow(settings.friction_coefficient >= 0.,
                ExcMessage("Contact/Friction coefficient = " +
                           format_number(settings.friction_coefficient) +
                           " must be >= 0."));
    setup_system();
  }



  // @sect3{Set-up: mesh, reference shape functions, mass, candidates}
  void
  AxisymmetricImpact::setup_system()
  {
    GridGenerator::subdivided_hyper_rectangle(
      triangulation,
      {settings.n_radial, settings.n_axial},
      Point<2>(0., 0.),
      Point<2>(settings.radius, settings.length),
      /*colorize: 0 axis, 1 side, 2 lower end, 3 upper end*/ true);
    dof_handler.reinit(triangulation);
    dof_handler.distribute_dofs(fe);
    smallest_cell_size = std::min(settings.radius / settings.n_radial,
                                  settings.length / settings.n_axial);

    DynamicSparsityPattern dsp(dof_handler.n_dofs());
    DoFTools::make_sparsity_pattern(dof_handler, dsp);
    sparsity.copy_from(dsp);
    step_matrix.reinit(sparsity);

    // Shape functions at the Gauss points and at the centre of each cell.
    std::vector<Point<2>> points = QGauss<2>(2).get_points();
    points.emplace_back(0.5, 0.5);
    const Quadrature<2> quadrature(points, std::vector<double>(n_points, 0.25));
    FEValues<2>         fe_values(fe,
                          quadrature,
                          update_values | update_gradients |
                            update_quadrature_points | update_JxW_values);
    lumped_mass.reinit(dof_handler.n_dofs());
    cells.resize(triangulation.n_active_cells());
    std::vector<types::global_dof_index> dofs(8);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        CellGeometry &g = cells[cell->active_cell_index()];
        for (unsigned int i = 0; i < 8; ++i)
          {
            g.dofs[i]      = dofs[i];
            g.component[i] = fe.system_to_component_index(i).first;
          }
        for (unsigned int q = 0; q < n_points; ++q)
          {
            g.radius[q] = fe_values.quadrature_point(q)[0];
            g.ring_weight[q] =
              (q < 4) ? 2. * numbers::PI * g.radius[q] * fe_values.JxW(q) : 0.;
            for (unsigned int i = 0; i < 8; ++i)
              {
                const unsigned int c = g.component[i];
                g.N[q][i]            = fe_values.shape_value_component(i, q, c);
                g.grad_N[q][i]       = fe_values.shape_grad_component(i, q, c);
                // Row sums of the consistent ring mass.
                if (q < 4)
                  lumped_mass[dofs[i]] +=
                    material.density * g.N[q][i] * g.ring_weight[q];
              }
          }
      }

    // u_r = 0 on the axis; candidates on the side and the lower end.
    std::set<types::global_dof_index> axis;
    std::set<unsigned int>            seen;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          for (const unsigned int v : cell->face(f)->vertex_indices())
            {
              const auto face = cell->face(f);
              if (face->boundary_id() == 0)
                axis.insert(face->vertex_dof_index(v, 0));
              if ((face->boundary_id() == 1 || face->boundary_id() == 2) &&
                  seen.insert(face->vertex_index(v)).second)
                {
                  candidate_dofs.push_back({{face->vertex_dof_index(v, 0),
                                             face->vertex_dof_index(v, 1)}});
                  candidate_positions.push_back(face->vertex(v));
                  on_lower_end.push_back(face->vertex(v)[1] == 0.);
                }
            }
    contact_states.assign(candidate_dofs.size(), ContactState::open);
    tied.assign(candidate_dofs.size(), false);
    for (const auto dof : axis)
      constraints.add_line(dof);
    constraints.close();

    displacement.reinit(dof_handler.n_dofs());
    velocity.reinit(dof_handler.n_dofs());
    old_force.reinit(dof_handler.n_dofs());
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        velocity[cell->vertex_dof_index(v, 1)] = -settings.speed;
    initial_kinetic_energy = kinetic_energy();

    history_old.resize(4 * cells.size());
    for (auto &h : history_old)
      law.initialize(h);
    history_new = history_old;
  }



  Tensor<2, 3>
  AxisymmetricImpact::deformation_gradient(const CellGeometry          &g,
                                           const std::array<double, 8> &u,
                                           const unsigned int           q)
  {
    Tensor<2, 3> F;
    F[0][0] = F[1][1] = F[2][2] = 1.;
    for (unsigned int i = 0; i < 8; ++i)
      {
        const unsigned int c = g.component[i];
        F[c][0] += u[i] * g.grad_N[q][i][0];
        F[c][1] += u[i] * g.grad_N[q][i][1];
        if (c == 0)
          F[2][2] += u[i] * g.N[q][i] / g.radius[q];
      }
    return F;
  }



  // @sect3{The internal force of a cell: F-bar, the return mapping}
  //
  // F = [[1 + du_r/dR, du_r/dZ, 0], [du_z/dR, 1 + du_z/dZ, 0], [0, 0,
  // 1 + u_r/R]]. F-bar (de Souza Neto, Peric, Dutko, Owen 1996): the law
  // sees Fbar = (J0/J)^{1/3} F, J0 = det F at the cell centre, so the
  // volume change is constant per cell and the isochoric plastic flow does
  // not lock Q1. The internal virtual work is that of the Cauchy stress
  // sigma = tau(Fbar)/J0 on the current configuration:
  // f_i = int (J/J0) tau : (dF_i F^{-1}) dV0.
  void
  AxisymmetricImpact::cell_force(const unsigned int                cell,
                                 const std::array<double, 8>      &u,
                                 std::array<double, 8>            &force,
                                 std::vector<std::vector<double>> *history,
                                 std::array<Branch, 4> &branches) const
  {
    const CellGeometry &g  = cells[cell];
    const double        J0 = determinant(deformation_gradient(g, u, 4));
    force.fill(0.);
    std::vector<double> updated;
    for (unsigned int q = 0; q < 4; ++q)
      {
        const Tensor<2, 3> F = deformation_gradient(g, u, q);
        const double       J = determinant(F);
        AssertThrow(J > 0. && J0 > 0.,
                    ExcMessage("Taylor bar: an element is inverted (det F = " +
                               std::to_string(J) +
                               "); reduce the time step or refine."));
        const double       scale = settings.f_bar ? std::cbrt(J0 / J) : 1.;
        const Tensor<2, 3> F_bar = scale * F;
        Tensor<2, 3>       P_bar;
        const bool         plastic = law.evaluate_3d(F_bar,
                                             history_old[4 * cell + q],
                                             updated,
                                             P_bar,
                                             nullptr,
                                             branches[q]);
        if (branches[q] == Branch::automatic)
          branches[q] = plastic ? Branch::plastic : Branch::elastic;
        const Tensor<2, 3> tau = P_bar * transpose(F_bar);
        const Tensor<2, 3> G =
          (J / determinant(F_bar)) * tau * transpose(invert(F));
        for (unsigned int i = 0; i < 8; ++i)
          {
            const unsigned int c = g.component[i];
            double             virtual_work =
              G[c][0] * g.grad_N[q][i][0] + G[c][1] * g.grad_N[q][i][1];
            if (c == 0)
              virtual_work += G[2][2] * g.N[q][i] / g.radius[q];
            force[i] += virtual_work * g.ring_weight[q];
          }
        if (history != nullptr)
          (*history)[4 * cell + q] = updated;
      }
  }



  void
  AxisymmetricImpact::assemble_internal_force(const Vector<double> &u,
                                              Vector<double>       &force,
                                              SparseMatrix<double> *tangent)
  {
    force = 0.;
    if (tangent != nullptr)
      *tangent = 0.;
    // The consistent tangent by central differences of the cell force
    // (F-bar's dependence on the centre included), each Gauss point on the
    // branch of the return mapping it took: a difference across the yield
    // surface would average the elastic and the plastic tangent, and
    // Newton's method would converge only linearly.
    const double                         delta = 1e-6 * smallest_cell_size;
    std::array<double, 8>                u_cell, f_cell, f_plus, f_minus;
    FullMatrix<double>                   k_cell(8, 8);
    std::vector<types::global_dof_index> dofs(8);
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        for (unsigned int i = 0; i < 8; ++i)
          u_cell[i] = u[cells[c].dofs[i]];
        std::array<Branch, 4> branches;
        branches.fill(Branch::automatic);
        cell_force(c, u_cell, f_cell, &history_new, branches);
        for (unsigned int i = 0; i < 8; ++i)
          force[cells[c].dofs[i]] += f_cell[i];
        if (tangent == nullptr)
          continue;
        for (unsigned int j = 0; j < 8; ++j)
          {
            const double saved = u_cell[j];
            u_cell[j]          = saved + delta;
            cell_force(c, u_cell, f_plus, nullptr, branches);
            u_cell[j] = saved - delta;
            cell_force(c, u_cell, f_minus, nullptr, branches);
            u_cell[j] = saved;
            for (unsigned int i = 0; i < 8; ++i)
              k_cell(i, j) = (f_plus[i] - f_minus[i]) / (2. * delta);
          }
        std::copy(cells[c].dofs.begin(), cells[c].dofs.end(), dofs.begin());
        tangent->add(dofs, k_cell);
      }
  }



  // @sect3{One time step: Newton's method with the contact LCP}
  //
  // The theta-method at velocity level (spec: schemes.md):
  //   u1 = u0 + h (theta v1 + (1 - theta) v0),
  //   M (v1 - v0) + h (theta f(u1) + (1 - theta) f(u0)) = H P,
  // Signorini on w_N = V_N1 + ((1 - theta)/theta) V_N0 + g0/(h theta).
  // Each Newton iterate linearises f at u1 (A = M + h^2 theta^2 K_t),
  // condenses onto the candidates (W = H^T A^{-1} H) and solves the LCP for
  // the whole impulse P with Lemke's method, verified.
  //
  // If Newton's method does not converge in `Maximum Newton iterations`,
  // the step is made again as 2, 4, then 8 steps of h/2, h/4, h/8 (counted
  // in FiniteStrainRunTotals::step_reductions); if that fails too, the run
  // stops with a message naming the step.
  FiniteStrainStepReport
  AxisymmetricImpact::do_time_step()
  {
    ++step_number;
    const double start_time = current_time;
    // A step that fails changes nothing but the contact states' guesses:
    // the full state is copied only when substeps are needed.
    const auto             saved_states = contact_states;
    FiniteStrainStepReport report;
    if (try_step(settings.time_step, report))
      return report;
    contact_states               = saved_states;
    const Vector<double> saved_v = velocity, saved_u = displacement,
                         saved_f = old_force;
    const auto saved_history     = history_old;
    const auto saved_tied        = tied;
    const auto saved_totals      = run_totals;
    for (unsigned int level = 1; level <= 3; ++level)
      {
        const unsigned int     n_sub = 1u << level;
        FiniteStrainStepReport total;
        bool                   converged = true;
        for (unsigned int k = 0; k < n_sub && converged; ++k)
          {
            converged = try_step(settings.time_step / n_sub, report);
            total.newton_iterations += report.newton_iterations;
            total.residuals = report.residuals;
            total.n_candidates =
              std::max(total.n_candidates, report.n_candidates);
            total.n_closed = std::max(total.n_closed, report.n_closed);
            total.normal_impulse += report.normal_impulse;
            total.contact_work += report.contact_work;
            total.scheme_dissipation += report.scheme_dissipation;
            total.contact_violation =
              std::max(total.contact_violation, report.contact_violation);
          }
        if (converged)
          {
            ++run_totals.step_reductions;
            current_time = start_time + settings.time_step;
            return total;
          }
        velocity       = saved_v;
        displacement   = saved_u;
        old_force      = saved_f;
        history_old    = saved_history;
        contact_states = saved_states;
        tied           = saved_tied;
        run_totals     = saved_totals;
        current_time   = start_time;
      }
    AssertThrow(false,
                ExcMessage("Taylor bar: Newton's method did not converge in "
                           "step " +
                           std::to_string(step_number) +
                           " (t = " + format_number(start_time) + " s) in " +
                           std::to_string(settings.max_newton_iterations) +
                           " iterations, nor in 8 steps of h/8; reduce the "
                           "time step or refine."));
    return {};
  }



  bool
  AxisymmetricImpact::try_step(const double h, FiniteStrainStepReport &report)
  {
    const double       theta        = settings.theta;
    const double       mu           = settings.friction_coefficient;
    const unsigned int n_directions = mu > 0. ? 2 : 1;

    // Candidates that can touch during the step: gap below twice the
    // distance they approach at their current speed.
    std::vector<unsigned int> active;
    std::vector<double>       gap0;
    auto                      gap = [&](const unsigned int k) {
      return candidate_positions[k][1] + displacement[candidate_dofs[k][1]];
    };
    // Rows held at zero velocity: u_r on the axis, and both components of
    // the nodes tied to the wall (bilateral contact).
    std::vector<types::global_dof_index> fixed;
    std::vector<bool> tied_normal; // per entry of fixed: a tied node's u_z
    for (const auto &line : constraints.get_lines())
      fixed.push_back(line.index);
    tied_normal.assign(fixed.size(), false);
    for (unsigned int k = 0; k < candidate_dofs.size(); ++k)
      {
        const double g = gap(k), vn = velocity[candidate_dofs[k][1]];
        if (tied[k])
          {
            fixed.insert(fixed.end(),
                         candidate_dofs[k].begin(),
                         candidate_dofs[k].end());
            tied_normal.insert(tied_normal.end(), {false, true});
          }
        else if (g <= 2. * h * std::max(-vn, 0.) + 1e-12 * settings.length)
          active.push_back(k);
        else
          contact_states[k] = ContactState::open; // out of reach
      }
    std::vector<bool> is_fixed(displacement.size(), false);
    for (const auto dof : fixed)
      is_fixed[dof] = true;
    // Tied nodes stop at once; their reaction is their residual row.
    std::vector<double> tied_reaction(fixed.size());

    const Vector<double> v0 = velocity, u0 = displacement;
    Vector<double>       v1 = v0, u1(u0.size()), force(u0.size()),
                   residual(u0.size()), dv_free(u0.size());
    for (const auto dof : fixed)
      v1[dof] = 0.;
    std::vector<Vector<double>> columns;
    std::vector<double>         P;
    lcp::ContactProblem         problem;
    const double momentum_scale = lumped_mass.linfty_norm() * settings.speed;

    for (unsigned int it = 0;; ++it)
      {
        if (it >= settings.max_newton_iterations)
          return false;
        u1 = u0;
        u1.add(h * theta, v1, h * (1. - theta), v0);
        assemble_internal_force(u1, force, &step_matrix);
        // residual = M (v1 - v0) + h (theta f1 + (1 - theta) f0) - H P
        for (unsigned int i = 0; i < u0.size(); ++i)
          residual[i] = lumped_mass[i] * (v1[i] - v0[i]) +
                        h * (theta * force[i] + (1. - theta) * old_force[i]);
        for (unsigned int c = 0; c < P.size(); ++c)
          residual[candidate_dofs[active[c / n_directions]]
                                 [c % n_directions == 0 ? 1 : 0]] -= P[c];
        for (unsigned int i = 0; i < fixed.size(); ++i)
          {
            tied_reaction[i]   = residual[fixed[i]];
            residual[fixed[i]] = 0.;
          }
        report.residuals.push_back(residual.linfty_norm() / momentum_scale);
        if (it > 0 && report.residuals.back() < settings.newton_tolerance)
          break;
        report.newton_iterations = it + 1;

        // A = M + h^2 theta^2 K_t; rows of the axis DoFs: identity (times M).
        step_matrix *= h * h * theta * theta;
        for (unsigned int i = 0; i < u0.size(); ++i)
          step_matrix.add(i, i, lumped_mass[i]);
        for (const auto dof : fixed)
          {
            for (auto entry = step_matrix.begin(dof);
                 entry != step_matrix.end(dof);
                 ++entry)
              entry->value() = 0.;
            step_matrix.set(dof, dof, lumped_mass[dof]);
          }
        SparseDirectUMFPACK solver;
        solver.initialize(step_matrix);
        // The whole impulse is the unknown: free step from the residual
        // without the contact impulse.
        for (unsigned int c = 0; c < P.size(); ++c)
          residual[candidate_dofs[active[c / n_directions]]
                                 [c % n_directions == 0 ? 1 : 0]] += P[c];
        residual *= -1.;
        solver.vmult(dv_free, residual);
        v1 += dv_free;
        if (active.empty())
          continue;

        const unsigned int n = active.size() * n_directions;
        columns.assign(n, Vector<double>(u0.size()));
        Vector<double> unit(u0.size());
        for (unsigned int c = 0; c < n; ++c)
          {
            const auto dof = candidate_dofs[active[c / n_directions]]
                                           [c % n_directions == 0 ? 1 : 0];
            unit      = 0.;
            unit[dof] = 1.;
            if (!is_fixed[dof])
              solver.vmult(columns[c], unit);
          }
        problem.n_directions = n_directions;
        problem.n_contacts   = active.size();
        problem.W.reinit(n, n);
        problem.free_velocity.assign(n, 0.);
        problem.gap_term.assign(active.size(), 0.);
        problem.mu.assign(active.size(), mu);
        for (unsigned int a = 0; a < n; ++a)
          {
            const auto dof = candidate_dofs[active[a / n_directions]]
                                           [a % n_directions == 0 ? 1 : 0];
            problem.free_velocity[a] = v1[dof];
            for (unsigned int b = 0; b < n; ++b)
              problem.W(a, b) = columns[b][dof];
          }
        for (unsigned int c = 0; c < active.size(); ++c)
          problem.gap_term[c] =
            (1. - theta) / theta * v0[candidate_dofs[active[c]][1]] +
            gap(active[c]) / (h * theta);
        std::vector<ContactState> guess(active.size());
        for (unsigned int c = 0; c < active.size(); ++c)
          guess[c] = contact_states[active[c]];
        const lcp::ContactSolution solution =
          lcp::solve_contact_problem(problem, {}, guess);
        AssertThrow(solution.lcp.status == lcp::Status::solved,
                    ExcMessage("Taylor bar, step " +
                               std::to_string(step_number) +
                               ": the contact LCP was not solved (" +
                               lcp::to_string(solution.lcp.status) + "). " +
                               solution.message));
        P = solution.P;
        for (unsigned int c = 0; c < active.size(); ++c)
          contact_states[active[c]] = solution.states[c];
        for (unsigned int c = 0; c < n; ++c)
          v1.add(P[c], columns[c]);
      }

    // Accept the step.
    report.n_candidates = active.size();
    if (!P.empty())
      {
        const auto check = lcp::verify_contact_solution(problem, P);
        report.contact_violation =
          std::max(check.max_signorini_violation, check.max_cone_violation);
      }
    for (unsigned int c = 0; c < P.size(); ++c)
      {
        const auto dof = candidate_dofs[active[c / n_directions]]
                                       [c % n_directions == 0 ? 1 : 0];
        report.contact_work +=
          P[c] * (theta * v1[dof] + (1. - theta) * v0[dof]);
        if (c % n_directions == 0)
          {
            report.normal_impulse += P[c];
            report.n_closed += P[c] > 0. ? 1 : 0;
          }
      }
    // Tied nodes: their reaction (the axis rows' is zero by symmetry).
    for (unsigned int i = constraints.n_constraints(); i < fixed.size(); ++i)
      {
        const auto dof = fixed[i];
        report.contact_work +=
          tied_reaction[i] * (theta * v1[dof] + (1. - theta) * v0[dof]);
        if (tied_normal[i])
          report.normal_impulse += tied_reaction[i];
      }
    if (settings.bilateral)
      for (unsigned int c = 0; c < P.size(); c += n_directions)
        if (P[c] > 0.)
          tied[active[c / n_directions]] = true;
    for (unsigned int i = 0; i < v0.size(); ++i)
      report.scheme_dissipation +=
        (theta - 0.5) * lumped_mass[i] * (v1[i] - v0[i]) * (v1[i] - v0[i]);
    current_time += h;
    FiniteStrainRunTotals &t = run_totals;
    ++t.steps;
    t.newton_iterations += report.newton_iterations;
    t.most_newton_iterations =
      std::max(t.most_newton_iterations, report.newton_iterations);
    t.wall_impulse += report.normal_impulse;
    t.peak_contact_force =
      std::max(t.peak_contact_force, report.normal_impulse / h);
    if (report.normal_impulse > 0.)
      t.last_contact_time = time();
    t.contact_dissipation -= report.contact_work;
    t.scheme_dissipation += report.scheme_dissipation;
    t.worst_contact_violation =
      std::max(t.worst_contact_violation, report.contact_violation);
    const auto &r = report.residuals;
    for (unsigned int k = 2; k < r.size(); ++k)
      if (r[k] > 1e-12 && r[k - 1] < 1e-2 && r[k - 1] < r[k - 2])
        t.convergence_orders.push_back(std::log(r[k] / r[k - 1]) /
                                       std::log(r[k - 1] / r[k - 2]));
    velocity     = v1;
    displacement = u1;
    old_force    = force;
    history_old  = history_new;
    return true;
  }



  double
  AxisymmetricImpact::time() const
  {
    return current_time;
  }



  const FiniteStrainRunTotals &
  AxisymmetricImpact::totals() const
  {
    return run_totals;
  }



  double
  FiniteStrainRunTotals::newton_iterations_per_step() const
  {
    return steps > 0 ? double(newton_iterations) / steps : 0.;
  }



  double
  FiniteStrainRunTotals::median_convergence_order() const
  {
    if (convergence_orders.empty())
      return 0.;
    std::vector<double> sorted = convergence_orders;
    std::sort(sorted.begin(), sorted.end());
    return sorted[sorted.size() / 2];
  }



  double
  AxisymmetricImpact::energy_balance_error() const
  {
    return (initial_kinetic_energy - kinetic_energy() - stored_energy() -
            plastic_work() - run_totals.contact_dissipation -
            run_totals.scheme_dissipation) /
           initial_kinetic_energy;
  }



  double
  AxisymmetricImpact::kinetic_energy() const
  {
    double e = 0.;
    for (unsigned int i = 0; i < velocity.size(); ++i)
      e += 0.5 * lumped_mass[i] * velocity[i] * velocity[i];
    return e;
  }



  double
  AxisymmetricImpact::stored_energy() const
  {
    // Hencky energy of the elastic part at each Gauss point; F-bar's F as
    // the law saw it.
    double                e = 0.;
    std::array<double, 8> u;
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        const CellGeometry &g = cells[c];
        for (unsigned int i = 0; i < 8; ++i)
          u[i] = displacement[g.dofs[i]];
        const double J0 = determinant(deformation_gradient(g, u, 4));
        for (unsigned int q = 0; q < 4; ++q)
          {
            const Tensor<2, 3> F = deformation_gradient(g, u, q);
            const double       scale =
              settings.f_bar ? std::cbrt(J0 / determinant(F)) : 1.;
            e += law.stored_energy(scale * F, history_old[4 * c + q]) *
                 g.ring_weight[q];
          }
      }
    return e;
  }



  double
  AxisymmetricImpact::plastic_work() const
  {
    double e = 0.;
    for (unsigned int c = 0; c < cells.size(); ++c)
      for (unsigned int q = 0; q < 4; ++q)
        e += law.plastic_work(FiniteStrainJ2Model<3>::equivalent_plastic_strain(
               history_old[4 * c + q])) *
             cells[c].ring_weight[q];
    return e;
  }



  double
  AxisymmetricImpact::current_length() const
  {
    double top = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        top = std::max(top,
                       cell->vertex(v)[1] +
                         displacement[cell->vertex_dof_index(v, 1)]);
    return top;
  }



  double
  AxisymmetricImpact::largest_candidate_radius(
    const std::function<bool(unsigned int)> &selected) const
  {
    double r = 0.;
    for (unsigned int k = 0; k < candidate_dofs.size(); ++k)
      if (selected(k))
        r = std::max(r,
                     candidate_positions[k][0] +
                       displacement[candidate_dofs[k][0]]);
    return r;
  }



  double
  AxisymmetricImpact::footprint_radius() const
  {
    return largest_candidate_radius(
      [this](const unsigned int k) { return bool(on_lower_end[k]); });
  }



  double
  AxisymmetricImpact::contact_radius() const
  {
    return largest_candidate_radius([this](const unsigned int k) {
      return tied[k] || contact_states[k] != ContactState::open;
    });
  }



  double
  AxisymmetricImpact::max_equivalent_plastic_strain() const
  {
    double alpha = 0.;
    for (const auto &h : history_old)
      alpha =
        std::max(alpha, FiniteStrainJ2Model<3>::equivalent_plastic_strain(h));
    return alpha;
  }



  unsigned int
  AxisymmetricImpact::n_dofs() const
  {
    return dof_handler.n_dofs();
  }



  double
  AxisymmetricImpact::initial_energy() const
  {
    return initial_kinetic_energy;
  }



  double
  AxisymmetricImpact::axial_momentum() const
  {
    std::vector<bool> counted(dof_handler.n_dofs(), false);
    double            p = 0.;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        {
          const auto dof = cell->vertex_dof_index(v, 1);
          if (!counted[dof])
            p += lumped_mass[dof] * velocity[dof];
          counted[dof] = true;
        }
    return p;
  }



  void
  AxisymmetricImpact::write_cells_csv(const std::string &file_name) const
  {
    std::ofstream out(file_name);
    AssertThrow(out, ExcMessage("Cannot write " + file_name));
    out << "r0,z0,r1,z1,r2,z2,r3,z3,alpha\n" << std::setprecision(8);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        for (const unsigned int v : {0u, 1u, 3u, 2u})
          out << cell->vertex(v)[0] + displacement[cell->vertex_dof_index(v, 0)]
              << ','
              << cell->vertex(v)[1] + displacement[cell->vertex_dof_index(v, 1)]
              << ',';
        double alpha = 0.;
        for (unsigned int q = 0; q < 4; ++q)
          alpha += 0.25 * FiniteStrainJ2Model<3>::equivalent_plastic_strain(
                            history_old[4 * cell->active_cell_index() + q]);
        out << alpha << '\n';
      }
  }



  void
  AxisymmetricImpact::write_vtu(const std::string &directory,
                                const unsigned int step)
  {
    const std::string name =
      "solution-" + Utilities::int_to_string(step, 5) + ".vtu";
    const std::string file_name = directory + "/" + name;
    DataOut<2>        data_out;
    data_out.attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector(2, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(displacement,
                             std::vector<std::string>(2, "displacement"),
                             DataOut<2>::type_dof_data,
                             vector);
    data_out.add_data_vector(velocity,
                             std::vector<std::string>(2, "velocity"),
                             DataOut<2>::type_dof_data,
                             vector);
    Vector<float> alpha(triangulation.n_active_cells());
    for (unsigned int c = 0; c < cells.size(); ++c)
      for (unsigned int q = 0; q < 4; ++q)
        alpha[c] += 0.25 * FiniteStrainJ2Model<3>::equivalent_plastic_strain(
                             history_old[4 * c + q]);
    data_out.add_data_vector(alpha, "equivalent_plastic_strain");
    const MappingQEulerian<2> mapping(1, dof_handler, displacement);
    data_out.build_patches(mapping);
    std::ofstream out(file_name);
    AssertThrow(out, ExcMessage("Cannot write " + file_name));
    data_out.write_vtu(out);
    vtu_records.emplace_back(time(), name);
    std::ofstream pvd(directory + "/solution.pvd");
    DataOutBase::write_pvd_record(pvd, vtu_records);
  }
} // namespace impactfe
