#include <deal.II/base/exceptions.h>
#include <deal.II/base/numbers.h>

#include <impactfe/time_integration/free_rhs_operator.h>
#include <impactfe/time_integration/time_integrator.h>
#include <impactfe/utilities/vectorized_kernel.h>

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
        set_up_diagonals(block);
        const Vector<double> &f = op.external_force.block(b);
        block.force.resize(n);
        for (unsigned int i = 0; i < n; ++i)
          block.force[i] = c.force * f[i];

        // the translation is taken off only where A t = M~ t: no damping
        block.component.clear();
        block.several_components = false;
        block.reference.fill(numbers::invalid_unsigned_int);
        if (C == nullptr && b < op.dof_components.size() &&
            !op.dof_components[b].empty())
          {
            AssertThrow(op.dof_components[b].size() == n,
                        ExcMessage("FreeRhsOperator: one component per DoF."));
            block.component = op.dof_components[b];
            for (const unsigned char d : block.component)
              {
                AssertThrow(d < 3,
                            ExcMessage("FreeRhsOperator: component "
                                       "out of range."));
                block.several_components |= d != 0;
              }
            // the reference DoF of each component: the first from the
            // middle of the numbering on (an interior node, as a rule)
            for (unsigned int i = n; i-- > n / 2;)
              block.reference[block.component[i]] = i;
            for (unsigned int i = n / 2; i-- > 0;)
              if (block.reference[block.component[i]] ==
                  numbers::invalid_unsigned_int)
                block.reference[block.component[i]] = i;
          }
      }
  }



  void
  FreeRhsOperator::set_up_diagonals(Block &block)
  {
    for (auto &diagonal : block.diagonals)
      diagonal.clear();
    const std::size_t n = block.row_start.size() - 1;
    if (n < 3)
      return;
    // deal.II stores a row's diagonal entry first: row i must hold
    // columns i, i - 1 (not in row 0) and i + 1 (not in row n - 1), in
    // this order, which is also the order of apply_rows()' sums
    for (std::size_t i = 0; i < n; ++i)
      {
        std::array<unsigned int, 3> expected;
        unsigned int                count = 0;
        expected[count++]                 = i;
        if (i > 0)
          expected[count++] = i - 1;
        if (i + 1 < n)
          expected[count++] = i + 1;
        if (block.row_start[i + 1] - block.row_start[i] != count)
          return;
        for (unsigned int c = 0; c < count; ++c)
          if (block.column[block.row_start[i] + c] != expected[c])
            return;
      }
    for (auto &diagonal : block.diagonals)
      diagonal.assign(n, 0.);
    for (std::size_t i = 0; i < n; ++i)
      for (unsigned int k = block.row_start[i]; k < block.row_start[i + 1]; ++k)
        {
          const unsigned int r      = block.column[k] + 1 - i;
          block.diagonals[r][i]     = block.values[2 * k];
          block.diagonals[3 + r][i] = block.values[2 * k + 1];
        }
  }



  namespace
  {
    // rhs = A (x - t) + B (y - s) + f on a tridiagonal block's rows, by
    // its diagonals (Block::diagonals), summed in the order of
    // apply_rows() below, so the result is the same to the bit.
    IMPACTFE_VECTORIZED_KERNEL void
    apply_tridiagonal_rows(const std::size_t                         n,
                           const std::array<std::vector<double>, 6> &diag,
                           const double                             *x,
                           const double                             *y,
                           const double                             *force,
                           const double                              t,
                           const double                              s,
                           double *__restrict out)
    {
      const double *al = diag[0].data(), *ad = diag[1].data(),
                   *au = diag[2].data(), *bl = diag[3].data(),
                   *bd = diag[4].data(), *bu = diag[5].data();
      out[0] = (ad[0] * (x[0] - t) + au[0] * (x[1] - t)) +
               (bd[0] * (y[0] - s) + bu[0] * (y[1] - s)) + force[0];
      for (std::size_t i = 1; i + 1 < n; ++i)
        out[i] = (ad[i] * (x[i] - t) + al[i] * (x[i - 1] - t) +
                  au[i] * (x[i + 1] - t)) +
                 (bd[i] * (y[i] - s) + bl[i] * (y[i - 1] - s) +
                  bu[i] * (y[i + 1] - s)) +
                 force[i];
      const std::size_t l = n - 1;
      out[l]              = (ad[l] * (x[l] - t) + al[l] * (x[l - 1] - t)) +
               (bd[l] * (y[l] - s) + bl[l] * (y[l - 1] - s)) + force[l];
    }



    // v_i += t for every entry: one component's translation.
    IMPACTFE_VECTORIZED_KERNEL void
    add_to_every_entry(const std::size_t n, const double t, double *v)
    {
      for (std::size_t i = 0; i < n; ++i)
        v[i] += t;
    }



    // rhs = A (x - t) + B (y - s) + f on one block's rows; Component(k)
    // gives the component of column k (constant 0 for one component).
    template <typename Component>
    void
    apply_rows(const unsigned int           n,
               const unsigned int          *start,
               const unsigned int          *col,
               const double                *ab,
               const double                *xb,
               const double                *yb,
               const double                *force,
               const std::array<double, 3> &t,
               const std::array<double, 3> &s,
               const Component             &component,
               double                      *out)
    {
      for (unsigned int i = 0; i < n; ++i)
        {
          double sum_x = 0., sum_y = 0.;
          for (unsigned int k = start[i]; k < start[i + 1]; ++k)
            {
              const unsigned int j = col[k];
              const unsigned int d = component(j);
              sum_x += ab[2 * k] * (xb[j] - t[d]);
              sum_y += ab[2 * k + 1] * (yb[j] - s[d]);
            }
          out[i] = sum_x + sum_y + force[i];
        }
    }
  } // namespace



  void
  FreeRhsOperator::apply(const BlockVector<double> &x,
                         const BlockVector<double> &y,
                         BlockVector<double>       &rhs,
                         Translations              &translation) const
  {
    AssertDimension(x.n_blocks(), blocks.size());
    translation.resize(blocks.size());
    for (unsigned int b = 0; b < blocks.size(); ++b)
      {
        const Block       &block = blocks[b];
        const unsigned int n     = block.force.size();
        AssertDimension(x.block(b).size(), n);
        AssertDimension(y.block(b).size(), n);
        AssertDimension(rhs.block(b).size(), n);
        const double         *xb = x.block(b).begin();
        const double         *yb = y.block(b).begin();
        std::array<double, 3> t = {{0., 0., 0.}}, s = {{0., 0., 0.}};
        const unsigned char  *component = block.component.data();
        if (!block.component.empty())
          for (unsigned int d = 0; d < 3; ++d)
            if (block.reference[d] != numbers::invalid_unsigned_int)
              {
                t[d] = xb[block.reference[d]];
                s[d] = yb[block.reference[d]];
              }
        translation[b]  = t;
        const auto rows = [&](const auto &component_of) {
          apply_rows(n,
                     block.row_start.data(),
                     block.column.data(),
                     block.values.data(),
                     xb,
                     yb,
                     block.force.data(),
                     t,
                     s,
                     component_of,
                     rhs.block(b).begin());
        };
        // one component (1D, or no translation): no lookup per entry
        if (!block.diagonals[0].empty() && !block.several_components)
          apply_tridiagonal_rows(n,
                                 block.diagonals,
                                 xb,
                                 yb,
                                 block.force.data(),
                                 t[0],
                                 s[0],
                                 rhs.block(b).begin());
        else if (!block.several_components)
          rows([](unsigned int) { return 0u; });
        else
          rows([component](unsigned int j) { return unsigned(component[j]); });
      }
  }



  void
  FreeRhsOperator::add_translation(const Translations  &translation,
                                   BlockVector<double> &v) const
  {
    AssertDimension(translation.size(), blocks.size());
    for (unsigned int b = 0; b < blocks.size(); ++b)
      {
        const Block &block = blocks[b];
        if (block.component.empty())
          continue;
        double                      *vb = v.block(b).begin();
        const std::array<double, 3> &t  = translation[b];
        const std::size_t            n  = block.component.size();
        if (!block.several_components)
          add_to_every_entry(n, t[0], vb);
        else
          for (std::size_t i = 0; i < n; ++i)
            vb[i] += t[block.component[i]];
      }
  }



  bool
  FreeRhsOperator::tridiagonal(const unsigned int b) const
  {
    AssertIndexRange(b, blocks.size());
    return !blocks[b].diagonals[0].empty();
  }



  std::size_t
  FreeRhsOperator::memory_consumption() const
  {
    std::size_t bytes = blocks.capacity() * sizeof(Block);
    for (const Block &block : blocks)
      bytes +=
        block.component.capacity() +
        (block.row_start.capacity() + block.column.capacity()) *
          sizeof(unsigned int) +
        (block.values.capacity() + block.force.capacity()) * sizeof(double);
    for (const Block &block : blocks)
      for (const auto &diagonal : block.diagonals)
        bytes += diagonal.capacity() * sizeof(double);
    return bytes;
  }
} // namespace impactfe
