#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/distributed/tria.h>

#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/fe/mapping_q_eulerian.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/manifold_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <deal.II/numerics/data_out.h>

#include <impactfe/dynamics/sparse_lu.h>
#include <impactfe/finite_strain/finite_strain_impact.h>
#include <impactfe/utilities/mpi_errors.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <set>
#include <sstream>

namespace impactfe
{
  void
  FiniteStrainImpact::Settings::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    prm.declare_entry("Model",
                      "axisymmetric",
                      Patterns::Selection("axisymmetric|3d"),
                      "axisymmetric: the r-z plane with the hoop terms; 3d: "
                      "the quarter x, y >= 0 of the cylinder with symmetry "
                      "planes (frictionless or bilateral wall only).");
    prm.declare_entry("Radius",
                      "3.2e-3",
                      Patterns::Double(),
                      "Initial radius r0 of the bar [m].");
    prm.declare_entry("Length",
                      "32.4e-3",
                      Patterns::Double(),
                      "Initial length L0 of the bar [m].");
    prm.declare_entry("Radial cells",
                      "5",
                      Patterns::Integer(1),
                      "Q1 cells across the radius [-] (3d: a power of two "
                      ">= 2, the refined quarter disc).");
    prm.declare_entry("Axial cells",
                      "50",
                      Patterns::Integer(1),
                      "Q1 cells along the length [-].");
    prm.leave_subsection();
    prm.enter_subsection("Initial conditions");
    prm.declare_entry("Impact velocity",
                      "227",
                      Patterns::Double(),
                      "Speed v0 of the bar towards the wall [m/s].");
    prm.leave_subsection();
    prm.enter_subsection("Time");
    prm.declare_entry("End time",
                      "80e-6",
                      Patterns::Double(),
                      "End time T [s]. Must be >= the time step. The run "
                      "makes ceil(T / h) steps: it ends at the first "
                      "multiple of h at or after T.");
    prm.declare_entry("Time step",
                      "2e-7",
                      Patterns::Double(),
                      "Time step h [s]. Must be > 0.");
    prm.declare_entry("Theta",
                      "1",
                      Patterns::Double(),
                      "theta of the theta-method [-], in [0.5, 1].");
    prm.leave_subsection();
    prm.enter_subsection("Contact");
    prm.declare_entry("Bilateral contact",
                      "false",
                      Patterns::Bool(),
                      "true: a node stays tied to the wall, in both "
                      "directions, from the step after it first pushes on "
                      "it (the full-stick treatment common for the Taylor "
                      "bar); false: unilateral contact with Coulomb "
                      "friction.");
    prm.declare_entry("Friction coefficient",
                      "0",
                      Patterns::Double(),
                      "Coulomb coefficient mu at the wall [-] (0: "
                      "frictionless, normal LCP rows only).");
    prm.leave_subsection();
    prm.enter_subsection("Discretisation");
    prm.declare_entry("F-bar",
                      "true",
                      Patterns::Bool(),
                      "Use F-bar (false: plain Q1, which locks under the "
                      "isochoric plastic flow).");
    prm.declare_entry("Tangent",
                      "closed form",
                      Patterns::Selection("closed form|finite differences"),
                      "The consistent tangent of Newton's method: 'closed "
                      "form', or 'finite differences' (central differences "
                      "of the cell forces, 16-48 cell evaluations per cell, "
                      "for checking).");
    prm.declare_entry("Newton tolerance",
                      "1e-9",
                      Patterns::Double(),
                      "Newton stops when the residual, relative to the "
                      "momentum max(M) v0, is below this [-].");
    prm.declare_entry("Maximum Newton iterations",
                      "25",
                      Patterns::Integer(1),
                      "A step that needs more stops the run with a message "
                      "[-].");
    prm.leave_subsection();
  }



  void
  FiniteStrainImpact::Settings::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Geometry");
    model =
      prm.get("Model") == "3d" ? Model::three_dimensional : Model::axisymmetric;
    radius   = prm.get_double("Radius");
    length   = prm.get_double("Length");
    n_radial = prm.get_integer("Radial cells");
    n_axial  = prm.get_integer("Axial cells");
    prm.leave_subsection();
    require_positive(radius, "Geometry", "Radius");
    require_positive(length, "Geometry", "Length");
    prm.enter_subsection("Initial conditions");
    speed = prm.get_double("Impact velocity");
    prm.leave_subsection();
    require_positive(speed, "Initial conditions", "Impact velocity");
    prm.enter_subsection("Time");
    end_time  = prm.get_double("End time");
    time_step = prm.get_double("Time step");
    theta     = prm.get_double("Theta");
    prm.leave_subsection();
    require_positive(end_time, "Time", "End time");
    prm.enter_subsection("Contact");
    friction_coefficient = prm.get_double("Friction coefficient");
    bilateral            = prm.get_bool("Bilateral contact");
    prm.leave_subsection();
    prm.enter_subsection("Discretisation");
    f_bar                 = prm.get_bool("F-bar");
    closed_form_tangent   = prm.get("Tangent") == "closed form";
    newton_tolerance      = prm.get_double("Newton tolerance");
    max_newton_iterations = prm.get_integer("Maximum Newton iterations");
    prm.leave_subsection();
    require_positive(newton_tolerance, "Discretisation", "Newton tolerance");
    check();
  }



  void
  FiniteStrainImpact::Settings::check() const
  {
    AssertThrow(theta >= 0.5 && theta <= 1.,
                ExcMessage("Time/Theta = " + format_number(theta) +
                           " must be in [0.5, 1]."));
    require_positive(time_step, "Time", "Time step");
    // no step would end within the run (it made 0 steps and exited 0)
    AssertThrow(time_step <= end_time,
                ExcMessage("Time: 'Time step' = " + format_number(time_step) +
                           " s is longer than 'End time' = " +
                           format_number(end_time) + " s."));
    require_friction_coefficient(friction_coefficient,
                                 "Contact",
                                 "Friction coefficient");
    if (model == Model::three_dimensional)
      {
        AssertThrow(friction_coefficient == 0.,
                    ExcMessage("Contact/Friction coefficient = " +
                               format_number(friction_coefficient) +
                               ": the 3d model has the frictionless and the "
                               "bilateral wall only; use Geometry/Model = "
                               "axisymmetric for Coulomb friction."));
        AssertThrow(n_radial >= 2 && (n_radial & (n_radial - 1)) == 0,
                    ExcMessage(
                      "Geometry/Radial cells = " + std::to_string(n_radial) +
                      ": the 3d model needs a power of two >= 2."));
      }
    // The 3d disc is a refined quarter ball: 3 (n_radial / 2)^2 cells.
    // Half the peak memory per cell measured on taylor_bar: 22 kB
    // (axisymmetric) and 60 kB (3d).
    if (model == Model::three_dimensional)
      require_mesh_fits_in_memory(0.75 * n_radial * n_radial * n_axial,
                                  3,
                                  "Geometry",
                                  "'Radial cells' and 'Axial cells'",
                                  3e4);
    else
      require_mesh_fits_in_memory(double(n_radial) * n_axial,
                                  2,
                                  "Geometry",
                                  "'Radial cells' and 'Axial cells'",
                                  1.1e4);
  }



  void
  FiniteStrainImpact::declare_material_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Material");
    prm.declare_entry("Young's modulus",
                      "117e9",
                      Patterns::Double(),
                      "Young's modulus E [Pa]. Must be > 0. Default: "
                      "copper, 117 GPa (the bar of the paper's section "
                      "6.4).");
    prm.declare_entry("Poisson's ratio",
                      "0.35",
                      Patterns::Double(),
                      "Poisson's ratio nu [-], in [0, 0.5). Default: "
                      "copper, 0.35.");
    prm.declare_entry("Density",
                      "8930",
                      Patterns::Double(),
                      "Mass density rho [kg/m^3]. Must be > 0. Default: "
                      "copper, 8930 kg/m^3.");
    prm.leave_subsection();
  }



  MaterialParameters
  FiniteStrainImpact::parse_material_parameters(ParameterHandler &prm)
  {
    MaterialParameters material;
    prm.enter_subsection("Material");
    material.youngs_modulus = prm.get_double("Young's modulus");
    material.poissons_ratio = prm.get_double("Poisson's ratio");
    material.density        = prm.get_double("Density");
    prm.leave_subsection();
    material.check("Material");
    return material;
  }



  std::unique_ptr<FiniteStrainImpact>
  FiniteStrainImpact::create(const Settings             &settings,
                             const MaterialParameters   &material,
                             const PlasticityParameters &plasticity,
                             const MPI_Comm              communicator)
  {
    if (settings.model == Model::three_dimensional)
      return std::make_unique<FiniteStrainCylinder<3>>(settings,
                                                       material,
                                                       plasticity,
                                                       communicator);
    return std::make_unique<FiniteStrainCylinder<2>>(settings,
                                                     material,
                                                     plasticity,
                                                     communicator);
  }



  unsigned int
  FiniteStrainImpact::Settings::n_steps() const
  {
    // as TimeSteppingParameters::n_steps(): the first multiple of h at or
    // after T (1e-9 of a step of rounding is not one more step)
    return static_cast<unsigned int>(std::ceil(end_time / time_step - 1e-9));
  }



  // A distributed run's Newton matrix: the rows of the locally owned DoFs,
  // factorised by MUMPS through Amesos.
  template <int dim>
  struct FiniteStrainCylinder<dim>::DistributedMatrix
  {
    IndexSet                                        owned;
    TrilinosWrappers::SparseMatrix                  matrix;
    SolverControl                                   control;
    std::unique_ptr<TrilinosWrappers::SolverDirect> solver;
    TrilinosWrappers::MPI::Vector                   rhs, solution;
  };



  template <int dim>
  FiniteStrainCylinder<dim>::FiniteStrainCylinder(
    const Settings             &settings,
    const MaterialParameters   &material,
    const PlasticityParameters &plasticity,
    const MPI_Comm              communicator)
    : settings(settings)
    , material(material)
    , law(material, plasticity)
    , communicator(communicator)
    , distributed(Utilities::MPI::job_supports_mpi() &&
                  Utilities::MPI::n_mpi_processes(communicator) > 1)
    , triangulation(
        distributed ?
          std::make_unique<parallel::distributed::Triangulation<dim>>(
            communicator) :
          std::make_unique<Triangulation<dim>>())
    , fe(FE_Q<dim>(1), dim)
    , step_solver(std::make_unique<SparseLU>())
  {
    settings.check();
    AssertThrow((dim == 3) == (settings.model == Model::three_dimensional),
                ExcMessage("FiniteStrainCylinder<" + std::to_string(dim) +
                           "> does not make this Geometry/Model."));
    setup_system();
  }



  template <int dim>
  FiniteStrainCylinder<dim>::~FiniteStrainCylinder() = default;



  // @sect3{Set-up: mesh, reference shape functions, mass, candidates}
  //
  // Axisymmetric: the rectangle [0, r0] x [0, L0] in the r-z plane. 3D: the
  // quarter disc (deal.II's quarter_hyper_ball, its curved edge on the
  // circle) refined to Radial cells across the radius, flattened and
  // extruded along z.
  template <>
  void
  FiniteStrainCylinder<2>::make_mesh()
  {
    GridGenerator::subdivided_hyper_rectangle(
      *triangulation,
      {settings.n_radial, settings.n_axial},
      Point<2>(0., 0.),
      Point<2>(settings.radius, settings.length));
  }



  template <>
  void
  FiniteStrainCylinder<3>::make_mesh()
  {
    Triangulation<2> disc;
    GridGenerator::quarter_hyper_ball(disc, Point<2>(), settings.radius);
    // quarter_hyper_ball has two cells across the radius.
    disc.refine_global(std::lround(std::log2(settings.n_radial)) - 1);
    Triangulation<2> flat_disc;
    GridGenerator::flatten_triangulation(disc, flat_disc);
    GridGenerator::extrude_triangulation(flat_disc,
                                         settings.n_axial + 1,
                                         settings.length,
                                         *triangulation);
    // The side faces (and their edges) follow the cylinder, and
    // setup_system() maps the reference cells with MappingQ(2): the initial
    // volume and mass are the cylinder's, not those of the inscribed
    // polygonal prism (2.5 % less at 4 cells across the radius).
    triangulation->set_manifold(1, CylindricalManifold<3>(2));
    const double tolerance = 1e-10 * settings.radius;
    for (const auto &cell : triangulation->active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            bool on_side = true;
            for (const unsigned int v : cell->face(f)->vertex_indices())
              {
                const Point<3> &x = cell->face(f)->vertex(v);
                on_side           = on_side && std::abs(std::hypot(x[0], x[1]) -
                                              settings.radius) < tolerance;
              }
            if (on_side)
              cell->face(f)->set_all_manifold_ids(1);
          }
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::setup_system()
  {
    make_mesh();
    dof_handler.reinit(*triangulation);
    dof_handler.distribute_dofs(fe);
    // The finite-difference step of the tangent is relative to this.
    smallest_cell_size =
      (dim == 2) ?
        std::min(settings.radius / settings.n_radial,
                 settings.length / settings.n_axial) :
        GridTools::minimal_cell_diameter(*triangulation) / std::sqrt(3.);

    if (distributed)
      {
        distributed_matrix   = std::make_unique<DistributedMatrix>();
        DistributedMatrix &A = *distributed_matrix;
        A.owned              = dof_handler.locally_owned_dofs();
        IndexSet relevant;
        DoFTools::extract_locally_relevant_dofs(dof_handler, relevant);
        TrilinosWrappers::SparsityPattern pattern(A.owned,
                                                  A.owned,
                                                  relevant,
                                                  communicator);
        DoFTools::make_sparsity_pattern(dof_handler,
                                        pattern,
                                        AffineConstraints<double>(),
                                        false,
                                        Utilities::MPI::this_mpi_process(
                                          communicator));
        pattern.compress();
        A.matrix.reinit(pattern);
        A.rhs.reinit(A.owned, communicator);
        A.solution.reinit(A.owned, communicator);
      }
    else
      {
        DynamicSparsityPattern dsp(dof_handler.n_dofs());
        DoFTools::make_sparsity_pattern(dof_handler, dsp);
        sparsity.copy_from(dsp);
        step_matrix.reinit(sparsity);
      }

    // Shape functions at the Gauss points and at the centre of each cell.
    std::vector<Point<dim>> points = QGauss<dim>(2).get_points();
    Point<dim>              centre;
    for (unsigned int d = 0; d < dim; ++d)
      centre[d] = 0.5;
    points.push_back(centre);
    const Quadrature<dim> quadrature(points,
                                     std::vector<double>(n_points,
                                                         1. / n_gauss));
    const MappingQ<dim>   mapping(dim == 3 ? 2 : 1);
    FEValues<dim>         fe_values(mapping,
                            fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points | update_JxW_values);
    lumped_mass.reinit(dof_handler.n_dofs());
    cells.clear();
    owned_cells.clear();
    local_cell.assign(triangulation->n_active_cells(),
                      numbers::invalid_unsigned_int);
    std::vector<types::global_dof_index> dofs(n_cell_dofs);
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        local_cell[cell->active_cell_index()] = cells.size();
        owned_cells.push_back(cell->active_cell_index());
        fe_values.reinit(cell);
        cell->get_dof_indices(dofs);
        CellGeometry &g = cells.emplace_back();
        for (unsigned int i = 0; i < n_cell_dofs; ++i)
          {
            g.dofs[i]      = dofs[i];
            g.component[i] = fe.system_to_component_index(i).first;
          }
        for (unsigned int q = 0; q < n_points; ++q)
          {
            const Point<dim> &x = fe_values.quadrature_point(q);
            g.radius[q] =
              dim == 2 ? x[0] : std::sqrt(x[0] * x[0] + x[1] * x[1]);
            g.weight[q] =
              (q == n_gauss) ? 0. :
              (dim == 2)     ? 2. * numbers::PI * x[0] * fe_values.JxW(q) :
                               4. * fe_values.JxW(q);
            for (unsigned int i = 0; i < n_cell_dofs; ++i)
              {
                const unsigned int c = g.component[i];
                g.N[q][i]            = fe_values.shape_value_component(i, q, c);
                g.grad_N[q][i]       = fe_values.shape_grad_component(i, q, c);
                // Row sums of the consistent mass.
                lumped_mass[dofs[i]] +=
                  material.density * g.N[q][i] * g.weight[q];
              }
          }
      }
    sum_over_ranks(lumped_mass);

    // Symmetry: u_x = 0 on x = 0 (the axis in r-z), and in 3D u_y = 0 on
    // y = 0. Candidates: the nodes of the side and of the lower end. Every
    // vertex, with its reference z and its DoF along z (lengths, momentum).
    // Each rank finds those of its cells; a distributed run gathers them on
    // every rank, the candidates sorted by position (z, then the other
    // coordinates from the last) so that the LCP's rows do not depend on
    // the partition.
    const double                      tolerance = 1e-10 * settings.radius;
    std::set<types::global_dof_index> symmetry, seen, seen_vertex;
    // per candidate: its dim DoFs, its dim coordinates, on the lower end
    std::vector<double> found;
    for (const auto &cell : dof_handler.active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        for (const unsigned int v : cell->vertex_indices())
          if (seen_vertex.insert(cell->vertex_dof_index(v, axial)).second)
            axial_vertices.emplace_back(cell->vertex(v)[axial],
                                        cell->vertex_dof_index(v, axial));
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary())
            for (const unsigned int v : cell->face(f)->vertex_indices())
              {
                const auto        face = cell->face(f);
                const Point<dim> &x    = face->vertex(v);
                for (unsigned int d = 0; d < dim - 1; ++d)
                  if (std::abs(x[d]) < tolerance)
                    symmetry.insert(face->vertex_dof_index(v, d));
                double r = std::abs(x[0]);
                if (dim == 3)
                  r = std::sqrt(x[0] * x[0] + x[1] * x[1]);
                const bool on_end = std::abs(x[axial]) < tolerance;
                if ((on_end || std::abs(r - settings.radius) < tolerance) &&
                    seen.insert(face->vertex_dof_index(v, axial)).second)
                  {
                    for (unsigned int d = 0; d < dim; ++d)
                      found.push_back(face->vertex_dof_index(v, d));
                    for (unsigned int d = 0; d < dim; ++d)
                      found.push_back(x[d]);
                    found.push_back(on_end ? 1. : 0.);
                  }
              }
      }
    const unsigned int record = 2 * dim + 1;
    if (distributed)
      {
        std::vector<types::global_dof_index> local_symmetry(symmetry.begin(),
                                                            symmetry.end());
        symmetry.clear();
        for (const auto &part :
             Utilities::MPI::all_gather(communicator, local_symmetry))
          symmetry.insert(part.begin(), part.end());
        std::vector<double> vertices;
        for (const auto &[z, dof] : axial_vertices)
          vertices.insert(vertices.end(), {z, double(dof)});
        std::map<types::global_dof_index, double> all_vertices;
        for (const auto &part :
             Utilities::MPI::all_gather(communicator, vertices))
          for (std::size_t i = 0; i < part.size(); i += 2)
            all_vertices.emplace(
              static_cast<types::global_dof_index>(part[i + 1]), part[i]);
        axial_vertices.clear();
        for (const auto &[dof, z] : all_vertices)
          axial_vertices.emplace_back(z, dof);
        // each candidate once (by its DoF along z), sorted by position
        std::map<types::global_dof_index, std::vector<double>> unique;
        for (const auto &part : Utilities::MPI::all_gather(communicator, found))
          for (std::size_t i = 0; i < part.size(); i += record)
            unique.emplace(
              static_cast<types::global_dof_index>(part[i + axial]),
              std::vector<double>(part.begin() + i, part.begin() + i + record));
        std::vector<std::vector<double>> sorted;
        for (auto &entry : unique)
          sorted.push_back(std::move(entry.second));
        std::sort(sorted.begin(),
                  sorted.end(),
                  [](const std::vector<double> &a,
                     const std::vector<double> &b) {
                    return std::lexicographical_compare(a.rbegin() + 1,
                                                        a.rbegin() + 1 + dim,
                                                        b.rbegin() + 1,
                                                        b.rbegin() + 1 + dim);
                  });
        found.clear();
        for (const auto &c : sorted)
          found.insert(found.end(), c.begin(), c.end());
      }
    for (std::size_t i = 0; i < found.size(); i += record)
      {
        std::array<types::global_dof_index, dim> node_dofs;
        Point<dim>                               x;
        for (unsigned int d = 0; d < dim; ++d)
          {
            node_dofs[d] = static_cast<types::global_dof_index>(found[i + d]);
            x[d]         = found[i + dim + d];
          }
        candidate_dofs.push_back(node_dofs);
        candidate_positions.push_back(x);
        on_lower_end.push_back(found[i + 2 * dim] > 0.5);
      }
    AssertThrow(!candidate_dofs.empty(),
                ExcMessage("Taylor bar: no contact candidate was found."));
    contact_states.assign(candidate_dofs.size(), ContactState::open);
    tied.assign(candidate_dofs.size(), false);
    for (const auto dof : symmetry)
      constraints.add_line(dof);
    constraints.close();

    displacement.reinit(dof_handler.n_dofs());
    velocity.reinit(dof_handler.n_dofs());
    old_force.reinit(dof_handler.n_dofs());
    for (const auto &[z, dof] : axial_vertices)
      velocity[dof] = -settings.speed;
    initial_kinetic_energy = kinetic_energy();

    history_old.resize(n_gauss * cells.size());
    for (auto &h : history_old)
      law.initialize(h);
    history_new = history_old;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::sum_over_ranks(const double x) const
  {
    Vector<double> v(1);
    v[0] = x;
    sum_over_ranks(v);
    return v[0];
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::sum_over_ranks(Vector<double> &v) const
  {
    // Summed on rank 0 and broadcast, not all-reduced: every rank must hold
    // the same bits, since each takes the Newton and LCP decisions on its
    // own copy, and an all-reduce need not round alike on all ranks.
    if (!distributed)
      return;
    const bool root  = Utilities::MPI::this_mpi_process(communicator) == 0;
    int        error = MPI_Reduce(root ? MPI_IN_PLACE : v.begin(),
                           root ? v.begin() : nullptr,
                           static_cast<int>(v.size()),
                           MPI_DOUBLE,
                           MPI_SUM,
                           0,
                           communicator);
    AssertThrowMPI(error);
    error = MPI_Bcast(
      v.begin(), static_cast<int>(v.size()), MPI_DOUBLE, 0, communicator);
    AssertThrowMPI(error);
  }



  template <int dim>
  Tensor<2, 3>
  FiniteStrainCylinder<dim>::deformation_gradient(const CellGeometry &g,
                                                  const CellVector   &u,
                                                  const unsigned int  q)
  {
    Tensor<2, 3> F;
    F[0][0] = F[1][1] = F[2][2] = 1.;
    for (unsigned int i = 0; i < n_cell_dofs; ++i)
      {
        const unsigned int c = g.component[i];
        for (unsigned int d = 0; d < dim; ++d)
          F[c][d] += u[i] * g.grad_N[q][i][d];
        if (dim == 2 && c == 0)
          F[2][2] += u[i] * g.N[q][i] / g.radius[q];
      }
    return F;
  }



  // @sect3{The internal force of a cell: F-bar, the return mapping}
  //
  // Axisymmetric: F = [[1 + du_r/dR, du_r/dZ, 0], [du_z/dR, 1 + du_z/dZ, 0],
  // [0, 0, 1 + u_r/R]]; 3D: F = I + Grad u. F-bar (de Souza Neto, Peric,
  // Dutko, Owen 1996): the law sees Fbar = (J0/J)^{1/3} F, J0 = det F at the
  // cell centre, so the volume change is constant per cell and the
  // isochoric plastic flow does not lock Q1. The internal virtual work is
  // that of the Cauchy stress sigma = tau(Fbar)/J0 on the current
  // configuration: f_i = int (J/J0) tau : (dF_i F^{-1}) dV0.
  template <int dim>
  Tensor<2, 3>
  FiniteStrainCylinder<dim>::shape_gradient(const CellGeometry &g,
                                            const unsigned int  q,
                                            const unsigned int  i)
  {
    Tensor<2, 3>       D;
    const unsigned int c = g.component[i];
    for (unsigned int d = 0; d < dim; ++d)
      D[c][d] = g.grad_N[q][i][d];
    if (dim == 2 && c == 0)
      D[2][2] = g.N[q][i] / g.radius[q];
    return D;
  }



  // The closed-form tangent: with s = (J0/J)^{1/3}, the force density is
  // G = (J/J0)^{2/3} Pbar(Fbar), so for the variation D_j = dF/du_j,
  //   dG = (J/J0)^{2/3} (A : dFbar - (2/3) d Pbar),
  //   dFbar = s D_j + (s/3) d F,  d = F0^{-T} : D0_j - F^{-T} : D_j,
  // with A = dP/dF of the law at Fbar and D0_j at the centre (plain Q1:
  // dG = A : D_j).
  template <int dim>
  void
  FiniteStrainCylinder<dim>::cell_force(
    const unsigned int                cell,
    const CellVector                 &u,
    CellVector                       &force,
    std::vector<std::vector<double>> *history,
    std::array<Branch, n_gauss>      &branches,
    FullMatrix<double>               *tangent) const
  {
    const CellGeometry &g  = cells[cell];
    const Tensor<2, 3>  F0 = deformation_gradient(g, u, n_gauss);
    const double        J0 = determinant(F0);
    force.fill(0.);
    CellVector centre_variation;
    if (tangent != nullptr)
      {
        *tangent                                = 0.;
        const Tensor<2, 3> F0_inverse_transpose = transpose(invert(F0));
        for (unsigned int j = 0; j < n_cell_dofs; ++j)
          centre_variation[j] =
            scalar_product(F0_inverse_transpose, shape_gradient(g, n_gauss, j));
      }
    std::vector<double> updated;
    Tensor<4, 3>        A;
    for (unsigned int q = 0; q < n_gauss; ++q)
      {
        const Tensor<2, 3> F = deformation_gradient(g, u, q);
        const double       J = determinant(F);
        AssertThrow(J > 0. && J0 > 0.,
                    ExcMessage("Taylor bar, step " +
                               std::to_string(step_number) +
                               " (from t = " + format_number(current_time) +
                               " s): an element is inverted (det F = " +
                               format_number(J > 0. ? J0 : J) +
                               "); reduce the time step or refine."));
        const double       scale = settings.f_bar ? std::cbrt(J0 / J) : 1.;
        const Tensor<2, 3> F_bar = scale * F;
        Tensor<2, 3>       P_bar;
        const bool         plastic = law.evaluate_3d(F_bar,
                                             history_old[n_gauss * cell + q],
                                             updated,
                                             P_bar,
                                             tangent != nullptr ? &A : nullptr,
                                             branches[q]);
        if (branches[q] == Branch::automatic)
          branches[q] = plastic ? Branch::plastic : Branch::elastic;
        // G = (J/J0) tau(Fbar) F^{-T} = (J/J0)^{2/3} Pbar, as det Fbar = J0.
        const double       ratio = 1. / (scale * scale);
        const Tensor<2, 3> G     = ratio * P_bar;
        for (unsigned int i = 0; i < n_cell_dofs; ++i)
          {
            const unsigned int c            = g.component[i];
            double             virtual_work = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              virtual_work += G[c][d] * g.grad_N[q][i][d];
            if (dim == 2 && c == 0)
              virtual_work += G[2][2] * g.N[q][i] / g.radius[q];
            force[i] += virtual_work * g.weight[q];
          }
        if (history != nullptr)
          (*history)[n_gauss * cell + q] = updated;
        if (tangent == nullptr)
          continue;

        const Tensor<2, 3> F_inverse_transpose = transpose(invert(F));
        for (unsigned int j = 0; j < n_cell_dofs; ++j)
          {
            const Tensor<2, 3> D      = shape_gradient(g, q, j);
            Tensor<2, 3>       dF_bar = D, dG;
            double             d      = 0.;
            if (settings.f_bar)
              {
                d =
                  centre_variation[j] - scalar_product(F_inverse_transpose, D);
                dF_bar = scale * D + (scale * d / 3.) * F;
              }
            for (unsigned int a = 0; a < 3; ++a)
              for (unsigned int b = 0; b < 3; ++b)
                {
                  double sum = -2. / 3. * d * P_bar[a][b];
                  for (unsigned int k = 0; k < 3; ++k)
                    for (unsigned int l = 0; l < 3; ++l)
                      sum += A[a][b][k][l] * dF_bar[k][l];
                  dG[a][b] = ratio * sum;
                }
            for (unsigned int i = 0; i < n_cell_dofs; ++i)
              {
                const unsigned int c     = g.component[i];
                double             value = 0.;
                for (unsigned int e = 0; e < dim; ++e)
                  value += dG[c][e] * g.grad_N[q][i][e];
                if (dim == 2 && c == 0)
                  value += dG[2][2] * g.N[q][i] / g.radius[q];
                (*tangent)(i, j) += value * g.weight[q];
              }
          }
      }
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::assemble_internal_force(const Vector<double> &u,
                                                     Vector<double> &force,
                                                     const bool with_tangent)
  {
    force = 0.;
    if (with_tangent && distributed)
      distributed_matrix->matrix = 0.;
    else if (with_tangent)
      step_matrix = 0.;
    // The consistent tangent in closed form (cell_force()), or by central
    // differences of the cell force (F-bar's dependence on the centre
    // included), each Gauss point on the branch of the return mapping it
    // took: a difference across the yield surface would average the elastic
    // and the plastic tangent, and Newton's method would converge only
    // linearly.
    const double                         delta = 1e-6 * smallest_cell_size;
    CellVector                           u_cell, f_cell, f_plus, f_minus;
    FullMatrix<double>                   k_cell(n_cell_dofs, n_cell_dofs);
    std::vector<types::global_dof_index> dofs(n_cell_dofs);
    // an inverted cell is met by the rank that owns it: all ranks stop
    on_every_rank(communicator, [&]() {
      for (unsigned int c = 0; c < cells.size(); ++c)
        {
          for (unsigned int i = 0; i < n_cell_dofs; ++i)
            u_cell[i] = u[cells[c].dofs[i]];
          std::array<Branch, n_gauss> branches;
          branches.fill(Branch::automatic);
          cell_force(c,
                     u_cell,
                     f_cell,
                     &history_new,
                     branches,
                     (with_tangent && settings.closed_form_tangent) ? &k_cell :
                                                                      nullptr);
          for (unsigned int i = 0; i < n_cell_dofs; ++i)
            force[cells[c].dofs[i]] += f_cell[i];
          if (!with_tangent)
            continue;
          for (unsigned int j = 0;
               j < n_cell_dofs && !settings.closed_form_tangent;
               ++j)
            {
              const double saved = u_cell[j];
              u_cell[j]          = saved + delta;
              cell_force(c, u_cell, f_plus, nullptr, branches);
              u_cell[j] = saved - delta;
              cell_force(c, u_cell, f_minus, nullptr, branches);
              u_cell[j] = saved;
              for (unsigned int i = 0; i < n_cell_dofs; ++i)
                k_cell(i, j) = (f_plus[i] - f_minus[i]) / (2. * delta);
            }
          std::copy(cells[c].dofs.begin(), cells[c].dofs.end(), dofs.begin());
          if (distributed)
            distributed_matrix->matrix.add(dofs, k_cell);
          else
            step_matrix.add(dofs, k_cell);
        }
    });
    sum_over_ranks(force);
    if (with_tangent && distributed)
      distributed_matrix->matrix.compress(VectorOperation::add);
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::factorize_newton_matrix(
    const double                                h,
    const std::vector<types::global_dof_index> &fixed)
  {
    const double scale = h * h * settings.theta * settings.theta;
    if (!distributed)
      {
        step_matrix *= scale;
        for (unsigned int i = 0; i < lumped_mass.size(); ++i)
          step_matrix.add(i, i, lumped_mass[i]);
        for (const auto dof : fixed)
          {
            for (auto entry = step_matrix.begin(dof);
                 entry != step_matrix.end(dof);
                 ++entry)
              entry->value() = 0.;
            step_matrix.set(dof, dof, lumped_mass[dof]);
          }
        step_solver->factorize(step_matrix, "the Newton matrix");
        return;
      }
    DistributedMatrix &A = *distributed_matrix;
    A.matrix *= scale;
    for (const auto i : A.owned)
      A.matrix.add(i, i, lumped_mass[i]);
    A.matrix.compress(VectorOperation::add);
    std::vector<types::global_dof_index> owned_fixed;
    for (const auto dof : fixed)
      if (A.owned.is_element(dof))
        owned_fixed.push_back(dof);
    A.matrix.clear_rows(owned_fixed, 0.);
    for (const auto dof : owned_fixed)
      A.matrix.set(dof, dof, lumped_mass[dof]);
    A.matrix.compress(VectorOperation::insert);
    A.solver = std::make_unique<TrilinosWrappers::SolverDirect>(
      A.control,
      TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Mumps"));
    A.solver->initialize(A.matrix);
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::solve_newton_matrix(const Vector<double> &b,
                                                 Vector<double>       &x)
  {
    if (!distributed)
      {
        step_solver->solve(b, x);
        return;
      }
    DistributedMatrix &A = *distributed_matrix;
    for (const auto i : A.owned)
      A.rhs[i] = b[i];
    A.rhs.compress(VectorOperation::insert);
    A.solver->solve(A.solution, A.rhs);
    x = 0.;
    for (const auto i : A.owned)
      x[i] = A.solution[i];
    sum_over_ranks(x);
  }



  // @sect3{One time step: Newton's method with the contact LCP}
  //
  // The theta-method at velocity level (spec: schemes.md):
  //   u1 = u0 + h (theta v1 + (1 - theta) v0),
  //   M (v1 - v0) + h (theta f(u1) + (1 - theta) f(u0)) = H P,
  // Signorini on w_N = V_N1 + ((1 - theta)/theta) V_N0 + g0/(h theta).
  // Each Newton iterate linearises f at u1 (A = M + h^2 theta^2 K_t),
  // condenses onto the candidates (W = H^T A^{-1} H) and solves the LCP for
  // the whole impulse P with Lemke's method, verified.
  //
  // If Newton's method does not converge in `Maximum Newton iterations`,
  // the step is made again as 2, 4, then 8 steps of h/2, h/4, h/8 (counted
  // in FiniteStrainRunTotals::step_reductions); if that fails too, the run
  // stops with a message naming the step.
  template <int dim>
  FiniteStrainStepReport
  FiniteStrainCylinder<dim>::do_time_step()
  {
    ++step_number;
    const double start_time = current_time;
    // A step that fails changes nothing but the contact states' guesses:
    // the full state is copied only when substeps are needed.
    const auto             saved_states = contact_states;
    FiniteStrainStepReport report;
    if (try_step(settings.time_step, report))
      return report;
    contact_states               = saved_states;
    const Vector<double> saved_v = velocity, saved_u = displacement,
                         saved_f = old_force;
    const auto saved_history     = history_old;
    const auto saved_tied        = tied;
    const auto saved_totals      = run_totals;
    for (unsigned int level = 1; level <= 3; ++level)
      {
        const unsigned int     n_sub = 1u << level;
        FiniteStrainStepReport total;
        bool                   converged = true;
        for (unsigned int k = 0; k < n_sub && converged; ++k)
          {
            converged = try_step(settings.time_step / n_sub, report);
            total.newton_iterations += report.newton_iterations;
            total.residuals = report.residuals;
            total.restarts  = report.restarts;
            total.late_candidates += report.late_candidates;
            total.n_candidates =
              std::max(total.n_candidates, report.n_candidates);
            total.n_closed = std::max(total.n_closed, report.n_closed);
            total.normal_impulse += report.normal_impulse;
            total.contact_work += report.contact_work;
            total.scheme_dissipation += report.scheme_dissipation;
            total.contact_violation =
              std::max(total.contact_violation, report.contact_violation);
          }
        if (converged)
          {
            ++run_totals.step_reductions;
            current_time = start_time + settings.time_step;
            return total;
          }
        velocity       = saved_v;
        displacement   = saved_u;
        old_force      = saved_f;
        history_old    = saved_history;
        contact_states = saved_states;
        tied           = saved_tied;
        run_totals     = saved_totals;
        current_time   = start_time;
      }
    AssertThrow(false,
                ExcMessage("Taylor bar: Newton's method did not converge in "
                           "step " +
                           std::to_string(step_number) +
                           " (t = " + format_number(start_time) + " s) in " +
                           std::to_string(settings.max_newton_iterations) +
                           " iterations, nor in 8 steps of h/8; reduce the "
                           "time step or refine."));
    return {};
  }



  template <int dim>
  bool
  FiniteStrainCylinder<dim>::try_step(const double            h,
                                      FiniteStrainStepReport &report)
  {
    // A report of this try only (substeps reuse the caller's).
    report                          = FiniteStrainStepReport();
    const double       theta        = settings.theta;
    const double       mu           = settings.friction_coefficient;
    const unsigned int n_directions = mu > 0. ? 2 : 1;

    // Candidates that can touch during the step: gap below twice the
    // distance they approach at their current speed.
    std::vector<unsigned int> active;
    auto                      gap = [&](const unsigned int k) {
      return candidate_positions[k][axial] +
             displacement[candidate_dofs[k][axial]];
    };
    // Rows held at a given velocity, their reaction being their residual:
    // the symmetry rows (u_r on the axis) and all components of the nodes
    // tied to the wall (bilateral contact), at zero; and, frictionless,
    // the normal rows of the contacts closed at the end of the last step,
    // "pinned" at the velocity that keeps them closed (w_N = 0). A pinned
    // contact whose reaction turns negative is released to the LCP. So the
    // LCP and its columns (one solve each) cover only the contacts that
    // may change state, not the whole contact zone.
    const Vector<double>                 v0 = velocity, u0 = displacement;
    std::vector<types::global_dof_index> fixed;
    std::vector<double>                  held_velocity;
    std::vector<bool> normal_row; // per entry of fixed: a contact's u_z
    std::vector<int>  pinned;     // per entry of fixed: the candidate or -1
    std::vector<bool> in_lcp(candidate_dofs.size(), false);
    const auto        hold = [&](const types::global_dof_index dof,
                          const double                  value,
                          const bool                    normal,
                          const int                     candidate) {
      fixed.push_back(dof);
      held_velocity.push_back(value);
      normal_row.push_back(normal);
      pinned.push_back(candidate);
    };
    for (const auto &line : constraints.get_lines())
      hold(line.index, 0., false, -1);
    for (unsigned int k = 0; k < candidate_dofs.size(); ++k)
      {
        const auto   normal_dof = candidate_dofs[k][axial];
        const double g = gap(k), vn = velocity[normal_dof];
        if (tied[k])
          for (unsigned int d = 0; d < dim; ++d)
            hold(candidate_dofs[k][d], 0., d == axial, -1);
        else if (mu == 0. && is_closed(contact_states[k]))
          hold(normal_dof,
               -(1. - theta) / theta * v0[normal_dof] - g / (h * theta),
               true,
               k);
        else if (g <= 2. * h * std::max(-vn, 0.) + 1e-12 * settings.length)
          {
            active.push_back(k);
            in_lcp[k] = true;
          }
        else
          contact_states[k] = ContactState::open; // out of reach
      }
    std::vector<bool> is_fixed(displacement.size(), false);
    for (const auto dof : fixed)
      is_fixed[dof] = true;
    std::vector<double> tied_reaction(fixed.size());

    Vector<double> v1 = v0, u1(u0.size()), force(u0.size()),
                   residual(u0.size()), dv_free(u0.size());
    for (unsigned int i = 0; i < fixed.size(); ++i)
      v1[fixed[i]] = held_velocity[i];
    std::vector<Vector<double>> columns;
    std::vector<double>         P;
    // The DoF of LCP row c: the normal (u_z) or the tangential (u_r) one.
    const auto lcp_dof = [&](const unsigned int c) {
      return candidate_dofs[active[c / n_directions]]
                           [c % n_directions == 0 ? axial : 0];
    };
    lcp::ContactProblem problem;
    const double momentum_scale = lumped_mass.linfty_norm() * settings.speed;

    for (unsigned int it = 0;; ++it)
      {
        if (it >= settings.max_newton_iterations)
          return false;
        u1 = u0;
        u1.add(h * theta, v1, h * (1. - theta), v0);
        assemble_internal_force(u1, force, true);
        // residual = M (v1 - v0) + h (theta f1 + (1 - theta) f0) - H P
        for (unsigned int i = 0; i < u0.size(); ++i)
          residual[i] = lumped_mass[i] * (v1[i] - v0[i]) +
                        h * (theta * force[i] + (1. - theta) * old_force[i]);
        for (unsigned int c = 0; c < P.size(); ++c)
          residual[lcp_dof(c)] -= P[c];
        for (unsigned int i = 0; i < fixed.size(); ++i)
          {
            tied_reaction[i]   = residual[fixed[i]];
            residual[fixed[i]] = 0.;
          }
        report.residuals.push_back(residual.linfty_norm() / momentum_scale);
        if (it > 0 && report.residuals.back() < settings.newton_tolerance)
          {
            // A candidate left out as out of reach that has crossed the
            // wall after all joins the LCP (tied and pinned ones are held
            // at their place), and Newton's method goes on.
            const std::size_t n_active = active.size();
            for (unsigned int k = 0; k < candidate_dofs.size(); ++k)
              if (!in_lcp[k] && !is_fixed[candidate_dofs[k][axial]] &&
                  candidate_positions[k][axial] + u1[candidate_dofs[k][axial]] <
                    0.)
                {
                  active.push_back(k);
                  in_lcp[k] = true;
                  ++report.late_candidates;
                }
            // A pinned contact pulling on the wall is released, its row
            // getting back its residual. (Reactions are as accurate as the
            // residual: a negative one within the tolerance is round-off.)
            for (unsigned int i = fixed.size(); i-- > 0;)
              if (pinned[i] >= 0 &&
                  tied_reaction[i] <
                    -settings.newton_tolerance * momentum_scale)
                {
                  active.push_back(pinned[i]);
                  in_lcp[pinned[i]]  = true;
                  is_fixed[fixed[i]] = false;
                  residual[fixed[i]] = tied_reaction[i];
                  for (auto *list : {&held_velocity, &tied_reaction})
                    list->erase(list->begin() + i);
                  fixed.erase(fixed.begin() + i);
                  normal_row.erase(normal_row.begin() + i);
                  pinned.erase(pinned.begin() + i);
                }
            if (active.size() == n_active)
              break;
            P.resize(active.size() * n_directions, 0.);
            // The problem changed: the next residual starts a new Newton
            // sequence.
            report.restarts.push_back(report.residuals.size());
          }
        report.newton_iterations = it + 1;

        // A = M + h^2 theta^2 K_t; the held rows (symmetry, tied, pinned):
        // identity (times M).
        factorize_newton_matrix(h, fixed);
        // The whole impulse is the unknown: free step from the residual
        // without the contact impulse.
        for (unsigned int c = 0; c < P.size(); ++c)
          residual[lcp_dof(c)] += P[c];
        residual *= -1.;
        solve_newton_matrix(residual, dv_free);
        v1 += dv_free;
        if (active.empty())
          continue;

        const unsigned int n = active.size() * n_directions;
        columns.assign(n, Vector<double>(u0.size()));
        Vector<double> unit(u0.size());
        for (unsigned int c = 0; c < n; ++c)
          {
            const auto dof = lcp_dof(c);
            unit           = 0.;
            unit[dof]      = 1.;
            if (!is_fixed[dof])
              solve_newton_matrix(unit, columns[c]);
          }
        problem.n_directions = n_directions;
        problem.n_contacts   = active.size();
        problem.W.reinit(n, n);
        problem.free_velocity.assign(n, 0.);
        problem.gap_term.assign(active.size(), 0.);
        problem.mu.assign(active.size(), mu);
        for (unsigned int a = 0; a < n; ++a)
          {
            const auto dof           = lcp_dof(a);
            problem.free_velocity[a] = v1[dof];
            for (unsigned int b = 0; b < n; ++b)
              problem.W(a, b) = columns[b][dof];
          }
        for (unsigned int c = 0; c < active.size(); ++c)
          problem.gap_term[c] =
            (1. - theta) / theta * v0[candidate_dofs[active[c]][axial]] +
            gap(active[c]) / (h * theta);
        std::vector<ContactState> guess(active.size());
        for (unsigned int c = 0; c < active.size(); ++c)
          guess[c] = contact_states[active[c]];
        const lcp::ContactSolution solution =
          lcp::solve_contact_problem(problem, {}, guess);
        AssertThrow(solution.lcp.status == lcp::Status::solved,
                    ExcMessage("Taylor bar, step " +
                               std::to_string(step_number) +
                               ": the contact LCP was not solved (" +
                               lcp::to_string(solution.lcp.status) + "). " +
                               solution.message));
        P = solution.P;
        for (unsigned int c = 0; c < active.size(); ++c)
          contact_states[active[c]] = solution.states[c];
        for (unsigned int c = 0; c < n; ++c)
          v1.add(P[c], columns[c]);
      }

    // Accept the step.
    report.n_candidates = active.size();
    if (!P.empty())
      {
        const auto check = lcp::verify_contact_solution(problem, P);
        report.contact_violation =
          std::max(check.max_signorini_violation, check.max_cone_violation);
      }
    for (unsigned int c = 0; c < P.size(); ++c)
      {
        const auto dof = lcp_dof(c);
        report.contact_work +=
          P[c] * (theta * v1[dof] + (1. - theta) * v0[dof]);
        if (c % n_directions == 0)
          {
            report.normal_impulse += P[c];
            report.n_closed += P[c] > 0. ? 1 : 0;
          }
      }
    // Tied and pinned nodes: their reaction (the axis rows' is zero by
    // symmetry).
    for (unsigned int i = constraints.n_constraints(); i < fixed.size(); ++i)
      {
        const auto dof = fixed[i];
        report.contact_work +=
          tied_reaction[i] * (theta * v1[dof] + (1. - theta) * v0[dof]);
        if (normal_row[i])
          report.normal_impulse += tied_reaction[i];
        if (pinned[i] >= 0)
          {
            contact_states[pinned[i]] = ContactState::stick;
            ++report.n_closed;
            report.contact_violation =
              std::max(report.contact_violation,
                       -tied_reaction[i] / momentum_scale);
          }
      }
    if (settings.bilateral)
      for (unsigned int c = 0; c < P.size(); c += n_directions)
        if (P[c] > 0.)
          tied[active[c / n_directions]] = true;
    for (unsigned int i = 0; i < v0.size(); ++i)
      report.scheme_dissipation +=
        (theta - 0.5) * lumped_mass[i] * (v1[i] - v0[i]) * (v1[i] - v0[i]);
    current_time += h;
    FiniteStrainRunTotals &t = run_totals;
    ++t.steps;
    t.newton_iterations += report.newton_iterations;
    t.most_newton_iterations =
      std::max(t.most_newton_iterations, report.newton_iterations);
    t.wall_impulse += report.normal_impulse;
    t.peak_contact_force =
      std::max(t.peak_contact_force, report.normal_impulse / h);
    if (report.normal_impulse > 0.)
      t.last_contact_time = time();
    t.contact_dissipation -= report.contact_work;
    t.scheme_dissipation += report.scheme_dissipation;
    t.worst_contact_violation =
      std::max(t.worst_contact_violation, report.contact_violation);
    // Newton's rate near the solution: pairs of successive residuals with
    // the first below 1e-3 and the second above the round-off floor, not
    // across a restart.
    const auto &r = report.residuals;
    t.contact_restarts += report.restarts.size();
    t.late_candidates += report.late_candidates;
    for (unsigned int k = 1; k < r.size(); ++k)
      if (r[k - 1] < 1e-3 && r[k] > 1e-12 &&
          std::find(report.restarts.begin(), report.restarts.end(), k) ==
            report.restarts.end())
        {
          ++t.pairs_near_solution;
          t.quadratic_pairs += (r[k] <= 10. * r[k - 1] * r[k - 1]) ? 1 : 0;
          if (k >= 2 && r[k - 1] < r[k - 2])
            t.convergence_orders.push_back(std::log(r[k] / r[k - 1]) /
                                           std::log(r[k - 1] / r[k - 2]));
        }
    velocity     = v1;
    displacement = u1;
    old_force    = force;
    history_old  = history_new;
    return true;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::time() const
  {
    return current_time;
  }



  template <int dim>
  const FiniteStrainRunTotals &
  FiniteStrainCylinder<dim>::totals() const
  {
    return run_totals;
  }



  double
  FiniteStrainRunTotals::newton_iterations_per_step() const
  {
    return steps > 0 ? double(newton_iterations) / steps : 0.;
  }



  double
  FiniteStrainRunTotals::quadratic_fraction() const
  {
    return pairs_near_solution > 0 ?
             double(quadratic_pairs) / pairs_near_solution :
             1.;
  }



  double
  FiniteStrainRunTotals::median_convergence_order() const
  {
    if (convergence_orders.empty())
      return 0.;
    std::vector<double> sorted = convergence_orders;
    std::sort(sorted.begin(), sorted.end());
    return sorted[sorted.size() / 2];
  }



  void
  FiniteStrainImpact::Verification::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Verification");
    prm.declare_entry("Elastic rebound check",
                      "false",
                      Patterns::Bool(),
                      "Compare with the 1D elastic bar hitting a rigid wall "
                      "(needs nu = 0 and an elastic impact): contact for "
                      "2 L0/c, force rho c v0 A, wall impulse 2 m v0.");
    prm.declare_entry("Maximum rebound error",
                      "0.05",
                      Patterns::Double(0),
                      "Largest relative error of the rebound check.");
    prm.declare_entry("Published range tolerance",
                      "0",
                      Patterns::Double(0),
                      "If > 0: the final length and footprint radius must "
                      "lie within the published ranges widened by this "
                      "relative amount.");
    prm.leave_subsection();
  }



  void
  FiniteStrainImpact::Verification::parse_parameters(
    ParameterHandler         &prm,
    const MaterialParameters &material)
  {
    prm.enter_subsection("Verification");
    rebound_check       = prm.get_bool("Elastic rebound check");
    max_rebound_error   = prm.get_double("Maximum rebound error");
    published_tolerance = prm.get_double("Published range tolerance");
    prm.leave_subsection();
    AssertThrow(!rebound_check || material.poissons_ratio == 0.,
                ExcMessage("Verification/Elastic rebound check needs "
                           "Material/Poisson's ratio = 0 (a 1D bar)."));
  }



  void
  FiniteStrainImpact::add_to_summary(JsonObject  &summary,
                                     const double initial_momentum) const
  {
    const FiniteStrainRunTotals &t = totals();
    const double momentum_change   = axial_momentum() - initial_momentum;
    summary.add("n_dofs", n_dofs())
      .add("final_length_mm", 1e3 * current_length())
      .add("footprint_radius_mm", 1e3 * footprint_radius())
      .add("contact_radius_mm", 1e3 * contact_radius())
      .add("max_equivalent_plastic_strain", max_equivalent_plastic_strain())
      .add("newton_iterations_per_step", t.newton_iterations_per_step())
      .add("newton_convergence_order", t.median_convergence_order())
      .add("newton_quadratic_fraction", t.quadratic_fraction())
      .add("newton_step_reductions", t.step_reductions)
      .add("late_contact_candidates", t.late_candidates)
      .add("newton_contact_restarts", t.contact_restarts)
      .add("deepest_node_below_wall_mm", 1e3 * deepest_node_below_wall())
      .add("max_contact_violation", t.worst_contact_violation)
      .add("wall_impulse", t.wall_impulse)
      .add("momentum_change", momentum_change)
      .add("impulse_balance_error",
           std::abs(t.wall_impulse - momentum_change) /
             std::abs(initial_momentum))
      .add("initial_momentum", initial_momentum)
      .add("last_contact_time", t.last_contact_time)
      .add("peak_contact_force", t.peak_contact_force)
      .add("kinetic_energy", kinetic_energy())
      .add("initial_kinetic_energy", initial_energy())
      .add("plastic_work", plastic_work())
      .add("stored_energy", stored_energy())
      .add("contact_dissipation", t.contact_dissipation)
      .add("scheme_dissipation", t.scheme_dissipation);
  }



  double
  FiniteStrainImpact::energy_balance_error() const
  {
    const FiniteStrainRunTotals &t = totals();
    return (initial_energy() - kinetic_energy() - stored_energy() -
            plastic_work() - t.contact_dissipation - t.scheme_dissipation) /
           initial_energy();
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::kinetic_energy() const
  {
    double e = 0.;
    for (unsigned int i = 0; i < velocity.size(); ++i)
      e += 0.5 * lumped_mass[i] * velocity[i] * velocity[i];
    return e;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::stored_energy() const
  {
    // Hencky energy of the elastic part at each Gauss point; F-bar's F as
    // the law saw it.
    double     e = 0.;
    CellVector u;
    for (unsigned int c = 0; c < cells.size(); ++c)
      {
        const CellGeometry &g = cells[c];
        for (unsigned int i = 0; i < n_cell_dofs; ++i)
          u[i] = displacement[g.dofs[i]];
        const double J0 = determinant(deformation_gradient(g, u, n_gauss));
        for (unsigned int q = 0; q < n_gauss; ++q)
          {
            const Tensor<2, 3> F = deformation_gradient(g, u, q);
            const double       scale =
              settings.f_bar ? std::cbrt(J0 / determinant(F)) : 1.;
            e += law.stored_energy(scale * F, history_old[n_gauss * c + q]) *
                 g.weight[q];
          }
      }
    return sum_over_ranks(e);
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::plastic_work() const
  {
    double e = 0.;
    for (unsigned int c = 0; c < cells.size(); ++c)
      for (unsigned int q = 0; q < n_gauss; ++q)
        e += law.plastic_work(FiniteStrainJ2Model<3>::equivalent_plastic_strain(
               history_old[n_gauss * c + q])) *
             cells[c].weight[q];
    return sum_over_ranks(e);
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::current_length() const
  {
    double top = 0.;
    for (const auto &[z, dof] : axial_vertices)
      top = std::max(top, z + displacement[dof]);
    return top;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::deepest_node_below_wall() const
  {
    double depth = 0.;
    for (const auto &[z, dof] : axial_vertices)
      depth = std::max(depth, -z - displacement[dof]);
    return depth;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::candidate_radius(const unsigned int k) const
  {
    double r2 = 0.;
    for (unsigned int d = 0; d < dim - 1; ++d)
      {
        const double x =
          candidate_positions[k][d] + displacement[candidate_dofs[k][d]];
        r2 += x * x;
      }
    return std::sqrt(r2);
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::largest_candidate_radius(
    const std::function<bool(unsigned int)> &selected) const
  {
    double r = 0.;
    for (unsigned int k = 0; k < candidate_dofs.size(); ++k)
      if (selected(k))
        r = std::max(r, candidate_radius(k));
    return r;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::footprint_radius() const
  {
    return largest_candidate_radius(
      [this](const unsigned int k) { return bool(on_lower_end[k]); });
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::contact_radius() const
  {
    return largest_candidate_radius([this](const unsigned int k) {
      return tied[k] || contact_states[k] != ContactState::open;
    });
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::max_equivalent_plastic_strain() const
  {
    double alpha = 0.;
    for (unsigned int c = 0; c < cells.size(); ++c)
      for (unsigned int q = 0; q < n_gauss; ++q)
        alpha = std::max(alpha,
                         FiniteStrainJ2Model<3>::equivalent_plastic_strain(
                           history_old[n_gauss * c + q]));
    return distributed ? Utilities::MPI::max(alpha, communicator) : alpha;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::cell_alpha(const unsigned int cell) const
  {
    double alpha = 0.;
    for (unsigned int q = 0; q < n_gauss; ++q)
      alpha += FiniteStrainJ2Model<3>::equivalent_plastic_strain(
                 history_old[n_gauss * cell + q]) /
               n_gauss;
    return alpha;
  }



  template <int dim>
  unsigned int
  FiniteStrainCylinder<dim>::n_dofs() const
  {
    return dof_handler.n_dofs();
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::initial_energy() const
  {
    return initial_kinetic_energy;
  }



  template <int dim>
  double
  FiniteStrainCylinder<dim>::axial_momentum() const
  {
    double p = 0.;
    for (const auto &[z, dof] : axial_vertices)
      p += lumped_mass[dof] * velocity[dof];
    return p;
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::write_cells_csv(const std::string &file_name) const
  {
    // Each rank its cells' rows; rank 0 writes them all.
    std::ostringstream out;
    out << std::setprecision(8);
    const double tolerance = 1e-10 * settings.radius;
    for (const auto &cell : dof_handler.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        {
          if (!cell->is_locally_owned())
            break;
          // The r-z section: the cell itself, or in 3D its face on y = 0,
          // its corners sorted counter-clockwise in the x-z plane.
          std::vector<Point<2>> corners;
          if (dim == 2 && f == 0)
            for (const unsigned int v : {0u, 1u, 3u, 2u})
              corners.emplace_back(
                cell->vertex(v)[0] + displacement[cell->vertex_dof_index(v, 0)],
                cell->vertex(v)[axial] +
                  displacement[cell->vertex_dof_index(v, axial)]);
          if (dim == 3 && std::abs(cell->face(f)->center()[1]) < tolerance)
            {
              for (const unsigned int v : cell->face(f)->vertex_indices())
                corners.emplace_back(
                  cell->face(f)->vertex(v)[0] +
                    displacement[cell->face(f)->vertex_dof_index(v, 0)],
                  cell->face(f)->vertex(v)[axial] +
                    displacement[cell->face(f)->vertex_dof_index(v, axial)]);
              const Point<2> centre =
                0.25 * (corners[0] + corners[1] + corners[2] + corners[3]);
              std::sort(corners.begin(),
                        corners.end(),
                        [&](const Point<2> &a, const Point<2> &b) {
                          return std::atan2(a[1] - centre[1],
                                            a[0] - centre[0]) <
                                 std::atan2(b[1] - centre[1], b[0] - centre[0]);
                        });
            }
          if (corners.empty())
            continue;
          for (const Point<2> &x : corners)
            out << x[0] << ',' << x[1] << ',';
          out << cell_alpha(local_cell[cell->active_cell_index()]) << '\n';
        }
    const std::vector<std::string> rows =
      distributed ? Utilities::MPI::gather(communicator, out.str(), 0) :
                    std::vector<std::string>{out.str()};
    const auto write = [&]() {
      std::ofstream file(file_name);
      AssertThrow(file, ExcMessage("Cannot write " + file_name));
      file << "r0,z0,r1,z1,r2,z2,r3,z3,alpha\n";
      for (const std::string &part : rows)
        file << part;
    };
    // (a serial run need not have initialised MPI)
    if (distributed)
      on_rank_zero(communicator, write);
    else
      write();
  }



  template <int dim>
  void
  FiniteStrainCylinder<dim>::write_vtu(const std::string &directory,
                                       const unsigned int step)
  {
    const std::string name =
      "solution-" + Utilities::int_to_string(step, 5) + ".vtu";
    const std::string file_name = directory + "/" + name;
    DataOut<dim>      data_out;
    data_out.attach_dof_handler(dof_handler);
    const std::vector<DataComponentInterpretation::DataComponentInterpretation>
      vector(dim, DataComponentInterpretation::component_is_part_of_vector);
    data_out.add_data_vector(displacement,
                             std::vector<std::string>(dim, "displacement"),
                             DataOut<dim>::type_dof_data,
                             vector);
    data_out.add_data_vector(velocity,
                             std::vector<std::string>(dim, "velocity"),
                             DataOut<dim>::type_dof_data,
                             vector);
    Vector<float> alpha(triangulation->n_active_cells());
    for (unsigned int c = 0; c < cells.size(); ++c)
      alpha[owned_cells[c]] = cell_alpha(c);
    data_out.add_data_vector(alpha, "equivalent_plastic_strain");
    const MappingQEulerian<dim> mapping(1, dof_handler, displacement);
    data_out.build_patches(mapping);
    if (distributed)
      {
        // one piece per rank and the .pvtu that names them
        const std::string record = data_out.write_vtu_with_pvtu_record(
          directory + "/", "solution", step, communicator, 5);
        vtu_records.emplace_back(time(), record);
        on_rank_zero(communicator, [&]() {
          std::ofstream pvd(directory + "/solution.pvd");
          AssertThrow(pvd,
                      ExcMessage("Cannot write " + directory +
                                 "/solution.pvd"));
          DataOutBase::write_pvd_record(pvd, vtu_records);
        });
        return;
      }
    std::ofstream out(file_name);
    AssertThrow(out, ExcMessage("Cannot write " + file_name));
    data_out.write_vtu(out);
    vtu_records.emplace_back(time(), name);
    std::ofstream pvd(directory + "/solution.pvd");
    DataOutBase::write_pvd_record(pvd, vtu_records);
  }



  template class FiniteStrainCylinder<2>;
  template class FiniteStrainCylinder<3>;
} // namespace impactfe
