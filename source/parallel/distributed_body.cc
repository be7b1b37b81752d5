#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>

#include <impactfe/bodies/cell_operators.h>
#include <impactfe/bodies/constitutive_model.h>
#include <impactfe/parallel/distributed_body.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace impactfe
{
  namespace distributed
  {
    template <int dim>
    DistributedElasticBody<dim>::DistributedElasticBody(
      const MPI_Comm                  communicator,
      const MaterialParameters       &material,
      const DiscretizationParameters &discretization,
      const double                    out_of_plane_measure)
      : mpi_communicator(communicator)
      , material_parameters(material)
      , discretization_parameters(discretization)
      , out_of_plane(out_of_plane_measure)
      , mesh(communicator)
      , fe(FE_Q<dim>(1), dim)
      , dofs(mesh)
    {
      AssertThrow(out_of_plane > 0. && std::isfinite(out_of_plane),
                  ExcMessage("DistributedElasticBody: the thickness must "
                             "be > 0."));
    }



    template <int dim>
    parallel::distributed::Triangulation<dim> &
    DistributedElasticBody<dim>::triangulation()
    {
      return mesh;
    }



    template <int dim>
    const parallel::distributed::Triangulation<dim> &
    DistributedElasticBody<dim>::triangulation() const
    {
      return mesh;
    }



    template <int dim>
    void
    DistributedElasticBody<dim>::set_gravity(const Tensor<1, dim> &acceleration)
    {
      gravity = acceleration;
    }



    template <int dim>
    void
    DistributedElasticBody<dim>::set_part_material(
      const types::material_id  part,
      const MaterialParameters &material)
    {
      part_materials[part] = material;
    }



    // @sect3{Set-up and assembly}
    // The same element operators as the serial body; each rank adds its
    // locally owned cells, and compress() sums the shared rows.
    template <int dim>
    void
    DistributedElasticBody<dim>::setup()
    {
      AssertThrow(mesh.n_global_active_cells() > 0,
                  ExcMessage("The distributed body has no cells."));
      dofs.distribute_dofs(fe);
      owned = dofs.locally_owned_dofs();
      // ML's AMG and the partitioned vectors need DoFs on every rank
      AssertThrow(Utilities::MPI::min(owned.n_elements(), mpi_communicator) > 0,
                  ExcMessage("A rank owns no degree of freedom of the "
                             "distributed body (" +
                             std::to_string(mesh.n_global_active_cells()) +
                             " cells): use fewer MPI ranks."));
      DoFTools::extract_locally_relevant_dofs(dofs, relevant);

      AffineConstraints<double> hanging;
      hanging.reinit(relevant);
      DoFTools::make_hanging_node_constraints(dofs, hanging);
      hanging.close();
      AssertThrow(Utilities::MPI::sum(hanging.n_constraints(),
                                      mpi_communicator) == 0,
                  ExcMessage("The distributed body's mesh has hanging nodes; "
                             "refine it uniformly."));

      TrilinosWrappers::SparsityPattern pattern(owned,
                                                owned,
                                                relevant,
                                                mpi_communicator);
      DoFTools::make_sparsity_pattern(dofs, pattern);
      pattern.compress();
      mass.reinit(pattern);
      stiffness.reinit(pattern);
      damping.reinit(pattern);
      body_force.reinit(owned, mpi_communicator);
      assemble();
    }



    template <int dim>
    void
    DistributedElasticBody<dim>::redistribute_mass(
      const std::vector<types::global_dof_index> &massless_dofs)
    {
      AssertThrow(dofs.n_dofs() > 0,
                  ExcMessage("DistributedElasticBody: redistribute_mass() "
                             "before setup()."));
      massless = massless_dofs;
      std::sort(massless.begin(), massless.end());
      massless.erase(std::unique(massless.begin(), massless.end()),
                     massless.end());
      part_mass_unit_fields.clear();
      assemble();
    }



    template <int dim>
    const std::vector<types::global_dof_index> &
    DistributedElasticBody<dim>::massless_dofs() const
    {
      return massless;
    }



    template <int dim>
    void
    DistributedElasticBody<dim>::assemble()
    {
      mass                       = 0.;
      stiffness                  = 0.;
      damping                    = 0.;
      body_force                 = 0.;
      const bool          lumped = discretization_parameters.lumped_mass;
      std::vector<double> row_sums;
      for_each_owned_cell([&](const CellOperators                        &cell,
                              const std::vector<types::global_dof_index> &dof,
                              const bool viscous) {
        if (lumped)
          {
            lumped_cell_mass(cell.mass, row_sums);
            for (unsigned int i = 0; i < dof.size(); ++i)
              mass.add(dof[i], dof[i], row_sums[i]);
          }
        else
          mass.add(dof, cell.mass);
        stiffness.add(dof, cell.stiffness);
        if (viscous)
          damping.add(dof, cell.viscous);
        body_force.add(dof, cell.load);
      });
      mass.compress(VectorOperation::add);
      stiffness.compress(VectorOperation::add);
      damping.compress(VectorOperation::add);
      body_force.compress(VectorOperation::add);
      // Moduli at the edge of double precision overflow in the element
      // integrals (as in ElasticBody::assemble()). Each rank looks at its
      // own rows entry by entry (a norm's max may drop a NaN) and the flag
      // is reduced, so that all ranks stop together.
      const std::string per_body =
        part_materials.empty() ? "" : " (or a body's own, in 'Bodies')";
      const auto check_finite =
        [&](const TrilinosWrappers::SparseMatrix &matrix,
            const std::string                    &what) {
          unsigned int overflowed = 0;
          for (const auto &entry : matrix)
            overflowed = overflowed || !std::isfinite(entry.value());
          AssertThrow(Utilities::MPI::max(overflowed, mpi_communicator) == 0,
                      ExcMessage("The " + what +
                                 " matrix overflows double precision (" +
                                 material_parameters.entries_of_matrix(what) +
                                 per_body + "); the run is not started."));
        };
      check_finite(mass, "mass");
      check_finite(stiffness, "stiffness");
      check_finite(damping, "damping");
      // A constant body force rho g is M g; with massless nodes it follows
      // the mass (ElasticBody::assemble()), so that a free body still
      // falls as a whole.
      if (!massless.empty())
        {
          DistributedVector acceleration(owned, mpi_communicator);
          fill_uniform(acceleration, gravity);
          mass.vmult(body_force, acceleration);
        }

      for (unsigned int d = 0; d < dim; ++d)
        {
          DistributedVector unit(owned, mpi_communicator);
          Tensor<1, dim>    e;
          e[d] = 1.;
          fill_uniform(unit, e);
          mass_unit_fields[d].reinit(owned, mpi_communicator);
          mass.vmult(mass_unit_fields[d], unit);
          if (d == 0)
            mass_total = mass_unit_fields[d] * unit;
        }
    }



    template <int dim>
    MPI_Comm
    DistributedElasticBody<dim>::communicator() const
    {
      return mpi_communicator;
    }



    template <int dim>
    const DoFHandler<dim> &
    DistributedElasticBody<dim>::dof_handler() const
    {
      return dofs;
    }



    template <int dim>
    const IndexSet &
    DistributedElasticBody<dim>::locally_owned_dofs() const
    {
      return owned;
    }



    template <int dim>
    const IndexSet &
    DistributedElasticBody<dim>::locally_relevant_dofs() const
    {
      return relevant;
    }



    template <int dim>
    const MaterialParameters &
    DistributedElasticBody<dim>::material() const
    {
      return material_parameters;
    }



    template <int dim>
    const DistributedMatrix &
    DistributedElasticBody<dim>::mass_matrix() const
    {
      return mass;
    }



    template <int dim>
    const DistributedMatrix &
    DistributedElasticBody<dim>::stiffness_matrix() const
    {
      return stiffness;
    }



    template <int dim>
    const DistributedMatrix &
    DistributedElasticBody<dim>::damping_matrix() const
    {
      return damping;
    }



    template <int dim>
    bool
    DistributedElasticBody<dim>::has_damping() const
    {
      bool damped = material_parameters.has_damping();
      for (const auto &part : part_materials)
        damped = damped || part.second.has_damping();
      return damped;
    }



    template <int dim>
    const DistributedVector &
    DistributedElasticBody<dim>::external_force() const
    {
      return body_force;
    }



    // The element operators of the serial body on each locally owned cell,
    // handed to @p add with the cell's DoFs and whether the law is viscous.
    template <int dim>
    void
    DistributedElasticBody<dim>::for_each_owned_cell(
      const std::function<void(const CellOperators &,
                               const std::vector<types::global_dof_index> &,
                               bool)> &add) const
    {
      // the tensors of the body's law and of each part's own
      struct Law
      {
        SymmetricTensor<4, dim> elasticity, viscosity;
        bool                    viscous       = false;
        double                  density       = 0.;
        double                  rayleigh_mass = 0., rayleigh_stiffness = 0.;
      };
      const auto law_of = [](const MaterialParameters &material) {
        const auto model = create_constitutive_model<dim>(material);
        AssertThrow(model->is_linear(),
                    ExcMessage("The material law '" + model->name() +
                               "' is nonlinear; the distributed body needs a "
                               "linear one."));
        Law law;
        law.elasticity         = model->elasticity_tensor();
        law.viscosity          = model->viscosity_tensor();
        law.viscous            = law.viscosity.norm() > 0.;
        law.density            = material.density;
        law.rayleigh_mass      = material.rayleigh_mass;
        law.rayleigh_stiffness = material.rayleigh_stiffness;
        return law;
      };
      const Law                         body_law = law_of(material_parameters);
      std::map<types::material_id, Law> part_laws;
      for (const auto &part : part_materials)
        part_laws[part.first] = law_of(part.second);

      const QGauss<dim> quadrature(2);
      FEValues<dim>     fe_values(
        fe, quadrature, update_values | update_gradients | update_JxW_values);
      const unsigned int n = fe.n_dofs_per_cell();
      CellOperators      cell_operators;
      cell_operators.reinit(n);
      std::vector<types::global_dof_index> local_dofs(n);
      std::vector<bool>   is_massless(GeometryInfo<dim>::vertices_per_cell);
      std::vector<double> row_sums;
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            const auto found = part_laws.find(cell->material_id());
            const Law &law =
              found == part_laws.end() ? body_law : found->second;
            fe_values.reinit(cell);
            integrate_cell_operators(fe_values,
                                     law.elasticity,
                                     law.viscosity,
                                     law.viscous,
                                     law.density,
                                     law.density * gravity,
                                     out_of_plane,
                                     cell_operators);
            cell->get_dof_indices(local_dofs);
            if (!massless.empty())
              {
                for (const unsigned int v : cell->vertex_indices())
                  is_massless[v] =
                    std::binary_search(massless.begin(),
                                       massless.end(),
                                       cell->vertex_dof_index(v, 0));
                redistribute_cell_mass(fe,
                                       is_massless,
                                       cell->center(),
                                       "body " + std::to_string(
                                                   cell->material_id() + 1),
                                       cell_operators.mass);
              }
            // C = the law's viscous matrix + Rayleigh a M + b K of the
            // cell's material (as ElasticBody, each part with its own a, b;
            // a M with the mass as assembled, lumped or not)
            bool viscous = law.viscous;
            if (law.rayleigh_mass != 0. || law.rayleigh_stiffness != 0.)
              {
                if (!viscous)
                  cell_operators.viscous = 0.;
                viscous = true;
                cell_operators.viscous.add(law.rayleigh_stiffness,
                                           cell_operators.stiffness);
                if (discretization_parameters.lumped_mass)
                  {
                    lumped_cell_mass(cell_operators.mass, row_sums);
                    for (unsigned int i = 0; i < n; ++i)
                      cell_operators.viscous(i, i) +=
                        law.rayleigh_mass * row_sums[i];
                  }
                else
                  cell_operators.viscous.add(law.rayleigh_mass,
                                             cell_operators.mass);
              }
            add(cell_operators, local_dofs, viscous);
          }
    }



    // The sum over the ranks of these matrices is the distributed
    // a M + b K + c C: each cell is owned by one rank. C's Rayleigh terms
    // are each cell's a M_e + b K_e, so they split by cells too.
    template <int dim>
    void
    DistributedElasticBody<dim>::assemble_subdomain_matrix(
      const double                          mass_coefficient,
      const double                          stiffness_coefficient,
      const double                          damping_coefficient,
      SparsityPattern                      &pattern,
      SparseMatrix<double>                 &matrix,
      std::vector<types::global_dof_index> &local_to_global,
      std::vector<bool>                    &on_interface) const
    {
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      local_to_global.clear();
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(cell_dofs);
            local_to_global.insert(local_to_global.end(),
                                   cell_dofs.begin(),
                                   cell_dofs.end());
          }
      std::sort(local_to_global.begin(), local_to_global.end());
      local_to_global.erase(std::unique(local_to_global.begin(),
                                        local_to_global.end()),
                            local_to_global.end());
      const auto local_index = [&](const types::global_dof_index g) {
        return static_cast<unsigned int>(
          std::lower_bound(local_to_global.begin(), local_to_global.end(), g) -
          local_to_global.begin());
      };
      // A DoF of an owned cell that a ghost cell has too is shared with
      // another rank (the ghost layer holds every cell that touches an
      // owned one).
      on_interface.assign(local_to_global.size(), false);
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_ghost())
          {
            cell->get_dof_indices(cell_dofs);
            for (const auto g : cell_dofs)
              if (const unsigned int l = local_index(g);
                  l < local_to_global.size() && local_to_global[l] == g)
                on_interface[l] = true;
          }

      const unsigned int        n = fe.n_dofs_per_cell();
      std::vector<unsigned int> local(n);
      DynamicSparsityPattern    dsp(local_to_global.size());
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            cell->get_dof_indices(cell_dofs);
            for (unsigned int i = 0; i < n; ++i)
              local[i] = local_index(cell_dofs[i]);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                dsp.add(local[i], local[j]);
          }
      matrix.clear();
      pattern.copy_from(dsp);
      matrix.reinit(pattern);

      // (the Rayleigh terms are in each cell's viscous matrix)
      const double        m_factor = mass_coefficient;
      const double        k_factor = stiffness_coefficient;
      const bool          lumped   = discretization_parameters.lumped_mass;
      std::vector<double> row_sums;
      for_each_owned_cell([&](const CellOperators                        &cell,
                              const std::vector<types::global_dof_index> &dof,
                              const bool viscous) {
        for (unsigned int i = 0; i < n; ++i)
          local[i] = local_index(dof[i]);
        if (lumped)
          lumped_cell_mass(cell.mass, row_sums);
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            {
              double value = k_factor * cell.stiffness(i, j);
              if (lumped)
                value += i == j ? m_factor * row_sums[i] : 0.;
              else
                value += m_factor * cell.mass(i, j);
              if (viscous)
                value += damping_coefficient * cell.viscous(i, j);
              matrix.add(local[i], local[j], value);
            }
      });
    }



    template <int dim>
    double
    DistributedElasticBody<dim>::total_mass() const
    {
      return mass_total;
    }



    template <int dim>
    double
    DistributedElasticBody<dim>::cell_transit_time() const
    {
      // The parts are the material ids of all ranks: sum volume and cell
      // count per id over the ranks, then take each part's mean cell.
      unsigned int highest_id = 0;
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned())
          highest_id = std::max<unsigned int>(highest_id, cell->material_id());
      highest_id = Utilities::MPI::max(highest_id, communicator());
      std::vector<double> volume(highest_id + 1, 0.),
        n_cells(highest_id + 1, 0.);
      for (const auto &cell : mesh.active_cell_iterators())
        if (cell->is_locally_owned())
          {
            volume[cell->material_id()] += cell->measure();
            n_cells[cell->material_id()] += 1.;
          }
      Utilities::MPI::sum(volume, communicator(), volume);
      Utilities::MPI::sum(n_cells, communicator(), n_cells);
      double shortest = std::numeric_limits<double>::infinity();
      for (unsigned int id = 0; id <= highest_id; ++id)
        if (n_cells[id] > 0.)
          {
            const auto                part = part_materials.find(id);
            const MaterialParameters &material =
              part == part_materials.end() ? material_parameters : part->second;
            const double cell_size =
              std::pow(volume[id] / n_cells[id], 1. / dim);
            shortest =
              std::min(shortest,
                       cell_size / material.longitudinal_wave_speed<dim>());
          }
      return shortest;
    }



    // Every owned DoF lies on a locally owned cell, where its component is
    // known.
    template <int dim>
    void
    DistributedElasticBody<dim>::fill_uniform(
      DistributedVector       &vector,
      const Tensor<1, dim>    &value,
      const types::material_id part) const
    {
      std::vector<types::global_dof_index> local_dofs(fe.n_dofs_per_cell());
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned() && (part == numbers::invalid_material_id ||
                                         cell->material_id() == part))
          {
            cell->get_dof_indices(local_dofs);
            for (unsigned int i = 0; i < local_dofs.size(); ++i)
              if (owned.is_element(local_dofs[i]))
                vector[local_dofs[i]] =
                  value[fe.system_to_component_index(i).first];
          }
      vector.compress(VectorOperation::insert);
    }



    template <int dim>
    Tensor<1, dim>
    DistributedElasticBody<dim>::momentum(
      const DistributedVector &velocity) const
    {
      Tensor<1, dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = mass_unit_fields[d] * velocity;
      return p;
    }



    template <int dim>
    double
    DistributedElasticBody<dim>::part_mass(const types::material_id part)
    {
      auto found = part_mass_unit_fields.find(part);
      if (found == part_mass_unit_fields.end())
        {
          auto &[fields, part_total] = part_mass_unit_fields[part];
          for (unsigned int d = 0; d < dim; ++d)
            {
              DistributedVector unit(owned, mpi_communicator);
              Tensor<1, dim>    e;
              e[d] = 1.;
              fill_uniform(unit, e, part);
              fields[d].reinit(owned, mpi_communicator);
              mass.vmult(fields[d], unit);
              if (d == 0)
                part_total = fields[d] * unit;
            }
          found = part_mass_unit_fields.find(part);
        }
      return found->second.second;
    }



    template <int dim>
    Tensor<1, dim>
    DistributedElasticBody<dim>::momentum(const DistributedVector &velocity,
                                          const types::material_id part)
    {
      part_mass(part);
      const auto    &fields = part_mass_unit_fields.at(part).first;
      Tensor<1, dim> p;
      for (unsigned int d = 0; d < dim; ++d)
        p[d] = fields[d] * velocity;
      return p;
    }



    template class DistributedElasticBody<2>;
    template class DistributedElasticBody<3>;
  } // namespace distributed
} // namespace impactfe
