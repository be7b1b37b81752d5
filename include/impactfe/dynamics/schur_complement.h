#ifndef impactfe_dynamics_schur_complement_h
#define impactfe_dynamics_schur_complement_h

#include <deal.II/base/types.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  class SparseCholesky;

  /**
   * The Schur complement S = A_CC - A_CI A_II^{-1} A_IC of a symmetric
   * positive definite matrix A on a set C of its unknowns, and its inverse
   * S^{-1} = (A^{-1})_CC, both dense.
   *
   * Why: with A = M~ and C the contact DoFs of the rigid-obstacle
   * candidates, H^T S^{-1} H is the Delassus operator W and H^T S H its
   * inverse when H is square (the active set method's preconditioner). A
   * product with either is then one dense symmetric matrix-vector product,
   * |C|^2 / 2 numbers read, instead of a solve pair with the sparse factor
   * of M~ (4 nnz(L) flops, and as many again for the preconditioner's
   * interior solve). In 3D, where nnz(L) grows like n^(4/3) and the contact
   * surface like n^(2/3), that is the cheaper product by far.
   *
   * Both are computed from one Cholesky factorisation of A that eliminates
   * C last (SparseCholesky::factorize_with_trailing_block()): S = L_CC
   * L_CC^T and S^{-1} from L_CC (LAPACK dpotri), O(|C|^3) flops once, and
   * no solve per contact DoF.
   *
   * Where A holds several bodies, the unknowns of C split into groups
   * that S does not couple (its entries between them are zeros: the
   * elimination never connects disconnected parts). Then only the groups'
   * diagonal blocks are kept, and a product reads sum |C_g|^2 / 2 numbers
   * instead of |C|^2 / 2: a chain of 64 bars has 64 groups of at most 20
   * contact DoFs in place of one of 1260 (n_groups()).
   */
  class DenseSchurComplement
  {
  public:
    /**
     * Compute S and S^{-1} of @p matrix on @p dofs. @p name names the
     * matrix in messages.
     */
    void
    compute(const SparseMatrix<double>                 &matrix,
            const std::vector<types::global_dof_index> &dofs,
            const std::string                          &name);

    /**
     * S and S^{-1} on @p dofs from the Cholesky factor @p factor of S
     * (dense, lower triangular, column-major, dofs.size() squared), as the
     * trailing block of a factorisation that eliminates @p dofs last gives
     * it (the substructured solves of the distributed programs).
     */
    void
    compute_from_factor(const std::vector<types::global_dof_index> &dofs,
                        std::vector<double>                         factor,
                        const std::string                          &name);
    /** Throws, naming @p name, if S on @p n DoFs cannot be dense. */
    static void
    check_dense_size(const std::size_t n, const std::string &name);
    /** The unknowns C, in the order of the vectors below. */
    const std::vector<types::global_dof_index> &
    dofs() const;

    /** |C|. */
    unsigned int
    size() const;

    /** y = S x (x, y of size() entries, in the order of dofs()). */
    void
    vmult(const double *x, double *y) const;

    /**
     * y = S x with S rounded to single precision: half the memory traffic
     * of vmult(), for a preconditioner (the active set method's flexible
     * GMRES keeps the preconditioned vectors, so this costs it no
     * accuracy).
     */
    void
    vmult_single_precision(const double *x, double *y) const;
    /** y = S^{-1} x. */
    void
    vmult_inverse(const double *x, double *y) const;

    /**
     * y += part @p part of n_parts of S^{-1} x (@p use_inverse) or of S x
     * in single precision (as vmult_single_precision()): the parts split
     * the stored triangle by columns into pieces of equal size, each entry
     * read once, so that ranks that all hold S split a product evenly and
     * sum their y (the distributed programs). The sum over the parts is
     * the product.
     */
    void
    add_part_of_product(const double      *x,
                        double            *y,
                        const unsigned int part,
                        const unsigned int n_parts,
                        const bool         use_inverse) const;

    std::size_t
    memory_consumption() const;

    /** The groups of unknowns that S does not couple (1 if it is one). */
    unsigned int
    n_groups() const;

    /**
     * Whether the dense products are cheaper than the sparse ones: the two
     * dense matrices (|C|^2 numbers read per pair of products, S also in
     * single precision) against a
     * solve pair with each of two factors of about @p n_factor_entries
     * entries, and at most @p memory_limit bytes for the two matrices.
     */
    static bool
    pays_off(const std::size_t n_contact_dofs,
             const std::size_t n_factor_entries,
             const std::size_t memory_limit = std::size_t(1) << 30);

  private:
    /// The columns of part @p part of n_parts (add_part_of_product()).
    std::pair<unsigned int, unsigned int>
    part_columns(const unsigned int part, const unsigned int n_parts) const;

    std::vector<types::global_dof_index> contact_dofs;
    /// S and S^{-1}, column-major; their lower triangles are used.
    std::vector<double> schur, inverse;
    /// S in single precision, and the vectors of its product.
    std::vector<float>         schur_single;
    mutable std::vector<float> x_single, y_single;

    /// With several groups: each group's positions in dofs() and its
    /// diagonal blocks of S, S^{-1} and S in single precision (lower
    /// triangles, column-major); schur, inverse and schur_single are then
    /// empty.
    struct Group
    {
      std::vector<unsigned int> index;
      std::vector<double>       schur, inverse;
      std::vector<float>        schur_single;
    };
    std::vector<Group>          groups;
    mutable std::vector<double> x_group, y_group;

    /// The groups of the n unknowns that the dense S and S^{-1} (lower
    /// triangles) do not couple, with their blocks; none if they are one
    /// (compute_from_factor()).
    static std::vector<Group>
    find_groups(const std::size_t          n,
                const std::vector<double> &schur,
                const std::vector<double> &inverse);
    /// y += the product of group @p g with x: S^{-1} (@p use_inverse), S,
    /// or S in single precision (@p single_precision).
    void
    group_product(const unsigned int g,
                  const double      *x,
                  double            *y,
                  const bool         use_inverse,
                  const bool         single_precision) const;
    /// y = the product of every group with x (as group_product()).
    void
    all_groups_product(const double *x,
                       double       *y,
                       const bool    use_inverse,
                       const bool    single_precision) const;
  };


  /**
   * The Schur complement S = A_CC - A_CI A_II^{-1} A_IC of a sparse
   * symmetric positive definite matrix A on a set C of its unknowns,
   * applied without forming it: a product S y is a sparse product with
   * the rows of A on C, one solve pair with the Cholesky factor of A_II
   * and a sparse product back.
   *
   * Optionally in rotated node frames: the unknowns of a node (its DoFs
   * @p dofs) are replaced by the components along the rows of an
   * orthogonal @p rotation, A' = Q A Q^T, and C may name single rotated
   * components (the k-th rotated unknown of a node sits in the slot of
   * its k-th DoF). With the contact normals as first rows, S' on the
   * normal slots is the inverse of the normal block W_NN of the Delassus
   * operator: the exact preconditioner of frictionless contact, and of
   * the normal rows of sliding contacts (doc/lcp.md, "Large contact
   * sets").
   *
   * Those products invert W_NN on all of C. The active set method needs
   * the inverse of the operator of its rows at the current contact states
   * instead: the closed contacts' normals (the open ones' slots belong to
   * the interior) and the sticking ones' tangents, with K = H_C^T A^{-1}
   * H_s, H_s = n + mu t_d (t_d the slip direction) for sliding contacts.
   * S is the worse an approximation of that the more contacts are open or
   * stick and the larger mu is (doc/lcp.md, "Large friction
   * coefficients"). set_contact_states() makes the products apply K^{-1}
   * exactly: the multiplier of the bordered system [A H_s; H_C^T 0], one
   * solve with A_RR - S A_NR (C': the closed normals and sticking
   * tangents, R: the other unknowns; A_RR with the tangential rows of each
   * sliding node minus its skew s times its normal row). That matrix has
   * A's pattern but is unsymmetric: an LU factorisation, redone whenever
   * the states change.
   */
  class SparseSchurComplement
  {
  public:
    /// The DoFs of one node and the rotation of its unknowns (row k: the
    /// k-th new unknown's coefficients on @p dofs).
    struct NodeFrame
    {
      std::vector<types::global_dof_index> dofs;
      std::array<std::array<double, 3>, 3> rotation{};

      /**
       * The frame of 1 to 3 @p dofs whose first row is the unit vector
       * @p normal (one coefficient per DoF), completed to an orthonormal
       * basis: in 2D by its perpendicular, in 3D by the axis least aligned
       * with it made orthogonal to it, and their cross product. Throws if
       * the sizes differ or @p normal is not of unit length.
       */
      static NodeFrame
      with_normal(const std::vector<types::global_dof_index> &dofs,
                  const std::vector<double>                  &normal);
    };

    SparseSchurComplement();
    ~SparseSchurComplement();
    SparseSchurComplement(SparseSchurComplement &&) noexcept;
    SparseSchurComplement &
    operator=(SparseSchurComplement &&) noexcept;

    /**
     * Set up S of @p matrix (rotated by @p frames, if any) on @p dofs. The
     * rotation needs the DoFs of a node to have the same couplings (as
     * those of a vector-valued element do); returns false, and leaves the
     * object empty, if they do not. @p name names the matrix in messages.
     * @p for_contact_states keeps what set_contact_states() needs (a copy of
     * A).
     */
    bool
    initialize(const SparseMatrix<double>                 &matrix,
               const std::vector<types::global_dof_index> &dofs,
               const std::string                          &name,
               const std::vector<NodeFrame>               &frames = {},
               const bool for_contact_states                      = false);

    /// The states of set_contact_states().
    static constexpr unsigned char open_state = 0, slide_state = 1,
                                   stick_state = 2;

    /**
     * The contact states whose normal rows (and sticking tangents) the
     * products invert (class documentation), per frame in the order given
     * to initialize() (with @p for_contact_states, whose @p dofs must then
     * be the frames' first DoFs, the normal slots): open_state,
     * slide_state (the normal closed, the tangents free but for the skew)
     * or stick_state (every unknown of the node closed), and the skew s of
     * a sliding one (s[l] for the rotated unknowns l = 1, 2, the
     * coordinates of mu times the slip direction in the frame; s[0] is not
     * read). The products then take and give values on the closed slots
     * C': the normal slot of a closed frame, and the tangential slots of a
     * sticking one (the rotated unknowns). Empty @p states: the products
     * are those of S again. Otherwise A_RR - S A_NR is factorised (the
     * analysis once), unless the products already invert states that
     * differ from @p states in at most @p max_stale_states contacts (a
     * contact differs if its state does, or its skew by more than
     * @p skew_tolerance): the products keep those, and factored_states()
     * says which they are. Returns whether it factorised. Throws, leaving
     * the products those of S, if that matrix is singular.
     */
    bool
    set_contact_states(const std::vector<unsigned char>         &states,
                       const std::vector<std::array<double, 3>> &skew,
                       const double       skew_tolerance   = 0.,
                       const unsigned int max_stale_states = 0);

    /// Whether the products invert the normal operator of contact states
    /// (set_contact_states()) rather than apply S.
    bool
    inverts_contact_states() const;

    /// The states that the products invert (set_contact_states()).
    const std::vector<unsigned char> &
    factored_states() const;

    /// The unknowns C (sorted).
    const std::vector<types::global_dof_index> &
    dofs() const;

    /**
     * (S y)_C into @p out on C, for @p y zero off C (full vectors; @p out
     * and @p work are overwritten off C).
     */
    void
    vmult(const Vector<double> &y,
          Vector<double>       &out,
          Vector<double>       &work) const;

    /**
     * The same with the solve of A_II in single precision
     * (SparseCholesky::solve_single_precision()), for a preconditioner
     * inside a flexible Krylov method: 8 % less time per step of the
     * active set method on the thin slab at 10^4 contacts, the same
     * iteration counts.
     */
    void
    vmult_single_precision(const Vector<double> &y,
                           Vector<double>       &out,
                           Vector<double>       &work) const;

    /// Entries of the factor of A_II.
    std::size_t
    n_factor_entries() const;

  private:
    void
    apply(const Vector<double> &y,
          Vector<double>       &out,
          Vector<double>       &work,
          const bool            single_precision) const;

    std::vector<types::global_dof_index> contact_dofs;
    /// The rows of A (or A') on C in compressed rows (k-th DoF of C:
    /// entries start[k] to start[k + 1]); A is symmetric, so they are its
    /// columns on C as well.
    std::vector<std::size_t>             row_start;
    std::vector<types::global_dof_index> row_column;
    std::vector<double>                  row_value;
    std::unique_ptr<SparseCholesky>      interior;

    /// The frames' unknowns (normal slot first); is_contact[i]: DoF i is
    /// in C' (set_contact_states()).
    std::vector<std::array<types::global_dof_index, 3>> frame_dofs;
    std::vector<unsigned char>                          frame_size;
    std::vector<unsigned char>                          is_contact;
    /// For set_contact_states() (initialize() with for_contact_states): A
    /// rotated, the matrix of the states and its LU factors (in one object, so
    /// that the matrices' pattern does not move), and the states it holds.
    struct StateMatrix;
    std::unique_ptr<StateMatrix>       state_matrix;
    std::vector<unsigned char>         state_code;
    std::vector<std::array<double, 3>> state_skew;
    bool                               for_states = false;
  };
} // namespace impactfe

#endif
