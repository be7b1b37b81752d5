#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <impactfe/bodies/cell_operators.h>
#include <impactfe/bodies/elastic_body.h>
#include <impactfe/utilities/program.h>

#include <cmath>
#include <sstream>

namespace impactfe
{
  // @sect3{Element operators}
  void
  CellOperators::reinit(const unsigned int dofs_per_cell)
  {
    mass.reinit(dofs_per_cell, dofs_per_cell);
    stiffness.reinit(dofs_per_cell, dofs_per_cell);
    viscous.reinit(dofs_per_cell, dofs_per_cell);
    load.reinit(dofs_per_cell);
  }



  template <int dim>
  void
  integrate_cell_operators(const FEValues<dim>           &fe_values,
                           const SymmetricTensor<4, dim> &elasticity,
                           const SymmetricTensor<4, dim> &viscosity,
                           const bool                     viscous,
                           const double                   rho,
                           const Tensor<1, dim>          &body_force_density,
                           const double                   out_of_plane,
                           CellOperators                 &cell)
  {
    const FiniteElement<dim> &fe = fe_values.get_fe();
    cell.mass                    = 0.;
    cell.stiffness               = 0.;
    cell.viscous                 = 0.;
    cell.load                    = 0.;
    for (const unsigned int q : fe_values.quadrature_point_indices())
      {
        const double dx = fe_values.JxW(q) * out_of_plane;
        for (const unsigned int i : fe_values.dof_indices())
          {
            const unsigned int      ci = fe.system_to_component_index(i).first;
            const double            phi_i = fe_values.shape_value(i, q);
            SymmetricTensor<2, dim> eps_i;
            const Tensor<1, dim>    grad_i = fe_values.shape_grad(i, q);
            // eps_i = sym(e_ci (x) grad phi_i); a SymmetricTensor stores
            // [ci][d] and [d][ci] once.
            for (unsigned int d = 0; d < dim; ++d)
              eps_i[ci][d] = (d == ci ? 1. : 0.5) * grad_i[d];
            const SymmetricTensor<2, dim> sigma_i = elasticity * eps_i;
            const SymmetricTensor<2, dim> viscous_i =
              viscous ? viscosity * eps_i : SymmetricTensor<2, dim>();
            cell.load(i) += body_force_density[ci] * phi_i * dx;
            for (const unsigned int j : fe_values.dof_indices())
              {
                const unsigned int cj = fe.system_to_component_index(j).first;
                if (ci == cj)
                  cell.mass(i, j) +=
                    rho * phi_i * fe_values.shape_value(j, q) * dx;
                const Tensor<1, dim> grad_j = fe_values.shape_grad(j, q);
                // sigma_i : eps_j with eps_j = sym(e_cj (x) grad_j)
                double contraction = 0., viscous_contraction = 0.;
                for (unsigned int d = 0; d < dim; ++d)
                  contraction += sigma_i[cj][d] * grad_j[d];
                cell.stiffness(i, j) += contraction * dx;
                if (viscous)
                  {
                    for (unsigned int d = 0; d < dim; ++d)
                      viscous_contraction += viscous_i[cj][d] * grad_j[d];
                    cell.viscous(i, j) += viscous_contraction * dx;
                  }
              }
          }
      }
  }



  void
  lumped_cell_mass(const FullMatrix<double> &cell_mass,
                   std::vector<double>      &row_sums)
  {
    row_sums.assign(cell_mass.m(), 0.);
    for (unsigned int i = 0; i < cell_mass.m(); ++i)
      for (unsigned int j = 0; j < cell_mass.n(); ++j)
        row_sums[i] += cell_mass(i, j);
  }



