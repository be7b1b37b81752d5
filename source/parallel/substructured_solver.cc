#include <deal.II/base/mpi.h>

#include <deal.II/lac/lapack_templates.h>

#include <impactfe/parallel/substructured_solver.h>
#include <impactfe/utilities/program.h>

#include <algorithm>

#include "../utilities/blas_lapack.h"

namespace impactfe
{
  namespace distributed
  {
    namespace
    {
      // The dense lower triangle of the sum over the ranks of L_r L_r^T,
      // L_r the n x n lower triangle at @p factor (leading dimension @p ld)
      // whose row j goes to row position[j] of the n_total x n_total
      // result; then its Cholesky factor (column-major, lower), on every
      // rank.
      std::vector<double>
      summed_cholesky_factor(const double                    *factor,
                             const unsigned int               n,
                             const unsigned int               ld,
                             const std::vector<unsigned int> &position,
                             const std::size_t                n_total,
                             const MPI_Comm                   communicator,
                             const std::string               &what)
      {
        std::vector<double> sum(n_total * n_total, 0.);
        if (n > 0)
          {
            std::vector<double>   part(std::size_t(n) * n);
            const types::blas_int n_b = n, ld_b = ld;
            const double          one = 1., zero = 0.;
            syrk("L",
                 "N",
                 &n_b,
                 &n_b,
                 &one,
                 factor,
                 &ld_b,
                 &zero,
                 part.data(),
                 &n_b);
            for (unsigned int j = 0; j < n; ++j)
              for (unsigned int i = j; i < n; ++i)
                {
                  const std::size_t r = std::max(position[i], position[j]),
                                    c = std::min(position[i], position[j]);
                  sum[c * n_total + r] += part[std::size_t(j) * n + i];
                }
          }
        const int mpi_error = MPI_Allreduce(MPI_IN_PLACE,
                                            sum.data(),
                                            static_cast<int>(sum.size()),
                                            MPI_DOUBLE,
                                            MPI_SUM,
                                            communicator);
        AssertThrowMPI(mpi_error);
        const int n_t  = n_total;
        int       info = 0;
        if (n_t > 0)
          dpotrf_("L", &n_t, sum.data(), &n_t, &info);
        AssertThrow(info == 0,
                    ExcMessage(what +
                               " is not positive definite (LAPACK "
                               "dpotrf info " +
                               std::to_string(info) + ")."));
        return sum;
      }
    } // namespace



