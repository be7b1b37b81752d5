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
     * Each rank factorises A_i once (SparseCholesky::
     * factorize_with_trailing_block()) ordered [I_i, C_i, B_i]: its
     * interior DoFs, its contact DoFs that no other rank has, and the DoFs
     * B_i it shares with other ranks, last. The bottom block of the factor
     * gives the rank's part of the Schur complement S_B of A on B = union
     * of the B_i, which is summed over the ranks once and factorised
     * densely on every rank. A solve is then a forward substitution
     * through [I_i, C_i] of each rank's factor, one sum over the ranks of
     * a vector on B, a dense solve with S_B and the backward substitution:
     * the sparse work splits by subdomains with no communication, where a
     * distributed sparse direct solver's triangular solves are
     * latency-bound (doc/parallel.md). On one rank B is empty and a solve
     * is one solve pair.
     *
     * The same trailing blocks, summed on Gamma = B u C and factorised
     * once with C last, give the Schur complement S_C of A on the contact
     * DoFs C as the trailing block of that factor, and S_C^{-1} =
     * (A^{-1})_CC: the contact problem's products W x and its
     * preconditioner become dense products, as with the serial programs'
     * DenseSchurComplement, on every rank with no communication.
     *
     * The interface problems are dense: |Gamma|^2 numbers on every rank
     * during the set-up, |B|^2 kept. That suits a few ranks (2D: |B| of the
     * order of the cut lines' DoFs) and a few thousand contact DoFs. With
     * more contact DoFs (ContactOperator::sparse) C stays in the factors'
     * fill-reducing order, no S_C is formed, and a product with (A^{-1})_CC
     * is a pair of partial substitutions (contact_solve()).
     */
    class SubstructuredSolver
    {
    public:
      /**
       * What the contact DoFs C get in the factors, and how contact_solve()
       * applies (A^{-1})_CC.
       */
      enum class ContactOperator
      {
        /// C last in the factors; S_C and S_C^{-1} formed densely on every
        /// rank (set-up O(|Gamma|^3), |Gamma|^2 numbers; a product costs
        /// 2 |C|^2 flops, no communication).
        dense,
        /// C last in the factors, no S_C: a level that makes no contact
        /// product (the free-flight steps of a dense run).
        factors_only,
        /// C in the factors' fill-reducing order, no dense matrix on C: a
        /// contact_solve() is a forward and a backward substitution from
        /// the first contact DoF on, with the interface solve between
        /// (about one solve pair, two all-reduces). For many contacts.
        sparse,
        /// dense if its set-up is cheap and fits @p memory_limit, else
        /// sparse (initialize(); chosen_contact_operator() says which).
        automatic
      };

      /// Bytes the dense set-up needs at its peak on every rank, for an
      /// interface Gamma of @p n_gamma DoFs of which @p n_contact are
      /// contact DoFs and @p n_trailing this rank's trailing unknowns.
      static double
      dense_setup_bytes(const double n_gamma,
                        const double n_contact,
                        const double n_trailing);

      /**
       * @p subdomain_matrix, @p local_to_global and @p on_interface as
       * DistributedElasticBody::assemble_subdomain_matrix() gives them;
       * @p contact_dofs: the global DoFs C (the same list on every rank);
       * @p owned: the DoFs of the distributed vectors this rank owns.
       * @p name names the matrix in messages. @p contact_operator: see
       * ContactOperator; with `automatic` the dense operator is chosen if
       * |Gamma| <= @p largest_dense_interface, |Gamma|^2 <= 1000 times the
       * DoFs (beyond, sparse products were faster) and its set-up fits
       * @p memory_limit on every rank. An explicit `dense` beyond
       * @p memory_limit is refused with a message.
       */
      void
      initialize(
        const MPI_Comm                              communicator,
        const SparseMatrix<double>                 &subdomain_matrix,
        const std::vector<types::global_dof_index> &local_to_global,
        const std::vector<bool>                    &on_interface,
        const std::vector<types::global_dof_index> &contact_dofs,
        const IndexSet                             &owned,
        const std::string                          &name,
        const ContactOperator contact_operator        = ContactOperator::dense,
        const std::size_t     memory_limit            = std::size_t(4) << 30,
        const unsigned int    largest_dense_interface = 6000);

      /// The contact operator initialize() chose (never `automatic`).
      ContactOperator
      chosen_contact_operator() const;

      /// x = A^{-1} b.
      void
      solve(const DistributedVector &b, DistributedVector &x) const;

      /**
       * The first half of x = A^{-1} (b + c) for a c on the contact DoFs
       * that is not known yet (a time step's impulses, which depend on the
       * free velocity): @p x_contact = (A^{-1} b) on the contact DoFs, in
       * the order given to initialize(), on every rank. Costs the forward
       * substitution with the rank's factor and a small part of the
       * backward one.
       */
      void
      start_solve(const DistributedVector &b,
                  std::vector<double>     &x_contact) const;

      /**
       * The second half: x = A^{-1} (b + c), b that of the last
       * start_solve() (once per start_solve()), @p c on the contact DoFs in
       * the order given to initialize(), the same on every rank. Costs the
       * forward substitution from the contact DoFs on and the backward
       * one: with start_solve(), one solve pair, where A^{-1} b and then
       * A^{-1} c would cost one and a half.
       */
      void
      finish_solve(const std::vector<double> &c, DistributedVector &x) const;

      /// S_C and S_C^{-1} on the contact DoFs (the same on every rank);
      /// throws unless the contact operator is dense.
      const DenseSchurComplement &
      contact_schur_complement() const;

      /**
       * @p x_contact = (A^{-1} c) on the contact DoFs, for @p c on them
       * (both in the order given to initialize(), the same on every rank):
       * S_C^{-1} c with the dense operator, partial substitutions with the
       * factors with the sparse one. Not with `factors_only`.
       */
      void
      contact_solve(const std::vector<double> &c,
                    std::vector<double>       &x_contact) const;

      /// |B|, the DoFs the ranks share (none on one rank).
      unsigned int
      n_interface_dofs() const;

      /// Entries of this rank's sparse factor.
      std::size_t
      n_factor_entries() const;

    private:
      /// z[k] = b at the factor's leading positions, zero after.
      void
      load(const DistributedVector &b, double *z) const;
      /// The dense solve with S_B of b_shared + the ranks' reductions in z,
      /// into g and into z's shared part.
      void
      solve_interface(double *z, const double *b_shared, double *g) const;
      /// The contact DoFs' values from a backward substitution in @p w
      /// and from x_B (interface_work), on every rank.
      void
      contact_values(const double *w, std::vector<double> &x_contact) const;
      /// x from the leading part of z and from x_B in g.
      void
      store(const double *z, const double *g, DistributedVector &x) const;

      MPI_Comm communicator = MPI_COMM_SELF;
      bool     first_rank   = true;
      /// A_i's factor, ordered [I, C_i, B_i]: the rank's interior DoFs,
      /// its contact DoFs that no other rank has (n_leading of them in
      /// all), then those it shares; with the sparse contact operator
      /// C_i is among I, in the fill-reducing order.
      SparseCholesky                       factor;
      std::vector<types::global_dof_index> local_to_global;
      unsigned int                         n_leading = 0, n_interior = 0;
      /// Per leading position of the factor, the DoF's offset in this
      /// rank's part of the distributed vectors.
      std::vector<unsigned int> owned_offset;
      /// The position in B of each of the factor's B_i rows.
      std::vector<unsigned int> shared_position;
      /// B, the DoFs the ranks share (sorted), and the Cholesky factor of
      /// the Schur complement S_B of A on them (column-major, lower).
      std::vector<types::global_dof_index> interface_dofs;
      std::vector<double>                  interface_factor;
      /// The positions in B of the DoFs this rank owns, and their offsets.
      std::vector<std::pair<unsigned int, unsigned int>> owned_interface;
      DenseSchurComplement                               contact_schur;
      ContactOperator contact_operator = ContactOperator::factors_only;
      /// The first factor position of a contact DoF of this rank's own
      /// (n_leading if it has none): the substitutions for the contact
      /// DoFs start there.
      unsigned int first_contact_position = 0;
      /// The contact DoFs (their index in the order of initialize()) that
      /// only this rank has, with their factor position, and those in B,
      /// with their position there.
      std::vector<std::pair<unsigned int, unsigned int>> own_contacts,
        shared_contacts;
      unsigned int n_contact_dofs = 0;
      /// Work vectors: in the factor's order, on B, and solve()'s b on B;
      /// start_solve()'s forward substitution and its b on B (kept for
      /// finish_solve(), whatever solve() does in between).
      mutable std::vector<double> local_work, interface_work, shared_rhs,
        started, started_shared;
    };
  } // namespace distributed
} // namespace impactfe

#endif
