// SubstructuredSolver (the distributed programs' `Parallel solver/Solver =
// substructured`) on a 2D body with viscous and Rayleigh damping, on one
// and on two ranks, against independent computations:
// - A x = b to 1e-12 of |b|, A = M + c_K K + c_C C the distributed matrix
//   the body assembles (Trilinos), not the subdomain matrices the solver
//   is built from: so the subdomain matrices sum to A;
// - the contact Schur complement's inverse S_C^{-1} equals (A^{-1})_CC,
//   column by column, by solves with unit vectors on the contact DoFs C
//   (the nodes of the bottom edge);
// - S_C S_C^{-1} x = x, and the parts of add_part_of_product() (for
//   ranks that split the dense products) sum to the products;
// - a solve in two halves (start_solve(), finish_solve() with c on C, a
//   solve() in between) equals solve() with b + c, and its first half's
//   values on C are those of A^{-1} b;
// - without S_C, and with the sparse contact operator (no dense matrix on
//   C): the same solves and halves, and (A^{-1} c)_C by partial
//   substitutions equal to a full solve; the automatic choice.

#include <deal.II/base/mpi.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <impactfe/parallel/distributed_body.h>
#include <impactfe/parallel/substructured_solver.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using namespace impactfe::distributed;
using impactfe_tests::check;

