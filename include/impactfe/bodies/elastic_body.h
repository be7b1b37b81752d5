#ifndef impactfe_bodies_elastic_body_h
#define impactfe_bodies_elastic_body_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/quadrature_point_data.h>
#include <deal.II/base/tensor.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <impactfe/bodies/constitutive_model.h>
#include <impactfe/bodies/material.h>

#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * Spatial discretisation options, parameter subsection `Discretization`.
   */
  struct DiscretizationParameters
  {
    /// Row-sum lumped mass instead of the consistent Q1/P1 mass.
    bool lumped_mass = false;
    /// Move the mass of the contact nodes to their neighbours (see
    /// ElasticBody::redistribute_mass()).
    bool mass_redistribution = false;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };



  /**
   * One deformable body: its mesh, Q1 (P1 in 1D) vector-valued finite element
   * space and its mass, stiffness and damping matrices, all in the body's own
   * DoF numbering. The multibody system puts several bodies side by side in
   * one block vector (one block per body); contact couples them only through
   * the H operator.
   *
   * In 1D the "Cross-section area" and in 2D the "Thickness" multiply all
   * matrices, so that forces and energies are those of the physical body.
   */
  template <int dim>
  class ElasticBody
  {
  public:
    ElasticBody(const std::string              &name,
                const MaterialParameters       &material,
                const DiscretizationParameters &discretization,
                const double                    out_of_plane_measure = 1.);

    /** The mesh; fill it (GridGenerator, GridIn) before calling setup(). */
    Triangulation<dim> &
    triangulation();
    const Triangulation<dim> &
    triangulation() const;

    /** Distribute DoFs and assemble M, K and (if there is damping) C. */
    void
    setup();

    /** Constant body force per unit volume [N/m^3], e.g. rho g. */
    void
    set_body_force(const Tensor<1, dim> &force_density);

    const std::string &
    name() const;
    const MaterialParameters &
    material() const;
    /**
     * dx / c_p: the time a P-wave takes to cross a cell, with dx = (volume /
     * number of cells)^(1/dim) the mean cell size and c_p the material's
     * longitudinal wave speed. h over it is the mesh's Courant number.
     */
    double
    cell_transit_time() const;
    /** The constitutive law of the body (from its MaterialParameters). */
    const ConstitutiveModel<dim> &
    constitutive_model() const;
    /**
     * The internal variables of the quadrature points of @p cell (a 2-point
     * Gauss rule per direction), set up by setup().
     */
    std::vector<std::shared_ptr<MaterialPointHistory>>
    material_point_history(
      const typename Triangulation<dim>::cell_iterator &cell);
    /** After an accepted step: the current internal variables become the
     * start-of-step ones. */
    void
    accept_material_step();
    const DoFHandler<dim> &
    dof_handler() const;
    unsigned int
    n_dofs() const;

    const SparsityPattern &
    sparsity_pattern() const;
    const SparseMatrix<double> &
    mass_matrix() const;
    const SparseMatrix<double> &
    stiffness_matrix() const;
    /** Empty (zero-sized) when the material has no damping. */
    const SparseMatrix<double> &
    damping_matrix() const;
    bool
    has_damping() const;
    /** Consistent load vector of the body force. */
    const Vector<double> &
    external_force() const;

    /**
     * Mass redistribution (Khenous, Laborde, Renard, Eur. J. Mech. A 27,
     * 2008): the vertices @p massless_vertices carry no mass. In each cell
     * that holds one, the element mass of those vertices (their row sums)
     * goes to the vertices of the cell joined to them by an edge and not
     * massless themselves (to all of the cell's other vertices if none is
     * joined), and the coupling of the other vertices to them goes to their
     * own diagonal. The rest of the element mass is unchanged (consistent or
     * lumped), so the total mass is kept; the first moments move by at most
     * a cell. Throws if a cell has only massless vertices. Re-assembles M
     * (and C, whose Rayleigh term uses M).
     */
    void
    redistribute_mass(const std::vector<unsigned int> &massless_vertices);

    /** The DoFs of the vertices that redistribute_mass() left massless. */
    std::vector<types::global_dof_index>
    massless_dofs() const;

    /** Total mass, from the mass matrix (a check on the assembly). */
    double
    total_mass() const;

    /**
     * The DoF of component @p component at the mesh vertex @p vertex_index.
     */
    types::global_dof_index
    vertex_dof(const unsigned int vertex_index,
               const unsigned int component) const;

    /** Nodal value of a DoF vector, by vertex and component. */
    double
    nodal_value(const Vector<double> &vector,
                const unsigned int    vertex_index,
                const unsigned int    component) const;

    /** Apply a constant vector (e.g. an initial velocity) to every node. */
    void
    fill_uniform(Vector<double> &vector, const Tensor<1, dim> &value) const;

  private:
    std::string                             body_name;
    MaterialParameters                      material_parameters;
    std::unique_ptr<ConstitutiveModel<dim>> model;
    CellDataStorage<typename Triangulation<dim>::cell_iterator,
                    MaterialPointHistory>
                             point_history;
    DiscretizationParameters discretization_parameters;
    double                   out_of_plane;

    Triangulation<dim>   mesh;
    FESystem<dim>        fe;
    DoFHandler<dim>      dofs;
    SparsityPattern      pattern;
    SparseMatrix<double> mass;
    SparseMatrix<double> stiffness;
    SparseMatrix<double> damping;
    Vector<double>       body_force_vector;
    Tensor<1, dim>       body_force_density;
    /// DoF of (vertex, component) at index vertex * dim + component.
    std::vector<types::global_dof_index> vertex_dofs;
    /// Per mesh vertex: no mass (redistribute_mass()). Empty if none.
    std::vector<bool> massless_vertex;

    void
    assemble();
  };
} // namespace impactfe

#endif