    // @sect3{Set-up}
    // The rank's factor ordered [I, C_i, B_i]: its interior, its contact
    // DoFs that no other rank has, and its shared DoFs B_i. Eliminating
    // [I, C_i] leaves the Schur complement on B, which the solves use;
    // eliminating only I leaves it on Gamma = B u C, whose Schur
    // complement on C is S_C.
    void
    SubstructuredSolver::initialize(
      const MPI_Comm                              comm,
      const SparseMatrix<double>                 &subdomain_matrix,
      const std::vector<types::global_dof_index> &local_dofs,
      const std::vector<bool>                    &on_interface,
      const std::vector<types::global_dof_index> &contact_dofs,
      const IndexSet                             &owned,
      const std::string                          &name,
      const bool                                  with_contact_schur_complement,
      const std::size_t                           memory_limit)
    {
      communicator               = comm;
      local_to_global            = local_dofs;
      const unsigned int n_local = local_to_global.size();
      AssertThrow(subdomain_matrix.m() == n_local &&
                    on_interface.size() == n_local,
                  ExcMessage("Substructured solve of " + name +
                             ": the subdomain matrix does not match its "
                             "DoF list."));
      std::vector<types::global_dof_index> sorted_contact(contact_dofs);
      std::sort(sorted_contact.begin(), sorted_contact.end());
      const auto is_contact = [&](const types::global_dof_index g) {
        return std::binary_search(sorted_contact.begin(),
                                  sorted_contact.end(),
                                  g);
      };

      // 1. The rank's factor, [C_i, B_i] last in that order.
      std::vector<types::global_dof_index> trailing;
      for (unsigned int l = 0; l < n_local; ++l)
        if (!on_interface[l] && is_contact(local_to_global[l]))
          trailing.push_back(l);
      const unsigned int n_own_contact = trailing.size();
      for (unsigned int l = 0; l < n_local; ++l)
        if (on_interface[l])
          trailing.push_back(l);
      std::vector<double> trailing_factor =
        factor.factorize_with_trailing_block(subdomain_matrix, trailing, name);
      // the blocks below need C_i before B_i: the factor's order of the
      // trailing unknowns (returned in trailing) must keep them apart
      for (unsigned int k = 0; k < trailing.size(); ++k)
        AssertThrow(on_interface[trailing[k]] == (k >= n_own_contact),
                    ExcMessage("Substructured solve of " + name +
                               ": the factor reordered the contact DoFs and "
                               "the shared DoFs among its last unknowns."));
      const unsigned int n_trailing = trailing.size();
      const unsigned int n_shared   = n_trailing - n_own_contact;
      n_leading                     = n_local - n_shared;
      n_interior                    = n_leading - n_own_contact;
      const int *perm               = factor.permutation();
      owned_offset.resize(n_leading);
      for (unsigned int k = 0; k < n_leading; ++k)
        {
          const types::global_dof_index g = local_to_global[perm[k]];
          AssertThrow(owned.is_element(g),
                      ExcMessage("Substructured solve of " + name +
                                 ": a DoF that only this rank's cells "
                                 "have is owned by another rank."));
          owned_offset[k] = owned.index_within_set(g);
        }

      // 2. B: every rank's shared DoFs; Gamma: B without C, then C in the
      // given order.
      std::vector<types::global_dof_index> mine;
      for (unsigned int j = n_own_contact; j < n_trailing; ++j)
        mine.push_back(local_to_global[trailing[j]]);
      std::vector<types::global_dof_index> shared;
      for (const auto &part : Utilities::MPI::all_gather(communicator, mine))
        shared.insert(shared.end(), part.begin(), part.end());
      std::sort(shared.begin(), shared.end());
      shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
      // Gamma's dense matrix is the largest of the set-up (B's alone
      // without S_C)
      std::vector<types::global_dof_index> gamma;
      for (const auto g : shared)
        if (!with_contact_schur_complement || !is_contact(g))
          gamma.push_back(g);
      const std::size_t n_b_outside_c = gamma.size();
      if (with_contact_schur_complement)
        gamma.insert(gamma.end(), contact_dofs.begin(), contact_dofs.end());
      const std::size_t n_gamma = gamma.size();
      DenseSchurComplement::check_dense_size(n_gamma, name);
      AssertThrow(n_gamma * n_gamma * sizeof(double) <= memory_limit,
                  ExcMessage(
                    "Substructured solve of " + name +
                    ": the interface problem has " + std::to_string(n_gamma) +
                    " DoFs (" + std::to_string(shared.size()) +
                    " shared by ranks, " +
                    std::to_string(
                      with_contact_schur_complement ? contact_dofs.size() : 0) +
                    " contact DoFs), and its dense matrix would need " +
                    format_number(n_gamma * n_gamma * 8. / (1 << 30)) +
                    " GiB on every rank. Use fewer ranks, or 'Parallel "
                    "solver/Solver = direct' or 'amg cg'."));

      // 3. S_C: the trailing block of the factor of S on Gamma, the sum of
      // the ranks' L_t L_t^T; S itself is not kept.
      has_contact_schur = with_contact_schur_complement;
      if (has_contact_schur)
        {
          // the position in Gamma of each of the factor's trailing rows
          // (C is not sorted: by a sorted copy)
          std::vector<unsigned int> gamma_position(n_trailing);
          std::vector<std::pair<types::global_dof_index, unsigned int>> order;
          for (unsigned int i = 0; i < n_gamma; ++i)
            order.emplace_back(gamma[i], i);
          std::sort(order.begin(), order.end());
          for (unsigned int j = 0; j < n_trailing; ++j)
            {
              const types::global_dof_index g  = local_to_global[trailing[j]];
              const auto                    it = std::lower_bound(order.begin(),
                                               order.end(),
                                               std::make_pair(g, 0u));
              AssertThrow(it != order.end() && it->first == g,
                          ExcMessage("Substructured solve of " + name +
                                     ": a DoF of the interface is missing."));
              gamma_position[j] = it->second;
            }
          std::vector<double> gamma_factor =
            summed_cholesky_factor(trailing_factor.data(),
                                   n_trailing,
                                   n_trailing,
                                   gamma_position,
                                   n_gamma,
                                   communicator,
                                   "Substructured solve of " + name +
                                     ": the Schur complement on the "
                                     "interface");
          const std::size_t   n_c = contact_dofs.size();
          std::vector<double> contact_factor(n_c * n_c, 0.);
          for (std::size_t j = 0; j < n_c; ++j)
            for (std::size_t i = j; i < n_c; ++i)
              contact_factor[j * n_c + i] =
                gamma_factor[(n_b_outside_c + j) * n_gamma + n_b_outside_c + i];
          contact_schur.compute_from_factor(contact_dofs,
                                            std::move(contact_factor),
                                            name);
        }

      // 4. S_B, the Schur complement on B, from the trailing B_i blocks.
      interface_dofs = shared;
      shared_position.resize(n_shared);
      for (unsigned int j = 0; j < n_shared; ++j)
        shared_position[j] =
          std::lower_bound(shared.begin(),
                           shared.end(),
                           local_to_global[trailing[n_own_contact + j]]) -
          shared.begin();
      const std::size_t offset =
        std::size_t(n_own_contact) * n_trailing + n_own_contact;
      interface_factor =
        summed_cholesky_factor(trailing_factor.data() + offset,
                               n_shared,
                               n_trailing,
                               shared_position,
                               shared.size(),
                               communicator,
                               "Substructured solve of " + name +
                                 ": the Schur complement on the DoFs the "
                                 "ranks share");
      owned_interface.clear();
      for (unsigned int i = 0; i < shared.size(); ++i)
        if (owned.is_element(shared[i]))
          owned_interface.emplace_back(i, owned.index_within_set(shared[i]));
      local_work.assign(n_local, 0.);
      started.assign(n_local, 0.);
      interface_work.assign(shared.size(), 0.);
      started_shared.assign(shared.size(), 0.);
      shared_rhs.assign(shared.size(), 0.);

      // Where each contact DoF is: this rank's own (a factor position), or
      // shared (a position in B).
      own_contacts.clear();
      shared_contacts.clear();
      {
        std::vector<std::pair<types::global_dof_index, unsigned int>> order;
        for (unsigned int i = 0; i < contact_dofs.size(); ++i)
          order.emplace_back(contact_dofs[i], i);
        std::sort(order.begin(), order.end());
        const auto contact_index = [&](const types::global_dof_index g) {
          return std::lower_bound(order.begin(),
                                  order.end(),
                                  std::make_pair(g, 0u))
            ->second;
        };
        for (unsigned int j = 0; j < n_own_contact; ++j)
          own_contacts.emplace_back(contact_index(local_to_global[trailing[j]]),
                                    n_interior + j);
        for (unsigned int i = 0; i < shared.size(); ++i)
          if (is_contact(shared[i]))
            shared_contacts.emplace_back(contact_index(shared[i]), i);
      }
      n_contact_dofs = contact_dofs.size();
      first_rank     = Utilities::MPI::this_mpi_process(communicator) == 0;

      // The first substitutions of a run cost some 0.2 s more than the
      // later ones (measured: 15 times a forward substitution at 2.5e5
      // DoFs; the BLAS's first calls), and a rank that pays it keeps the
      // others waiting in the first all-reduce: paid here, with the
      // set-up, so that the time steps cost what they do in a long run.
      std::fill(local_work.begin(), local_work.end(), 1.);
      factor.solve_lower(local_work.data(), false, n_leading);
      factor.solve_lower(local_work.data(), true, n_leading);
    }



