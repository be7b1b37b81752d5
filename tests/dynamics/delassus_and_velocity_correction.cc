// The Delassus operator and the velocity correction of MultibodySystem,
// checked against an independent computation.
//
// Scene: an elastic block (plane strain, 6 x 3 Q1 cells) thrown down and
// sideways onto a rigid plane with Coulomb friction (mu = 0.3), theta-Euler.
//  - W = H^T M~^{-1} H, which the system computes column block by column
//    block with its Cholesky factorisation when candidates first enter an
//    LCP, is compared with W built here from deal.II's UMFPACK LU of
//    M~ = M + c_K K (one solve per column): relative difference <= 1e-12;
//    W is symmetric to rounding.
//  - The velocity correction v = v_free + M~^{-1} H P is done either as a
//    sum of stored columns M~^{-1} H_j (default) or as one more solve (no
//    column storage). Both runs must give the same velocities at every step
//    (relative difference <= 1e-12) and the same contact states.
//  - The impulse balance of the block: change of momentum = sum of the
//    impulses H P (the plane is the only external force), per step.


#include <deal.II/lac/sparse_direct.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/dynamics/multibody_system.h>

#include <memory>

#include "../tests.h"

#include "elastic_block.h"

using namespace impactfe;
using namespace impactfe_tests;

namespace
{
  struct Scene
  {
    std::unique_ptr<ElasticBody<2>>     block;
    std::unique_ptr<MultibodySystem<2>> system;

    explicit Scene(const std::size_t column_storage_budget)
    {
      block = make_elastic_block();

      const TimeSteppingParameters time_stepping = block_time_stepping();
      ContactSolverParameters      solver;
      system = std::make_unique<MultibodySystem<2>>(time_stepping, solver, 2);
      system->add_body(*block);
      system->contacts().add_node_to_plane(
        system->bodies(), 0, 2, Point<2>(0., 0.), Tensor<1, 2>({0., 1.}), 0.3);
      system->set_column_storage_budget(column_storage_budget);
      Vector<double> &v        = system->state().velocity.block(0);
      const auto     &vertices = block->triangulation().get_vertices();
      for (unsigned int i = 0; i < vertices.size(); ++i)
        {
          v(block->vertex_dof(i, 0)) = 0.3;
          v(block->vertex_dof(i, 1)) = -(0.2 + 1.6 * vertices[i][0] / 0.6);
        }
      system->setup();
    }
  };

  double
  max_abs(const Vector<double> &v)
  {
    return v.linfty_norm();
  }
} // namespace



int
main()
{
  initlog();
  Scene stored(64 << 20), solved(0);

  // Independent W: UMFPACK LU of M~ = M + c_K K, one solve per column.
  const ElasticBody<2> &block = *stored.block;
  SparseMatrix<double>  step_matrix(block.sparsity_pattern());
  step_matrix.copy_from(block.mass_matrix());
  step_matrix.add(stored.system->integrator().stiffness_coefficient(),
                  block.stiffness_matrix());
  SparseDirectUMFPACK lu;
  lu.factorize(step_matrix);
  const ContactSet   &contacts  = stored.system->contacts();
  const unsigned int  n_columns = contacts.n_columns();
  BlockVector<double> column(
    std::vector<types::global_dof_index>{block.n_dofs()});

  double max_abs_difference = 0., max_steps_difference = 0.,
         max_balance_error         = 0.;
  unsigned int n_state_differences = 0, max_active = 0, n_sliding_steps = 0;
  const Tensor<1, 2> p0 = stored.system->momentum(0);
  Tensor<1, 2>       impulse;
  const double       h = 2e-3;
  for (unsigned int step = 0; step < 60; ++step)
    {
      const StepReport a = stored.system->do_time_step();
      const StepReport b = solved.system->do_time_step();
      max_active         = std::max(max_active, a.active_contacts);
      n_sliding_steps += a.tangential_force > 0. ? 1 : 0;
      Vector<double> difference(stored.system->state().velocity.block(0));
      difference -= solved.system->state().velocity.block(0);
      max_steps_difference =
        std::max(max_steps_difference,
                 max_abs(difference) /
                   max_abs(stored.system->state().velocity.block(0)));
      if (stored.system->active_set() != solved.system->active_set())
        ++n_state_differences;
      impulse += stored.system->contact_force(0) * h;
      max_balance_error =
        std::max(max_balance_error,
                 (stored.system->momentum(0) - p0 - impulse).norm() /
                   p0.norm());
    }

  const lcp::DenseMatrix &W         = stored.system->delassus_operator();
  double                  max_entry = 0., max_asymmetry = 0.;
  for (unsigned int j = 0; j < n_columns; ++j)
    {
      column = 0.;
      contacts.add_column(j, 1., column);
      lu.solve(column.block(0));
      for (unsigned int i = 0; i < n_columns; ++i)
        {
          const double w = contacts.column_dot(i, column);
          max_entry      = std::max(max_entry, std::abs(w));
          max_abs_difference =
            std::max(max_abs_difference, std::abs(W(i, j) - w));
          max_asymmetry = std::max(max_asymmetry, std::abs(W(i, j) - W(j, i)));
        }
    }

  deallog << "Block 6 x 3 cells, " << contacts.n_candidates() << " candidates, "
          << n_columns << " columns of W; up to " << max_active
          << " active contacts, " << n_sliding_steps
          << " of 60 steps with a tangential force" << std::endl;
  check(max_active == contacts.n_candidates(),
        "all bottom nodes come into contact");
  check(n_sliding_steps > 0, "friction acts");
  check(max_abs_difference <= 1e-12 * max_entry,
        "W = H^T M~^{-1} H against UMFPACK, relative difference <= 1e-12");
  check(max_asymmetry <= 1e-12 * max_entry, "W symmetric to rounding");
  check(max_steps_difference <= 1e-12,
        "stored columns and one solve give the same velocities");
  check(n_state_differences == 0, "and the same active sets");
  check(max_balance_error <= 1e-12,
        "change of momentum = sum of the impulses at every step");
  return n_failed_checks == 0 ? 0 : 1;
}
