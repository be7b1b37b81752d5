// A linear (visco)elastic body on a distributed mesh (p4est) with Trilinos
// matrices and vectors: the distributed counterpart of ElasticBody for
// meshes that do not fit one process (issue 14, doc/parallel.md).
#ifndef impactfe_parallel_distributed_body_h
#define impactfe_parallel_distributed_body_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/tensor.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <impactfe/bodies/cell_operators.h>
#include <impactfe/bodies/elastic_body.h>
#include <impactfe/bodies/material.h>

#include <functional>
#include <map>
#include <utility>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  namespace distributed
  {
    using DistributedVector = TrilinosWrappers::MPI::Vector;
    using DistributedMatrix = TrilinosWrappers::SparseMatrix;

    /**
     * Q1 vector-valued body on a parallel::distributed::Triangulation. Each
     * rank assembles its locally owned cells with the element operators of
     * the serial ElasticBody (integrate_cell_operators()), so the two give
     * the same M, K, C and body force, with mass redistribution
     * (redistribute_mass()) as well.
     */
    template <int dim>
    class DistributedElasticBody
    {
    public:
      /// @p out_of_plane_measure: the thickness in 2D [m] (1 in 3D), as
      /// for the serial ElasticBody.
      DistributedElasticBody(const MPI_Comm                  communicator,
                             const MaterialParameters       &material,
                             const DiscretizationParameters &discretization,
                             const double out_of_plane_measure = 1.);

      parallel::distributed::Triangulation<dim> &
      triangulation();
      const parallel::distributed::Triangulation<dim> &
      triangulation() const;

      /// The acceleration of gravity [m/s^2], set before setup(): the body
      /// force density is rho g with each cell's density.
      void
      set_gravity(const Tensor<1, dim> &acceleration);

      /**
       * The material of the cells with material id @p part (a second body
       * held in the same mesh, merge_body_meshes()); the other cells keep
       * the body's. Set before setup(). Its Rayleigh coefficients must be
       * the body's (C's Rayleigh terms are combinations of the whole M and
       * K).
       */
      void
      set_part_material(const types::material_id  part,
                        const MaterialParameters &material);

      /// Distribute the DoFs, build the sparsity and assemble M, K, C, f.
      void
      setup();

      /**
       * Mass redistribution (ElasticBody::redistribute_mass(), the cells'
       * rule redistribute_cell_mass()): the nodes whose DoFs are in @p
       * massless_dofs (the same list on every rank, each node's DoFs, e.g.
       * the contact candidates') carry no mass. Re-assembles M, K, C and
       * f after setup(); the body force then follows the mass, f = M g,
       * as in the serial body. Throws if a cell would keep no mass.
       */
      void
      redistribute_mass(
        const std::vector<types::global_dof_index> &massless_dofs);

      /// The DoFs of redistribute_mass(), sorted (empty without it).
      const std::vector<types::global_dof_index> &
      massless_dofs() const;

      MPI_Comm
      communicator() const;
      const DoFHandler<dim> &
      dof_handler() const;
      const IndexSet &
      locally_owned_dofs() const;
      const IndexSet &
      locally_relevant_dofs() const;
      const MaterialParameters &
      material() const;

      const DistributedMatrix &
      mass_matrix() const;
      const DistributedMatrix &
      stiffness_matrix() const;
      /// C = viscous matrix + Rayleigh terms (zero matrix without damping).
      const DistributedMatrix &
      damping_matrix() const;
      bool
      has_damping() const;
      const DistributedVector &
      external_force() const;

      /// 1^T M 1 per component (the same for all components).
      double
      total_mass() const;

      /**
       * The shortest time a longitudinal wave takes to cross a mean cell,
       * dx / c_p [s], with dx = (V / N)^(1/dim) over the cells of one
       * material id (one body of a merged mesh) and c_p of that part's
       * material: the minimum over the parts. For one body it equals
       * ElasticBody::cell_transit_time() (the same sums, over all ranks).
       * Collective.
       */
      double
      cell_transit_time() const;

      /// @p value at every node (all components) of the cells with
      /// material id @p part (all cells by default: one body); the other
      /// entries are left as they are.
      void
      fill_uniform(
        DistributedVector       &vector,
        const Tensor<1, dim>    &value,
        const types::material_id part = numbers::invalid_material_id) const;

      /**
       * This rank's subdomain matrix a M + b K + c C (@p mass_coefficient,
       * @p stiffness_coefficient, @p damping_coefficient), assembled from
       * the locally owned cells only, so that the sum over the ranks is
       * the distributed matrix. Its rows are numbered locally: @p
       * local_to_global holds the global DoF of each row (sorted), and
       * @p on_interface marks those that cells of other ranks share. For
       * the substructured solves (SubstructuredSolver).
       */
      void
      assemble_subdomain_matrix(
        const double                          mass_coefficient,
        const double                          stiffness_coefficient,
        const double                          damping_coefficient,
        SparsityPattern                      &pattern,
        SparseMatrix<double>                 &matrix,
        std::vector<types::global_dof_index> &local_to_global,
        std::vector<bool>                    &on_interface) const;

      /// e_d^T M v for each direction d: the momentum of velocity @p v.
      Tensor<1, dim>
      momentum(const DistributedVector &velocity) const;

      /**
       * The momentum of the cells with material id @p part alone (a body
       * of a mesh that holds two, which share no node): e_d restricted to
       * the part's nodes. Its weights M e_d are made at the first call for
       * a part (collective).
       */
      Tensor<1, dim>
      momentum(const DistributedVector &velocity,
               const types::material_id part);
      /// 1^T M 1 of the cells with material id @p part (collective).
      double
      part_mass(const types::material_id part);

    private:
      /// M, K, C and f from the cells (zeroed first), and the momentum
      /// weights.
      void
      assemble();

      /// Calls @p add with the element operators (the mass redistributed
      /// at massless nodes), the DoFs of each locally owned cell and
      /// whether the law is viscous.
      void
      for_each_owned_cell(
        const std::function<void(const CellOperators &,
                                 const std::vector<types::global_dof_index> &,
                                 bool)> &add) const;

      MPI_Comm                                  mpi_communicator;
      MaterialParameters                        material_parameters;
      DiscretizationParameters                  discretization_parameters;
      double                                    out_of_plane;
      parallel::distributed::Triangulation<dim> mesh;
      FESystem<dim>                             fe;
      DoFHandler<dim>                           dofs;
      IndexSet                                  owned, relevant;
      Tensor<1, dim>                            gravity;
      std::map<types::material_id, MaterialParameters> part_materials;
      std::vector<types::global_dof_index>             massless;
      DistributedMatrix                                mass, stiffness, damping;
      DistributedVector                                body_force;
      /// M e_d for each direction d (the momentum weights).
      std::array<DistributedVector, dim> mass_unit_fields;
      /// The same per part (momentum(velocity, part)), and its mass.
      std::map<types::material_id,
               std::pair<std::array<DistributedVector, dim>, double>>
             part_mass_unit_fields;
      double mass_total = 0.;
    };
  } // namespace distributed
} // namespace impactfe

#endif
