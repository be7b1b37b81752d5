#include <deal.II/base/exceptions.h>

#include <impactfe/time_integration/free_rhs_operator.h>
#include <impactfe/time_integration/time_integrator.h>

namespace impactfe
{
  // The entries of M, C and K are read row by row with deal.II's iterators,
  // in the order of the shared sparsity pattern; a matrix on another pattern
  // is refused (the step matrix M~ is built on the same one).
  void
  FreeRhsOperator::reinit(const MechanicalOperators &op,
                          const FreeRhsCoefficients &c)
  {
    const unsigned int n_blocks = op.mass.size();
    AssertThrow(op.stiffness.size() == n_blocks &&
                  op.damping.size() == n_blocks &&
                  op.external_force.n_blocks() == n_blocks,
                ExcMessage("FreeRhsOperator: one mass, stiffness and damping "
                           "matrix and one load block per body."));
    blocks.resize(n_blocks);
    for (unsigned int b = 0; b < n_blocks; ++b)
      {
        const SparseMatrix<double> &M = *op.mass[b];
        const SparseMatrix<double> &K = *op.stiffness[b];
        const SparseMatrix<double> *C = op.damping[b];
        AssertThrow(&M.get_sparsity_pattern() == &K.get_sparsity_pattern() &&
                      (C == nullptr ||
                       &M.get_sparsity_pattern() == &C->get_sparsity_pattern()),
                    ExcMessage("FreeRhsOperator: the mass, stiffness and "
                               "damping matrices of a body must share one "
                               "sparsity pattern."));
        Block             &block = blocks[b];
        const unsigned int n     = M.m();
        block.row_start.assign(1, 0);
        block.row_start.reserve(n + 1);
        block.column.clear();
        block.values.clear();
        block.column.reserve(M.n_nonzero_elements());
        block.values.reserve(2 * M.n_nonzero_elements());
        for (unsigned int i = 0; i < n; ++i)
          {
            auto k = K.begin(i);
            auto d = C != nullptr ? C->begin(i) : M.begin(i);
            for (auto m = M.begin(i); m != M.end(i); ++m, ++k)
              {
                double a = m->value() + c.velocity_stiffness * k->value();
                if (C != nullptr)
                  {
                    a += c.velocity_damping * d->value();
                    ++d;
                  }
                block.column.push_back(m->column());
                block.values.push_back(a);
                block.values.push_back(c.displacement_stiffness * k->value());
              }
            block.row_start.push_back(block.column.size());
          }
        const Vector<double> &f = op.external_force.block(b);
        block.force.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          block.force[i] = c.force * f[i];
      }
  }



  void
  FreeRhsOperator::apply(const BlockVector<double> &x,
                         const BlockVector<double> &y,
                         BlockVector<double>       &rhs) const
  {
    AssertDimension(x.n_blocks(), blocks.size());
    for (unsigned int b = 0; b < blocks.size(); ++b)
      {
        const Block        &block = blocks[b];
        const unsigned int  n     = block.force.size();
        const unsigned int *start = block.row_start.data();
        const unsigned int *col   = block.column.data();
        const double       *ab    = block.values.data();
        const double       *xb    = x.block(b).begin();
        const double       *yb    = y.block(b).begin();
        double             *out   = rhs.block(b).begin();
        AssertDimension(x.block(b).size(), n);
        AssertDimension(y.block(b).size(), n);
        AssertDimension(rhs.block(b).size(), n);
        for (unsigned int i = 0; i < n; ++i)
          {
            double sum_x = 0., sum_y = 0.;
            for (unsigned int k = start[i]; k < start[i + 1]; ++k)
              {
                sum_x += ab[2 * k] * xb[col[k]];
                sum_y += ab[2 * k + 1] * yb[col[k]];
              }
            out[i] = sum_x + sum_y + block.force[i];
          }
      }
  }



  std::size_t
  FreeRhsOperator::memory_consumption() const
  {
    std::size_t bytes = blocks.capacity() * sizeof(Block);
    for (const Block &block : blocks)
      bytes +=
        (block.row_start.capacity() + block.column.capacity()) *
          sizeof(unsigned int) +
        (block.values.capacity() + block.force.capacity()) * sizeof(double);
    return bytes;
  }
} // namespace impactfe