  // @sect3{Mass redistribution}
  // The element mass of a cell with massless vertices, as documented at
  // ElasticBody::redistribute_mass(). The mass matrix couples equal
  // components only, so each component is treated alike.
  template <int dim>
  void
  redistribute_cell_mass(const FiniteElement<dim> &fe,
                         const std::vector<bool>  &massless,
                         const Point<dim>         &center,
                         const std::string        &body_name,
                         FullMatrix<double>       &cell_mass)
  {
    const auto n_massless = std::count(massless.begin(), massless.end(), true);
    if (n_massless == 0)
      return;
    if (n_massless == static_cast<long>(massless.size()))
      {
        std::ostringstream where;
        where << center;
        AssertThrow(false,
                    ExcMessage("Body '" + body_name +
                               "': mass redistribution would leave the cell "
                               "at (" +
                               where.str() +
                               ") without mass: all its vertices are contact "
                               "nodes. Refine the mesh or set 'Mass "
                               "redistribution' to false."));
      }
    const unsigned int n      = fe.n_dofs_per_cell();
    auto               vertex = [&](const unsigned int i) {
      return fe.system_to_component_index(i).second;
    };
    auto component = [&](const unsigned int i) {
      return fe.system_to_component_index(i).first;
    };
    auto joined = [](const unsigned int v, const unsigned int w) {
      for (unsigned int l = 0; l < GeometryInfo<dim>::lines_per_cell; ++l)
        {
          const unsigned int a = GeometryInfo<dim>::line_to_cell_vertices(l, 0),
                             b = GeometryInfo<dim>::line_to_cell_vertices(l, 1);
          if ((a == v && b == w) || (a == w && b == v))
            return true;
        }
      return false;
    };

    FullMatrix<double> result(n, n);
    for (unsigned int i = 0; i < n; ++i)
      if (!massless[vertex(i)])
        for (unsigned int j = 0; j < n; ++j)
          {
            if (massless[vertex(j)])
              result(i, i) += cell_mass(i, j);
            else
              result(i, j) += cell_mass(i, j);
          }
    for (unsigned int i = 0; i < n; ++i)
      if (massless[vertex(i)])
        {
          double row_sum = 0.;
          for (unsigned int j = 0; j < n; ++j)
            row_sum += cell_mass(i, j);
          std::vector<unsigned int> receivers;
          for (unsigned int j = 0; j < n; ++j)
            if (component(j) == component(i) && !massless[vertex(j)] &&
                joined(vertex(i), vertex(j)))
              receivers.push_back(j);
          if (receivers.empty())
            for (unsigned int j = 0; j < n; ++j)
              if (component(j) == component(i) && !massless[vertex(j)])
                receivers.push_back(j);
          Assert(!receivers.empty(), ExcInternalError());
          for (const unsigned int j : receivers)
            result(j, j) += row_sum / receivers.size();
        }
    cell_mass = result;
  }



