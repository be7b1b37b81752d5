#include <deal.II/base/exceptions.h>

#include <impactfe/dynamics/multibody_system.h>
#include <impactfe/lcp/problem_io.h>
#include <impactfe/utilities/column_sum.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace impactfe
{
  namespace
  {
    /// Adds the wall time since the last call to one of the cost counters
    /// (a CPU clock is too dear to be read several times per step, see
    /// wall_seconds()).
    class CostClock
    {
    public:
      explicit CostClock(const bool enabled)
        : enabled(enabled)
        , last(enabled ? wall_seconds() : 0.)
      {}
      void
      charge(double &counter)
      {
        if (!enabled)
          return;
        const double now = wall_seconds();
        counter += now - last;
        last = now;
      }

    private:
      const bool enabled;
      double     last;
    };

  } // namespace



  template <int dim>
  MultibodySystem<dim>::MultibodySystem(
    const TimeSteppingParameters  &time_stepping,
    const ContactSolverParameters &solver_parameters,
    const unsigned int             contact_directions)
    : time_stepping(time_stepping)
    , solver_parameters(solver_parameters)
    , contact_set(contact_directions)
    , scheme(create_time_integrator(time_stepping))
  {}



  template <int dim>
  unsigned int
  MultibodySystem<dim>::add_body(const ElasticBody<dim> &body)
  {
    AssertThrow(body.n_dofs() > 0,
                ExcMessage("Body '" + body.name() +
                           "' must be set up before it is added."));
    body_list.push_back(&body);
    current.displacement = make_block_vector();
    current.velocity     = make_block_vector();
    current.acceleration = make_block_vector();
    return body_list.size() - 1;
  }



  template <int dim>
  const std::vector<const ElasticBody<dim> *> &
  MultibodySystem<dim>::bodies() const
  {
    return body_list;
  }

  template <int dim>
  ContactSet &
  MultibodySystem<dim>::contacts()
  {
    return contact_set;
  }

  template <int dim>
  const ContactSet &
  MultibodySystem<dim>::contacts() const
  {
    return contact_set;
  }

  template <int dim>
  void
  MultibodySystem<dim>::set_dump_directory(const std::string &directory)
  {
    dump_directory = directory;
  }

  template <int dim>
  MechanicalState &
  MultibodySystem<dim>::state()
  {
    ++state_version; // the caller may change it
    return current;
  }

  template <int dim>
  const MechanicalState &
  MultibodySystem<dim>::state() const
  {
    return current;
  }

  template <int dim>
  const TimeIntegrator &
  MultibodySystem<dim>::integrator() const
  {
    return *scheme;
  }



  template <int dim>
  BlockVector<double>
  MultibodySystem<dim>::make_block_vector() const
  {
    std::vector<types::global_dof_index> sizes;
    for (const auto *body : body_list)
      sizes.push_back(body->n_dofs());
    return BlockVector<double>(sizes);
  }



  template <int dim>
  void
  MultibodySystem<dim>::solve_step_matrix(BlockVector<double> &x) const
  {
    SparseCholesky::solve_together(step_solvers, x);
  }



  template <int dim>
  void
  MultibodySystem<dim>::factorize_step_matrices(
    const TimeIntegrator                               &level_scheme,
    std::vector<std::unique_ptr<SparseMatrix<double>>> &matrices,
    std::vector<std::unique_ptr<SparseCholesky>>       &solvers) const
  {
    matrices.clear();
    solvers.clear();
    for (const ElasticBody<dim> *body : body_list)
      {
        auto step_matrix =
          std::make_unique<SparseMatrix<double>>(body->sparsity_pattern());
        step_matrix->copy_from(body->mass_matrix());
        step_matrix->add(level_scheme.stiffness_coefficient(),
                         body->stiffness_matrix());
        if (body->has_damping())
          step_matrix->add(level_scheme.damping_coefficient(),
                           body->damping_matrix());
        auto solver = std::make_unique<SparseCholesky>();
        solver->factorize(*step_matrix,
                          "the step matrix of body '" + body->name() + "'");
        matrices.push_back(std::move(step_matrix));
        solvers.push_back(std::move(solver));
      }
  }



  // @sect3{Set-up: M~ and its factorisation}
  // M~ = M + c_C C + c_K K depends only on the scheme and h, so it is
  // factorised once per body. The Delassus operator is not built here: its
  // columns are computed when their candidate first enters an LCP (see
  // ensure_delassus_columns()).
  template <int dim>
  void
  MultibodySystem<dim>::setup()
  {
    AssertThrow(!body_list.empty(), ExcMessage("The scene has no body."));
    const unsigned int n_bodies = body_list.size();
    costs                       = CostBreakdown();
    CostClock clock(measure_costs);

    operators.mass.clear();
    operators.stiffness.clear();
    operators.damping.clear();
    operators.external_force = make_block_vector();
    step_matrices.clear();
    step_solvers.clear();
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        const ElasticBody<dim> &body = *body_list[b];
        operators.mass.push_back(&body.mass_matrix());
        operators.stiffness.push_back(&body.stiffness_matrix());
        operators.damping.push_back(
          body.has_damping() ? &body.damping_matrix() : nullptr);
        operators.external_force.block(b) = body.external_force();
      }
    for (unsigned int d = 0; d < dim; ++d)
      {
        unit_fields[d] = make_block_vector();
        Tensor<1, dim> e;
        e[d]                = 1.;
        mass_unit_fields[d] = make_block_vector();
        for (unsigned int b = 0; b < n_bodies; ++b)
          {
            body_list[b]->fill_uniform(unit_fields[d].block(b), e);
            body_list[b]->mass_matrix().vmult(mass_unit_fields[d].block(b),
                                              unit_fields[d].block(b));
          }
      }
    ++state_version; // the cached momenta used the old fields
    // F~ relative to each body's translation (FreeRhsOperator)
    operators.dof_components.assign(n_bodies, {});
    for (unsigned int b = 0; b < n_bodies; ++b)
      {
        operators.dof_components[b].assign(unit_fields[0].block(b).size(), 0);
        for (unsigned int d = 1; d < dim; ++d)
          for (unsigned int i = 0; i < unit_fields[d].block(b).size(); ++i)
            if (unit_fields[d].block(b)(i) != 0.)
              operators.dof_components[b][i] = d;
      }
    factorize_step_matrices(*scheme, step_matrices, step_solvers);
    free_rhs_operator.reinit(operators, scheme->free_rhs_coefficients());

    // The free-flight level: the same scheme with k h.
    coarse_scheme.reset();
    coarse_step_matrices.clear();
    coarse_step_solvers.clear();
    if (time_stepping.free_flight_step_factor > 1)
      {
        coarse_scheme =
          create_time_integrator(time_stepping.free_flight_parameters());
        factorize_step_matrices(*coarse_scheme,
                                coarse_step_matrices,
                                coarse_step_solvers);
        coarse_free_rhs_operator.reinit(operators,
                                        coarse_scheme->free_rhs_coefficients());
      }
    last_step_had_impulses = true; // the first step is made with h
    massless_dofs.clear();
    massless_impulses.clear();
    bool any_massless = false;
    for (const auto &body : body_list)
      {
        massless_dofs.push_back(body->massless_dofs());
        massless_impulses.emplace_back(massless_dofs.back().size(), 0.);
        any_massless = any_massless || !massless_dofs.back().empty();
      }
    scheme->set_massless_contact_nodes(any_massless);
    if (coarse_scheme)
      coarse_scheme->set_massless_contact_nodes(any_massless);

    solve_cost = 0.;
    for (const auto &solver : step_solvers)
      solve_cost += 4. * solver->n_factor_entries();

    contact_set.build_operator(body_list);
    dense_contact_products       = dense_products_pay_off();
    const unsigned int n_columns = contact_set.n_columns();
    delassus.reinit(0, 0); // allocated when a first column is computed
    delassus_ready.assign(contact_set.n_candidates(), false);
    column_work              = make_block_vector();
    const std::size_t n_dofs = column_work.size();
    const std::size_t n_slots =
      std::min<std::size_t>(n_columns,
                            column_storage_budget /
                              (8 * std::max<std::size_t>(n_dofs, 1)));
    stored_columns.assign(n_slots, column_work);
    stored_column_slot.assign(n_columns, -1);
    n_stored_columns = 0;

    // Newmark starts from a^0 with M a^0 = F - K u^0 - C v^0 (no contact
    // force at t = 0).
    if (scheme->needs_initial_acceleration())
      for (unsigned int b = 0; b < n_bodies; ++b)
        {
          const ElasticBody<dim> &body = *body_list[b];
          Vector<double>          rhs(body.external_force());
          Vector<double>          tmp(body.n_dofs());
          body.stiffness_matrix().vmult(tmp, current.displacement.block(b));
          rhs -= tmp;
          if (body.has_damping())
            {
              body.damping_matrix().vmult(tmp, current.velocity.block(b));
              rhs -= tmp;
            }
          SparseCholesky mass_solver;
          mass_solver.factorize(body.mass_matrix(),
                                "the mass matrix of body '" + body.name() +
                                  "'");
          mass_solver.solve(rhs);
          current.acceleration.block(b) = rhs;
        }

    next                = current;
    free_velocity       = make_block_vector();
    contact_force_field = make_block_vector();
    impulse_response    = make_block_vector();
    impulse_velocity    = make_block_vector();
    step_matrix_list.clear();
    for (const auto &matrix : step_matrices)
      step_matrix_list.push_back(matrix.get());
    schur_complements.clear();
    normal_schur_complements.clear();
    normal_schur_pending       = false;
    schur_preconditioner_ready = false;
    dense_schur.clear();
    active_set_stats    = ActiveSetStatistics();
    lcp_path_statistics = LcpStatistics();
    cone_statistics     = ExactConeStatistics();
    pivot_count         = 0;
    lcp_max_size        = 0;
    last_impulses.assign(n_columns, 0.);
    local_impulses.assign(n_columns, 0.);
    start_local_velocity.assign(n_columns, 0.);
    active.assign(contact_set.n_candidates(), false);
    // sized once, so that the time loop does not allocate (see
    // tests/dynamics/step_allocations)
    lcp_candidates.reserve(contact_set.n_candidates());
    state_guess.reserve(contact_set.n_candidates());
    last_contact_states.assign(contact_set.n_candidates(), ContactState::open);
    step_number = 0;
    clock.charge(costs.factorization);
  }



  // @sect3{The Delassus operator, column by column}
  // The columns W(:, j) = H^T M~^{-1} H_j of the directions j of a
  // candidate: a solve each, then a dot product with every (sparse) column
  // of H. Done once per candidate, when it first can touch; W(i, j) for two
  // candidates in an LCP is then always available, and so is W(i, j) for
  // any i against a candidate j of the LCP (the check of excluded
  // candidates). The solves are done in blocks of up to 128 right-hand
  // sides (at most 256 MiB), which the supernodal Cholesky solve handles
  // with dense block operations: several times faster per column than one
  // solve per column on large meshes.
  template <int dim>
  void
  MultibodySystem<dim>::ensure_delassus_columns(
    const std::vector<unsigned int> &candidates) const
  {
    const unsigned int        nd = contact_set.n_directions();
    std::vector<unsigned int> columns;
    for (const unsigned int c : candidates)
      if (!delassus_ready[c])
        {
          for (unsigned int k = 0; k < nd; ++k)
            columns.push_back(c * nd + k);
          delassus_ready[c] = true;
          ++costs.delassus_candidates;
        }
    if (columns.empty())
      return;
    if (delassus.n_rows() != contact_set.n_columns())
      delassus.reinit(contact_set.n_columns(), contact_set.n_columns());

    const std::size_t  n_dofs     = column_work.size();
    const unsigned int block_size = std::max<std::size_t>(
      1, std::min<std::size_t>(128, (std::size_t(256) << 20) / (8 * n_dofs)));
    const unsigned int               n_bodies = body_list.size();
    std::vector<std::vector<double>> rhs(n_bodies);
    for (std::size_t first = 0; first < columns.size(); first += block_size)
      {
        const unsigned int n_block =
          std::min<std::size_t>(block_size, columns.size() - first);
        for (unsigned int b = 0; b < n_bodies; ++b)
          rhs[b].assign(n_block * column_work.block(b).size(), 0.);
        for (unsigned int r = 0; r < n_block; ++r)
          {
            column_work = 0.;
            contact_set.add_column(columns[first + r], 1., column_work);
            for (unsigned int b = 0; b < n_bodies; ++b)
              {
                const Vector<double> &block = column_work.block(b);
                std::copy(block.begin(),
                          block.end(),
                          rhs[b].begin() + r * block.size());
              }
          }
        for (unsigned int b = 0; b < n_bodies; ++b)
          step_solvers[b]->solve(rhs[b].data(), n_block);
        for (unsigned int r = 0; r < n_block; ++r)
          {
            const unsigned int j = columns[first + r];
            for (unsigned int b = 0; b < n_bodies; ++b)
              {
                Vector<double> &block = column_work.block(b);
                const auto      start = rhs[b].begin() + r * block.size();
                std::copy(start, start + block.size(), block.begin());
              }
            for (unsigned int i = 0; i < contact_set.n_columns(); ++i)
              delassus(i, j) = contact_set.column_dot(i, column_work);
            if (n_stored_columns < stored_columns.size())
              {
                stored_columns[n_stored_columns] = column_work;
                stored_column_slot[j]            = n_stored_columns++;
              }
          }
      }
  }



  // @sect3{The LCP of one step}
  // The condensed contact problem on the candidates that can touch: their
  // block of W, their free local velocities and gap terms, and mu. The LCP
  // module assembles the form the scene needs (the n_c x n_c normal block
  // when frictionless, Klarbring's 3 n_c form in 2D, the facet form in 3D).
  template <int dim>
  void
  MultibodySystem<dim>::build_contact_problem(
    lcp::ContactProblem &problem) const
  {
    const unsigned int nd = contact_set.n_directions();
    const unsigned int n  = lcp_candidates.size();
    problem.n_directions  = nd;
    problem.n_contacts    = n;
    problem.W.reinit(n * nd, n * nd);
    problem.free_velocity.resize(n * nd);
    problem.gap_term.resize(n);
    problem.mu.resize(n);
    for (unsigned int a = 0; a < n; ++a)
      {
        const unsigned int ca = lcp_candidates[a];
        problem.gap_term[a]   = gap_terms[ca];
        problem.mu[a]         = contact_set.candidate(ca).friction_coefficient;
        for (unsigned int k = 0; k < nd; ++k)
          {
            problem.free_velocity[a * nd + k] =
              local_free_velocity[ca * nd + k];
            for (unsigned int b = 0; b < n; ++b)
              for (unsigned int l = 0; l < nd; ++l)
                problem.W(a * nd + k, b * nd + l) =
                  delassus(ca * nd + k, lcp_candidates[b] * nd + l);
          }
      }
  }



  template <int dim>
  const lcp::Result &
  MultibodySystem<dim>::solve_contact_lcp()
  {
    build_contact_problem(problem);
    const unsigned int nd = contact_set.n_directions();
    // Warm start from the contact states (open, stick, slip+, slip-) that
    // the candidates had at the last solve: the previous step's answer, or
    // this step's first answer when the candidate set has grown. The LCP
    // module turns them into a guess for any form (block pivoting on the
    // states in 2D with friction, Lemke from the guessed basis otherwise);
    // the answer is verified like a cold one.
    if (last_contact_states.size() != contact_set.n_candidates())
      last_contact_states.assign(contact_set.n_candidates(),
                                 ContactState::open);
    // The solver keeps its storage (LCP matrix, Lemke basis, block
    // pivoting systems) from step to step: no allocation here once the
    // largest LCP of the run has been seen (tests/lcp/allocations).
    lcp::ContactOptions options;
    options.n_facets = solver_parameters.n_facets;
    state_guess.resize(solver_parameters.warm_start ? lcp_candidates.size() :
                                                      0);
    for (unsigned int a = 0; a < state_guess.size(); ++a)
      state_guess[a] = last_contact_states[lcp_candidates[a]];
    // 3D friction with the exact cone: each candidate's facets start where
    // its last solve left them.
    const bool exact_cone =
      nd == 3 && solver_parameters.friction_cone == lcp::ConeModel::exact;
    if (exact_cone)
      {
        facet_angles.resize(contact_set.n_candidates(), 0.);
        facet_angle_guess.resize(lcp_candidates.size());
        for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
          facet_angle_guess[a] = facet_angles[lcp_candidates[a]];
      }
    lcp::ExactConeOptions cone_options;
    cone_options.tolerance = solver_parameters.exact_cone_tolerance;
    const lcp::ContactSolution &solution =
      exact_cone ?
        exact_cone_solver.solve(
          problem, options, cone_options, facet_angle_guess, state_guess) :
      solver_parameters.warm_start ?
        contact_solver.solve(problem, options, state_guess) :
        contact_solver.solve(problem, options);
    if (!exact_cone)
      {
        static_assert(static_cast<unsigned int>(
                        lcp::StartPath::block_pivoting) == 4,
                      "one count per lcp::StartPath");
        LcpStatistics &stats = lcp_path_statistics;
        ++stats.solves;
        ++stats.by_path[static_cast<unsigned int>(solution.lcp.start_path)];
        const bool by_block_pivoting =
          solution.lcp.start_path == lcp::StartPath::block_pivoting;
        if (by_block_pivoting || solution.block_pivoting_iterations > 0)
          {
            ++stats.block_pivoting_attempts;
            stats.block_pivoting_gave_up += by_block_pivoting ? 0 : 1;
          }
        stats.block_pivoting_linear_solves +=
          solution.block_pivoting_iterations;
        stats.block_pivoting_reused_factors +=
          solution.block_pivoting_reused_factors;
      }
    if (exact_cone && solution.lcp.status == lcp::Status::solved)
      {
        const lcp::ExactConeReport &cone = exact_cone_solver.report();
        ++cone_statistics.solves;
        cone_statistics.facet_lcps += cone.iterations;
        cone_statistics.most_facet_lcps =
          std::max(cone_statistics.most_facet_lcps, cone.iterations);
        cone_statistics.largest_residual =
          std::max(cone_statistics.largest_residual, cone.residual);
        if (!cone.converged)
          ++cone_statistics.not_converged;
        for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
          facet_angles[lcp_candidates[a]] = exact_cone_solver.facet_angles()[a];
      }
    if (solution.lcp.status == lcp::Status::solved)
      {
        std::fill(last_contact_states.begin(),
                  last_contact_states.end(),
                  ContactState::open);
        for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
          last_contact_states[lcp_candidates[a]] = solution.states[a];
      }
    last_lcp_size = solution.lcp.z.empty() ? lcp_candidates.size() * nd :
                                             solution.lcp.z.size();
    std::fill(local_impulses.begin(), local_impulses.end(), 0.);
    if (solution.lcp.status == lcp::Status::solved)
      for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
        for (unsigned int k = 0; k < nd; ++k)
          local_impulses[lcp_candidates[a] * nd + k] = solution.P[a * nd + k];
    return solution.lcp;
  }



  // @sect3{Large contact sets: the active set method}
  // W is never formed: a product W x is H^T M~^{-1} (H x), one solve pair
  // with the factorisation of M~. The solver (lcp/active_set.h) needs a few
  // tens of products per active set iteration, preconditioned by the
  // contact nodes' block of M~ (ContactSet::approximate_inverse_delassus()),
  // instead of the n_c solves and the O(n_c^3) pivots of Lemke's method on
  // the dense W. The last product is with the answer, so M~^{-1} H P is
  // the velocity correction and the check of the excluded candidates.
  //
  // In 3D with friction, automatic takes the active set method for every
  // size when its products are dense: Lemke's method there solves facet
  // LCPs of (k + 2) n_c rows (the exact cone: one or more per problem),
  // which on the default block_sliding_3d scene (25 contacts) cost 4.4 ms
  // per step against 0.05 ms, and 0.15 against 0.04 ms on
  // oblique_plate_3d's 36 (doc/lcp.md, "Which method automatic takes").
  // In 2D and without friction Lemke's small LCPs are the cheaper ones.
  template <int dim>
  bool
  MultibodySystem<dim>::use_active_set(const unsigned int n) const
  {
    using Method = ContactSolverParameters::Method;
    if (solver_parameters.method != Method::automatic)
      return solver_parameters.method == Method::active_set;
    return n >= solver_parameters.active_set_threshold ||
           (contact_set.n_directions() == 3 && dense_contact_products);
  }



  // The dense Schur complements (DenseSchurComplement) serve the active set
  // method's products if every candidate is against a rigid obstacle (so
  // that C holds every DoF of H), they are not turned off, and for every
  // body with contact DoFs they are the cheaper products (typically 3D).
  template <int dim>
  bool
  MultibodySystem<dim>::dense_products_pay_off() const
  {
    if (!solver_parameters.dense_schur_complement)
      return false;
    for (unsigned int c = 0; c < contact_set.n_candidates(); ++c)
      if (!contact_set.candidate(c).against_rigid_obstacle())
        return false;
    const auto dofs = contact_set.obstacle_contact_dofs(body_list.size());
    for (unsigned int b = 0; b < body_list.size(); ++b)
      if (!dofs[b].empty() &&
          !DenseSchurComplement::pays_off(dofs[b].size(),
                                          step_solvers[b]->n_factor_entries()))
        return false;
    return true;
  }



  template <int dim>
  bool
  MultibodySystem<dim>::solve_contact_active_set(StepReport &report)
  {
    const unsigned int nd = contact_set.n_directions();
    const unsigned int n  = lcp_candidates.size();
    // set up by do_time_step(), where its cost is counted
    Assert(schur_preconditioner_ready, ExcInternalError());
    contact_set.inverse_delassus_diagonal(step_matrix_list,
                                          lcp_candidates,
                                          lcp_penalty);
    lcp_free_velocity.resize(n * nd);
    lcp_impulse_guess.resize(n * nd);
    lcp_gap_terms.resize(n);
    lcp_mu.resize(n);
    state_guess.resize(n);
    for (unsigned int a = 0; a < n; ++a)
      {
        const unsigned int c = lcp_candidates[a];
        lcp_gap_terms[a]     = gap_terms[c];
        lcp_mu[a]            = contact_set.candidate(c).friction_coefficient;
        state_guess[a] =
          last_contact_states.size() == contact_set.n_candidates() ?
            last_contact_states[c] :
            ContactState::open;
        for (unsigned int k = 0; k < nd; ++k)
          {
            lcp_free_velocity[a * nd + k] = local_free_velocity[c * nd + k];
            lcp_impulse_guess[a * nd + k] = last_impulses[c * nd + k];
          }
      }
    const lcp::DelassusProduct product = [&](const std::vector<double> &x,
                                             std::vector<double>       &y) {
      if (!dense_schur.empty())
        {
          dense_schur_product(x, y, false);
          return;
        }
      impulse_velocity = 0.;
      add_lcp_columns(x, impulse_velocity);
      solve_step_matrix(impulse_velocity);
      lcp_column_dots(impulse_velocity, y);
    };
    // The Schur complement preconditioners (schur_preconditioner_product()).
    // Frictionless: the normal one is the exact inverse of W.
    const bool has_full = !schur_complements.empty() || !dense_schur.empty();
    const lcp::DelassusProduct preconditioner =
      [&, has_full](const std::vector<double> &x, std::vector<double> &y) {
        if (!dense_schur.empty())
          dense_schur_product(x, y, true);
        else
          schur_preconditioner_product(x, y, !has_full);
      };
    // Made on first use; their set-up time is charged to the Delassus line.
    const auto timed_ensure_normal = [&]() {
      const double start  = measure_costs ? wall_seconds() : 0.;
      const bool   normal = ensure_normal_schur_complements();
      if (measure_costs)
        normal_schur_seconds += wall_seconds() - start;
      return normal;
    };
    const lcp::DelassusProduct normal_preconditioner =
      [&](const std::vector<double> &x, std::vector<double> &y) {
        // the full one's normal rows if the normal ones cannot be made
        schur_preconditioner_product(x, y, timed_ensure_normal());
      };
    // the active set method's state codes are SparseSchurComplement's
    static_assert(SparseSchurComplement::open_state == 0 &&
                  SparseSchurComplement::slide_state == 1 &&
                  SparseSchurComplement::stick_state == 2);
    const lcp::NormalStateUpdate normal_state_update =
      [&](const std::vector<unsigned char> &states,
          const std::vector<double>        &slip) {
        if (timed_ensure_normal())
          update_normal_states(states, slip);
      };
    const unsigned int singular_before =
      active_set_stats.singular_state_matrices;
    lcp::ActiveSetOptions options;
    options.max_iterations = solver_parameters.active_set_iterations;
    options.max_front_iterations =
      solver_parameters.active_set_front_iterations;
    // the exact normal rows: from the first solve, or as the schedule of
    // the solves that switched to them says (lcp::ExactRowsSchedule)
    options.exact_normal_rows       = exact_rows_schedule.start_exact();
    options.exact_normal_rows_after = solver_parameters.exact_normal_rows_after;
    if (nd == 3 && solver_parameters.friction_cone == lcp::ConeModel::facets)
      options.n_facets = solver_parameters.n_facets;
    const lcp::ActiveSetReport &result = active_set_solver.solve(
      product,
      preconditioner,
      lcp_penalty,
      nd,
      lcp_free_velocity,
      lcp_gap_terms,
      lcp_mu,
      solver_parameters.warm_start ? state_guess : std::vector<ContactState>(),
      solver_parameters.warm_start ? lcp_impulse_guess : std::vector<double>(),
      options,
      has_full && (normal_schur_pending || !normal_schur_complements.empty()) ?
        normal_preconditioner :
        lcp::DelassusProduct(),
      nd > 1 ? normal_state_update : lcp::NormalStateUpdate());
    ActiveSetStatistics &stats = active_set_stats;
    ++stats.solves;
    stats.iterations += result.iterations;
    stats.most_iterations = std::max(stats.most_iterations, result.iterations);
    stats.linear_iterations += result.linear_iterations;
    stats.operator_applications += result.operator_applications;
    report.active_set_iterations += result.iterations;
    exact_normal_rows = exact_normal_rows || result.exact_normal_rows;
    exact_rows_schedule.finish(result.exact_normal_rows);
    if (!result.converged)
      {
        ++stats.fallbacks;
        stats.last_fallback_reason = result.message;
        if (const unsigned int singular =
              stats.singular_state_matrices - singular_before;
            singular > 0)
          stats.last_fallback_reason +=
            "; the normal rows' matrix at the contact states was singular " +
            std::to_string(singular) + (singular == 1 ? " time" : " times") +
            ", and W_NN^{-1} preconditioned them instead";
        report.active_set_fallback = true;
        return false;
      }
    stats.largest_cone_error =
      std::max(stats.largest_cone_error, result.cone_error);
    stats.refinements += result.refinements;
    stats.largest_linear_residual =
      std::max(stats.largest_linear_residual, result.linear_residual);
    stats.largest_violation =
      std::max({stats.largest_violation,
                result.verification.max_signorini_violation,
                result.verification.max_cone_violation,
                result.verification.max_sliding_violation});

    const std::vector<double> &P = active_set_solver.impulses();
    std::fill(local_impulses.begin(), local_impulses.end(), 0.);
    std::fill(last_contact_states.begin(),
              last_contact_states.end(),
              ContactState::open);
    bool any_impulse = false;
    for (unsigned int a = 0; a < n; ++a)
      {
        last_contact_states[lcp_candidates[a]] = active_set_solver.states()[a];
        for (unsigned int k = 0; k < nd; ++k)
          {
            local_impulses[lcp_candidates[a] * nd + k] = P[a * nd + k];
            any_impulse = any_impulse || P[a * nd + k] != 0.;
          }
      }
    if (!any_impulse) // the solver made no product with P = 0
      impulse_velocity = 0.;
    else if (!dense_schur.empty())
      {
        // The dense products give W P on the contact DoFs only: M~^{-1} H P
        // (the velocity correction, and the excluded candidates' check) is
        // one solve pair.
        impulse_velocity = 0.;
        add_lcp_columns(P, impulse_velocity);
        solve_step_matrix(impulse_velocity);
      }
    impulse_velocity_ready = true;
    return true;
  }



  // H^T S^{-1} H x (W x) or H^T S H x (the preconditioner) with the dense
  // Schur complements of the bodies: H x on each body's contact DoFs, one
  // dense product, and H^T back. Every candidate is against a rigid
  // obstacle (setup_schur_preconditioner()), so C holds all DoFs of H.
  template <int dim>
  void
  MultibodySystem<dim>::dense_schur_product(const std::vector<double> &x,
                                            std::vector<double>       &y,
                                            const bool use_schur) const
  {
    for (unsigned int b = 0; b < dense_schur.size(); ++b)
      for (const auto d : dense_schur[b].dofs())
        schur_nodal.block(b)(d) = 0.;
    add_lcp_columns(x, schur_nodal);
    for (unsigned int b = 0; b < dense_schur.size(); ++b)
      {
        const DenseSchurComplement &schur = dense_schur[b];
        const auto                 &dofs  = schur.dofs();
        dense_in.resize(dofs.size());
        dense_out.resize(dofs.size());
        for (unsigned int i = 0; i < dofs.size(); ++i)
          dense_in[i] = schur_nodal.block(b)(dofs[i]);
        if (use_schur) // the preconditioner: single precision suffices
          schur.vmult_single_precision(dense_in.data(), dense_out.data());
        else
          schur.vmult_inverse(dense_in.data(), dense_out.data());
        for (unsigned int i = 0; i < dofs.size(); ++i)
          schur_product.block(b)(dofs[i]) = dense_out[i];
      }
    lcp_column_dots(schur_product, y);
  }



  // H x for x on the LCP's candidates (added to @p target), and H^T v.
  template <int dim>
  void
  MultibodySystem<dim>::add_lcp_columns(const std::vector<double> &x,
                                        BlockVector<double>       &target) const
  {
    const unsigned int nd = contact_set.n_directions();
    for (unsigned int j = 0; j < x.size(); ++j)
      if (x[j] != 0.)
        contact_set.add_column(lcp_candidates[j / nd] * nd + j % nd,
                               x[j],
                               target);
  }



  template <int dim>
  void
  MultibodySystem<dim>::lcp_column_dots(const BlockVector<double> &v,
                                        std::vector<double>       &y) const
  {
    const unsigned int nd = contact_set.n_directions();
    y.resize(lcp_candidates.size() * nd);
    for (unsigned int j = 0; j < y.size(); ++j)
      y[j] = contact_set.column_dot(lcp_candidates[j / nd] * nd + j % nd, v);
  }



  // The factorisation behind the preconditioner: M~ with the rows and
  // columns of the contact DoFs C replaced by those of the identity, so
  // that a solve with a right-hand side that is zero on C gives
  // M~_II^{-1} on the other DoFs and zero on C. Made once, at the first
  // active set solve (as costly as the factorisation of M~).
  template <int dim>
  void
  MultibodySystem<dim>::setup_schur_preconditioner()
  {
    const unsigned int n_bodies = body_list.size();
    schur_contact_dofs          = contact_set.obstacle_contact_dofs(n_bodies);
    schur_nodal                 = make_block_vector();
    schur_product               = make_block_vector();
    schur_interior              = make_block_vector();
    schur_complements.clear();
    normal_schur_complements.clear();
    normal_schur_pending = false;
    dense_schur.clear();
    schur_preconditioner_ready = true;
    if (dense_contact_products)
      {
        active_set_stats.dense_schur_complement = true;
        dense_schur.resize(n_bodies);
        for (unsigned int b = 0; b < n_bodies; ++b)
          if (!schur_contact_dofs[b].empty())
            dense_schur[b].compute(*step_matrices[b],
                                   schur_contact_dofs[b],
                                   "the step matrix of body '" +
                                     body_list[b]->name() + "'");
        return;
      }
    const unsigned int nd = contact_set.n_directions();
    // The normal Schur complements: each obstacle candidate's node in its
    // contact frame, the normal component in the slot of the node's first
    // DoF. Not if a node has two such candidates (or the rotation does not
    // fit the matrices' patterns): then only the full ones.
    frame_slots.assign(contact_set.n_candidates(), {});
    normal_frame_index.assign(contact_set.n_candidates(),
                              numbers::invalid_unsigned_int);
    normal_frame_tangents.assign(contact_set.n_candidates(), {});
    normal_frames.assign(n_bodies, {});
    normal_dofs.assign(n_bodies, {});
    std::vector<types::global_dof_index> node_dofs(dim);
    std::vector<double>                  node_normal(dim);
    for (unsigned int c = 0; c < contact_set.n_candidates(); ++c)
      if (const ContactCandidate &candidate = contact_set.candidate(c);
          candidate.against_rigid_obstacle())
        {
          // All DoFs of the node, also those the normal has no part in:
          // the tangents' slots are where set_contact_states() acts. The
          // columns of H are the candidate's frame
          // (ContactSet::build_operator()).
          const unsigned int b = candidate.body_a;
          for (unsigned int d = 0; d < dim; ++d)
            {
              node_dofs[d]   = body_list[b]->vertex_dof(candidate.vertex_a, d);
              node_normal[d] = candidate.frame[0][d];
            }
          const auto frame =
            SparseSchurComplement::NodeFrame::with_normal(node_dofs,
                                                          node_normal);
          for (unsigned int k = 1; k < nd; ++k)
            for (unsigned int l = 1; l < dim; ++l)
              for (unsigned int d = 0; d < dim; ++d)
                normal_frame_tangents[c][k - 1][l - 1] +=
                  candidate.frame[k][d] * frame.rotation[l][d];
          normal_frame_index[c] = normal_frames[b].size();
          normal_frames[b].push_back(frame);
          std::copy(node_dofs.begin(), node_dofs.end(), frame_slots[c].begin());
          normal_dofs[b].push_back(node_dofs[0]);
        }
    normal_schur_pending = true;
    // Frictionless, the normal ones are the exact inverse of W: nothing
    // else is needed. With friction they serve only solves in which nearly
    // every closed contact slides, which many scenes never have: they are
    // factorised when a solve first asks for them (as costly as the
    // factorisation of M~, and as large).
    if (nd == 1 && ensure_normal_schur_complements())
      return;

    schur_complements.resize(n_bodies);
    for (unsigned int b = 0; b < n_bodies; ++b)
      if (!schur_contact_dofs[b].empty())
        schur_complements[b].initialize(*step_matrices[b],
                                        schur_contact_dofs[b],
                                        "the interior step matrix of body '" +
                                          body_list[b]->name() + "'");
  }



  template <int dim>
  bool
  MultibodySystem<dim>::ensure_normal_schur_complements()
  {
    if (normal_schur_pending)
      {
        normal_schur_pending = false;
        bool normal          = true;
        normal_schur_complements.resize(body_list.size());
        for (unsigned int b = 0; b < body_list.size() && normal; ++b)
          if (!normal_dofs[b].empty())
            normal = normal_schur_complements[b].initialize(
              *step_matrices[b],
              normal_dofs[b],
              "the step matrix of body '" + body_list[b]->name() +
                "' without its contact normals",
              normal_frames[b],
              contact_set.n_directions() > 1);
        if (!normal)
          normal_schur_complements.clear();
        const unsigned int n_complements = normal_schur_complements.size();
        normal_state.assign(n_complements, {});
        normal_skew.assign(n_complements, {});
        for (unsigned int b = 0; b < n_complements; ++b)
          {
            normal_state[b].assign(normal_frames[b].size(), 0);
            normal_skew[b].assign(normal_frames[b].size(), {{0., 0., 0.}});
          }
        normal_frames.clear();
        normal_dofs.clear();
      }
    return !normal_schur_complements.empty();
  }



  // The skew of a sliding contact is mu d in the contact frame's tangents:
  // in its node's frame, the coordinates of mu (d_1 t_1 + d_2 t_2).
  template <int dim>
  void
  MultibodySystem<dim>::update_normal_states(
    const std::vector<unsigned char> &states,
    const std::vector<double>        &slip)
  {
    const unsigned int nt = contact_set.n_directions() - 1;
    for (unsigned int b = 0; b < normal_schur_complements.size(); ++b)
      {
        std::fill(normal_state[b].begin(),
                  normal_state[b].end(),
                  SparseSchurComplement::open_state);
        std::fill(normal_skew[b].begin(),
                  normal_skew[b].end(),
                  std::array<double, 3>{});
      }
    for (unsigned int a = 0; a < states.size(); ++a)
      if (const unsigned int c = lcp_candidates[a];
          normal_frame_index[c] != numbers::invalid_unsigned_int)
        {
          const unsigned int b = contact_set.candidate(c).body_a;
          normal_state[b][normal_frame_index[c]] = states[a];
          auto &s = normal_skew[b][normal_frame_index[c]];
          for (unsigned int k = 0; k < nt; ++k)
            for (unsigned int l = 0; l + 1 < dim; ++l)
              s[l + 1] += slip[a * nt + k] * normal_frame_tangents[c][k][l];
        }
    for (unsigned int b = 0; b < normal_schur_complements.size(); ++b)
      {
        SparseSchurComplement &complement = normal_schur_complements[b];
        if (states.empty())
          {
            complement.set_contact_states({}, {});
            continue;
          }
        // A preconditioner whose slips lag by less than 0.05 mu, or whose
        // states lag by a few contacts (`Exact normal rows state lag`),
        // costs GMRES a few iterations, far less than a factorisation.
        try
          {
            if (complement.set_contact_states(
                  normal_state[b],
                  normal_skew[b],
                  0.05,
                  solver_parameters.exact_normal_rows_state_lag))
              ++active_set_stats.state_factorizations;
          }
        catch (const ExceptionBase &)
          {
            // singular (mu beyond uniqueness): the normal Schur complement
            // again, which set_contact_states() has left in place; GMRES
            // copes or stalls, and a stall falls back to Lemke's method
            ++active_set_stats.state_factorizations;
            ++active_set_stats.singular_state_matrices;
          }
      }
  }



  // S_CC y = M~_CC y - M~_CI M~_II^{-1} M~_IC y for y = H x on C, or the
  // same with the normal Schur complement on the normal slots.
  template <int dim>
  void
  MultibodySystem<dim>::schur_preconditioner_product(
    const std::vector<double> &x,
    std::vector<double>       &y,
    const bool                 normal) const
  {
    const unsigned int nd = contact_set.n_directions();
    const unsigned int n  = lcp_candidates.size();
    const auto        &complements =
      normal ? normal_schur_complements : schur_complements;
    // At contact states (update_normal_states()) the products invert the
    // states they were factorised at, which may lag the active set
    // method's by a few contacts (SparseSchurComplement::
    // set_contact_states()): a closed contact's normal and a sticking
    // contact's tangents are the factorised inverse's unknowns if its
    // factorised state has them; the other rows the method asks for are
    // scaled by the penalties c ~ 1 / W_jj (the active set method's
    // complementarity constants, which average the two tangents' in 3D).
    auto factored_state = [&](const unsigned int c) {
      const unsigned int b = contact_set.candidate(c).body_a;
      return complements[b].factored_states()[normal_frame_index[c]];
    };
    auto at_states = [&](const unsigned int c) {
      return normal && complements[contact_set.candidate(c).body_a]
                         .inverts_contact_states();
    };
    auto normal_unknown = [&](const unsigned int c) {
      return !at_states(c) ||
             factored_state(c) != SparseSchurComplement::open_state;
    };
    auto sticks = [&](const unsigned int c) {
      return at_states(c) &&
             factored_state(c) == SparseSchurComplement::stick_state;
    };
    schur_nodal = 0.;
    for (unsigned int j = 0; j < n * nd; ++j)
      if (const unsigned int c = lcp_candidates[j / nd];
          x[j] != 0. && contact_set.candidate(c).against_rigid_obstacle())
        {
          const unsigned int b = contact_set.candidate(c).body_a;
          if (!normal)
            contact_set.add_column(c * nd + j % nd, x[j], schur_nodal);
          else if (j % nd == 0)
            {
              if (normal_unknown(c))
                schur_nodal.block(b)(frame_slots[c][0]) = x[j];
            }
          else if (sticks(c))
            for (unsigned int l = 0; l + 1 < dim; ++l)
              schur_nodal.block(b)(frame_slots[c][l + 1]) +=
                normal_frame_tangents[c][j % nd - 1][l] * x[j];
        }
    for (unsigned int b = 0; b < complements.size(); ++b)
      if (!complements[b].dofs().empty())
        complements[b].vmult_single_precision(schur_nodal.block(b),
                                              schur_product.block(b),
                                              schur_interior.block(b));
    y.resize(n * nd);
    for (unsigned int j = 0; j < n * nd; ++j)
      {
        const unsigned int      c         = lcp_candidates[j / nd];
        const ContactCandidate &candidate = contact_set.candidate(c);
        if (!candidate.against_rigid_obstacle())
          y[j] = lcp_penalty[j] * x[j];
        else if (!normal)
          y[j] = contact_set.column_dot(c * nd + j % nd, schur_product);
        else if (j % nd == 0)
          y[j] = normal_unknown(c) ?
                   schur_product.block(candidate.body_a)(frame_slots[c][0]) :
                   lcp_penalty[j] * x[j];
        else if (sticks(c))
          {
            y[j] = 0.;
            for (unsigned int l = 0; l + 1 < dim; ++l)
              y[j] +=
                normal_frame_tangents[c][j % nd - 1][l] *
                schur_product.block(candidate.body_a)(frame_slots[c][l + 1]);
          }
        else
          // a tangent the products do not invert: the method reads it only
          // if the contact sticks now (the lag, or a singular state matrix
          // that left the products those of S_N)
          y[j] = lcp_penalty[j] * x[j];
      }
  }



  template <int dim>
  const typename MultibodySystem<dim>::ActiveSetStatistics &
  MultibodySystem<dim>::active_set_statistics() const
  {
    return active_set_stats;
  }



  template <int dim>
  std::size_t
  MultibodySystem<dim>::lcp_memory_consumption() const
  {
    return contact_solver.memory_consumption() +
           problem.W.memory_consumption() +
           lcp::memory_consumption(problem.free_velocity) +
           lcp::memory_consumption(problem.gap_term) +
           lcp::memory_consumption(problem.mu) +
           lcp::memory_consumption(lcp_candidates) +
           lcp::memory_consumption(state_guess);
  }



  template <int dim>
  void
  MultibodySystem<dim>::dump_lcp(const std::string &file_name,
                                 const bool         problem_built)
  {
    // The active set method solves without W: form it only for the file.
    if (!problem_built)
      {
        ensure_delassus_columns(lcp_candidates);
        build_contact_problem(problem);
      }
    // The frictional-contact text format of Siconos numerics: W, q with the
    // gap term folded into the normal rows, mu (see doc/lcp.md).
    lcp::write_friction_contact_file(file_name, problem);
  }



  // A step that fails writes its problem for replay with lcp-solve. After
  // the active set method W has not been formed: beyond a few thousand
  // rows its columns (a solve pair each) and its text (about 20 bytes per
  // entry) would cost more than the failed run, and only 'Dump LCP of
  // step' for that step writes it then.
  template <int dim>
  std::string
  MultibodySystem<dim>::write_unsolved_problem(const bool w_formed)
  {
    // after Lemke's method, solve_contact_lcp() has built the problem
    return solver_parameters.write_unsolved_problem(
      dump_directory,
      step_number,
      lcp_candidates.size() * contact_set.n_directions(),
      w_formed,
      [&](const std::string &name) { dump_lcp(name, w_formed); });
  }



  template <int dim>
  void
  MultibodySystem<dim>::complete_and_advance(const TimeIntegrator &level_scheme,
                                             const double          time)
  {
    level_scheme.complete_step(current, next);
    // A massless node has no inertia: its v^{i+1} from the step solve is
    // only what the displacement update needs, and would alternate by the
    // factor -(1 - theta)/theta per step. Its velocity is the one that
    // moves it: (u^{i+1} - u^i) / h.
    for (unsigned int b = 0; b < massless_dofs.size(); ++b)
      for (const types::global_dof_index i : massless_dofs[b])
        next.velocity.block(b)(i) =
          (next.displacement.block(b)(i) - current.displacement.block(b)(i)) /
          level_scheme.time_step();
    next.time = time;
    swap(current, next); // no allocation (time_integrator.h)
    ++state_version;
  }



  // @sect3{A free-flight step}
  // No contact acted in the last step. The step is tried with k h: if no
  // candidate's free velocity closes its gap under the Signorini condition
  // of k h (the test that puts candidates into the LCP, with an empty
  // active set), no contact acts in it and it is kept. Otherwise nothing
  // has changed and the caller makes the step with h.
  template <int dim>
  bool
  MultibodySystem<dim>::try_free_flight_step(StepReport &report)
  {
    CostClock          clock(measure_costs);
    const unsigned int nd = contact_set.n_directions();
    const double       H  = coarse_scheme->time_step();

    coarse_scheme->free_rhs(coarse_free_rhs_operator,
                            current,
                            free_velocity,
                            free_velocity_translation);
    for (unsigned int b = 0; b < body_list.size(); ++b)
      coarse_step_solvers[b]->solve(free_velocity.block(b));
    coarse_free_rhs_operator.add_translation(free_velocity_translation,
                                             free_velocity);
    contact_set.local_velocities(free_velocity, local_free_velocity);
    coarse_scheme->gap_term(contact_set, current, gap_terms);
    for (unsigned int c = 0; c < contact_set.n_candidates(); ++c)
      if (local_free_velocity[c * nd] + gap_terms[c] < 0.)
        {
          clock.charge(costs.free_velocity);
          return false;
        }
    clock.charge(costs.free_velocity);

    const unsigned int k = time_stepping.free_flight_step_factor;
    step_number += k;
    report            = StepReport();
    report.step       = step_number;
    report.time       = current.time + H;
    report.time_step  = H;
    report.n_substeps = k;
    std::fill(local_impulses.begin(), local_impulses.end(), 0.);
    std::fill(active.begin(), active.end(), false);
    contact_force_field = 0.;
    for (auto &impulses : massless_impulses)
      std::fill(impulses.begin(), impulses.end(), 0.);
    next.velocity.swap(free_velocity);
    complete_and_advance(*coarse_scheme, report.time);
    last_step_had_impulses = false;
    clock.charge(costs.update);
    return true;
  }



  // @sect3{One time step}
  template <int dim>
  StepReport
  MultibodySystem<dim>::do_time_step(const unsigned int max_substeps)
  {
    if (coarse_scheme && !last_step_had_impulses &&
        max_substeps >= time_stepping.free_flight_step_factor)
      {
        StepReport report;
        if (try_free_flight_step(report))
          return report;
      }

    ++step_number;
    const double       h            = scheme->time_step();
    const unsigned int nd           = contact_set.n_directions();
    const unsigned int n_candidates = contact_set.n_candidates();

    StepReport report;
    report.step      = step_number;
    report.time      = current.time + h;
    report.time_step = h;
    CostClock clock(measure_costs);

    // 1. Free velocity. Massless nodes are balanced at t^{i+1}
    // (TimeIntegrator::set_massless_contact_nodes()).
    scheme->free_rhs(free_rhs_operator,
                     current,
                     free_velocity,
                     free_velocity_translation);
    const double carry = scheme->massless_impulse_carry();
    for (unsigned int b = 0; b < massless_dofs.size(); ++b)
      for (unsigned int k = 0; k < massless_dofs[b].size(); ++k)
        free_velocity.block(b)(massless_dofs[b][k]) +=
          carry * massless_impulses[b][k];
    solve_step_matrix(free_velocity);
    free_rhs_operator.add_translation(free_velocity_translation, free_velocity);

    // 2. Local free velocities and the scheme's gap terms.
    contact_set.local_velocities(free_velocity, local_free_velocity);
    scheme->gap_term(contact_set, current, gap_terms);
    // Massless nodes slide with their mean velocity over the step: Coulomb
    // on V_T^{i+1} + c V_T^i (TimeIntegrator::slip_velocity_carry()).
    if (const double c = scheme->slip_velocity_carry(); c != 0. && nd > 1)
      {
        contact_set.local_velocities(current.velocity, start_local_velocity);
        for (unsigned int j = 0; j < local_free_velocity.size(); ++j)
          if (j % nd != 0)
            local_free_velocity[j] += c * start_local_velocity[j];
      }
    clock.charge(costs.free_velocity);

    // 3. The LCP on the candidates that can touch: those whose free normal
    // velocity would close the gap within the step, plus the previous
    // active set. If the impulses push an excluded candidate into
    // penetration, it joins and the LCP is solved again.
    in_lcp.assign(n_candidates, false);
    double scale = 0.;
    for (unsigned int c = 0; c < n_candidates; ++c)
      {
        const double w_free = local_free_velocity[c * nd] + gap_terms[c];
        in_lcp[c]           = (w_free < 0.) || active[c];
        scale               = std::max({scale,
                                        std::abs(local_free_velocity[c * nd]),
                                        std::abs(gap_terms[c])});
      }
    const double tolerance = 1e-12 * scale;
    std::fill(local_impulses.begin(), local_impulses.end(), 0.);
    for (;;)
      {
        lcp_candidates.clear();
        for (unsigned int c = 0; c < n_candidates; ++c)
          if (in_lcp[c])
            lcp_candidates.push_back(c);
        if (lcp_candidates.empty())
          break;

        // The active set method (large sets): no W, its answer verified;
        // Lemke's method otherwise, and when it does not converge.
        impulse_velocity_ready = false;
        if (use_active_set(lcp_candidates.size()) &&
            !schur_preconditioner_ready)
          {
            clock.charge(costs.lcp);
            setup_schur_preconditioner();
            clock.charge(costs.delassus);
          }
        if (use_active_set(lcp_candidates.size()) &&
            solve_contact_active_set(report))
          {
            report.lcp_size = lcp_candidates.size() * nd;
            if (solver_parameters.dump_step == static_cast<int>(step_number))
              dump_lcp(dump_directory + "/lcp_step_" +
                         std::to_string(step_number) + ".dat",
                       false);
            bool grown = false;
            for (unsigned int c = 0; c < n_candidates; ++c)
              if (!in_lcp[c] &&
                  local_free_velocity[c * nd] + gap_terms[c] +
                      contact_set.column_dot(c * nd, impulse_velocity) <
                    -tolerance)
                {
                  in_lcp[c] = true;
                  grown     = true;
                }
            if (!grown)
              break;
            ++report.lcp_resolves;
            continue;
          }

        if (report.active_set_fallback &&
            !solver_parameters.lemke_fallback_allowed(lcp_candidates.size(),
                                                      nd))
          throw ContactSolverFailure(
            "The contact problem of step " + std::to_string(step_number) +
            " (t = " + format_number(report.time) + " s, " +
            std::to_string(lcp_candidates.size()) +
            " contact candidates) was not solved: the active set method did "
            "not converge (" +
            active_set_stats.last_fallback_reason + "), and " +
            solver_parameters.lemke_fallback_limit_text(lcp_candidates.size(),
                                                        nd) +
            "." + write_unsolved_problem(false));
        clock.charge(costs.lcp);
        ensure_delassus_columns(lcp_candidates);
        clock.charge(costs.delassus);

        const lcp::Result &result = solve_contact_lcp();
        report.lcp_size           = last_lcp_size;
        report.lcp_pivots += result.pivots;
        if (result.status != lcp::Status::solved)
          {
            std::ostringstream message;
            message << "The contact LCP of step " << step_number
                    << " (t = " << report.time << " s, "
                    << lcp_candidates.size()
                    << " contact candidates) was not solved: "
                    << lcp::to_string(result.status) << ". " << result.message
                    << (report.active_set_fallback ?
                          " (The active set method had not converged: " +
                            active_set_stats.last_fallback_reason + ".)" :
                          std::string())
                    << write_unsolved_problem(true);
            throw ContactSolverFailure(message.str());
          }
        if (solver_parameters.dump_step == static_cast<int>(step_number))
          dump_lcp(dump_directory + "/lcp_step_" + std::to_string(step_number) +
                     ".dat",
                   true);

        bool grown = false;
        for (unsigned int c = 0; c < n_candidates; ++c)
          if (!in_lcp[c])
            {
              double w = local_free_velocity[c * nd] + gap_terms[c];
              for (const unsigned int a : lcp_candidates)
                for (unsigned int k = 0; k < nd; ++k)
                  w +=
                    delassus(c * nd, a * nd + k) * local_impulses[a * nd + k];
              if (w < -tolerance)
                {
                  in_lcp[c] = true;
                  grown     = true;
                }
            }
        if (!grown)
          break;
        ++report.lcp_resolves;
      }
    pivot_count += report.lcp_pivots;
    lcp_max_size = std::max(lcp_max_size, report.lcp_size);
    clock.charge(costs.lcp);
    if (measure_costs)
      {
        // a set-up made during the solve
        costs.lcp -= normal_schur_seconds;
        costs.delassus += normal_schur_seconds;
      }
    normal_schur_seconds = 0.;

    // 4. v^{i+1} = v_free + M~^{-1} (H P), and the nodal forces. With few
    // impulses whose columns M~^{-1} H_j are stored, their sum is cheaper
    // than a solve; otherwise one solve with H P.
    // v_free is formed anew (every entry) at the next step: a swap, not a
    // copy.
    next.velocity.swap(free_velocity);
    const double force_factor = scheme->force_per_impulse();
    unsigned int n_impulses   = 0;
    bool         all_stored   = true;
    for (unsigned int j = 0; j < contact_set.n_columns(); ++j)
      if (local_impulses[j] != 0.)
        {
          ++n_impulses;
          all_stored = all_stored && stored_column_slot[j] >= 0;
        }
    // After a step without impulses H P and the force field are zero
    // already: a step in free flight skips two passes over the DoFs.
    if (n_impulses > 0 || last_step_had_impulses)
      {
        impulse_response = 0.;
        for (unsigned int j = 0; j < contact_set.n_columns(); ++j)
          if (local_impulses[j] != 0.)
            contact_set.add_column(j, local_impulses[j], impulse_response);
        contact_force_field.equ(force_factor, impulse_response);
      }
    for (unsigned int b = 0; b < massless_dofs.size(); ++b)
      for (unsigned int k = 0; k < massless_dofs[b].size(); ++k)
        massless_impulses[b][k] =
          impulse_response.block(b)(massless_dofs[b][k]);
    if (impulse_velocity_ready)
      next.velocity += impulse_velocity;
    else if (all_stored && 2. * n_impulses * next.velocity.size() < solve_cost)
      {
        // The stored columns four at a time (add_columns()).
        for (unsigned int b = 0; b < next.velocity.n_blocks(); ++b)
          {
            Vector<double>               &v = next.velocity.block(b);
            std::array<double, 4>         a;
            std::array<const double *, 4> c;
            unsigned int                  k = 0;
            for (unsigned int j = 0; j < contact_set.n_columns(); ++j)
              if (local_impulses[j] != 0.)
                {
                  a[k] = local_impulses[j];
                  c[k] = stored_columns[stored_column_slot[j]].block(b).begin();
                  if (++k == 4)
                    {
                      add_columns(v.begin(), v.size(), a.data(), c.data(), k);
                      k = 0;
                    }
                }
            add_columns(v.begin(), v.size(), a.data(), c.data(), k);
          }
        report.stored_columns_summed = n_impulses;
      }
    else if (n_impulses > 0)
      {
        solve_step_matrix(impulse_response);
        next.velocity += impulse_response;
      }

    // 5. Displacement (and acceleration) update.
    complete_and_advance(*scheme, report.time);
    last_step_had_impulses = n_impulses > 0;

    // Report.
    Tensor<1, dim> tangential;
    for (unsigned int c = 0; c < n_candidates; ++c)
      {
        const double p_n = local_impulses[c * nd];
        active[c]        = p_n > 0.;
        report.active_contacts += active[c] ? 1 : 0;
        report.normal_force += force_factor * p_n;
        for (unsigned int k = 1; k < nd; ++k)
          for (unsigned int d = 0; d < dim; ++d)
            tangential[d] += force_factor * local_impulses[c * nd + k] *
                             contact_set.candidate(c).frame[k][d];
      }
    report.tangential_force = tangential.norm();
    last_impulses           = local_impulses;
    clock.charge(costs.update);
    return report;
  }



  // @sect3{Energies, momenta and forces}
  template <int dim>
  double
  MultibodySystem<dim>::kinetic_energy(const unsigned int b) const
  {
    return body_integrals(b).kinetic_energy;
  }

  template <int dim>
  double
  MultibodySystem<dim>::kinetic_energy() const
  {
    double e = 0.;
    for (unsigned int b = 0; b < body_list.size(); ++b)
      e += kinetic_energy(b);
    return e;
  }

  template <int dim>
  double
  MultibodySystem<dim>::elastic_energy(const unsigned int b) const
  {
    return body_integrals(b).elastic_energy;
  }



  // Each energy costs a product with M or K, each momentum and force
  // component a dot product: once per state (body_integrals()).
  template <int dim>
  const typename MultibodySystem<dim>::BodyIntegrals &
  MultibodySystem<dim>::body_integrals(const unsigned int b) const
  {
    if (integrals_version != state_version ||
        integrals.size() != body_list.size())
      {
        integrals.resize(body_list.size());
        for (unsigned int i = 0; i < body_list.size(); ++i)
          {
            const Vector<double> &v = current.velocity.block(i);
            BodyIntegrals        &x = integrals[i];
            x.kinetic_energy =
              0.5 * body_list[i]->mass_matrix().matrix_norm_square(v);
            x.elastic_energy =
              0.5 * body_list[i]->stiffness_matrix().matrix_norm_square(
                      current.displacement.block(i));
            for (unsigned int d = 0; d < dim; ++d)
              {
                x.momentum[d] = mass_unit_fields[d].block(i) * v;
                x.contact_force[d] =
                  unit_fields[d].block(i) * contact_force_field.block(i);
              }
          }
        integrals_version = state_version;
      }
    return integrals[b];
  }

  template <int dim>
  double
  MultibodySystem<dim>::elastic_energy() const
  {
    double e = 0.;
    for (unsigned int b = 0; b < body_list.size(); ++b)
      e += elastic_energy(b);
    return e;
  }

  template <int dim>
  Tensor<1, dim>
  MultibodySystem<dim>::momentum(const unsigned int b) const
  {
    return body_integrals(b).momentum;
  }

  template <int dim>
  Tensor<1, dim>
  MultibodySystem<dim>::contact_force(const unsigned int b) const
  {
    return body_integrals(b).contact_force;
  }

  template <int dim>
  const BlockVector<double> &
  MultibodySystem<dim>::nodal_contact_force() const
  {
    return contact_force_field;
  }

  template <int dim>
  const std::vector<double> &
  MultibodySystem<dim>::impulses() const
  {
    return local_impulses;
  }

  template <int dim>
  const std::vector<bool> &
  MultibodySystem<dim>::active_set() const
  {
    return active;
  }

  template <int dim>
  const lcp::DenseMatrix &
  MultibodySystem<dim>::delassus_operator() const
  {
    std::vector<unsigned int> all(contact_set.n_candidates());
    for (unsigned int c = 0; c < all.size(); ++c)
      all[c] = c;
    ensure_delassus_columns(all);
    return delassus;
  }

  template <int dim>
  void
  MultibodySystem<dim>::set_column_storage_budget(const std::size_t bytes)
  {
    column_storage_budget = bytes;
  }

  template <int dim>
  void
  MultibodySystem<dim>::enable_cost_breakdown(const bool enable)
  {
    measure_costs = enable;
  }

  template <int dim>
  const CostBreakdown &
  MultibodySystem<dim>::cost_breakdown() const
  {
    return costs;
  }

  template <int dim>
  unsigned long long
  MultibodySystem<dim>::total_pivots() const
  {
    return pivot_count;
  }

  template <int dim>
  unsigned int
  MultibodySystem<dim>::largest_lcp() const
  {
    return lcp_max_size;
  }

  template <int dim>
  const typename MultibodySystem<dim>::ExactConeStatistics &
  MultibodySystem<dim>::exact_cone_statistics() const
  {
    return cone_statistics;
  }

  template <int dim>
  const typename MultibodySystem<dim>::LcpStatistics &
  MultibodySystem<dim>::lcp_statistics() const
  {
    return lcp_path_statistics;
  }

  template <int dim>
  const ContactSolverParameters &
  MultibodySystem<dim>::contact_solver_parameters() const
  {
    return solver_parameters;
  }

  template class MultibodySystem<1>;
  template class MultibodySystem<2>;
  template class MultibodySystem<3>;
} // namespace impactfe
