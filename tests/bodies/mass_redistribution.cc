// Mass redistribution (ElasticBody::redistribute_mass()) against masses
// computed here from the geometry alone: the total mass rho |Omega|, empty
// rows for the massless nodes, the P1 end-node masses of the 1D bar in
// closed form, and the first moments of a 2D block whose top nodes give
// their mass to the nodes below them. A cell whose vertices are all contact
// nodes is refused with a message.

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>

#include <cmath>
#include <string>
#include <vector>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;

namespace
{
  MaterialParameters
  steel()
  {
    MaterialParameters material;
    material.youngs_modulus = 2e11;
    material.poissons_ratio = 0.3;
    material.density        = 7800.;
    return material;
  }

  // The vertices with coordinate @p d equal to @p value.
  template <int dim>
  std::vector<unsigned int>
  vertices_at(const Triangulation<dim> &mesh,
              const unsigned int        d,
              const double              value)
  {
    std::vector<unsigned int> result;
    for (unsigned int v = 0; v < mesh.n_vertices(); ++v)
      if (std::abs(mesh.get_vertices()[v][d] - value) < 1e-12)
        result.push_back(v);
    return result;
  }

  // Nodal masses of component 0 (row sums of M) and their moments.
  template <int dim>
  void
  moments(const ElasticBody<dim> &body, double &mass, Tensor<1, dim> &moment)
  {
    mass                             = 0.;
    moment                           = Tensor<1, dim>();
    const SparseMatrix<double> &M    = body.mass_matrix();
    const auto                 &mesh = body.triangulation();
    for (unsigned int v = 0; v < mesh.n_vertices(); ++v)
      {
        const auto row = body.vertex_dof(v, 0);
        double     m   = 0.;
        for (auto e = M.begin(row); e != M.end(row); ++e)
          m += e->value();
        mass += m;
        moment += m * mesh.get_vertices()[v];
      }
  }

  template <int dim>
  bool
  rows_are_empty(const ElasticBody<dim>          &body,
                 const std::vector<unsigned int> &vertices)
  {
    const SparseMatrix<double> &M = body.mass_matrix();
    for (const unsigned int v : vertices)
      for (unsigned int c = 0; c < dim; ++c)
        {
          const auto row = body.vertex_dof(v, c);
          for (auto e = M.begin(row); e != M.end(row); ++e)
            if (e->value() != 0.)
              return false;
          for (unsigned int i = 0; i < M.m(); ++i)
            if (M.el(i, row) != 0.)
              return false;
        }
    return true;
  }

  // A bar of n P1 cells, length L, area A; the end x = L loses its mass.
  void
  check_bar(const bool lumped)
  {
    const std::string        mode = lumped ? "lumped" : "consistent";
    const unsigned int       n    = 10;
    const double             L = 0.254, A = 6.4516e-4, rho = steel().density;
    const double             dx = L / n;
    DiscretizationParameters discretization;
    discretization.lumped_mass = lumped;
    ElasticBody<1> bar("bar", steel(), discretization, A);
    GridGenerator::subdivided_hyper_cube(bar.triangulation(), n, 0., L);
    bar.setup();
    const auto end  = vertices_at(bar.triangulation(), 0, L);
    const auto next = vertices_at(bar.triangulation(), 0, L - dx);
    bar.redistribute_mass(end);

    const double exact_mass = rho * A * L;
    impactfe_tests::check(std::abs(bar.total_mass() - exact_mass) <
                            1e-13 * exact_mass,
                          "1D " + mode + ": total mass rho A L kept");
    impactfe_tests::check(rows_are_empty(bar, end),
                          "1D " + mode + ": the end node has no mass");
    // The end cell's mass rho A dx goes to its other node, on top of that
    // node's share of its other cell: consistent 2/6 + (1/6 + 3/6) + 2/6,
    // lumped 1/2 + 1.
    const double expected = (lumped ? 1.5 : 4. / 3.) * rho * A * dx;
    const auto   dof      = bar.vertex_dof(next[0], 0);
    const double diagonal = bar.mass_matrix().el(dof, dof);
    impactfe_tests::check(std::abs(diagonal - expected) < 1e-13 * expected,
                          "1D " + mode + ": the next node's mass",
                          std::to_string(diagonal) + " vs " +
                            std::to_string(expected));
  }

