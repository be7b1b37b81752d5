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
    // @sect3{Set-up}
    // The rank's factor with Gamma_i last; Gamma from all ranks; S summed
    // over the ranks and factorised with C last; S_C from its trailing
    // block.
    void
    SubstructuredSolver::initialize(
      const MPI_Comm                              comm,
      const SparseMatrix<double>                 &subdomain_matrix,
      const std::vector<types::global_dof_index> &local_dofs,
      const std::vector<bool>                    &on_interface,
      const std::vector<types::global_dof_index> &contact_dofs,
      const IndexSet                             &owned,
      const std::string                          &name,
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

      // 1. The rank's factor, Gamma_i last.
      std::vector<types::global_dof_index> trailing;
      for (unsigned int l = 0; l < n_local; ++l)
        if (on_interface[l] || is_contact(local_to_global[l]))
          trailing.push_back(l);
      trailing_factor =
        factor.factorize_with_trailing_block(subdomain_matrix, trailing, name);
      const unsigned int n_trailing = trailing.size();
      n_interior                    = n_local - n_trailing;
      const int *perm               = factor.permutation();
      for (unsigned int k = 0; k < n_interior; ++k)
        AssertThrow(owned.is_element(local_to_global[perm[k]]),
                    ExcMessage("Substructured solve of " + name +
                               ": an interior DoF of a subdomain is owned "
                               "by another rank."));

      // 2. Gamma: B (sorted), then C in the given order.
      std::vector<types::global_dof_index> mine;
      for (const auto l : trailing)
        if (!is_contact(local_to_global[l]))
          mine.push_back(local_to_global[l]);
      std::vector<types::global_dof_index> shared;
      for (const auto &part : Utilities::MPI::all_gather(communicator, mine))
        shared.insert(shared.end(), part.begin(), part.end());
      std::sort(shared.begin(), shared.end());
      shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
      interface_dofs = shared;
      interface_dofs.insert(interface_dofs.end(),
                            contact_dofs.begin(),
                            contact_dofs.end());
      const std::size_t n_gamma = interface_dofs.size();
      DenseSchurComplement::check_dense_size(n_gamma, name);
      AssertThrow(n_gamma * n_gamma * sizeof(double) <= memory_limit,
                  ExcMessage(
                    "Substructured solve of " + name +
                    ": the interface "
                    "problem has " +
                    std::to_string(n_gamma) + " DoFs (" +
                    std::to_string(shared.size()) +
                    " shared by ranks, the others contact DoFs), and its "
                    "dense matrix would need " +
                    format_number(n_gamma * n_gamma * 8. / (1 << 30)) +
                    " GiB on every rank. Use fewer ranks, or 'Parallel "
                    "solver/Solver = direct' or 'amg cg'."));
      std::vector<std::pair<types::global_dof_index, unsigned int>> position;
      position.reserve(n_gamma);
      for (unsigned int i = 0; i < n_gamma; ++i)
        position.emplace_back(interface_dofs[i], i);
      std::sort(position.begin(), position.end());
      const auto gamma_index = [&](const types::global_dof_index g) {
        const auto it = std::lower_bound(position.begin(),
                                         position.end(),
                                         std::make_pair(g, 0u));
        AssertThrow(it != position.end() && it->first == g,
                    ExcMessage("Substructured solve of " + name +
                               ": a DoF of the interface is missing."));
        return it->second;
      };
      trailing_position.resize(n_trailing);
      for (unsigned int j = 0; j < n_trailing; ++j)
        trailing_position[j] = gamma_index(local_to_global[trailing[j]]);
      owned_interface.clear();
      for (unsigned int i = 0; i < n_gamma; ++i)
        if (owned.is_element(interface_dofs[i]))
          owned_interface.push_back(i);
      // every contact DoF is a DoF of its owner's cells, so in its Gamma_i
      std::vector<unsigned int> covered(n_gamma, 0);
      for (const auto p : trailing_position)
        covered[p] = 1;
      Utilities::MPI::max(covered, communicator, covered);
      AssertThrow(std::all_of(covered.begin(),
                              covered.end(),
                              [](const unsigned int c) { return c != 0; }),
                  ExcMessage("Substructured solve of " + name +
                             ": a contact DoF is not a DoF of the body."));

      // 3. S = sum over the ranks of L_t L_t^T (lower triangles), then its
      // Cholesky factor on every rank.
      interface_factor.assign(n_gamma * n_gamma, 0.);
      if (n_trailing > 0)
        {
          std::vector<double>   part(std::size_t(n_trailing) * n_trailing);
          const types::blas_int n_t = n_trailing;
          const double          one = 1., zero = 0.;
          syrk("L",
               "N",
               &n_t,
               &n_t,
               &one,
               trailing_factor.data(),
               &n_t,
               &zero,
               part.data(),
               &n_t);
          for (unsigned int j = 0; j < n_trailing; ++j)
            for (unsigned int i = j; i < n_trailing; ++i)
              {
                const std::size_t r = std::max(trailing_position[i],
                                               trailing_position[j]),
                                  c = std::min(trailing_position[i],
                                               trailing_position[j]);
                interface_factor[c * n_gamma + r] +=
                  part[std::size_t(j) * n_trailing + i];
              }
        }
      const int mpi_error = MPI_Allreduce(MPI_IN_PLACE,
                                          interface_factor.data(),
                                          static_cast<int>(n_gamma * n_gamma),
                                          MPI_DOUBLE,
                                          MPI_SUM,
                                          communicator);
      AssertThrowMPI(mpi_error);
      {
        const int n    = n_gamma;
        int       info = 0;
        if (n > 0)
          dpotrf_("L", &n, interface_factor.data(), &n, &info);
        AssertThrow(info == 0,
                    ExcMessage("Substructured solve of " + name +
                               ": the interface matrix is not positive "
                               "definite (LAPACK dpotrf info " +
                               std::to_string(info) + ")."));
      }

      // 4. S_C: its factor is the trailing block of S's.
      const std::size_t   n_b = shared.size(), n_c = contact_dofs.size();
      std::vector<double> contact_factor(n_c * n_c, 0.);
      for (std::size_t j = 0; j < n_c; ++j)
        for (std::size_t i = j; i < n_c; ++i)
          contact_factor[j * n_c + i] =
            interface_factor[(n_b + j) * n_gamma + n_b + i];
      contact_schur.compute_from_factor(contact_dofs,
                                        std::move(contact_factor),
                                        name);
      local_work.assign(n_local, 0.);
      interface_work.assign(n_gamma, 0.);
    }



    // @sect3{A solve}
    // With L_i = [L_II 0; L_GI L_GG] the rank's factor: y_I = L_II^{-1} b_I
    // by a forward substitution of [b_I; 0], whose trailing part z_G gives
    // the rank's reduction -L_GI y_I = L_GG z_G; S x_G = b_G + the ranks'
    // reductions; then the backward substitution of [y_I; L_GG^T x_G]
    // gives x_I = L_II^{-T} (y_I - L_GI^T x_G) and x_G again.
    void
    SubstructuredSolver::solve(const DistributedVector &b,
                               DistributedVector       &x) const
    {
      const int         *perm       = factor.permutation();
      const unsigned int n_local    = local_to_global.size();
      const int          n_trailing = n_local - n_interior;
      const int          n_gamma    = interface_dofs.size();
      const int          one        = 1;
      double            *z          = local_work.data();
      double            *g          = interface_work.data();
      for (unsigned int k = 0; k < n_interior; ++k)
        z[k] = b(local_to_global[perm[k]]);
      std::fill(z + n_interior, z + n_local, 0.);
      factor.solve_lower(z);
      std::fill(g, g + n_gamma, 0.);
      if (n_trailing > 0)
        {
          double *z_g = z + n_interior;
          dtrmv_("L",
                 "N",
                 "N",
                 &n_trailing,
                 trailing_factor.data(),
                 &n_trailing,
                 z_g,
                 &one);
          for (int j = 0; j < n_trailing; ++j)
            g[trailing_position[j]] = z_g[j];
        }
      for (const auto i : owned_interface)
        g[i] += b(interface_dofs[i]);
      const int mpi_error = MPI_Allreduce(
        MPI_IN_PLACE, g, n_gamma, MPI_DOUBLE, MPI_SUM, communicator);
      AssertThrowMPI(mpi_error);
      if (n_gamma > 0)
        {
          int info = 0;
          dpotrs_("L",
                  &n_gamma,
                  &one,
                  interface_factor.data(),
                  &n_gamma,
                  g,
                  &n_gamma,
                  &info);
          AssertThrow(info == 0, ExcInternalError());
        }
      if (n_trailing > 0)
        {
          double *z_g = z + n_interior;
          for (int j = 0; j < n_trailing; ++j)
            z_g[j] = g[trailing_position[j]];
          dtrmv_("L",
                 "T",
                 "N",
                 &n_trailing,
                 trailing_factor.data(),
                 &n_trailing,
                 z_g,
                 &one);
        }
      factor.solve_lower(z, true);
      for (unsigned int k = 0; k < n_interior; ++k)
        x(local_to_global[perm[k]]) = z[k];
      for (const auto i : owned_interface)
        x(interface_dofs[i]) = g[i];
      x.compress(VectorOperation::insert);
    }



    const DenseSchurComplement &
    SubstructuredSolver::contact_schur_complement() const
    {
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
