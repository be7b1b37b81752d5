#ifndef impactfe_time_integration_free_rhs_operator_h
#define impactfe_time_integration_free_rhs_operator_h

#include <deal.II/lac/block_vector.h>
#include <deal.II/lac/sparse_matrix.h>

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
   */
  class FreeRhsOperator
  {
  public:
    /** Combine the operators of every body with @p coefficients. */
    void
    reinit(const MechanicalOperators &operators,
           const FreeRhsCoefficients &coefficients);

    /** rhs = A x + B y + gamma f. */
    void
    apply(const BlockVector<double> &x,
          const BlockVector<double> &y,
          BlockVector<double>       &rhs) const;

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
    };
    std::vector<Block> blocks;
  };
} // namespace impactfe

#endif