int
main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const MPI_Comm                   comm = MPI_COMM_WORLD;
  const bool root = Utilities::MPI::this_mpi_process(comm) == 0;
  if (root)
    impactfe_tests::initlog();

  MaterialParameters material;
  material.youngs_modulus     = 1e9;
  material.density            = 1e3;
  material.poissons_ratio     = 0.3;
  material.viscosity          = 1e4;
  material.rayleigh_mass      = 2.;
  material.rayleigh_stiffness = 1e-6;
  DiscretizationParameters  discretization;
  DistributedElasticBody<2> body(comm, material, discretization);
  GridGenerator::subdivided_hyper_rectangle(body.triangulation(),
                                            {12, 3},
                                            Point<2>(0., 0.),
                                            Point<2>(0.1, 0.02));
  body.triangulation().refine_global(1);
  body.setup();

  // A = M + c_K K + c_C C, distributed.
  const double      c_k = 2e-9, c_c = 3e-5;
  DistributedMatrix A;
  A.copy_from(body.mass_matrix());
  A.add(c_k, body.stiffness_matrix());
  A.add(c_c, body.damping_matrix());

  // C: every DoF of the nodes on y = 0, the same list on every rank.
  std::vector<types::global_dof_index> mine, cell_dofs(8);
  for (const auto &cell : body.dof_handler().active_cell_iterators())
    if (cell->is_locally_owned())
      {
        cell->get_dof_indices(cell_dofs);
        for (unsigned int v = 0; v < 4; ++v)
          if (std::abs(cell->vertex(v)[1]) < 1e-12)
            for (unsigned int d = 0; d < 2; ++d)
              mine.push_back(cell->vertex_dof_index(v, d));
      }
  std::vector<types::global_dof_index> contact_dofs;
  for (const auto &part : Utilities::MPI::all_gather(comm, mine))
    contact_dofs.insert(contact_dofs.end(), part.begin(), part.end());
  std::sort(contact_dofs.begin(), contact_dofs.end());
  contact_dofs.erase(std::unique(contact_dofs.begin(), contact_dofs.end()),
                     contact_dofs.end());

  SparsityPattern                      pattern;
  SparseMatrix<double>                 subdomain;
  std::vector<types::global_dof_index> local_to_global;
  std::vector<bool>                    on_interface;
  body.assemble_subdomain_matrix(
    1., c_k, c_c, pattern, subdomain, local_to_global, on_interface);
  SubstructuredSolver solver;
  solver.initialize(comm,
                    subdomain,
                    local_to_global,
                    on_interface,
                    contact_dofs,
                    body.locally_owned_dofs(),
                    "A");
  const DenseSchurComplement &schur = solver.contact_schur_complement();
  check(schur.size() == contact_dofs.size(),
        "S_C on the " + std::to_string(contact_dofs.size()) + " contact DoFs");
  check((solver.n_interface_dofs() > 0) ==
          (Utilities::MPI::n_mpi_processes(comm) > 1),
        "the ranks share DoFs if there are several");

  // 1. A x = b.
  const IndexSet   &owned = body.locally_owned_dofs();
  DistributedVector b(owned, comm), x(owned, comm), r(owned, comm);
  for (const auto i : owned)
    b(i) = std::sin(0.37 * i + 1.);
  b.compress(VectorOperation::insert);
  solver.solve(b, x);
  A.vmult(r, x);
  r -= b;
  const double residual = r.l2_norm() / b.l2_norm();
  check(residual < 1e-12,
        "A x = b with the subdomain factors",
        "(relative residual " + std::to_string(residual) + ")");

  // 2. (A^{-1})_CC by solves with unit vectors, against S_C^{-1}.
  const unsigned int  n_c = contact_dofs.size();
  std::vector<double> unit(n_c), column(n_c), solved(n_c);
  double              largest_difference = 0., largest_entry = 0.;
  for (const unsigned int j : {0u, n_c / 2, n_c - 1})
    {
      const types::global_dof_index dof = schur.dofs()[j];
      b                                 = 0.;
      if (owned.is_element(dof))
        b(dof) = 1.;
      b.compress(VectorOperation::insert);
      solver.solve(b, x);
      std::fill(solved.begin(), solved.end(), 0.);
      for (unsigned int i = 0; i < n_c; ++i)
        if (owned.is_element(schur.dofs()[i]))
          solved[i] = x(schur.dofs()[i]);
      Utilities::MPI::sum(solved, comm, solved);
      std::fill(unit.begin(), unit.end(), 0.);
      unit[j] = 1.;
      schur.vmult_inverse(unit.data(), column.data());
      for (unsigned int i = 0; i < n_c; ++i)
        {
          largest_difference =
            std::max(largest_difference, std::abs(column[i] - solved[i]));
          largest_entry = std::max(largest_entry, std::abs(solved[i]));
        }
    }
  check(largest_difference <= 1e-10 * largest_entry,
        "S_C^{-1} = (A^{-1})_CC on three columns",
        "(difference " + std::to_string(largest_difference / largest_entry) +
          ")");

  // 3. S_C S_C^{-1} x = x.
  for (unsigned int i = 0; i < n_c; ++i)
    unit[i] = std::cos(1.3 * i);
  schur.vmult_inverse(unit.data(), column.data());
  schur.vmult(column.data(), solved.data());
  double error = 0.;
  for (unsigned int i = 0; i < n_c; ++i)
    error = std::max(error, std::abs(solved[i] - unit[i]));
  check(error < 1e-10, "S_C S_C^{-1} x = x");

  // 3b. The parts of add_part_of_product() sum to the products.
  double part_error = 0.;
  for (const unsigned int n_parts : {1u, 2u, 3u})
    for (const bool use_inverse : {true, false})
      {
        std::fill(column.begin(), column.end(), 0.);
        for (unsigned int part = 0; part < n_parts; ++part)
          schur.add_part_of_product(
            unit.data(), column.data(), part, n_parts, use_inverse);
        if (use_inverse)
          schur.vmult_inverse(unit.data(), solved.data());
        else
          schur.vmult_single_precision(unit.data(), solved.data());
        double scale = 0., difference = 0.;
        for (unsigned int i = 0; i < n_c; ++i)
          {
            scale      = std::max(scale, std::abs(solved[i]));
            difference = std::max(difference, std::abs(column[i] - solved[i]));
          }
        part_error =
          std::max(part_error,
                   difference / scale / (use_inverse ? 1e-13 : 1e-5));
      }
  check(part_error <= 1.,
        "the parts of the dense products sum to them (1, 2, 3 parts)");

  // 4. start_solve() + finish_solve() = solve() with b + c, c on C; and
  // start_solve()'s values on C are those of A^{-1} b.
  for (const auto i : owned)
    b(i) = std::sin(0.37 * i + 1.);
  b.compress(VectorOperation::insert);
  std::vector<double> c(n_c), x_contact;
  for (unsigned int i = 0; i < n_c; ++i)
    c[i] = std::cos(0.7 * i + 0.2);
  solver.start_solve(b, x_contact);
  solver.solve(b, x); // in between, as the Lemke fallback's products do
  double contact_error = 0., contact_scale = 0.;
  for (unsigned int i = 0; i < n_c; ++i)
    if (owned.is_element(schur.dofs()[i]))
      {
        contact_error =
          std::max(contact_error, std::abs(x_contact[i] - x(schur.dofs()[i])));
        contact_scale = std::max(contact_scale, std::abs(x(schur.dofs()[i])));
      }
  contact_error = Utilities::MPI::max(contact_error, comm);
  contact_scale = Utilities::MPI::max(contact_scale, comm);
  check(contact_error <= 1e-12 * contact_scale,
        "start_solve() gives A^{-1} b on the contact DoFs");
  DistributedVector two_halves(owned, comm);
  solver.finish_solve(c, two_halves);
  for (unsigned int i = 0; i < n_c; ++i)
    if (owned.is_element(schur.dofs()[i]))
      b(schur.dofs()[i]) += c[i];
  b.compress(VectorOperation::insert);
  solver.solve(b, x);
  two_halves -= x;
  check(two_halves.linfty_norm() <= 1e-12 * x.linfty_norm(),
        "start_solve() and finish_solve() give A^{-1} (b + c)");

  // 5. Without S_C (the free-flight level's solver): the same two halves,
  // and a clear refusal of the contact Schur complement.
  SubstructuredSolver without_schur;
  without_schur.initialize(comm,
                           subdomain,
                           local_to_global,
                           on_interface,
                           contact_dofs,
                           owned,
                           "A",
                           SubstructuredSolver::ContactOperator::factors_only);
  for (const auto i : owned)
    b(i) = std::sin(0.37 * i + 1.);
  b.compress(VectorOperation::insert);
  std::vector<double> x_contact_without;
  without_schur.start_solve(b, x_contact_without);
  solver.start_solve(b, x_contact);
  double start_difference = 0.;
  for (unsigned int i = 0; i < n_c; ++i)
    start_difference =
      std::max(start_difference, std::abs(x_contact_without[i] - x_contact[i]));
  DistributedVector without(owned, comm);
  without_schur.finish_solve(c, without);
  solver.finish_solve(c, two_halves);
  without -= two_halves;
  check(start_difference <= 1e-13 * contact_scale &&
          without.linfty_norm() <= 1e-13 * two_halves.linfty_norm(),
        "without S_C: the same start_solve() and finish_solve()");
  bool refused = false;
  try
    {
      without_schur.contact_schur_complement();
    }
  catch (const ExceptionBase &)
    {
      refused = true;
    }
  check(refused, "without S_C: contact_schur_complement() throws");

  // 6. The sparse contact operator (C in the factors' fill-reducing
  // order, no S_C): A x = b; its contact_solve() equals a full solve with
  // the first solver on C; its two halves equal the first solver's.
  using ContactOperator = SubstructuredSolver::ContactOperator;
  SubstructuredSolver sparse;
  sparse.initialize(comm,
                    subdomain,
                    local_to_global,
                    on_interface,
                    contact_dofs,
                    owned,
                    "A",
                    ContactOperator::sparse);
  check(sparse.chosen_contact_operator() == ContactOperator::sparse,
        "sparse: chosen as asked");
  for (const auto i : owned)
    b(i) = std::sin(0.37 * i + 1.);
  b.compress(VectorOperation::insert);
  sparse.solve(b, x);
  A.vmult(r, x);
  r -= b;
  check(r.l2_norm() < 1e-12 * b.l2_norm(),
        "sparse: A x = b with the subdomain factors");
  b = 0.;
  for (unsigned int i = 0; i < n_c; ++i)
    if (owned.is_element(contact_dofs[i]))
      b(contact_dofs[i]) = c[i];
  b.compress(VectorOperation::insert);
  solver.solve(b, x);
  std::vector<double> on_c(n_c, 0.), sparse_on_c;
  for (unsigned int i = 0; i < n_c; ++i)
    if (owned.is_element(contact_dofs[i]))
      on_c[i] = x(contact_dofs[i]);
  Utilities::MPI::sum(on_c, comm, on_c);
  sparse.contact_solve(c, sparse_on_c);
  double sparse_error = 0., sparse_scale = 0.;
  for (unsigned int i = 0; i < n_c; ++i)
    {
      sparse_error = std::max(sparse_error, std::abs(sparse_on_c[i] - on_c[i]));
      sparse_scale = std::max(sparse_scale, std::abs(on_c[i]));
    }
  check(sparse_scale > 0. && sparse_error <= 1e-12 * sparse_scale,
        "sparse: contact_solve() gives (A^{-1} c) on the contact DoFs");
  for (const auto i : owned)
    b(i) = std::sin(0.37 * i + 1.);
  b.compress(VectorOperation::insert);
  std::vector<double> sparse_start;
  sparse.start_solve(b, sparse_start);
  solver.start_solve(b, x_contact);
  start_difference = 0.;
  for (unsigned int i = 0; i < n_c; ++i)
    start_difference =
      std::max(start_difference, std::abs(sparse_start[i] - x_contact[i]));
  DistributedVector sparse_halves(owned, comm);
  sparse.contact_solve(c, sparse_on_c); // in between, as products do
  sparse.finish_solve(c, sparse_halves);
  solver.finish_solve(c, two_halves);
  sparse_halves -= two_halves;
  check(start_difference <= 1e-12 * contact_scale &&
          sparse_halves.linfty_norm() <= 1e-12 * two_halves.linfty_norm(),
        "sparse: the same start_solve() and finish_solve()");

  // 7. The choice: automatic takes the dense operator for this small
  // problem, and the sparse one if the dense set-up would exceed the
  // memory limit (20 kB: S_C's set-up needs more than 100 kB, the
  // interface problem on the DoFs two ranks share about 5 kB), where an
  // explicit dense operator is refused.
  SubstructuredSolver automatic;
  automatic.initialize(comm,
                       subdomain,
                       local_to_global,
                       on_interface,
                       contact_dofs,
                       owned,
                       "A",
                       ContactOperator::automatic);
  check(automatic.chosen_contact_operator() == ContactOperator::dense,
        "automatic: dense for " + std::to_string(n_c) + " contact DoFs");
  automatic.initialize(comm,
                       subdomain,
                       local_to_global,
                       on_interface,
                       contact_dofs,
                       owned,
                       "A",
                       ContactOperator::automatic,
                       20000);
  check(automatic.chosen_contact_operator() == ContactOperator::sparse,
        "automatic: sparse beyond the memory limit");
  // The message of a set-up under @p limit bytes, empty if none.
  const auto refusal = [&](const ContactOperator contact_operator,
                           const std::size_t     limit) {
    try
      {
        SubstructuredSolver limited;
        limited.initialize(comm,
                           subdomain,
                           local_to_global,
                           on_interface,
                           contact_dofs,
                           owned,
                           "A",
                           contact_operator,
                           limit);
      }
    catch (const ExceptionBase &e)
      {
        std::ostringstream what;
        e.print_info(what);
        return what.str();
      }
    return std::string();
  };
  check(refusal(ContactOperator::dense, 20000)
            .find("Contact operator = sparse") != std::string::npos,
        "dense beyond the memory limit: refused, naming the remedy");

  // 8. Every operator keeps the dense interface problem on the DoFs the
  // ranks share: beyond the memory limit (100 bytes) it is refused with
  // its own message on two ranks; one rank shares none.
  check((refusal(ContactOperator::sparse, 100).find("Use fewer ranks") !=
         std::string::npos) == (Utilities::MPI::n_mpi_processes(comm) > 1),
        "the shared DoFs' problem beyond the memory limit: refused if "
        "there are several ranks");

  if (root)
    deallog << "failed checks: " << impactfe_tests::n_failed_checks
            << std::endl;
  return Utilities::MPI::max(impactfe_tests::n_failed_checks, comm) == 0 ? 0 :
                                                                           1;
}