  // A block [0, W] x [0, H] of nx x ny cells (thickness t); its top nodes
  // lose their mass. Each top node's share rho t dx dy / 4 of each of its
  // cells moves down by dy along the vertical edge: the x-moment is kept
  // and the y-moment drops by rho t W dy / 2 * dy.
  void
  check_block(const bool lumped)
  {
    const std::string        mode = lumped ? "lumped" : "consistent";
    const unsigned int       nx = 6, ny = 4;
    const double             W = 0.3, H = 0.2, t = 0.01, rho = steel().density;
    const double             dy = H / ny;
    DiscretizationParameters discretization;
    discretization.lumped_mass = lumped;
    ElasticBody<2> block("block", steel(), discretization, t);
    GridGenerator::subdivided_hyper_rectangle(block.triangulation(),
                                              {nx, ny},
                                              Point<2>(0., 0.),
                                              Point<2>(W, H));
    block.setup();
    double       mass_before, mass_after;
    Tensor<1, 2> moment_before, moment_after;
    moments(block, mass_before, moment_before);
    const auto top = vertices_at(block.triangulation(), 1, H);
    block.redistribute_mass(top);
    moments(block, mass_after, moment_after);

    const double exact_mass = rho * t * W * H;
    impactfe_tests::check(std::abs(mass_before - exact_mass) <
                              1e-13 * exact_mass &&
                            std::abs(mass_after - exact_mass) <
                              1e-13 * exact_mass,
                          "2D " + mode + ": total mass rho t W H kept");
    impactfe_tests::check(rows_are_empty(block, top),
                          "2D " + mode + ": the top nodes have no mass");
    const double scale = exact_mass * W;
    impactfe_tests::check(std::abs(moment_after[0] - moment_before[0]) <
                            1e-13 * scale,
                          "2D " + mode + ": x-moment kept");
    const double drop = rho * t * W * dy / 2. * dy;
    impactfe_tests::check(std::abs(moment_before[1] - moment_after[1] - drop) <
                            1e-13 * scale,
                          "2D " + mode +
                            ": y-moment drops by rho t W dy^2 / 2");
  }

  // A 3D cube of 2^3 cells whose face z = 1 loses its mass.
  void
  check_cube()
  {
    DiscretizationParameters discretization;
    ElasticBody<3>           cube("cube", steel(), discretization);
    GridGenerator::subdivided_hyper_cube(cube.triangulation(), 2, 0., 1.);
    cube.setup();
    const auto top = vertices_at(cube.triangulation(), 2, 1.);
    cube.redistribute_mass(top);
    impactfe_tests::check(std::abs(cube.total_mass() - steel().density) <
                              1e-13 * steel().density &&
                            rows_are_empty(cube, top),
                          "3D: total mass kept, the top nodes have no mass");
  }

  // One cell whose vertices are all contact nodes: no vertex can take
  // their mass.
  void
  check_refused()
  {
    DiscretizationParameters discretization;
    ElasticBody<2>           square("square", steel(), discretization);
    GridGenerator::hyper_cube(square.triangulation(), 0., 1.);
    square.setup();
    std::vector<unsigned int> all     = {0, 1, 2, 3};
    bool                      refused = false;
    std::string               first_line;
    try
      {
        square.redistribute_mass(all);
      }
    catch (const ExceptionBase &e)
      {
        // The library's message, without the file and line of the throw.
        const std::string what  = e.what();
        const auto        begin = what.find("Body '");
        refused = what.find("without mass") != std::string::npos;
        if (begin != std::string::npos)
          first_line = what.substr(begin, what.find('\n', begin) - begin);
      }
    dealii::deallog << "all vertices massless: " << first_line << std::endl;
    impactfe_tests::check(refused, "a cell with only contact nodes is refused");
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  deal_II_exceptions::disable_abort_on_exception();
  for (const bool lumped : {false, true})
    {
      check_bar(lumped);
      check_block(lumped);
    }
  check_cube();
  check_refused();
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
