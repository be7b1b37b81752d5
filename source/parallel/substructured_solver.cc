#include <deal.II/base/mpi.h>

#include <deal.II/lac/lapack_templates.h>

#include <impactfe/parallel/substructured_solver.h>
#include <impactfe/utilities/mpi_errors.h>
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



    double
    SubstructuredSolver::dense_setup_bytes(const double n_gamma,
                                           const double n_contact,
                                           const double n_trailing)
    {
      // the rank's trailing block of its factor, then either its product
      // with itself and the sum over the ranks (summed_cholesky_factor())
      // or, with that sum factorised, S_C's factor turned into S_C^{-1}
      // beside S_C, and their blocks per uncoupled group with S_C in
      // single precision (compute_from_factor(); measured on one rank:
      // 6.5 |C|^2 numbers at the peak)
      return 8. *
             (n_trailing * n_trailing + n_gamma * n_gamma +
              std::max(n_trailing * n_trailing, 4.5 * n_contact * n_contact));
    }



    // @sect3{Set-up}
    // The rank's factor ordered [I, C_i, B_i]: its interior, its contact
    // DoFs that no other rank has, and its shared DoFs B_i. Eliminating
    // [I, C_i] leaves the Schur complement on B, which the solves use;
    // eliminating only I leaves it on Gamma = B u C, whose Schur
    // complement on C is S_C. With the sparse contact operator C_i is
    // part of I.
    void
    SubstructuredSolver::initialize(
      const MPI_Comm                              comm,
      const SparseMatrix<double>                 &subdomain_matrix,
      const std::vector<types::global_dof_index> &local_dofs,
      const std::vector<bool>                    &on_interface,
      const std::vector<types::global_dof_index> &contact_dofs,
      const IndexSet                             &owned,
      const std::string                          &name,
      const ContactOperator                       requested_operator,
      const std::size_t                           memory_limit,
      const unsigned int                          largest_dense_interface)
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

      // 1. B: every rank's shared DoFs (sorted); Gamma: B without C, then
      // C in the given order. The dense operator's interface problem is
      // on Gamma, the largest matrix of the set-up.
      std::vector<types::global_dof_index> mine;
      unsigned int                         n_local_contact = 0;
      for (unsigned int l = 0; l < n_local; ++l)
        if (on_interface[l])
          mine.push_back(local_to_global[l]);
        else if (is_contact(local_to_global[l]))
          ++n_local_contact;
      std::vector<types::global_dof_index> shared;
      for (const auto &part : Utilities::MPI::all_gather(communicator, mine))
        shared.insert(shared.end(), part.begin(), part.end());
      std::sort(shared.begin(), shared.end());
      shared.erase(std::unique(shared.begin(), shared.end()), shared.end());
      std::size_t n_b_outside_c = 0;
      for (const auto g : shared)
        n_b_outside_c += is_contact(g) ? 0 : 1;
      const std::size_t n_gamma = n_b_outside_c + contact_dofs.size();
      const double      dense_bytes =
        Utilities::MPI::max(dense_setup_bytes(n_gamma,
                                              contact_dofs.size(),
                                              n_local_contact + mine.size()),
                            communicator);
      contact_operator = requested_operator;
      // a dense product costs 2 |C|^2 flops, a sparse one about a solve
      // pair, 4 nnz(L); with the iterations each needs, the dense
      // operator paid on the block on a slab of doc/parallel.md up to
      // |Gamma|^2 about 1000 times the DoFs (measured: 700 dense faster,
      // 1400 sparse)
      if (contact_operator == ContactOperator::automatic)
        contact_operator = (n_gamma <= largest_dense_interface &&
                            double(n_gamma) * n_gamma <= 1000. * owned.size() &&
                            dense_bytes <= memory_limit) ?
                             ContactOperator::dense :
                             ContactOperator::sparse;
      if (contact_operator == ContactOperator::dense)
        {
          AssertThrow(
            dense_bytes <= memory_limit,
            ExcMessage(
              "Substructured solve of " + name +
              ": the dense contact operator's interface problem has " +
              std::to_string(n_gamma) + " DoFs (" +
              std::to_string(shared.size()) + " shared by ranks, " +
              std::to_string(contact_dofs.size()) +
              " contact DoFs), and its set-up would need " +
              format_number(dense_bytes / (1 << 30)) +
              " GiB on a rank, more than the limit of " +
              format_number(double(memory_limit) / (1 << 30)) +
              " GiB. Use 'Parallel solver/Contact operator = sparse' (or "
              "automatic)" +
              (shared.empty() ? std::string(".") :
                                std::string(", or fewer ranks."))));
          DenseSchurComplement::check_dense_size(n_gamma, name);
        }
      const bool contacts_last = contact_operator != ContactOperator::sparse;
      // every operator keeps S_B, dense on every rank: the rank's block
      // of its factor on B_i (and C_i, last with it), its product with
      // itself, and their sum over the ranks
      const double own_trailing =
        mine.size() + (contacts_last ? n_local_contact : 0.);
      const double interface_bytes =
        Utilities::MPI::max(8. * (own_trailing * own_trailing +
                                  double(mine.size()) * mine.size() +
                                  double(shared.size()) * shared.size()),
                            communicator);
      AssertThrow(shared.size() < 46340 && interface_bytes <= memory_limit,
                  ExcMessage(
                    "Substructured solve of " + name + ": the ranks share " +
                    std::to_string(shared.size()) +
                    " DoFs, and the dense interface problem on them would "
                    "need " +
                    format_number(interface_bytes / (1 << 30)) +
                    " GiB on a rank (the limit: " +
                    format_number(double(memory_limit) / (1 << 30)) +
                    " GiB, and 46340 DoFs). Use fewer ranks, or 'Parallel "
                    "solver/Solver = direct' or 'amg cg'."));

      // 2. The rank's factor, [C_i, B_i] last in that order ([B_i] with
      // the sparse operator).
      std::vector<types::global_dof_index> trailing;
      if (contacts_last)
        for (unsigned int l = 0; l < n_local; ++l)
          if (!on_interface[l] && is_contact(local_to_global[l]))
            trailing.push_back(l);
      const unsigned int n_own_contact = trailing.size();
      for (unsigned int l = 0; l < n_local; ++l)
        if (on_interface[l])
          trailing.push_back(l);
      // a rank's own factor may fail alone (a folded cell in its part):
      // every rank stops with its message
      std::vector<double> trailing_factor;
      on_every_rank(communicator, [&]() {
        trailing_factor = factor.factorize_with_trailing_block(subdomain_matrix,
                                                               trailing,
                                                               name);
      });
      // the blocks below need C_i before B_i: the factor's order of the
      // trailing unknowns (returned in trailing) must keep them apart
      for (unsigned int k = 0; k < trailing.size(); ++k)
        AssertThrow(on_interface[trailing[k]] == (k >= n_own_contact),
                    ExcMessage("Substructured solve of " + name +
                               ": the factor reordered the contact DoFs and "
                               "the shared DoFs among its last unknowns."));
      const unsigned int n_trailing = trailing.size();
      const unsigned int n_shared   = n_trailing - n_own_contact;
      AssertThrow(n_shared == mine.size(), ExcInternalError());
      n_leading       = n_local - n_shared;
      n_interior      = n_leading - n_own_contact;
      const int *perm = factor.permutation();
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
      std::vector<types::global_dof_index> gamma;
      for (const auto g : shared)
        if (!is_contact(g))
          gamma.push_back(g);
      gamma.insert(gamma.end(), contact_dofs.begin(), contact_dofs.end());

      // 3. S_C: the trailing block of the factor of S on Gamma, the sum of
      // the ranks' L_t L_t^T; S itself is not kept.
      contact_schur = DenseSchurComplement();
      if (contact_operator == ContactOperator::dense)
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
        if (contacts_last)
          for (unsigned int j = 0; j < n_own_contact; ++j)
            own_contacts.emplace_back(
              contact_index(local_to_global[trailing[j]]), n_interior + j);
        else
          for (unsigned int k = 0; k < n_leading; ++k)
            if (is_contact(local_to_global[perm[k]]))
              own_contacts.emplace_back(contact_index(local_to_global[perm[k]]),
                                        k);
        for (unsigned int i = 0; i < shared.size(); ++i)
          if (is_contact(shared[i]))
            shared_contacts.emplace_back(contact_index(shared[i]), i);
      }
      n_contact_dofs = contact_dofs.size();
      first_rank     = Utilities::MPI::this_mpi_process(communicator) == 0;
      first_contact_position = n_leading;
      for (const auto &[i, k] : own_contacts)
        first_contact_position = std::min(first_contact_position, k);

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



    // The contact DoFs' values on every rank: the rank's own ones from the
    // backward substitution in w (summed over the ranks: each has its
    // own), the shared ones from x_B in interface_work.
    void
    SubstructuredSolver::contact_values(const double        *w,
                                        std::vector<double> &x_contact) const
    {
      x_contact.assign(n_contact_dofs, 0.);
      for (const auto &[i, k] : own_contacts)
        x_contact[i] = w[k];
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        Utilities::MPI::sum(x_contact, communicator, x_contact);
      for (const auto &[i, j] : shared_contacts)
        x_contact[i] = interface_work[j];
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
    // (With the sparse contact operator the contact DoFs are spread
    // through the factor's order, so the partial substitutions from
    // first_contact_position are nearly whole ones: a step costs up to two
    // solve pairs there.)
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
      std::copy(z + first_contact_position,
                z + local_to_global.size(),
                w + first_contact_position);
      solve_interface(w, started_shared.data(), interface_work.data());
      factor.solve_lower(w, true, n_leading, first_contact_position);
      contact_values(w, x_contact);
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
      for (unsigned int k = first_contact_position; k < n_local; ++k)
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
      AssertThrow(contact_operator == ContactOperator::dense,
                  ExcMessage("Substructured solve: the contact Schur "
                             "complement was not built (initialize())."));
      return contact_schur;
    }



    SubstructuredSolver::ContactOperator
    SubstructuredSolver::chosen_contact_operator() const
    {
      return contact_operator;
    }



    // (A^{-1} c)_C: with the sparse operator, the forward substitution of
    // c (zero before the first contact DoF: skipped), the interface solve
    // and the backward substitution down to the first contact DoF only.
    void
    SubstructuredSolver::contact_solve(const std::vector<double> &c,
                                       std::vector<double> &x_contact) const
    {
      AssertDimension(c.size(), n_contact_dofs);
      if (contact_operator == ContactOperator::dense)
        {
          x_contact.resize(n_contact_dofs);
          contact_schur.vmult_inverse(c.data(), x_contact.data());
          return;
        }
      AssertThrow(contact_operator == ContactOperator::sparse,
                  ExcMessage("Substructured solve: this level makes no "
                             "contact products (initialize())."));
      double *w = local_work.data();
      std::fill(w, w + local_to_global.size(), 0.);
      for (const auto &[i, k] : own_contacts)
        w[k] = c[i];
      factor.solve_lower(w, false, n_leading);
      // c on the shared contact DoFs: once in the sum over the ranks
      std::fill(shared_rhs.begin(), shared_rhs.end(), 0.);
      if (first_rank)
        for (const auto &[i, j] : shared_contacts)
          shared_rhs[j] = c[i];
      solve_interface(w, shared_rhs.data(), interface_work.data());
      factor.solve_lower(w, true, n_leading, first_contact_position);
      contact_values(w, x_contact);
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