  void
  DiscretizationParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discretization");
    prm.declare_entry(
      "Mass matrix",
      "consistent",
      Patterns::Selection("consistent|lumped"),
      "Consistent Q1/P1 mass matrix, or its row-sum lumped (diagonal) form.");
    prm.declare_entry(
      "Mass redistribution",
      "false",
      Patterns::Bool(),
      "Move the mass of every contact candidate's nodes to their neighbours "
      "in the same cells (Khenous, Laborde, Renard 2008): the contact nodes "
      "carry no mass, the total mass is kept, and a closed contact does not "
      "chatter. Theta-schemes only (Newmark needs an invertible mass for its "
      "initial acceleration).");
    prm.leave_subsection();
  }



  void
  DiscretizationParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Discretization");
    lumped_mass         = (prm.get("Mass matrix") == "lumped");
    mass_redistribution = prm.get_bool("Mass redistribution");
    prm.leave_subsection();
  }



  template <int dim>
  ElasticBody<dim>::ElasticBody(const std::string              &name,
                                const MaterialParameters       &material,
                                const DiscretizationParameters &discretization,
                                const double out_of_plane_measure)
    : body_name(name)
    , material_parameters(material)
    , model(create_constitutive_model<dim>(material))
    , discretization_parameters(discretization)
    , out_of_plane(out_of_plane_measure)
    , fe(FE_Q<dim>(1), dim)
  {
    AssertThrow(out_of_plane > 0.,
                ExcMessage("Body '" + name +
                           "': the cross-section area (1D) or thickness (2D) "
                           "must be > 0."));
  }



  template <int dim>
  Triangulation<dim> &
  ElasticBody<dim>::triangulation()
  {
    return mesh;
  }



  template <int dim>
  const Triangulation<dim> &
  ElasticBody<dim>::triangulation() const
  {
    return mesh;
  }



  template <int dim>
  void
  ElasticBody<dim>::setup()
  {
    AssertThrow(mesh.n_active_cells() > 0,
                ExcMessage("Body '" + body_name + "' has an empty mesh."));
    dofs.reinit(mesh);
    dofs.distribute_dofs(fe);

    DynamicSparsityPattern dsp(dofs.n_dofs(), dofs.n_dofs());
    DoFTools::make_sparsity_pattern(dofs, dsp);
    pattern.copy_from(dsp);

    vertex_dofs.assign(mesh.n_vertices() * dim, numbers::invalid_dof_index);
    for (const auto &cell : dofs.active_cell_iterators())
      for (const unsigned int v : cell->vertex_indices())
        for (unsigned int c = 0; c < dim; ++c)
          vertex_dofs[cell->vertex_index(v) * dim + c] =
            cell->vertex_dof_index(v, c);
    mass.reinit(pattern);
    stiffness.reinit(pattern);
    if (has_damping())
      damping.reinit(pattern);
    else
      damping.clear();
    body_force_vector.reinit(dofs.n_dofs());

    // Internal variables at every quadrature point of the assembly rule.
    const unsigned int n_points = QGauss<dim>(2).size();
    point_history.clear();
    for (const auto &cell : mesh.active_cell_iterators())
      {
        point_history.initialize(cell, n_points);
        for (const auto &point : point_history.get_data(cell))
          {
            model->initialize(point->old_values);
            point->new_values = point->old_values;
          }
      }
    assemble();
  }



  template <int dim>
  std::vector<std::shared_ptr<MaterialPointHistory>>
  ElasticBody<dim>::material_point_history(
    const typename Triangulation<dim>::cell_iterator &cell)
  {
    return point_history.get_data(cell);
  }



  template <int dim>
  void
  ElasticBody<dim>::accept_material_step()
  {
    for (const auto &cell : mesh.active_cell_iterators())
      for (const auto &point : point_history.get_data(cell))
        point->old_values = point->new_values;
  }



  template <int dim>
  const ConstitutiveModel<dim> &
  ElasticBody<dim>::constitutive_model() const
  {
    return *model;
  }



  template <int dim>
  void
  ElasticBody<dim>::set_body_force(const Tensor<1, dim> &force_density)
  {
    body_force_density = force_density;
    if (dofs.n_dofs() > 0)
      assemble();
  }



  // @sect3{Assembly of M, K, C and the load}
  // Q1 elements with a 2-point Gauss rule: exact for the consistent mass and
  // the stiffness of affine cells. The damping matrix is the Kelvin--Voigt
  // term (eta/E) K plus Rayleigh a M + b K.
  template <int dim>
  void
  ElasticBody<dim>::assemble()
  {
    mass      = 0.;
    stiffness = 0.;
    if (has_damping())
      damping = 0.;
    body_force_vector = 0.;

    const QGauss<dim> quadrature(2);
    FEValues<dim>     fe_values(
      fe, quadrature, update_values | update_gradients | update_JxW_values);
    const unsigned int dofs_per_cell = fe.n_dofs_per_cell();
    CellOperators      cell_operators;
    cell_operators.reinit(dofs_per_cell);
    FullMatrix<double>                  &cell_mass = cell_operators.mass;
    std::vector<double>                  row_sums;
    std::vector<types::global_dof_index> local_dofs(dofs_per_cell);

    // A linear law: K and C are assembled once, from its elasticity and
    // viscosity tensors. (A nonlinear law is evaluated at each iterate of
    // a nonlinear step instead.)
    AssertThrow(model->is_linear(),
                ExcMessage("Body '" + body_name + "': the material law '" +
                           model->name() +
                           "' is nonlinear; its body cannot be assembled "
                           "into constant matrices."));
    const SymmetricTensor<4, dim> elasticity = model->elasticity_tensor();
    const SymmetricTensor<4, dim> viscosity  = model->viscosity_tensor();
    const bool                    viscous    = viscosity.norm() > 0.;
    const double                  rho        = material_parameters.density;

    for (const auto &cell : dofs.active_cell_iterators())
      {
        fe_values.reinit(cell);
        integrate_cell_operators(fe_values,
                                 elasticity,
                                 viscosity,
                                 viscous,
                                 rho,
                                 body_force_density,
                                 out_of_plane,
                                 cell_operators);
        cell->get_dof_indices(local_dofs);
        if (!massless_vertex.empty())
          {
            std::vector<bool> massless(cell->n_vertices());
            for (const unsigned int v : cell->vertex_indices())
              massless[v] = massless_vertex[cell->vertex_index(v)];
            redistribute_cell_mass(
              fe, massless, cell->center(), body_name, cell_mass);
          }
        if (discretization_parameters.lumped_mass)
          {
            lumped_cell_mass(cell_mass, row_sums);
            for (unsigned int i = 0; i < dofs_per_cell; ++i)
              mass.add(local_dofs[i], local_dofs[i], row_sums[i]);
          }
        else
          mass.add(local_dofs, cell_mass);
        stiffness.add(local_dofs, cell_operators.stiffness);
        if (has_damping())
          damping.add(local_dofs, cell_operators.viscous);
        for (unsigned int i = 0; i < dofs_per_cell; ++i)
          body_force_vector(local_dofs[i]) += cell_operators.load(i);
      }

    // A constant body force rho g is M g for the consistent or lumped mass.
    // With massless nodes it follows the mass, so that a massless node
    // carries no load it has no inertia against and a free body still
    // falls as a whole.
    if (!massless_vertex.empty())
      {
        Vector<double> acceleration(dofs.n_dofs());
        fill_uniform(acceleration, body_force_density / rho);
        mass.vmult(body_force_vector, acceleration);
      }

    // C = the law's viscous matrix + Rayleigh a M + b K.
    if (has_damping())
      {
        damping.add(material_parameters.rayleigh_stiffness, stiffness);
        damping.add(material_parameters.rayleigh_mass, mass);
      }

    // Moduli at the edge of double precision (E = 1e305 Pa, say) overflow
    // in the element integrals; every later product would carry the inf or
    // NaN, so the data that caused it are named here.
    const auto check_finite = [&](const SparseMatrix<double> &matrix,
                                  const std::string          &what) {
      for (const auto &entry : matrix)
        AssertThrow(std::isfinite(entry.value()),
                    ExcMessage("Body '" + body_name + "': the " + what +
                               " matrix overflows double precision (" +
                               material_parameters.entries_of_matrix(what) +
                               "); the run is not started."));
    };
    check_finite(mass, "mass");
    check_finite(stiffness, "stiffness");
    if (has_damping())
      check_finite(damping, "damping");
  }



  template <int dim>
  const std::string &
  ElasticBody<dim>::name() const
  {
    return body_name;
  }

  template <int dim>
  const MaterialParameters &
  ElasticBody<dim>::material() const
  {
    return material_parameters;
  }

  template <int dim>
  double
  ElasticBody<dim>::cell_transit_time() const
  {
    double volume = 0.;
    for (const auto &cell : mesh.active_cell_iterators())
      volume += cell->measure();
    const double cell_size = std::pow(volume / mesh.n_active_cells(), 1. / dim);
    return cell_size / material_parameters.longitudinal_wave_speed<dim>();
  }

  template <int dim>
  const DoFHandler<dim> &
  ElasticBody<dim>::dof_handler() const
  {
    return dofs;
  }

  template <int dim>
  unsigned int
  ElasticBody<dim>::n_dofs() const
  {
    return dofs.n_dofs();
  }

  template <int dim>
  const SparsityPattern &
  ElasticBody<dim>::sparsity_pattern() const
  {
    return pattern;
  }

  template <int dim>
  const SparseMatrix<double> &
  ElasticBody<dim>::mass_matrix() const
  {
    return mass;
  }

  template <int dim>
  const SparseMatrix<double> &
  ElasticBody<dim>::stiffness_matrix() const
  {
    return stiffness;
  }

  template <int dim>
  const SparseMatrix<double> &
  ElasticBody<dim>::damping_matrix() const
  {
    return damping;
  }

  template <int dim>
  bool
  ElasticBody<dim>::has_damping() const
  {
    return material_parameters.has_damping();
  }

  template <int dim>
  const Vector<double> &
  ElasticBody<dim>::external_force() const
  {
    return body_force_vector;
  }



  template <int dim>
  void
  ElasticBody<dim>::redistribute_mass(
    const std::vector<unsigned int> &massless_vertices)
  {
    AssertThrow(dofs.n_dofs() > 0,
                ExcMessage("Body '" + body_name +
                           "': redistribute_mass() before setup()."));
    massless_vertex.assign(mesh.n_vertices(), false);
    for (const unsigned int v : massless_vertices)
      {
        AssertThrow(v < mesh.n_vertices(),
                    ExcMessage("Body '" + body_name + "': vertex " +
                               std::to_string(v) + " does not exist."));
        massless_vertex[v] = true;
      }
    assemble();
  }



  template <int dim>
  std::vector<types::global_dof_index>
  ElasticBody<dim>::massless_dofs() const
  {
    std::vector<types::global_dof_index> result;
    for (unsigned int v = 0; v < massless_vertex.size(); ++v)
      if (massless_vertex[v])
        for (unsigned int c = 0; c < dim; ++c)
          result.push_back(vertex_dof(v, c));
    return result;
  }



  template <int dim>
  double
  ElasticBody<dim>::total_mass() const
  {
    // 1^T M 1 for one displacement component.
    Vector<double> ones(dofs.n_dofs()), tmp(dofs.n_dofs());
    Tensor<1, dim> e0;
    e0[0] = 1.;
    fill_uniform(ones, e0);
    mass.vmult(tmp, ones);
    return ones * tmp;
  }



  template <int dim>
  types::global_dof_index
  ElasticBody<dim>::vertex_dof(const unsigned int vertex_index,
                               const unsigned int component) const
  {
    const types::global_dof_index dof =
      vertex_index < mesh.n_vertices() ?
        vertex_dofs[vertex_index * dim + component] :
        numbers::invalid_dof_index;
    AssertThrow(dof != numbers::invalid_dof_index,
                ExcMessage("Body '" + body_name + "': vertex " +
                           std::to_string(vertex_index) +
                           " belongs to no cell."));
    return dof;
  }



  template <int dim>
  double
  ElasticBody<dim>::nodal_value(const Vector<double> &vector,
                                const unsigned int    vertex_index,
                                const unsigned int    component) const
  {
    return vector(vertex_dof(vertex_index, component));
  }



  template <int dim>
  void
  ElasticBody<dim>::fill_uniform(Vector<double>       &vector,
                                 const Tensor<1, dim> &value) const
  {
    vector.reinit(dofs.n_dofs());
    std::vector<types::global_dof_index> local_dofs(fe.n_dofs_per_cell());
    for (const auto &cell : dofs.active_cell_iterators())
      {
        cell->get_dof_indices(local_dofs);
        for (unsigned int i = 0; i < local_dofs.size(); ++i)
          vector(local_dofs[i]) = value[fe.system_to_component_index(i).first];
      }
  }



  template void
  integrate_cell_operators<1>(const FEValues<1> &,
                              const SymmetricTensor<4, 1> &,
                              const SymmetricTensor<4, 1> &,
                              const bool,
                              const double,
                              const Tensor<1, 1> &,
                              const double,
                              CellOperators &);
  template void
  integrate_cell_operators<2>(const FEValues<2> &,
                              const SymmetricTensor<4, 2> &,
                              const SymmetricTensor<4, 2> &,
                              const bool,
                              const double,
                              const Tensor<1, 2> &,
                              const double,
                              CellOperators &);
  template void
  integrate_cell_operators<3>(const FEValues<3> &,
                              const SymmetricTensor<4, 3> &,
                              const SymmetricTensor<4, 3> &,
                              const bool,
                              const double,
                              const Tensor<1, 3> &,
                              const double,
                              CellOperators &);
  template void
  redistribute_cell_mass<1>(const FiniteElement<1> &,
                            const std::vector<bool> &,
                            const Point<1> &,
                            const std::string &,
                            FullMatrix<double> &);
  template void
  redistribute_cell_mass<2>(const FiniteElement<2> &,
                            const std::vector<bool> &,
                            const Point<2> &,
                            const std::string &,
                            FullMatrix<double> &);
  template void
  redistribute_cell_mass<3>(const FiniteElement<3> &,
                            const std::vector<bool> &,
                            const Point<3> &,
                            const std::string &,
                            FullMatrix<double> &);
  template class ElasticBody<1>;
  template class ElasticBody<2>;
  template class ElasticBody<3>;
} // namespace impactfe
