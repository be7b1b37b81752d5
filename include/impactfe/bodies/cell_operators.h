// The element matrices of a linear (visco)elastic body, shared by the
// serial ElasticBody and the distributed body (parallel/distributed_body.h)
// so that both integrate the same operators.
#ifndef impactfe_bodies_cell_operators_h
#define impactfe_bodies_cell_operators_h

#include <deal.II/base/point.h>
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /// The element mass, stiffness and viscous matrices and body-force load
  /// of one cell (Q1 vector element, dim components).
  struct CellOperators
  {
    FullMatrix<double> mass, stiffness, viscous;
    Vector<double>     load;

    void
    reinit(const unsigned int dofs_per_cell);
  };

  /**
   * Integrates the element operators of the cell @p fe_values was reinit'ed
   * on: M_ij = rho phi_i phi_j (equal components), K_ij = C eps_i : eps_j,
   * C_ij = D eps_i : eps_j (if @p viscous), f_i = b . e_ci phi_i, each
   * times @p out_of_plane (the thickness of a 2D body, 1 else).
   */
  template <int dim>
  void
  integrate_cell_operators(const FEValues<dim>           &fe_values,
                           const SymmetricTensor<4, dim> &elasticity,
                           const SymmetricTensor<4, dim> &viscosity,
                           const bool                     viscous,
                           const double                   density,
                           const Tensor<1, dim>          &body_force_density,
                           const double                   out_of_plane,
                           CellOperators                 &cell);

  /// The row sums of the element mass (the lumped mass's diagonal).
  void
  lumped_cell_mass(const FullMatrix<double> &cell_mass,
                   std::vector<double>      &row_sums);

  /**
   * Mass redistribution on one cell (ElasticBody::redistribute_mass(),
   * Khenous, Laborde, Renard, Eur. J. Mech. A 27, 2008): the element mass
   * of the vertices @p massless (by the cell's vertex numbers) goes to the
   * cell's other vertices joined to them by an edge (to all of its other
   * vertices if none is), and the coupling of the other vertices to them
   * to their own diagonal. Unchanged if no vertex is massless. Throws,
   * naming @p body_name and the cell's @p center, if every vertex is.
   */
  template <int dim>
  void
  redistribute_cell_mass(const FiniteElement<dim> &fe,
                         const std::vector<bool>  &massless,
                         const Point<dim>         &center,
                         const std::string        &body_name,
                         FullMatrix<double>       &cell_mass);
} // namespace impactfe

#endif