    // @sect3{A solve}
    // With L = [L_11 0; L_B1 L_BB] the rank's factor (1 = [I, C_i]): the
    // forward substitution of [b_1; 0] through the first block gives
    // y_1 = L_11^{-1} b_1 and the rank's reduction -L_B1 y_1; S_B x_B =
    // b_B + the ranks' reductions; the backward substitution through the
    // first block with x_B gives x_1 = L_11^{-T} (y_1 - L_B1^T x_B).
    void
    SubstructuredSolver::load(const DistributedVector &b, double *z) const
    {
      const double *b_local = b.begin();
      for (unsigned int k = 0; k < n_leading; ++k)
        z[k] = b_local[owned_offset[k]];
      std::fill(z + n_leading, z + local_to_global.size(), 0.);
    }



    // g = b_B (the owned entries of each rank, in @p b_shared) + the ranks'
    // reductions from @p z, summed over the ranks, then S_B^{-1} g into g;
    // and z_B = x_B for the backward substitution.
    void
    SubstructuredSolver::solve_interface(double       *z,
                                         const double *b_shared,
                                         double       *g) const
    {
      const int n_shared = interface_dofs.size();
      std::copy(b_shared, b_shared + n_shared, g);
      for (unsigned int j = 0; j < shared_position.size(); ++j)
        g[shared_position[j]] += z[n_leading + j];
      if (n_shared > 0)
        {
          const int mpi_error = MPI_Allreduce(
            MPI_IN_PLACE, g, n_shared, MPI_DOUBLE, MPI_SUM, communicator);
          AssertThrowMPI(mpi_error);
          int       info = 0;
          const int one  = 1;
          dpotrs_("L",
                  &n_shared,
                  &one,
                  interface_factor.data(),
                  &n_shared,
                  g,
                  &n_shared,
                  &info);
          AssertThrow(info == 0, ExcInternalError());
        }
      for (unsigned int j = 0; j < shared_position.size(); ++j)
        z[n_leading + j] = g[shared_position[j]];
    }



