#ifndef impactfe_time_integration_free_rhs_operator_h
#define impactfe_time_integration_free_rhs_operator_h

#include <deal.II/lac/block_vector.h>
#include <deal.II/lac/sparse_matrix.h>

#include <array>
#include <cstddef>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  struct MechanicalOperators;

  /**
   * The coefficients of a scheme's free right-hand side
   *
   *   F~ = (M + a_C C + a_K K) x + b_K K y + gamma f,
   *
   * with x and y the state's v and u (Newmark: its predictors), fixed while
   * h is fixed (time_integrator.h, ../shared/spec/schemes.md).
   */
  struct FreeRhsCoefficients
  {
    double velocity_damping       = 0.; ///< a_C
    double velocity_stiffness     = 0.; ///< a_K
    double displacement_stiffness = 0.; ///< b_K
    double force                  = 0.; ///< gamma
  };



  /**
   * F~ of FreeRhsCoefficients in one pass over the rows. The matrices
   * A = M + a_C C + a_K K and B = b_K K of each body are combined once, in
   * compressed rows on the body's sparsity pattern (M, C and K share it),
   * with gamma f. A step then reads each row of A and B once: no work
   * vector, no separate products and sums, no thread dispatch, where three
   * deal.II products with their sums took most of a step's time on small
   * meshes (doc/performance.md).
   *
   * **Relative to the rigid translation.** A body that slides or flies
   * far has x and y dominated by a translation t (t_d on every DoF of
   * component d), for which K t = 0 holds in exact arithmetic only: the
   * round-off of K's row sums times |t| put spurious forces into every
   * step, and the momentum balance of a block sliding at 1 m/s on 2.5e5
   * DoFs was off by 1.9e-7 after 11 steps. Since A t = M t = M~ t for a
   * body without damping (a_K, c_K multiply K, and M's coefficient is 1 in
   * both), the solution of M~ v = A x + B y + gamma f is v = t +
   * M~^{-1} (A (x - t) + B (y - s) + gamma f) for any translations t and
   * s: apply() takes off x and y of one reference DoF per component (any
   * node's motion is within the vibrations of the body's translation; a
   * mean would cost two more passes, 7 % of a 1D step) and
   * add_translation() adds t back to the solution (the balance above:
   * 4.2e-12). A body with damping is left as it is (C t need not be zero:
   * Rayleigh's a M).
   */
  class FreeRhsOperator
  {
  public:
    /// Per body, the translation t_d taken off x per component d.
    using Translations = std::vector<std::array<double, 3>>;

    /**
     * Combine the operators of every body with @p coefficients.
     * operators.dof_components gives each DoF's component (empty for a
     * body: no translation taken off).
     */
    void
    reinit(const MechanicalOperators &operators,
           const FreeRhsCoefficients &coefficients);

    /**
     * rhs = A (x - t) + B (y - s) + gamma f with t and s the values of x
     * and y at the reference DoF of each body and component (zero for a
     * body with damping), and t in
     * @p translation: the solve of M~ v = rhs is then completed by
     * add_translation().
     */
    void
    apply(const BlockVector<double> &x,
          const BlockVector<double> &y,
          BlockVector<double>       &rhs,
          Translations              &translation) const;

    /** v += t per body and component (the translation of apply()). */
    void
    add_translation(const Translations  &translation,
                    BlockVector<double> &v) const;

    /**
     * Whether body @p b's rows are applied by their diagonals (a
     * tridiagonal pattern: a 1D body numbered along its cells).
     */
    bool
    tridiagonal(const unsigned int b) const;

    /** Bytes held. */
    std::size_t
    memory_consumption() const;

  private:
    struct Block
    {
      std::vector<unsigned int> row_start;
      std::vector<unsigned int> column;
      /// Entries of A and B, interleaved: a_0, b_0, a_1, b_1, ...
      std::vector<double> values;
      std::vector<double> force;
      /// Component of each DoF (empty: no translation taken off), and
      /// whether any is not 0 (else the row kernel needs no lookup).
      std::vector<unsigned char> component;
      bool                       several_components = false;
      /// A DoF of each component (invalid for a component no DoF has):
      /// t_d and s_d are x and y there.
      std::array<unsigned int, 3> reference = {{0, 0, 0}};
      /// A tridiagonal pattern (a 1D body numbered along its cells) also
      /// keeps A's and B's three diagonals as arrays of their own:
      /// diagonals[3 m + r][i] holds the entry of row i, column i - 1 + r
      /// of A (m = 0) or B (m = 1), so that a row needs no column index
      /// and the rows' loop vectorises. Empty for any other pattern.
      std::array<std::vector<double>, 6> diagonals;
    };
    std::vector<Block> blocks;

    /// Fill Block::diagonals if the block's pattern is tridiagonal.
    static void
    set_up_diagonals(Block &block);
  };
} // namespace impactfe

#endif
