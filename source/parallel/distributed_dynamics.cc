#include <deal.II/base/utilities.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <impactfe/lcp/exact_cone.h>
#include <impactfe/lcp/problem_io.h>
#include <impactfe/parallel/distributed_dynamics.h>
#include <impactfe/utilities/mpi_errors.h>
#include <impactfe/utilities/program.h>

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

namespace impactfe
{
  namespace distributed
  {
    void
    DistributedRunStatistics::record(const lcp::ContactVerification &check)
    {
      largest_signorini =
        std::max(largest_signorini, check.max_signorini_violation);
      largest_cone    = std::max(largest_cone, check.max_cone_violation);
      largest_sliding = std::max(largest_sliding, check.max_sliding_violation);
    }



    void
    ParallelSolverParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Parallel solver");
      prm.declare_entry("Solver",
                        "substructured",
                        Patterns::Selection("direct|amg cg|substructured"),
                        "The solves with the step matrix M~: direct (MUMPS "
                        "through Trilinos' Amesos: M~ factorised once, then "
                        "a distributed solve pair per product W x of the "
                        "contact problem), amg cg (CG with ML's algebraic "
                        "multigrid, set up once, one CG solve per product), "
                        "or substructured (each rank's part of M~ "
                        "factorised by CHOLMOD with its shared and contact "
                        "DoFs last, and a dense interface problem on every "
                        "rank: the products W x are then dense, with no "
                        "solve; for a few ranks, doc/parallel.md).");
      prm.declare_entry(
        "Contact operator",
        "automatic",
        Patterns::Selection("automatic|dense|sparse"),
        "Solver = substructured: how the contact problem's products W x = "
        "H^T M~^{-1} H x are made. dense: the Schur complement S_C of M~ on "
        "the contact DoFs (every node of the boundaries that contacts "
        "name) is formed and inverted once on every rank (set-up time "
        "grows like the cube of their number, memory like its square; "
        "each product is a dense one, and H^T S_C H preconditions the "
        "contact problem). sparse: nothing dense on them; each product is "
        "a forward and a backward substitution with the ranks' factors "
        "(about one solve pair), preconditioned by H^T M~ H. automatic: "
        "dense if the dense problem (contact DoFs and those the ranks "
        "share) has at most 6000 DoFs, its square is at most 1000 times "
        "the DoFs of the mesh, and its set-up needs at most 4 GiB per "
        "rank; sparse otherwise (doc/parallel.md).");
      prm.declare_entry(
        "Contact preconditioner",
        "automatic",
        Patterns::Selection("automatic|contact block|Schur complement"),
        "Contact operator = sparse: the contact problem's preconditioner "
        "H^T X H. contact block: X = M~'s block on the contact DoFs (no "
        "solve). Schur complement: X = S_C, the dense operator's "
        "preconditioner, applied by a solve with M~ pinned on the contact "
        "DoFs (a second factorisation; each application costs about a "
        "solve pair, and the GMRES iterations are fewer: 10 times fewer "
        "on a 3D slab sliding with the exact cone, 1.5 times in 2D). "
        "automatic: Schur complement in 3D with friction, contact block "
        "otherwise.");
      prm.declare_entry(
        "Tolerance",
        "1e-12",
        Patterns::Double(0.),
        "amg cg: relative residual of each CG solve with the step "
        "matrix M~ (AMG-preconditioned) [-]. The contact "
        "problem's products W x are such solves, so this "
        "bounds the accuracy of the answer.");
      prm.declare_entry("Maximum iterations",
                        "1000",
                        Patterns::Integer(1),
                        "CG iterations per solve before the run stops with "
                        "an error [-].");
      prm.leave_subsection();
    }