    void
    SubstructuredSolver::store(const double      *z,
                               const double      *g,
                               DistributedVector &x) const
    {
      double *x_local = x.begin();
      for (unsigned int k = 0; k < n_leading; ++k)
        x_local[owned_offset[k]] = z[k];
      for (const auto &[i, offset] : owned_interface)
        x_local[offset] = g[i];
      x.compress(VectorOperation::insert);
    }



    void
    SubstructuredSolver::solve(const DistributedVector &b,
                               DistributedVector       &x) const
    {
      double *z = local_work.data();
      load(b, z);
      factor.solve_lower(z, false, n_leading);
      std::vector<double> &b_shared = shared_rhs;
      std::fill(b_shared.begin(), b_shared.end(), 0.);
      for (const auto &[i, offset] : owned_interface)
        b_shared[i] = b.begin()[offset];
      solve_interface(z, b_shared.data(), interface_work.data());
      factor.solve_lower(z, true, n_leading);
      store(z, interface_work.data(), x);
    }



    // @sect3{A solve in two halves}
    // start_solve(): the forward substitution of b (kept), x_B, and the
    // contact DoFs' values: the rank's own ones by the backward
    // substitution through their columns only (the interior's are not
    // needed), the shared ones are in x_B. finish_solve(): the forward
    // substitution of c (zero on the interior, so only from the contact
    // DoFs' columns on) added to b's, x_B again, and the whole backward
    // substitution. Together one solve pair with A's factors, where x =
    // A^{-1} b and A^{-1} c separately would be one and a half.
    void
    SubstructuredSolver::start_solve(const DistributedVector &b,
                                     std::vector<double>     &x_contact) const
    {
      double *z = started.data();
      load(b, z);
      factor.solve_lower(z, false, n_leading);
      std::fill(started_shared.begin(), started_shared.end(), 0.);
      for (const auto &[i, offset] : owned_interface)
        started_shared[i] = b.begin()[offset];
      // on a copy of z: the forward substitution of b is kept for
      // finish_solve()
      double *w = local_work.data();
      std::copy(z + n_interior, z + local_to_global.size(), w + n_interior);
      solve_interface(w, started_shared.data(), interface_work.data());
      factor.solve_lower(w, true, n_leading, n_interior);
      x_contact.assign(n_contact_dofs, 0.);
      for (const auto &[i, k] : own_contacts)
        x_contact[i] = w[k];
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        Utilities::MPI::sum(x_contact, communicator, x_contact);
      for (const auto &[i, j] : shared_contacts)
        x_contact[i] = interface_work[j];
    }



    void
    SubstructuredSolver::finish_solve(const std::vector<double> &c,
                                      DistributedVector         &x) const
    {
      AssertDimension(c.size(), n_contact_dofs);
      const unsigned int n_local = local_to_global.size();
      double            *w       = local_work.data();
      std::fill(w, w + n_local, 0.);
      for (const auto &[i, k] : own_contacts)
        w[k] = c[i];
      factor.solve_lower(w, false, n_leading);
      double *z = started.data();
      for (unsigned int k = n_interior; k < n_local; ++k)
        z[k] += w[k];
      // c on the shared contact DoFs: once in the sum over the ranks
      if (first_rank)
        for (const auto &[i, j] : shared_contacts)
          started_shared[j] += c[i];
      solve_interface(z, started_shared.data(), interface_work.data());
      factor.solve_lower(z, true, n_leading);
      store(z, interface_work.data(), x);
    }



    const DenseSchurComplement &
    SubstructuredSolver::contact_schur_complement() const
    {
      AssertThrow(has_contact_schur,
                  ExcMessage("Substructured solve: the contact Schur "
                             "complement was not built (initialize())."));
      return contact_schur;
    }



    unsigned int
    SubstructuredSolver::n_interface_dofs() const
    {
      return interface_dofs.size();
    }



    std::size_t
    SubstructuredSolver::n_factor_entries() const
    {
      return factor.n_factor_entries();
    }
  } // namespace distributed
} // namespace impactfe
