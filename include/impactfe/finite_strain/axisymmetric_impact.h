// An axisymmetric (r-z) cylinder of finite-strain J2 plastic material
// hitting the rigid wall z = 0: total Lagrangian Q1 with F-bar, the
// theta-method at velocity level, Newton's method with the contact LCP
// condensed on the current tangent at every iterate. The Taylor bar of
// issue 13 (programs/taylor_bar).
#ifndef impactfe_finite_strain_axisymmetric_impact_h
#define impactfe_finite_strain_axisymmetric_impact_h

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <impactfe/bodies/finite_strain_plasticity.h>
#include <impactfe/bodies/material.h>
#include <impactfe/lcp/contact_problem.h>

#include <array>
#include <functional>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /** What one time step did. */
  struct FiniteStrainStepReport
  {
    unsigned int newton_iterations = 0;
    /// Relative residual of each Newton iterate (for the rate).
    std::vector<double> residuals;
    unsigned int        n_candidates = 0;
    unsigned int        n_closed     = 0;
    /// Sum of the normal ring impulses [N s] (2 pi r included).
    double normal_impulse = 0.;
    /// Largest relative violation reported by verify_contact_solution().
    double contact_violation = 0.;
    /// Work of the contact impulses over the step [J] (<= 0: dissipated).
    double contact_work = 0.;
    /// Energy the theta-scheme dissipated: (theta - 1/2) |v1 - v0|_M^2 [J].
    double scheme_dissipation = 0.;
  };

  /** Sums over the steps so far. */
  struct FiniteStrainRunTotals
  {
    /// Steps made (substeps included), Newton iterations, steps redone
    /// with smaller substeps because Newton's method did not converge.
    unsigned int steps = 0, newton_iterations = 0, most_newton_iterations = 0;
    unsigned int step_reductions = 0;
    /// Wall impulse [N s], largest contact force [N], last step with one [s].
    double wall_impulse = 0., peak_contact_force = 0., last_contact_time = 0.;
    /// Energy taken out by the contact impulses and by the scheme [J].
    double contact_dissipation = 0., scheme_dissipation = 0.;
    double worst_contact_violation = 0.;
    /// Newton's order log(r_k/r_k-1)/log(r_k-1/r_k-2) near the solution.
    std::vector<double> convergence_orders;

    double
    newton_iterations_per_step() const;
    double
    median_convergence_order() const;
  };



  /**
   * The cylinder 0 <= r <= radius, 0 <= z <= length, its lower end touching
   * the wall z = 0 at t = 0 and moving at -speed e_z. Nodal unknowns are
   * (u_r, u_z); u_r = 0 on the axis. Forces and impulses are those of the
   * whole ring (2 pi r included). Contact candidates: the nodes of the
   * lower end and of the side, in the frame n = e_z, t = e_r; Coulomb
   * friction with coefficient mu (0: frictionless, the normal block only).
   */
  class AxisymmetricImpact
  {
  public:
    /**
     * Parameter subsections `Geometry`, `Initial conditions`, `Time`,
     * `Contact` and `Discretisation` (the Taylor bar's defaults).
     */
    struct Settings
    {
      double       radius = 3.2e-3, length = 32.4e-3, speed = 227.;
      unsigned int n_radial = 5, n_axial = 50;
      double       theta = 1., time_step = 2e-7, end_time = 80e-6;
      double       friction_coefficient  = 0.;
      bool         bilateral             = false;
      bool         f_bar                 = true;
      double       newton_tolerance      = 1e-9;
      unsigned int max_newton_iterations = 25;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
      unsigned int
      n_steps() const;
    };

    AxisymmetricImpact(const Settings             &settings,
                       const MaterialParameters   &material,
                       const PlasticityParameters &plasticity);

    /** Advance one step; throws with the step number if Newton fails. */
    FiniteStrainStepReport
    do_time_step();

    double
    time() const;
    const FiniteStrainRunTotals &
    totals() const;
    /**
     * (E_kin(0) - E_kin - stored - plastic work - contact and scheme
     * dissipation) / E_kin(0): what the internal forces' discrete work
     * misses of the energy increments.
     */
    double
    energy_balance_error() const;
    double
    kinetic_energy() const;
    /** Stored elastic energy [J] (Hencky energy of F-bar). */
    double
    stored_energy() const;
    /** Plastic work int (sigma_y + H alpha) dalpha over the body [J]. */
    double
    plastic_work() const;
    /** Largest z of the deformed body [m]. */
    double
    current_length() const;
    /** Largest r of the nodes of the lower end [m]. */
    double
    footprint_radius() const;
    /**
     * Largest r of the nodes touching the wall (closed in the last contact
     * problem, or tied) [m]: the radius of the contact zone.
     */
    double
    contact_radius() const;
    /** Largest equivalent plastic strain at a quadrature point. */
    double
    max_equivalent_plastic_strain() const;
    unsigned int
    n_dofs() const;
    /** Kinetic energy at t = 0 [J]. */
    double
    initial_energy() const;

    /** Momentum of the bar along z [N s]. */
    double
    axial_momentum() const;

    /**
     * The deformed cells as CSV rows `r0,z0,r1,z1,r2,z2,r3,z3,alpha`
     * (corners counter-clockwise, alpha the cell's mean equivalent plastic
     * strain): for figures of the deformed shape.
     */
    void
    write_cells_csv(const std::string &file_name) const;

    /**
     * `solution-<step>.vtu` in @p directory (the deformed mesh with the
     * displacement, the velocity and alpha per cell) and the record of all
     * written so far in `solution.pvd`.
     */
    void
    write_vtu(const std::string &directory, const unsigned int step);

  private:
    /// Shape functions of one cell at its 2x2 Gauss points and its centre
    /// (the last point, for F-bar's J0), in the reference configuration:
    /// total Lagrangian, so computed once.
    static constexpr unsigned int n_points = 5;
    struct CellGeometry
    {
      std::array<std::array<double, 8>, n_points>       N;
      std::array<std::array<Tensor<1, 2>, 8>, n_points> grad_N;
      std::array<double, n_points>                      radius;
      /// 2 pi r JxW (the centre's is unused).
      std::array<double, n_points>           ring_weight;
      std::array<unsigned int, 8>            component;
      std::array<types::global_dof_index, 8> dofs;
    };

    void
    setup_system();
    /// Largest current r of the candidates that @p selected picks [m].
    double
    largest_candidate_radius(
      const std::function<bool(unsigned int)> &selected) const;
    /// F = I + Grad u with the hoop stretch 1 + u_r/r at point @p q of a
    /// cell (4: the centre) for its nodal displacements @p u.
    static Tensor<2, 3>
    deformation_gradient(const CellGeometry          &cell,
                         const std::array<double, 8> &u,
                         const unsigned int           q);
    /// One theta-step of length @p h; false if Newton's method did not
    /// converge (the state is then partly updated: the caller restores it).
    bool
    try_step(const double h, FiniteStrainStepReport &report);
    /** f_int(u) (and its tangent by element central differences). */
    void
    assemble_internal_force(const Vector<double> &displacement,
                            Vector<double>       &force,
                            SparseMatrix<double> *tangent);
    using Branch = FiniteStrainJ2Model<3>::Branch;
    /// The cell's internal force; updated internal variables to @p history
    /// (one vector per Gauss point) if not null. A Gauss point whose entry
    /// of @p branches is automatic gets the return-mapping branch it took;
    /// the others are evaluated on the branch given.
    void
    cell_force(const unsigned int                cell,
               const std::array<double, 8>      &cell_displacement,
               std::array<double, 8>            &force,
               std::vector<std::vector<double>> *history,
               std::array<Branch, 4>            &branches) const;

    Settings                         settings;
    MaterialParameters               material;
    FiniteStrainJ2Model<3>           law;
    Triangulation<2>                 triangulation;
    std::vector<CellGeometry>        cells;
    double                           smallest_cell_size     = 0.;
    double                           initial_kinetic_energy = 0.;
    FESystem<2>                      fe;
    DoFHandler<2>                    dof_handler;
    AffineConstraints<double>        constraints;
    SparsityPattern                  sparsity;
    SparseMatrix<double>             step_matrix;
    Vector<double>                   lumped_mass;
    Vector<double>                   displacement, velocity, old_force;
    std::vector<std::vector<double>> history_old, history_new;
    /// Per candidate node: its (u_r, u_z) DoFs; and which are on the end.
    std::vector<std::array<types::global_dof_index, 2>> candidate_dofs;
    std::vector<Point<2>>                               candidate_positions;
    std::vector<bool>                                   on_lower_end;
    /// The last contact state of every candidate (guess for the next LCP).
    std::vector<ContactState> contact_states;
    /// Candidates tied to the wall (bilateral contact).
    std::vector<bool>                           tied;
    unsigned int                                step_number  = 0;
    double                                      current_time = 0.;
    FiniteStrainRunTotals                       run_totals;
    std::vector<std::pair<double, std::string>> vtu_records;
  };
} // namespace impactfe

#endif
