// A cylinder of finite-strain J2 plastic material hitting the rigid wall
// z = 0: total Lagrangian Q1 with F-bar, the theta-method at velocity
// level, Newton's method with the contact LCP condensed on the current
// tangent at every iterate. Two models of the same bar: axisymmetric (r-z,
// dim = 2) and a 3D quarter of it (dim = 3) that checks the first. The
// Taylor bar of issue 13 (programs/taylor_bar).
#ifndef impactfe_finite_strain_finite_strain_impact_h
#define impactfe_finite_strain_finite_strain_impact_h

#include <deal.II/base/mpi.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/fe/fe_system.h>

#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <impactfe/bodies/finite_strain_plasticity.h>
#include <impactfe/bodies/material.h>
#include <impactfe/lcp/contact_problem.h>
#include <impactfe/output/output.h>

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  class SparseLU;

  /** What one time step did. */
  struct FiniteStrainStepReport
  {
    unsigned int newton_iterations = 0;
    /// Relative residual of each Newton iterate (for the rate).
    std::vector<double> residuals;
    /// Indices into residuals where Newton's method restarted on a changed
    /// problem: a late candidate joined the LCP or a pinned contact was
    /// released, after the iterates had converged.
    std::vector<unsigned int> restarts;
    /// Candidates left out of the LCP that crossed the wall and joined it.
    unsigned int late_candidates = 0;
    unsigned int n_candidates    = 0;
    unsigned int n_closed        = 0;
    /// Sum of the normal impulses on the wall [N s] (the whole bar's).
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
    /// Candidates left out of a step's LCP (out of reach at the start of
    /// the step) that crossed the wall, and were added to it.
    unsigned int late_candidates = 0;
    /// Wall impulse [N s], largest contact force [N], last step with one [s].
    double wall_impulse = 0., peak_contact_force = 0., last_contact_time = 0.;
    /// Energy taken out by the contact impulses and by the scheme [J].
    double contact_dissipation = 0., scheme_dissipation = 0.;
    double worst_contact_violation = 0.;
    /// Newton's order log(r_k/r_k-1)/log(r_k-1/r_k-2) near the solution
    /// (r_k-1 < 1e-3, r_k > 1e-12; relative residuals).
    std::vector<double> convergence_orders;
    /// The pairs (r_k-1 < 1e-3, r_k > 1e-12) of successive residuals not
    /// across a restart, and those with r_k <= 10 r_k-1^2: quadratic
    /// convergence. Restarts of Newton's method (FiniteStrainStepReport).
    unsigned int pairs_near_solution = 0, quadratic_pairs = 0;
    unsigned int contact_restarts = 0;

    double
    newton_iterations_per_step() const;
    double
    median_convergence_order() const;
    /// quadratic_pairs / pairs_near_solution (1 if there are none). Below 1
    /// where a Gauss point or a contact changes state between iterates.
    double
    quadratic_fraction() const;
  };



  /**
   * A cylinder 0 <= r <= radius, 0 <= z <= length, its lower end touching
   * the wall z = 0 at t = 0 and moving at -speed e_z. Contact candidates:
   * the nodes of the lower end and of the side, with normal e_z. Forces,
   * impulses, masses and energies are those of the whole cylinder.
   *
   * The interface of the two models; create() makes the one that
   * Settings::model names. The model is FiniteStrainCylinder<dim>.
   */
  class FiniteStrainImpact
  {
  public:
    /** Which discretisation of the cylinder. */
    enum class Model
    {
      /// r-z plane, unknowns (u_r, u_z), hoop stretch 1 + u_r/r.
      axisymmetric,
      /// The quarter x >= 0, y >= 0 in 3D, with symmetry planes.
      three_dimensional
    };

    /**
     * Parameter subsections `Geometry`, `Initial conditions`, `Time`,
     * `Contact` and `Discretisation` (the Taylor bar's defaults).
     */
    struct Settings
    {
      Model        model  = Model::axisymmetric;
      double       radius = 3.2e-3, length = 32.4e-3, speed = 227.;
      unsigned int n_radial = 5, n_axial = 50;
      double       theta = 1., time_step = 2e-7, end_time = 80e-6;
      double       friction_coefficient = 0.;
      bool         bilateral            = false;
      bool         f_bar                = true;
      /// Newton's tangent in closed form (false: by central differences
      /// of the cell forces, 'finite differences').
      bool         closed_form_tangent   = true;
      double       newton_tolerance      = 1e-9;
      unsigned int max_newton_iterations = 25;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
      unsigned int
      n_steps() const;
      /// Throws, naming the entry, if a value is out of range.
      void
      check() const;
    };

    /**
     * Parameter subsection `Material` of the Taylor bar: Young's modulus,
     * Poisson's ratio and the density, copper by default (the bar of the
     * paper's section 6.4). The J2 model has no viscosity or Rayleigh
     * damping, so those entries of MaterialParameters are not declared.
     */
    static void
    declare_material_parameters(ParameterHandler &prm);
    static MaterialParameters
    parse_material_parameters(ParameterHandler &prm);

    /**
     * Parameter subsection `Verification`: checks against results known
     * without the run (taylor_bar's report_checks()).
     */
    struct Verification
    {
      /// The 1D elastic bar hitting a rigid wall (needs nu = 0 and an
      /// elastic impact), and the largest relative error it allows.
      bool   rebound_check     = false;
      double max_rebound_error = 0.05;
      /// If > 0: the final length and the footprint radius within the
      /// published ranges widened by this relative amount.
      double published_tolerance = 0.;

      static void
      declare_parameters(ParameterHandler &prm);
      /// Throws if the rebound check is asked for with @p material's
      /// Poisson's ratio other than 0.
      void
      parse_parameters(ParameterHandler         &prm,
                       const MaterialParameters &material);
    };

    /**
     * The model @p settings names, set up at t = 0. On a @p communicator of
     * more than one process the mesh is distributed (p4est): each rank
     * assembles its cells and keeps their internal variables, the Newton
     * matrices are Trilinos matrices factorised by MUMPS (Amesos), and the
     * nodal vectors, the candidates and the contact LCP are held on every
     * rank; every query below is then collective. On one process: the
     * serial mesh and UMFPACK.
     */
    static std::unique_ptr<FiniteStrainImpact>
    create(const Settings             &settings,
           const MaterialParameters   &material,
           const PlasticityParameters &plasticity,
           const MPI_Comm              communicator = MPI_COMM_SELF);

    virtual ~FiniteStrainImpact() = default;

    /** Advance one step; throws with the step number if Newton fails. */
    virtual FiniteStrainStepReport
    do_time_step() = 0;

    virtual double
    time() const = 0;
    virtual const FiniteStrainRunTotals &
    totals() const = 0;
    /**
     * (E_kin(0) - E_kin - stored - plastic work - contact and scheme
     * dissipation) / E_kin(0): what the internal forces' discrete work
     * misses of the energy increments.
     */
    double
    energy_balance_error() const;
    virtual double
    kinetic_energy() const = 0;
    /** Stored elastic energy [J] (Hencky energy of F-bar). */
    virtual double
    stored_energy() const = 0;
    /** Plastic work int (sigma_y + H alpha) dalpha over the body [J]. */
    virtual double
    plastic_work() const = 0;
    /** Largest z of the deformed body [m]. */
    virtual double
    current_length() const = 0;
    /**
     * Depth of the deepest node below the wall [m] (0 if none). Contact
     * candidates stay above it; a node inside the body gets below it only
     * where the cells between it and the wall have folded, so this measures
     * the mesh's failure, not the contact's.
     */
    virtual double
    deepest_node_below_wall() const = 0;
    /** Largest distance from the axis of the nodes of the lower end [m]. */
    virtual double
    footprint_radius() const = 0;
    /**
     * Largest distance from the axis of the nodes touching the wall
     * (closed in the last contact problem, or tied) [m]: the radius of the
     * contact zone.
     */
    virtual double
    contact_radius() const = 0;
    /** Largest equivalent plastic strain at a quadrature point. */
    virtual double
    max_equivalent_plastic_strain() const = 0;
    virtual unsigned int
    n_dofs() const = 0;
    /** Kinetic energy at t = 0 [J]. */
    virtual double
    initial_energy() const = 0;
    /** Momentum of the bar along z [N s]. */
    virtual double
    axial_momentum() const = 0;

    /**
     * Add the run's figures to @p summary (summary.json): the size, the
     * shape, the energies, Newton's statistics and the contact totals,
     * with the impulse balance against @p initial_momentum. Collective.
     */
    void
    add_to_summary(JsonObject &summary, const double initial_momentum) const;

    /**
     * The deformed cells of the r-z section (in 3D: the faces on the
     * symmetry plane y = 0) as CSV rows `r0,z0,r1,z1,r2,z2,r3,z3,alpha`,
     * corners counter-clockwise, alpha the cell's mean equivalent plastic
     * strain: for figures of the deformed shape.
     */
    virtual void
    write_cells_csv(const std::string &file_name) const = 0;

    /**
     * `solution-<step>.vtu` in @p directory (the deformed mesh with the
     * displacement, the velocity and alpha per cell) and the record of all
     * written so far in `solution.pvd`; distributed: one piece per rank,
     * `solution_<step>.<rank>.vtu`, and `solution_<step>.pvtu`.
     */
    virtual void
    write_vtu(const std::string &directory, const unsigned int step) = 0;
  };



  /**
   * The two models. dim = 2: the r-z plane (x = r, y = z), unknowns
   * (u_r, u_z), u_r = 0 on the axis, weights 2 pi r JxW. dim = 3: the
   * quarter x, y >= 0 of the cylinder (axis z), u_x = 0 on x = 0 and u_y = 0
   * on y = 0, weights 4 JxW so that all totals are the whole cylinder's; its
   * cross-section is deal.II's quarter_hyper_ball refined, Radial cells
   * across the radius (a power of two). Friction needs a tangent direction
   * per contact: the 3D model has the frictionless and the bilateral wall.
   */
  template <int dim>
  class FiniteStrainCylinder : public FiniteStrainImpact
  {
  public:
    FiniteStrainCylinder(const Settings             &settings,
                         const MaterialParameters   &material,
                         const PlasticityParameters &plasticity,
                         const MPI_Comm              communicator);
    ~FiniteStrainCylinder() override;

    FiniteStrainStepReport
    do_time_step() override;
    double
    time() const override;
    const FiniteStrainRunTotals &
    totals() const override;
    double
    kinetic_energy() const override;
    double
    stored_energy() const override;
    double
    plastic_work() const override;
    double
    current_length() const override;
    double
    deepest_node_below_wall() const override;
    double
    footprint_radius() const override;
    double
    contact_radius() const override;
    double
    max_equivalent_plastic_strain() const override;
    unsigned int
    n_dofs() const override;
    double
    initial_energy() const override;
    double
    axial_momentum() const override;
    void
    write_cells_csv(const std::string &file_name) const override;
    void
    write_vtu(const std::string &directory, const unsigned int step) override;

  private:
    static constexpr unsigned int n_vertices =
      GeometryInfo<dim>::vertices_per_cell;
    static constexpr unsigned int n_cell_dofs = dim * n_vertices;
    /// Gauss points per cell (2 per direction).
    static constexpr unsigned int n_gauss = n_vertices;
    /// The Gauss points and the centre (the last, for F-bar's J0).
    static constexpr unsigned int n_points = n_gauss + 1;
    /// The component along the axis (z).
    static constexpr unsigned int axial = dim - 1;
    using CellVector                    = std::array<double, n_cell_dofs>;

    /// Shape functions of one cell at its points, in the reference
    /// configuration: total Lagrangian, so computed once.
    struct CellGeometry
    {
      std::array<std::array<double, n_cell_dofs>, n_points>         N;
      std::array<std::array<Tensor<1, dim>, n_cell_dofs>, n_points> grad_N;
      std::array<double, n_points>                                  radius;
      /// 2 pi r JxW (axisymmetric) or 4 JxW (3D); the centre's is unused.
      std::array<double, n_points>                     weight;
      std::array<unsigned int, n_cell_dofs>            component;
      std::array<types::global_dof_index, n_cell_dofs> dofs;
    };

    void
    setup_system();
    void
    make_mesh();
    /// Current distance from the axis of candidate @p k [m].
    double
    candidate_radius(const unsigned int k) const;
    /// Largest current distance from the axis of the candidates that
    /// @p selected picks [m].
    double
    largest_candidate_radius(
      const std::function<bool(unsigned int)> &selected) const;
    /// F = I + Grad u (with the hoop stretch 1 + u_r/r if axisymmetric) at
    /// point @p q of a cell (n_gauss: the centre) for its nodal
    /// displacements @p u.
    static Tensor<2, 3>
    deformation_gradient(const CellGeometry &cell,
                         const CellVector   &u,
                         const unsigned int  q);
    /// One theta-step of length @p h; false if Newton's method did not
    /// converge (the state is then partly updated: the caller restores it).
    bool
    try_step(const double h, FiniteStrainStepReport &report);
    /**
     * f_int(u) on every rank and, if @p with_tangent, its tangent into the
     * Newton matrix (serial or distributed).
     */
    void
    assemble_internal_force(const Vector<double> &displacement,
                            Vector<double>       &force,
                            const bool            with_tangent);
    /**
     * The Newton matrix from the tangent: A = M + (h theta)^2 K_t, the rows
     * of @p fixed replaced by M's diagonal; then factorised.
     */
    void
    factorize_newton_matrix(const double                                h,
                            const std::vector<types::global_dof_index> &fixed);
    /** x = A^{-1} b, on every rank. */
    void
    solve_newton_matrix(const Vector<double> &b, Vector<double> &x);
    /**
     * Sum a vector over the ranks (nothing on one), the same bits on
     * every rank (reduced on rank 0, broadcast).
     */
    void
    sum_over_ranks(Vector<double> &v) const;
    /// The same for a number (the energies, which the checks compare).
    double
    sum_over_ranks(const double x) const;
    using Branch = FiniteStrainJ2Model<3>::Branch;
    /// The cell's internal force; updated internal variables to @p history
    /// (one vector per Gauss point) if not null. A Gauss point whose entry
    /// of @p branches is automatic gets the return-mapping branch it took;
    /// the others are evaluated on the branch given.
    /// With @p tangent not null, also the cell's consistent tangent in
    /// closed form.
    void
    cell_force(const unsigned int                cell,
               const CellVector                 &cell_displacement,
               CellVector                       &force,
               std::vector<std::vector<double>> *history,
               std::array<Branch, n_gauss>      &branches,
               FullMatrix<double>               *tangent = nullptr) const;
    /// dF/du_i at point @p q of a cell (hoop term included).
    static Tensor<2, 3>
    shape_gradient(const CellGeometry &cell,
                   const unsigned int  q,
                   const unsigned int  i);
    /// Mean equivalent plastic strain of a cell.
    double
    cell_alpha(const unsigned int cell) const;

    Settings               settings;
    MaterialParameters     material;
    FiniteStrainJ2Model<3> law;
    MPI_Comm               communicator;
    /// More than one rank: a parallel::distributed::Triangulation.
    bool                                distributed;
    std::unique_ptr<Triangulation<dim>> triangulation;
    /// The locally owned cells (all in a serial run), in the order of
    /// their active_cell_index(), owned_cells[c] for the c-th; their
    /// internal variables below are numbered alike. local_cell: the
    /// inverse (invalid for the cells of other ranks).
    std::vector<CellGeometry> cells;
    std::vector<unsigned int> owned_cells, local_cell;
    /// Every vertex once: its reference coordinate along the axis and its
    /// DoF along it (on every rank).
    std::vector<std::pair<double, types::global_dof_index>> axial_vertices;
    double                    smallest_cell_size     = 0.;
    double                    initial_kinetic_energy = 0.;
    FESystem<dim>             fe;
    DoFHandler<dim>           dof_handler;
    AffineConstraints<double> constraints;
    SparsityPattern           sparsity;
    SparseMatrix<double>      step_matrix;
    /// LU of the Newton matrix; the analysis is kept for all steps.
    std::unique_ptr<SparseLU> step_solver;
    /// Distributed runs: the Trilinos Newton matrix and its MUMPS solver.
    struct DistributedMatrix;
    std::unique_ptr<DistributedMatrix> distributed_matrix;
    Vector<double>                     lumped_mass;
    Vector<double>                     displacement, velocity, old_force;
    std::vector<std::vector<double>>   history_old, history_new;
    /// Per candidate node: its DoFs (the last along z); which are on the
    /// lower end.
    std::vector<std::array<types::global_dof_index, dim>> candidate_dofs;
    std::vector<Point<dim>>                               candidate_positions;
    std::vector<bool>                                     on_lower_end;
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