    void
    ParallelSolverParameters::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Parallel solver");
      const std::string name    = prm.get("Solver");
      solver                    = name == "direct" ? Solver::direct :
                                  name == "amg cg" ? Solver::amg_cg :
                                                     Solver::substructured;
      const std::string contact = prm.get("Contact operator");
      contact_operator =
        contact == "dense"  ? SubstructuredSolver::ContactOperator::dense :
        contact == "sparse" ? SubstructuredSolver::ContactOperator::sparse :
                              SubstructuredSolver::ContactOperator::automatic;
      const std::string preconditioner = prm.get("Contact preconditioner");
      contact_preconditioner           = preconditioner == "contact block" ?
                                           ContactPreconditioner::contact_block :
                                         preconditioner == "Schur complement" ?
                                           ContactPreconditioner::schur_complement :
                                           ContactPreconditioner::automatic;
      tolerance                        = prm.get_double("Tolerance");
      max_iterations                   = prm.get_integer("Maximum iterations");
      prm.leave_subsection();
      AssertThrow(tolerance > 0. && tolerance < 1.,
                  ExcMessage("Parallel solver: 'Tolerance' must be in (0, 1), "
                             "got " +
                             format_number(tolerance) + "."));
    }



    template <int dim>
    DistributedImpactSolver<dim>::DistributedImpactSolver(
      const DistributedElasticBody<dim> &body,
      const DistributedContact<dim>     &contact,
      const TimeSteppingParameters      &time,
      const ContactSolverParameters     &solver,
      const ParallelSolverParameters    &linear_solver)
      : body(body)
      , contact(contact)
      , solver_parameters(solver)
      , linear_parameters(linear_solver)
      , newmark(time.scheme == Scheme::newmark)
    {
      const auto set_rule = [this](StepOperators &level) {
        if (newmark)
          level.newmark_rule = level.scheme->newmark_step_rule();
        else
          level.rule = level.scheme->theta_step_rule();
      };
      fine.scheme = create_time_integrator(time);
      set_rule(fine);
      // the free-flight level: the same scheme with k h
      if (time.free_flight_step_factor > 1)
        {
          coarse = std::make_unique<StepOperators>();
          coarse->scheme =
            create_time_integrator(time.free_flight_parameters());
          set_rule(*coarse);
          free_flight_factor = time.free_flight_step_factor;
        }
    }



    // @sect3{Set-up}
    template <int dim>
    void
    DistributedImpactSolver<dim>::setup()
    {
      // mass redistribution (the step matrices are those of the mass)
      const auto &massless = body.massless_dofs();
      fine.scheme->set_massless_contact_nodes(!massless.empty());
      if (coarse)
        coarse->scheme->set_massless_contact_nodes(!massless.empty());
      owned_massless_offsets.clear();
      for (const types::global_dof_index i : massless)
        if (body.locally_owned_dofs().is_element(i))
          owned_massless_offsets.push_back(
            body.locally_owned_dofs().index_within_set(i));
      all_candidates.resize(contact.n_candidates());
      std::iota(all_candidates.begin(), all_candidates.end(), 0u);

      if (linear_parameters.solver ==
          ParallelSolverParameters::Solver::substructured)
        setup_contact_slots();
      setup_operators(fine);
      if (coarse)
        setup_operators(*coarse);
      // the contact block preconditions the sparse operator unless the
      // pinned solves do
      if (fine.substructured_solver && !dense_contact_operator() &&
          !pinned_solver)
        setup_contact_block();

      const IndexSet &owned = body.locally_owned_dofs();
      const MPI_Comm  comm  = body.communicator();
      for (DistributedVector *x : {&u,
                                   &v,
                                   &u_old,
                                   &v_old,
                                   &rhs,
                                   &impulse_force,
                                   &work,
                                   &last_impulse_field})
        x->reinit(owned, comm);
      last_body_impulses.assign(contact.n_bodies(), {{0., 0., 0.}});
      // the substructured solver's step needs neither (start_solve() and
      // finish_solve())
      if (!fine.substructured_solver)
        for (DistributedVector *x : {&v_free, &correction})
          x->reinit(owned, comm);
      if (newmark)
        for (DistributedVector *x :
             {&acceleration, &predicted_displacement, &predicted_velocity})
          x->reinit(owned, comm);

      // F~ relative to the translation: the components of the owned DoFs
      // and, per component, the smallest DoF index any rank owns
      owned_components.assign(owned.n_elements(), 0);
      reference_dofs.fill(numbers::invalid_dof_index);
      free_translation = {{0., 0., 0.}};
      if (!body.has_damping())
        {
          for (DistributedVector *x :
               {&shifted_velocity, &shifted_displacement})
            x->reinit(owned, comm);
          std::array<types::global_dof_index, 3> first;
          first.fill(numbers::invalid_dof_index);
          for (unsigned int d = 0; d < dim; ++d)
            {
              Tensor<1, dim> e;
              e[d] = 1.;
              work = 0.;
              body.fill_uniform(work, e);
              const double *unit = work.begin();
              for (unsigned int k = 0; k < owned.n_elements(); ++k)
                if (unit[k] != 0.)
                  {
                    owned_components[k] = d;
                    first[d] = std::min(first[d], owned.nth_index_in_set(k));
                  }
              reference_dofs[d] = Utilities::MPI::min(first[d], comm);
            }
          work = 0.;
        }
      const unsigned int n  = contact.n_candidates();
      const unsigned int nd = contact.n_directions();
      active.assign(n, false);
      in_lcp.assign(n, false);
      last_impulses.assign(n * nd, 0.);
      last_states.assign(n, ContactState::open);
      local_impulses.assign(n * nd, 0.);
    }



    // M~ = M + c_C C + c_K K and the matrix of F~'s velocity term, M + a_C
    // C + a_K K, on the body's sparsity pattern, for the level's scheme;
    // MUMPS's factors of M~, ML's AMG on M~ with the rigid translations as
    // its near null space, or the substructured solver.
    template <int dim>
    void
    DistributedImpactSolver<dim>::setup_operators(StepOperators &level)
    {
      const TimeIntegrator     &scheme = *level.scheme;
      const FreeRhsCoefficients f      = scheme.free_rhs_coefficients();
      level.step_matrix.copy_from(body.mass_matrix());
      level.step_matrix.add(scheme.stiffness_coefficient(),
                            body.stiffness_matrix());
      level.velocity_matrix.copy_from(body.mass_matrix());
      if (f.velocity_stiffness != 0.)
        level.velocity_matrix.add(f.velocity_stiffness,
                                  body.stiffness_matrix());
      if (body.has_damping())
        {
          level.step_matrix.add(scheme.damping_coefficient(),
                                body.damping_matrix());
          level.velocity_matrix.add(f.velocity_damping, body.damping_matrix());
        }
      level.displacement_factor = f.displacement_stiffness;

      if (linear_parameters.solver == ParallelSolverParameters::Solver::direct)
        {
          level.direct_solver =
            std::make_unique<TrilinosWrappers::SolverDirect>(
              level.direct_control,
              TrilinosWrappers::SolverDirect::AdditionalData(false,
                                                             "Amesos_Mumps"));
          level.direct_solver->initialize(level.step_matrix);
        }
      else if (linear_parameters.solver ==
               ParallelSolverParameters::Solver::substructured)
        setup_substructured_solver(level);
      else
        setup_amg(level);
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::setup_amg(StepOperators &level)
    {
      TrilinosWrappers::PreconditionAMG::AdditionalData data;
      std::vector<std::vector<bool>>                    modes;
      DoFTools::extract_constant_modes(body.dof_handler(),
                                       ComponentMask(),
                                       modes);
      data.constant_modes        = modes;
      data.elliptic              = true;
      data.higher_order_elements = false;
      data.smoother_sweeps       = 2;
      data.aggregation_threshold = 0.02;
      level.amg.initialize(level.step_matrix, data);
    }



    // C: every DoF of every candidate, so that H x of any set of candidates
    // lies in C; each node once (a node of side B may serve several
    // candidates), in the order the dense complement keeps.
    // With a contact search during the run, C holds the DoFs of every node
    // it may pair (DistributedContact::potential_contact_nodes()) first.
    template <int dim>
    void
    DistributedImpactSolver<dim>::setup_contact_slots()
    {
      slot_of_node.clear();
      contact_dofs.clear();
      const auto add_node = [&](const auto &node) {
        const auto slot =
          slot_of_node.emplace(node.dofs[0], contact_dofs.size());
        if (slot.second)
          contact_dofs.insert(contact_dofs.end(),
                              node.dofs.begin(),
                              node.dofs.end());
      };
      for (const auto &[vertex, node] : contact.potential_contact_nodes())
        add_node(node);
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        for (unsigned int i = 0; i < contact.candidate(c).n_nodes; ++i)
          add_node(contact.candidate(c).nodes[i]);
      n_contact_dofs = contact_dofs.size();
      dense_in.assign(n_contact_dofs, 0.);
      dense_out.assign(n_contact_dofs, 0.);
      find_contact_slots();
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::find_contact_slots()
    {
      contact_slots.resize(contact.n_candidates());
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        for (unsigned int i = 0; i < contact.candidate(c).n_nodes; ++i)
          {
            const auto slot =
              slot_of_node.find(contact.candidate(c).nodes[i].dofs[0]);
            AssertThrow(slot != slot_of_node.end(),
                        ExcMessage("A contact candidate found during the run "
                                   "has a node outside the contact boundaries "
                                   "of the set-up."));
            for (unsigned int d = 0; d < dim; ++d)
              contact_slots[c][i][d] = slot->second + d;
          }
      const unsigned int nd = contact.n_directions();
      h_row_start.assign(1, 0);
      h_slot.clear();
      h_value.clear();
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        {
          const auto &candidate = contact.candidate(c);
          for (unsigned int k = 0; k < nd; ++k)
            {
              for (unsigned int i = 0; i < candidate.n_nodes; ++i)
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    h_slot.push_back(contact_slots[c][i][d]);
                    h_value.push_back(candidate.nodes[i].weight *
                                      candidate.frame[k][d]);
                  }
              h_row_start.push_back(h_slot.size());
            }
        }
    }



    // @sect3{New candidates}
    // After a contact search the candidates are new; what a candidate
    // carries from step to step (active in the last step, its contact
    // state, its last impulse) goes with it to its successor.
    template <int dim>
    void
    DistributedImpactSolver<dim>::candidates_changed(
      const std::vector<unsigned int> &previous)
    {
      AssertThrow(previous.size() == contact.n_candidates(),
                  ExcMessage("candidates_changed(): one entry per candidate "
                             "is needed."));
      const unsigned int n  = contact.n_candidates();
      const unsigned int nd = contact.n_directions();
      const unsigned int old_nd =
        active.empty() ? nd : last_impulses.size() / active.size();
      const std::vector<bool>         old_active   = active;
      const std::vector<ContactState> old_states   = last_states;
      const std::vector<double>       old_impulses = last_impulses;
      active.assign(n, false);
      last_states.assign(n, ContactState::open);
      last_impulses.assign(n * nd, 0.);
      for (unsigned int c = 0; c < n; ++c)
        if (const unsigned int p = previous[c];
            p != numbers::invalid_unsigned_int)
          {
            AssertIndexRange(p, old_active.size());
            active[c]      = old_active[p];
            last_states[c] = old_states[p];
            for (unsigned int k = 0; k < std::min(nd, old_nd); ++k)
              last_impulses[c * nd + k] = old_impulses[p * old_nd + k];
          }
      in_lcp.assign(n, false);
      local_impulses.assign(n * nd, 0.);
      all_candidates.resize(n);
      std::iota(all_candidates.begin(), all_candidates.end(), 0u);
      if (fine.substructured_solver)
        find_contact_slots();
    }



    // Each rank's part of the level's M~ from its own cells.
    template <int dim>
    void
    DistributedImpactSolver<dim>::setup_substructured_solver(
      StepOperators &level)
    {
      SparsityPattern                      pattern;
      SparseMatrix<double>                 subdomain_matrix;
      std::vector<types::global_dof_index> local_to_global;
      std::vector<bool>                    on_interface;
      body.assemble_subdomain_matrix(1.,
                                     level.scheme->stiffness_coefficient(),
                                     body.has_damping() ?
                                       level.scheme->damping_coefficient() :
                                       0.,
                                     pattern,
                                     subdomain_matrix,
                                     local_to_global,
                                     on_interface);
      using ContactOperator      = SubstructuredSolver::ContactOperator;
      level.substructured_solver = std::make_unique<SubstructuredSolver>();
      // the free-flight level makes no contact product; its factors keep
      // the contact DoFs where the fine level's do (set up first)
      const ContactOperator contact_operator =
        &level == &fine          ? linear_parameters.contact_operator :
        dense_contact_operator() ? ContactOperator::factors_only :
                                   ContactOperator::sparse;
      level.substructured_solver->initialize(body.communicator(),
                                             subdomain_matrix,
                                             local_to_global,
                                             on_interface,
                                             contact_dofs,
                                             body.locally_owned_dofs(),
                                             "the step matrix",
                                             contact_operator);
      if (&level == &fine && !dense_contact_operator())
        {
          using Preconditioner =
            ParallelSolverParameters::ContactPreconditioner;
          const bool schur = linear_parameters.contact_preconditioner ==
                               Preconditioner::schur_complement ||
                             (linear_parameters.contact_preconditioner ==
                                Preconditioner::automatic &&
                              dim == 3 && contact.n_directions() == 3);
          stats.contact_preconditioner =
            schur ? "Schur complement" : "contact block";
          if (schur)
            {
              // M~ with the contact DoFs' rows and columns those of the
              // identity, up to a positive diagonal (1 / n_ranks on each
              // rank that has them): they are decoupled, and their right-
              // hand side is zero, so their solution is zero whatever it is
              std::vector<bool> pinned(subdomain_matrix.m(), false);
              const std::set<types::global_dof_index> contact_set(
                contact_dofs.begin(), contact_dofs.end());
              for (unsigned int l = 0; l < subdomain_matrix.m(); ++l)
                pinned[l] = contact_set.count(local_to_global[l]) > 0;
              const double share =
                1. / Utilities::MPI::n_mpi_processes(body.communicator());
              for (unsigned int l = 0; l < subdomain_matrix.m(); ++l)
                for (auto entry = subdomain_matrix.begin(l);
                     entry != subdomain_matrix.end(l);
                     ++entry)
                  if (pinned[l] || pinned[entry->column()])
                    entry->value() =
                      (pinned[l] && entry->column() == l) ? share : 0.;
              pinned_solver = std::make_unique<SubstructuredSolver>();
              pinned_solver->initialize(body.communicator(),
                                        subdomain_matrix,
                                        local_to_global,
                                        on_interface,
                                        {},
                                        body.locally_owned_dofs(),
                                        "the step matrix pinned on the "
                                        "contact DoFs",
                                        ContactOperator::sparse);
              owned_contact_dofs.clear();
              const IndexSet &owned = body.locally_owned_dofs();
              for (unsigned int k = 0; k < contact_dofs.size(); ++k)
                if (owned.is_element(contact_dofs[k]))
                  owned_contact_dofs.emplace_back(
                    k, owned.index_within_set(contact_dofs[k]));
              schur_in.reinit(owned, body.communicator());
              schur_out.reinit(owned, body.communicator());
            }
        }
      if (&level == &fine)
        {
          stats.contact_operator =
            dense_contact_operator() ? "dense" : "sparse";
          if (dense_contact_operator())
            stats.contact_schur_groups =
              level.substructured_solver->contact_schur_complement().n_groups();
        }
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::setup_contact_block()
    {
      std::map<types::global_dof_index, unsigned int> index_of;
      for (unsigned int k = 0; k < contact_dofs.size(); ++k)
        index_of.emplace(contact_dofs[k], k);
      // (row, column, value) of the rows this rank owns
      std::vector<std::tuple<unsigned int, unsigned int, double>> mine;
      const IndexSet &owned = body.locally_owned_dofs();
      // Epetra's view of the owned rows (deal.II's row iterator copies
      // the row at every entry: 10 s instead of 0.1 s at 4e4 contact DoFs)
      const Epetra_CrsMatrix &matrix = fine.step_matrix.trilinos_matrix();
      for (unsigned int k = 0; k < contact_dofs.size(); ++k)
        if (owned.is_element(contact_dofs[k]))
          {
            const int row = matrix.RowMap().LID(
              static_cast<TrilinosWrappers::types::int_type>(contact_dofs[k]));
            int     n_entries = 0;
            double *values    = nullptr;
            int    *columns   = nullptr;
            AssertThrow(row >= 0 && matrix.ExtractMyRowView(
                                      row, n_entries, values, columns) == 0,
                        ExcInternalError());
            for (int p = 0; p < n_entries; ++p)
              {
                const auto column =
                  index_of.find(static_cast<types::global_dof_index>(
                    matrix.ColMap().GID(columns[p])));
                if (column != index_of.end() && values[p] != 0.)
                  mine.emplace_back(k, column->second, values[p]);
              }
          }
      std::vector<std::tuple<unsigned int, unsigned int, double>> all;
      for (const auto &part :
           Utilities::MPI::all_gather(body.communicator(), mine))
        all.insert(all.end(), part.begin(), part.end());
      std::sort(all.begin(), all.end());
      contact_block_start.assign(contact_dofs.size() + 1, 0);
      contact_block_column.clear();
      contact_block_value.clear();
      for (const auto &[row, column, value] : all)
        {
          ++contact_block_start[row + 1];
          contact_block_column.push_back(column);
          contact_block_value.push_back(value);
        }
      for (unsigned int k = 0; k < contact_dofs.size(); ++k)
        contact_block_start[k + 1] += contact_block_start[k];
    }



    // S_C y = A_CC y - A_CI A_II^{-1} A_IC y for y on the contact DoFs C,
    // I the others: with b = A y, b_C = 0, and z = A_II^{-1} b_I (the
    // pinned solve, z_C = 0), S_C y = (A (y - z))_C, as (A (y - z))_I = 0.
    template <int dim>
    void
    DistributedImpactSolver<dim>::schur_complement_product(
      const std::vector<double> &x,
      std::vector<double>       &y)
    {
      schur_in = 0.;
      for (const auto &[k, offset] : owned_contact_dofs)
        schur_in.begin()[offset] = x[k];
      fine.step_matrix.vmult(schur_out, schur_in);
      for (const auto &[k, offset] : owned_contact_dofs)
        schur_out.begin()[offset] = 0.;
      pinned_solver->solve(schur_out, work);
      schur_in -= work;
      fine.step_matrix.vmult(schur_out, schur_in);
      y.assign(n_contact_dofs, 0.);
      for (const auto &[k, offset] : owned_contact_dofs)
        y[k] = schur_out.begin()[offset];
      Utilities::MPI::sum(y, body.communicator(), y);
    }



    template <int dim>
    bool
    DistributedImpactSolver<dim>::dense_contact_operator() const
    {
      return fine.substructured_solver &&
             fine.substructured_solver->chosen_contact_operator() ==
               SubstructuredSolver::ContactOperator::dense;
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::set_initial_velocity(
      const Tensor<1, dim>    &velocity,
      const types::material_id part)
    {
      body.fill_uniform(v, velocity, part);
    }



    // Newmark starts from a^0 with M a^0 = F - K u^0 - C v^0 (no contact
    // force at t = 0), as the serial MultibodySystem; M is well
    // conditioned, so CG with Jacobi reaches round-off in a few dozen
    // iterations.
    template <int dim>
    void
    DistributedImpactSolver<dim>::compute_initial_acceleration()
    {
      rhs = body.external_force();
      body.stiffness_matrix().vmult(work, u);
      rhs -= work;
      if (body.has_damping())
        {
          body.damping_matrix().vmult(work, v);
          rhs -= work;
        }
      acceleration       = 0.;
      const double normb = rhs.l2_norm();
      if (normb > 0.)
        {
          SolverControl control(1000, 1e-14 * normb, false, false);
          SolverCG<DistributedVector>          cg(control);
          TrilinosWrappers::PreconditionJacobi jacobi;
          jacobi.initialize(body.mass_matrix());
          try
            {
              cg.solve(body.mass_matrix(), acceleration, rhs, jacobi);
            }
          catch (const SolverControl::NoConvergence &e)
            {
              AssertThrow(false,
                          ExcMessage("Newmark's initial acceleration: the CG "
                                     "solve with the mass matrix did not "
                                     "reach the relative residual 1e-14 in " +
                                     std::to_string(e.last_step) +
                                     " iterations."));
            }
        }
      acceleration_ready = true;
    }



    // One solve with M~: a solve pair with the factors, or CG; a CG solve
    // that does not converge stops the run with the time named.
    template <int dim>
    void
    DistributedImpactSolver<dim>::solve_step_matrix(const StepOperators &level,
                                                    const DistributedVector &b,
                                                    DistributedVector       &x)
    {
      ++stats.solves;
      const auto start  = std::chrono::steady_clock::now();
      const auto charge = [&]() {
        stats.solve_seconds += std::chrono::duration<double>(
                                 std::chrono::steady_clock::now() - start)
                                 .count();
      };
      if (level.direct_solver)
        {
          level.direct_solver->solve(x, b);
          charge();
          return;
        }
      if (level.substructured_solver)
        {
          level.substructured_solver->solve(b, x);
          charge();
          return;
        }
      x                  = 0.;
      const double normb = b.l2_norm();
      // an infinite norm makes any residual small enough: CG would stop
      // at once with x = 0 (the same norm on every rank)
      AssertThrow(std::isfinite(normb),
                  ExcMessage("The right-hand side of the step's solve is not "
                             "finite at t = " +
                             format_number(current_time) +
                             " s: the loads or the state overflowed (check "
                             "'Gravity', the velocities and 'Time step')."));
      if (normb == 0.)
        return;
      SolverControl               control(linear_parameters.max_iterations,
                            linear_parameters.tolerance * normb,
                            false,
                            false);
      SolverCG<DistributedVector> cg(control);
      try
        {
          cg.solve(level.step_matrix, x, b, level.amg);
        }
      catch (const SolverControl::NoConvergence &e)
        {
          AssertThrow(false,
                      ExcMessage(
                        "The CG solve with the step matrix did not reach "
                        "the relative residual " +
                        format_number(linear_parameters.tolerance) + " in " +
                        std::to_string(e.last_step) +
                        " iterations at t = " + format_number(current_time) +
                        " s (Parallel solver/Maximum iterations)."));
        }
      stats.cg_iterations += control.last_step();
      charge();
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::delassus_product(const std::vector<double> &x,
                                                   std::vector<double>       &y)
    {
      impulse_force = 0.;
      contact.add_impulses(lcp_candidates, x, impulse_force);
      solve_step_matrix(fine, impulse_force, correction);
      contact.local_values(correction, lcp_candidates, y);
      ++stats.products;
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::contact_dof_product(
      const std::vector<double> &x,
      std::vector<double>       &y,
      const bool                 use_schur)
    {
      const unsigned int nd = contact.n_directions();
      impulses_on_contact_dofs(x, dense_in);
      const unsigned int n_ranks =
        Utilities::MPI::n_mpi_processes(body.communicator());
      if (pinned_solver && use_schur)
        schur_complement_product(dense_in, dense_out);
      else if (!dense_contact_operator() && use_schur)
        {
          // H^T M~ H: M~'s block on the contact DoFs
          dense_out.assign(n_contact_dofs, 0.);
          for (unsigned int k = 0; k < n_contact_dofs; ++k)
            for (unsigned int p = contact_block_start[k];
                 p < contact_block_start[k + 1];
                 ++p)
              dense_out[k] +=
                contact_block_value[p] * dense_in[contact_block_column[p]];
        }
      else if (!dense_contact_operator())
        fine.substructured_solver->contact_solve(dense_in, dense_out);
      else if (n_ranks > 1)
        {
          // S and S^{-1} are on every rank: each computes the part of the
          // product that an even share of their stored triangle gives, and
          // the parts are summed
          std::fill(dense_out.begin(), dense_out.end(), 0.);
          fine.substructured_solver->contact_schur_complement()
            .add_part_of_product(dense_in.data(),
                                 dense_out.data(),
                                 Utilities::MPI::this_mpi_process(
                                   body.communicator()),
                                 n_ranks,
                                 !use_schur);
          const int mpi_error = MPI_Allreduce(MPI_IN_PLACE,
                                              dense_out.data(),
                                              dense_out.size(),
                                              MPI_DOUBLE,
                                              MPI_SUM,
                                              body.communicator());
          AssertThrowMPI(mpi_error);
        }
      else if (use_schur) // the preconditioner: single precision suffices
        fine.substructured_solver->contact_schur_complement()
          .vmult_single_precision(dense_in.data(), dense_out.data());
      else
        fine.substructured_solver->contact_solve(dense_in, dense_out);
      y.assign(lcp_candidates.size() * nd, 0.);
      for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
        for (unsigned int k = 0; k < nd; ++k)
          y[a * nd + k] = frame_component(lcp_candidates[a], k, dense_out);
      if (!use_schur)
        ++stats.products;
    }



    // H x on the contact DoFs for the impulses x of lcp_candidates, and
    // the frames' components of values on the contact DoFs, per
    // candidate: the substructured path's H and H^T (replicated, no
    // communication).
    template <int dim>
    void
    DistributedImpactSolver<dim>::impulses_on_contact_dofs(
      const std::vector<double> &x,
      std::vector<double>       &on_dofs) const
    {
      const unsigned int nd = contact.n_directions();
      on_dofs.assign(n_contact_dofs, 0.);
      for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
        for (unsigned int k = 0; k < nd; ++k)
          {
            const unsigned int row = lcp_candidates[a] * nd + k;
            const double       xk  = x[a * nd + k];
            for (unsigned int p = h_row_start[row]; p < h_row_start[row + 1];
                 ++p)
              on_dofs[h_slot[p]] += h_value[p] * xk;
          }
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::local_components(
      const std::vector<double> &on_dofs,
      std::vector<double>       &local) const
    {
      const unsigned int nd = contact.n_directions();
      local.resize(contact_slots.size() * nd);
      for (unsigned int c = 0; c < contact_slots.size(); ++c)
        for (unsigned int k = 0; k < nd; ++k)
          local[c * nd + k] = frame_component(c, k, on_dofs);
    }



    template <int dim>
    double
    DistributedImpactSolver<dim>::frame_component(
      const unsigned int         c,
      const unsigned int         direction,
      const std::vector<double> &on_dofs) const
    {
      const unsigned int row   = c * contact.n_directions() + direction;
      double             value = 0.;
      for (unsigned int p = h_row_start[row]; p < h_row_start[row + 1]; ++p)
        value += h_value[p] * on_dofs[h_slot[p]];
      return value;
    }



    // @sect3{The contact problem}
    template <int dim>
    void
    DistributedImpactSolver<dim>::solve_contact_problem()
    {
      const unsigned int nd = contact.n_directions();
      const unsigned int n  = lcp_candidates.size();
      lcp_q.resize(n * nd);
      lcp_b.resize(n);
      lcp_mu.resize(n);
      lcp_guess.resize(n * nd);
      lcp_state_guess.resize(n);
      for (unsigned int a = 0; a < n; ++a)
        {
          const unsigned int c = lcp_candidates[a];
          lcp_b[a]             = gap_terms[c];
          lcp_mu[a]            = contact.candidate(c).friction_coefficient;
          lcp_state_guess[a]   = last_states[c];
          for (unsigned int k = 0; k < nd; ++k)
            {
              lcp_q[a * nd + k]     = local_free_velocity[c * nd + k];
              lcp_guess[a * nd + k] = last_impulses[c * nd + k];
            }
        }
      ++stats.contact_problems;
      stats.largest_lcp = std::max(stats.largest_lcp, n);
      if (solver_parameters.method == ContactSolverParameters::Method::lemke)
        {
          solve_by_lemke();
          return;
        }

      // 1/W_jj ~ f_k^T M~_node f_k, the nodes' blocks of M~ in the frame
      // (M~ is nearly block diagonal where the mass dominates; the two
      // nodes of a pair belong to different bodies), each from the rank
      // that owns the node's rows
      const unsigned int this_rank =
        Utilities::MPI::this_mpi_process(body.communicator());
      lcp_penalty.assign(n * nd, 0.);
      for (unsigned int a = 0; a < n; ++a)
        {
          const auto &cand = contact.candidate(lcp_candidates[a]);
          for (unsigned int i = 0; i < cand.n_nodes; ++i)
            if (cand.nodes[i].owner == this_rank)
              for (unsigned int k = 0; k < nd; ++k)
                for (unsigned int d = 0; d < dim; ++d)
                  for (unsigned int e = 0; e < dim; ++e)
                    lcp_penalty[a * nd + k] +=
                      cand.frame[k][d] * cand.frame[k][e] *
                      fine.step_matrix.el(cand.nodes[i].dofs[d],
                                          cand.nodes[i].dofs[e]);
        }
      Utilities::MPI::sum(lcp_penalty, body.communicator(), lcp_penalty);

      // With the substructured solver, W x is a product on the contact
      // DoFs, and so is the preconditioner: H^T S_C H with the dense
      // contact operator, as in the serial programs, H^T M~ H with the
      // sparse one (M~'s block on the contact DoFs).
      const bool substructured = fine.substructured_solver != nullptr;
      const lcp::DelassusProduct product =
        [this, substructured](const std::vector<double> &x,
                              std::vector<double>       &y) {
          if (substructured)
            contact_dof_product(x, y, false);
          else
            delassus_product(x, y);
        };
      const lcp::DelassusProduct preconditioner =
        [this, substructured](const std::vector<double> &x,
                              std::vector<double>       &y) {
          if (substructured)
            {
              contact_dof_product(x, y, true);
              return;
            }
          impulse_force = 0.;
          contact.add_impulses(lcp_candidates, x, impulse_force);
          fine.step_matrix.vmult(work, impulse_force);
          contact.local_values(work, lcp_candidates, y);
        };
      // GMRES cannot go below the products' own error, which the CG
      // tolerance sets (times the condition of M~, modest at small steps)
      lcp::ActiveSetOptions options;
      options.max_iterations = solver_parameters.active_set_iterations;
      options.max_front_iterations =
        solver_parameters.active_set_front_iterations;
      if (!fine.direct_solver)
        options.linear_tolerance =
          std::max(options.linear_tolerance, 1e2 * linear_parameters.tolerance);
      if (nd == 3 && solver_parameters.friction_cone == lcp::ConeModel::facets)
        options.n_facets = solver_parameters.n_facets;
      const bool                  warm = solver_parameters.warm_start;
      const lcp::ActiveSetReport &result =
        active_set_solver.solve(product,
                                preconditioner,
                                lcp_penalty,
                                nd,
                                lcp_q,
                                lcp_b,
                                lcp_mu,
                                warm ? lcp_state_guess :
                                       std::vector<ContactState>(),
                                warm ? lcp_guess : std::vector<double>(),
                                options);
      stats.active_set_iterations += result.iterations;
      if (!result.converged)
        {
          ++stats.fallbacks;
          stats.last_fallback_reason = result.message;
          report.fallback            = true;
          if (!solver_parameters.lemke_fallback_allowed(n, nd))
            {
              const std::string written = write_unsolved_problem(nullptr);
              AssertThrow(false,
                          ExcMessage(
                            "The contact problem of step " +
                            std::to_string(step_number) +
                            " (t = " + format_number(report.time) + " s, " +
                            std::to_string(n) +
                            " candidates) was not solved: the active set "
                            "method did not converge (" +
                            result.message + "), and " +
                            solver_parameters.lemke_fallback_limit_text(n, nd) +
                            "." + written));
            }
          solve_by_lemke();
          return;
        }
      stats.record(result.verification);
      if (solver_parameters.dump_step == static_cast<int>(step_number))
        write_contact_problem(dump_directory + "/lcp_step_" +
                                std::to_string(step_number) + ".dat",
                              nullptr);
      lcp_P = active_set_solver.impulses();
      // with every contact open the solver makes no last product
      if (!fine.substructured_solver &&
          std::all_of(lcp_P.begin(), lcp_P.end(), [](const double p) {
            return p == 0.;
          }))
        correction = 0.;
      // else the solver's last product was with lcp_P: correction =
      // M~^{-1} H P (the substructured path makes no correction: the time
      // step finishes its solve with H P instead)
      for (unsigned int a = 0; a < n; ++a)
        last_states[lcp_candidates[a]] = active_set_solver.states()[a];
    }



    // W of the candidates column by column (n n_d solves, or products on
    // the contact DoFs with the substructured solver), then Lemke's
    // method on the contact LCP (the exact cone by re-aligned facets in 3D,
    // or the facet form), verified as in the serial programs.
    template <int dim>
    void
    DistributedImpactSolver<dim>::solve_by_lemke()
    {
      const unsigned int  nd = contact.n_directions();
      const unsigned int  n  = lcp_candidates.size();
      lcp::ContactProblem problem;
      build_contact_problem(problem);
      std::vector<double> column;

      lcp::ContactSolution solution;
      lcp::ContactOptions  options;
      if (nd == 3 && solver_parameters.friction_cone == lcp::ConeModel::exact)
        {
          lcp::ExactConeSolver  exact;
          lcp::ExactConeOptions cone;
          cone.tolerance = solver_parameters.exact_cone_tolerance;
          solution       = exact.solve(problem, options, cone);
          if (solution.lcp.status == lcp::Status::solved &&
              !exact.report().converged)
            {
              const std::string written = write_unsolved_problem(&problem);
              AssertThrow(false,
                          ExcMessage("The exact cone was not reached in step " +
                                     std::to_string(step_number) +
                                     " (t = " + format_number(report.time) +
                                     " s): residual " +
                                     format_number(exact.report().residual) +
                                     "." + written));
            }
        }
      else
        {
          if (nd == 3)
            {
              options.form     = lcp::FrictionForm::facets;
              options.n_facets = solver_parameters.n_facets;
            }
          solution = lcp::solve_contact_problem(problem, options);
        }
      if (solution.lcp.status != lcp::Status::solved)
        {
          const std::string written = write_unsolved_problem(&problem);
          AssertThrow(false,
                      ExcMessage("The contact LCP of step " +
                                 std::to_string(step_number) +
                                 " (t = " + format_number(report.time) +
                                 " s, " + std::to_string(n) +
                                 " candidates) was not solved: " +
                                 lcp::to_string(solution.lcp.status) + ". " +
                                 solution.lcp.message + written));
        }
      if (solver_parameters.dump_step == static_cast<int>(step_number))
        write_contact_problem(dump_directory + "/lcp_step_" +
                                std::to_string(step_number) + ".dat",
                              &problem);
      stats.record(lcp::verify_contact_solution(problem, solution.P));
      lcp_P = solution.P;
      const std::vector<ContactState> states =
        solution.states.size() == n ? solution.states :
                                      lcp::contact_states(problem, solution.P);
      for (unsigned int a = 0; a < n; ++a)
        last_states[lcp_candidates[a]] = states[a];
      // correction = M~^{-1} H P (the substructured path's time step
      // finishes its solve with H P instead)
      if (!fine.substructured_solver)
        delassus_product(lcp_P, column);
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::build_contact_problem(
      lcp::ContactProblem &problem)
    {
      const unsigned int nd = contact.n_directions();
      const unsigned int n  = lcp_candidates.size();
      problem.n_directions  = nd;
      problem.n_contacts    = n;
      problem.W.reinit(n * nd, n * nd);
      problem.free_velocity = lcp_q;
      problem.gap_term      = lcp_b;
      problem.mu            = lcp_mu;
      std::vector<double> unit(n * nd, 0.), column;
      for (unsigned int j = 0; j < n * nd; ++j)
        {
          unit[j] = 1.;
          // with the substructured solver a column is a product on the
          // contact DoFs
          if (fine.substructured_solver)
            contact_dof_product(unit, column, false);
          else
            delassus_product(unit, column);
          unit[j] = 0.;
          for (unsigned int i = 0; i < n * nd; ++i)
            problem.W(i, j) = column[i];
        }
      // W is symmetric; the CG solves leave it so only to their tolerance
      for (unsigned int i = 0; i < n * nd; ++i)
        for (unsigned int j = 0; j < i; ++j)
          problem.W(i, j) = problem.W(j, i) =
            0.5 * (problem.W(i, j) + problem.W(j, i));
    }



    // The problem is replicated: rank 0 writes it in the frictional-contact
    // text format of Siconos numerics, as the serial programs do.
    template <int dim>
    void
    DistributedImpactSolver<dim>::write_contact_problem(
      const std::string         &file,
      const lcp::ContactProblem *built)
    {
      lcp::ContactProblem formed;
      if (built == nullptr)
        {
          // W's columns are products, which leave their last solve in
          // `correction` and `impulse_force`; the step goes on with the
          // answer's (M~^{-1} H P); the run's counts of products and solves
          // are those of the run without the file
          const DistributedVector        saved_correction    = correction;
          const DistributedVector        saved_impulse_force = impulse_force;
          const DistributedRunStatistics saved_stats         = stats;
          build_contact_problem(formed);
          correction    = saved_correction;
          impulse_force = saved_impulse_force;
          stats         = saved_stats;
        }
      const lcp::ContactProblem &problem = built ? *built : formed;
      on_rank_zero(body.communicator(),
                   [&]() { lcp::write_friction_contact_file(file, problem); });
    }



    template <int dim>
    std::string
    DistributedImpactSolver<dim>::write_unsolved_problem(
      const lcp::ContactProblem *built)
    {
      return solver_parameters.write_unsolved_problem(
        dump_directory,
        step_number,
        lcp_candidates.size() * contact.n_directions(),
        built != nullptr,
        [&](const std::string &name) { write_contact_problem(name, built); });
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::set_dump_directory(
      const std::string &directory)
    {
      dump_directory = directory;
    }



    // t and s: x and y at the reference DoFs, summed over the ranks (the
    // owner's value); any translation would do (FreeRhsOperator).
    template <int dim>
    bool
    DistributedImpactSolver<dim>::take_off_translation(
      const DistributedVector &x,
      const DistributedVector &y)
    {
      if (reference_dofs[0] == numbers::invalid_dof_index)
        return false;
      const IndexSet       &owned = body.locally_owned_dofs();
      std::array<double, 6> ts    = {{0., 0., 0., 0., 0., 0.}};
      for (unsigned int d = 0; d < dim; ++d)
        if (owned.is_element(reference_dofs[d]))
          {
            ts[d]     = x[reference_dofs[d]];
            ts[3 + d] = y[reference_dofs[d]];
          }
      Utilities::MPI::sum(ArrayView<const double>(ts.data(), 6),
                          body.communicator(),
                          ArrayView<double>(ts.data(), 6));
      const double *xk = x.begin(), *yk = y.begin();
      double *sx = shifted_velocity.begin(), *sy = shifted_displacement.begin();
      for (unsigned int k = 0; k < owned_components.size(); ++k)
        {
          const unsigned int d = owned_components[k];
          sx[k]                = xk[k] - ts[d];
          sy[k]                = yk[k] - ts[3 + d];
        }
      for (unsigned int d = 0; d < 3; ++d)
        free_translation[d] = ts[d];
      return true;
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::add_translation(DistributedVector &x) const
    {
      if (reference_dofs[0] == numbers::invalid_dof_index)
        return;
      double *xk = x.begin();
      for (unsigned int k = 0; k < owned_components.size(); ++k)
        xk[k] += free_translation[owned_components[k]];
    }



    // C's DoFs are the nodes' dim DoFs in component order
    // (setup_contact_slots()).
    template <int dim>
    void
    DistributedImpactSolver<dim>::add_translation(
      std::vector<double> &contact_values) const
    {
      if (reference_dofs[0] == numbers::invalid_dof_index)
        return;
      for (unsigned int k = 0; k < contact_values.size(); ++k)
        contact_values[k] += free_translation[k % dim];
    }



    // @sect3{The time step}
    // The free velocity: M~ v_free = F~, and its local components. The
    // substructured solver starts the solve with F~ and gives the free
    // velocity on the contact DoFs; it finishes it with F~ + H P once P is
    // known (one solve pair per step). Then b_N of the scheme:
    // g(u + a h v) / d + c V_N(v).
    template <int dim>
    void
    DistributedImpactSolver<dim>::start_step(const StepOperators &level)
    {
      // F~'s arguments: u and v, or Newmark's prediction from them
      const DistributedVector *velocity = &v, *displacement = &u;
      if (newmark)
        {
          const NewmarkStepRule &rule = level.newmark_rule;
          predicted_displacement      = u;
          predicted_displacement.add(rule.time_step,
                                     v,
                                     rule.predicted_displacement_acceleration,
                                     acceleration);
          predicted_velocity = v;
          predicted_velocity.add(rule.predicted_velocity_acceleration,
                                 acceleration);
          velocity     = &predicted_velocity;
          displacement = &predicted_displacement;
        }
      // relative to the translation (FreeRhsOperator): v = t + M~^{-1} F~'
      if (take_off_translation(*velocity, *displacement))
        {
          velocity     = &shifted_velocity;
          displacement = &shifted_displacement;
        }
      level.velocity_matrix.vmult(rhs, *velocity);
      if (level.displacement_factor != 0.)
        {
          body.stiffness_matrix().vmult(work, *displacement);
          rhs.add(level.displacement_factor, work);
        }
      rhs.add(level.scheme->free_rhs_coefficients().force,
              body.external_force());
      // massless nodes are balanced at t^{i+1}: a part of the last impulse
      // H P^i acts in this step (zero after a step without impulses)
      if (const double carry = level.scheme->massless_impulse_carry();
          carry != 0. && last_step_had_impulses)
        rhs.add(carry, last_impulse_field);
      if (level.substructured_solver)
        {
          const auto start = std::chrono::steady_clock::now();
          level.substructured_solver->start_solve(rhs, contact_dof_values);
          stats.solve_seconds += std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
          ++stats.solves;
          add_translation(contact_dof_values);
          local_components(contact_dof_values, local_free_velocity);
        }
      else
        {
          solve_step_matrix(level, rhs, v_free);
          add_translation(v_free);
          contact.local_velocities(v_free, local_free_velocity);
        }
      // massless nodes slide with their mean velocity over the step:
      // Coulomb on V_T^{i+1} + c V_T^i
      const unsigned int nd = contact.n_directions();
      if (const double c = level.scheme->slip_velocity_carry();
          c != 0. && nd > 1)
        {
          contact.local_velocities(v, start_velocity);
          for (unsigned int j = 0; j < local_free_velocity.size(); ++j)
            if (j % nd != 0)
              local_free_velocity[j] += c * start_velocity[j];
        }

      if (newmark)
        {
          // b_N = c g(u~) - V_N(v~)
          contact.gaps(predicted_displacement, gap_terms);
          contact.normal_velocities(predicted_velocity, normal_velocity);
          for (unsigned int c = 0; c < contact.n_candidates(); ++c)
            gap_terms[c] =
              level.newmark_rule.gap_factor * gap_terms[c] - normal_velocity[c];
          return;
        }
      const ThetaStepRule &rule = level.rule;
      const double         h    = level.scheme->time_step();
      if (rule.gap_prediction != 0.)
        {
          work = u;
          work.add(h * rule.gap_prediction, v);
          contact.gaps(work, gap_terms);
        }
      else
        contact.gaps(u, gap_terms);
      if (rule.gap_velocity != 0.)
        contact.normal_velocities(v, normal_velocity);
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        gap_terms[c] =
          gap_terms[c] / rule.gap_divisor +
          (rule.gap_velocity != 0. ? rule.gap_velocity * normal_velocity[c] :
                                     0.);
    }



    // u from the scheme's rule, with v^i in v_old and v^{i+1} in v.
    template <int dim>
    void
    DistributedImpactSolver<dim>::advance_displacement(
      const StepOperators &level)
    {
      const double h = level.scheme->time_step();
      u_old          = u;
      if (newmark)
        {
          // a^{i+1} = (v^{i+1} - v~) / e, u^{i+1} = u~ + f a^{i+1}
          acceleration = v;
          acceleration -= predicted_velocity;
          acceleration *= 1. / level.newmark_rule.acceleration_divisor;
          u = predicted_displacement;
          u.add(level.newmark_rule.displacement_acceleration, acceleration);
        }
      else if (level.rule.new_velocity_weight == 1.)
        u.add(h, v);
      else
        u.add(h * level.rule.new_velocity_weight,
              v,
              h * (1. - level.rule.new_velocity_weight),
              v_old);
      // a massless node has no inertia: the velocity that moves it
      if (!owned_massless_offsets.empty())
        {
          double       *v_local   = v.begin();
          const double *u_local   = u.begin();
          const double *old_local = u_old.begin();
          for (const unsigned int k : owned_massless_offsets)
            v_local[k] = (u_local[k] - old_local[k]) / h;
        }
      current_time += h;
    }



    template <int dim>
    bool
    DistributedImpactSolver<dim>::try_free_flight_step()
    {
      const unsigned int nd = contact.n_directions();
      start_step(*coarse);
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        if (local_free_velocity[c * nd] + gap_terms[c] < 0.)
          return false;

      step_number += free_flight_factor;
      report            = DistributedStepReport();
      report.time       = current_time + coarse->scheme->time_step();
      report.n_substeps = free_flight_factor;
      // no contact acts: zero impulses on every body
      report.body_impulse.assign(contact.n_bodies(), {{0., 0., 0.}});
      report.carried_impulse  = report.body_impulse;
      report.load_coefficient = coarse->scheme->time_step();
      v_old                   = v;
      if (coarse->substructured_solver)
        {
          contact_dof_values.assign(n_contact_dofs, 0.);
          const auto start = std::chrono::steady_clock::now();
          coarse->substructured_solver->finish_solve(contact_dof_values, v);
          add_translation(v);
          stats.solve_seconds += std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
        }
      else
        v = v_free;
      advance_displacement(*coarse);
      std::fill(active.begin(), active.end(), false);
      std::fill(last_states.begin(), last_states.end(), ContactState::open);
      std::fill(local_impulses.begin(), local_impulses.end(), 0.);
      last_impulses = local_impulses;
      last_body_impulses.assign(contact.n_bodies(), {{0., 0., 0.}});
      last_impulse_field = 0.;
      ++stats.free_flight_steps;
      return true;
    }



    template <int dim>
    const DistributedStepReport &
    DistributedImpactSolver<dim>::do_time_step(const unsigned int max_substeps)
    {
      if (newmark && !acceleration_ready)
        compute_initial_acceleration();
      if (coarse && !last_step_had_impulses &&
          max_substeps >= free_flight_factor && try_free_flight_step())
        return report;

      ++step_number;
      const double       h    = fine.scheme->time_step();
      const unsigned int n    = contact.n_candidates();
      const unsigned int nd   = contact.n_directions();
      report                  = DistributedStepReport();
      report.time             = current_time + h;
      report.load_coefficient = h;

      // 1. The free velocity, M~ v_free = F~, and 2. b_N of the scheme.
      start_step(fine);

      // 3. The candidates that can touch, and the contact problem; a
      // candidate left out that the impulses push in joins, and the
      // problem is solved again.
      double scale = 0.;
      for (unsigned int c = 0; c < n; ++c)
        {
          const double w_free = local_free_velocity[c * nd] + gap_terms[c];
          in_lcp[c]           = (w_free < 0.) || active[c];
          scale               = std::max({scale,
                                          std::abs(local_free_velocity[c * nd]),
                                          std::abs(gap_terms[c])});
        }
      std::fill(local_impulses.begin(), local_impulses.end(), 0.);
      if (!fine.substructured_solver)
        correction = 0.;
      std::vector<double> &all_correction = gap_work;
      for (;;)
        {
          lcp_candidates.clear();
          for (unsigned int c = 0; c < n; ++c)
            if (in_lcp[c])
              lcp_candidates.push_back(c);
          if (lcp_candidates.empty())
            {
              if (!fine.substructured_solver)
                correction = 0.;
              break;
            }
          const auto start = std::chrono::steady_clock::now();
          solve_contact_problem();
          stats.contact_problem_seconds +=
            std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                          start)
              .count();
          if (fine.substructured_solver)
            {
              // M~^{-1} H P on the contact DoFs: (M~^{-1})_CC (H P)
              impulses_on_contact_dofs(lcp_P, contact_dof_values);
              fine.substructured_solver->contact_solve(contact_dof_values,
                                                       dense_out);
              local_components(dense_out, all_correction);
            }
          else
            contact.local_velocities(correction, all_correction);
          bool grown = false;
          for (unsigned int c = 0; c < n; ++c)
            if (!in_lcp[c] && local_free_velocity[c * nd] + gap_terms[c] +
                                  all_correction[c * nd] <
                                -1e-12 * scale)
              {
                in_lcp[c] = true;
                grown     = true;
              }
          if (!grown)
            break;
          ++stats.lcp_resolves;
        }
      report.lcp_size = lcp_candidates.size() * nd;
      for (unsigned int a = 0; a < lcp_candidates.size(); ++a)
        for (unsigned int k = 0; k < nd; ++k)
          local_impulses[lcp_candidates[a] * nd + k] = lcp_P[a * nd + k];

      // 4. v = v_free + M~^{-1} H P, then u from the scheme's fine.rule.
      v_old = v;
      if (fine.substructured_solver)
        {
          if (lcp_candidates.empty())
            contact_dof_values.assign(n_contact_dofs, 0.);
          else
            impulses_on_contact_dofs(lcp_P, contact_dof_values);
          const auto start = std::chrono::steady_clock::now();
          fine.substructured_solver->finish_solve(contact_dof_values, v);
          add_translation(v);
          stats.solve_seconds += std::chrono::duration<double>(
                                   std::chrono::steady_clock::now() - start)
                                   .count();
        }
      else
        {
          v = v_free;
          v += correction;
        }
      advance_displacement(fine);

      Tensor<1, dim> tangential;
      for (unsigned int c = 0; c < n; ++c)
        {
          const double p_n = local_impulses[c * nd];
          active[c]        = p_n > 0.;
          if (!in_lcp[c])
            last_states[c] = ContactState::open;
          report.active_contacts += active[c] ? 1 : 0;
          report.normal_impulse += p_n;
          const auto &frame = contact.candidate(c).frame;
          for (unsigned int k = 1; k < nd; ++k)
            for (unsigned int d = 0; d < dim; ++d)
              tangential[d] += frame[k][d] * local_impulses[c * nd + k];
        }
      report.tangential_impulse = tangential.norm();
      report.body_impulse       = body_impulses(local_impulses, 1.);
      // the last step's impulse as it acted, per body and on the DoFs: a
      // contact search before this step may have replaced its candidates
      const double w         = fine.scheme->contact_force_weight();
      report.carried_impulse = last_body_impulses;
      for (auto &impulse : report.carried_impulse)
        for (double &component : impulse)
          component *= (1. - w) / w;
      last_body_impulses = report.body_impulse;
      last_impulses      = local_impulses;
      if (fine.scheme->massless_impulse_carry() != 0.)
        {
          last_impulse_field = 0.;
          contact.add_impulses(all_candidates,
                               local_impulses,
                               last_impulse_field);
        }
      last_step_had_impulses =
        std::any_of(local_impulses.begin(),
                    local_impulses.end(),
                    [](const double p) { return p != 0.; });
      return report;
    }



    template <int dim>
    std::vector<std::array<double, 3>>
    DistributedImpactSolver<dim>::body_impulses(
      const std::vector<double> &local,
      const double               factor) const
    {
      const unsigned int                 nd = contact.n_directions();
      std::vector<std::array<double, 3>> result(contact.n_bodies(),
                                                {{0., 0., 0.}});
      if (factor == 0.) // no carry (w = 1)
        return result;
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        {
          const auto &candidate = contact.candidate(c);
          for (unsigned int k = 0; k < nd; ++k)
            for (unsigned int d = 0; d < dim; ++d)
              {
                const double p =
                  factor * candidate.frame[k][d] * local[c * nd + k];
                result[candidate.body_a][d] += p;
                if (candidate.body_b != numbers::invalid_unsigned_int)
                  result[candidate.body_b][d] -= p;
              }
        }
      return result;
    }



    template <int dim>
    double
    DistributedImpactSolver<dim>::time() const
    {
      return current_time;
    }



    template <int dim>
    const DistributedVector &
    DistributedImpactSolver<dim>::displacement() const
    {
      return u;
    }



    template <int dim>
    const DistributedVector &
    DistributedImpactSolver<dim>::velocity() const
    {
      return v;
    }



    template <int dim>
    const std::vector<bool> &
    DistributedImpactSolver<dim>::active_set() const
    {
      return active;
    }



    template <int dim>
    void
    DistributedImpactSolver<dim>::contact_impulse_field(
      DistributedVector &field) const
    {
      field.reinit(body.locally_owned_dofs(), body.communicator());
      contact.add_impulses(all_candidates, last_impulses, field);
    }



    template <int dim>
    const DistributedRunStatistics &
    DistributedImpactSolver<dim>::statistics() const
    {
      return stats;
    }



    template <int dim>
    const TimeIntegrator &
    DistributedImpactSolver<dim>::integrator() const
    {
      return *fine.scheme;
    }



    template <int dim>
    double
    DistributedImpactSolver<dim>::energy() const
    {
      DistributedVector tmp(body.locally_owned_dofs(), body.communicator());
      body.mass_matrix().vmult(tmp, v);
      double e = 0.5 * (tmp * v);
      body.stiffness_matrix().vmult(tmp, u);
      e += 0.5 * (tmp * u);
      return e - body.external_force() * u;
    }



    template class DistributedImpactSolver<2>;
    template class DistributedImpactSolver<3>;
  } // namespace distributed
} // namespace impactfe
