// Direct solves with the distributed step matrix by substructuring: a
// sparse Cholesky factor per rank and a dense interface problem, and the
// Schur complement of the contact DoFs as a by-product (issue 14,
// doc/parallel.md).
#ifndef impactfe_parallel_substructured_solver_h
#define impactfe_parallel_substructured_solver_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>

#include <deal.II/lac/sparse_matrix.h>

#include <impactfe/dynamics/schur_complement.h>
#include <impactfe/dynamics/sparse_cholesky.h>
#include <impactfe/parallel/distributed_body.h>

#include <string>
#include <vector>

namespace impactfe
{
  namespace distributed
  {
    /**
     * Solves A x = b for a symmetric positive definite A = sum_i A_i, A_i
     * the matrix rank i assembles from its own cells
     * (DistributedElasticBody::assemble_subdomain_matrix()).
     *
     * Each rank factorises A_i with its trailing unknowns Gamma_i last
     * (SparseCholesky::factorize_with_trailing_block()): the DoFs it shares
     * with other ranks, and the contact DoFs C. Its trailing block gives
     * the rank's part of the Schur complement S of A on Gamma = union of
     * the Gamma_i, S = sum_i (A_i)_GG - (A_i)_GI (A_i)_II^{-1} (A_i)_IG,
     * which is summed over the ranks once and factorised densely on every
     * rank with C last. A solve is then a forward substitution with each
     * rank's factor, one sum over the ranks of a vector on Gamma, a dense
     * solve with S and a backward substitution: the sparse work splits by
     * subdomains with no communication, where a distributed sparse direct
     * solver's triangular solves are latency-bound (doc/parallel.md).
     *
     * Since C is eliminated last, the trailing block of S's factor is the
     * Cholesky factor of the Schur complement S_C of A on C, and
     * S_C^{-1} = (A^{-1})_CC: the contact problem's products W x and its
     * preconditioner become dense products, as in the serial programs'
     * DenseSchurComplement, on every rank with no communication.
     *
     * The interface problem is dense: |Gamma|^2 numbers on every rank. That
     * suits a few ranks (2D: |Gamma| of the order of the contact DoFs plus
     * the cut lines); initialize() refuses an S larger than @p memory_limit.
     */
    class SubstructuredSolver
    {
    public:
      /**
       * @p subdomain_matrix, @p local_to_global and @p on_interface as
       * DistributedElasticBody::assemble_subdomain_matrix() gives them;
       * @p contact_dofs: the global DoFs C (the same list on every rank);
       * @p owned: the DoFs of the distributed vectors this rank owns.
       * @p name names the matrix in messages.
       */
      void
      initialize(const MPI_Comm                              communicator,
                 const SparseMatrix<double>                 &subdomain_matrix,
                 const std::vector<types::global_dof_index> &local_to_global,
                 const std::vector<bool>                    &on_interface,
                 const std::vector<types::global_dof_index> &contact_dofs,
                 const IndexSet                             &owned,
                 const std::string                          &name,
                 const std::size_t memory_limit = std::size_t(4) << 30);

      /// x = A^{-1} b.
      void
      solve(const DistributedVector &b, DistributedVector &x) const;

      /// S_C and S_C^{-1} on the contact DoFs (the same on every rank).
      const DenseSchurComplement &
      contact_schur_complement() const;

      /// |Gamma|, of which contact_schur_complement().size() are in C.
      unsigned int
      n_interface_dofs() const;

      /// Entries of this rank's sparse factor.
      std::size_t
      n_factor_entries() const;

    private:
      MPI_Comm communicator = MPI_COMM_SELF;
      /// A_i's factor; positions 0 to n_interior - 1 of its order are the
      /// rank's interior DoFs, the others Gamma_i.
      SparseCholesky                       factor;
      std::vector<types::global_dof_index> local_to_global;
      unsigned int                         n_interior = 0;
      /// The trailing block of A_i's factor (column-major, lower), and the
      /// position in Gamma of each of its rows.
      std::vector<double>       trailing_factor;
      std::vector<unsigned int> trailing_position;
      /// Gamma (B, the shared DoFs not in C, sorted; then C) and the
      /// Cholesky factor of S in that order (column-major, lower).
      std::vector<types::global_dof_index> interface_dofs;
      std::vector<double>                  interface_factor;
      /// The positions in Gamma of the DoFs this rank owns.
      std::vector<unsigned int> owned_interface;
      DenseSchurComplement      contact_schur;
      /// Work vectors: in the factor's order, and on Gamma.
      mutable std::vector<double> local_work, interface_work;
    };
  } // namespace distributed
} // namespace impactfe

#endif
