// SparseSchurComplement: S = A_CC - A_CI A_II^{-1} A_IC applied without
// forming it, for a sparse symmetric positive definite A with three
// unknowns per node and full 3 x 3 node couplings (as a vector-valued
// element's: A = L (x) B + a diagonal shift, L a 7-point operator with a
// mass-like shift on a 9 x 9 x 9 grid, B symmetric positive definite),
// against independent computations:
// - on C = every unknown of the nodes of the face k = 0, S y equals the
//   dense Schur complement (DenseSchurComplement, another factorisation),
//   and with A_II solved in single precision is within 1e-5 of it;
// - SparseCholesky::solve_single_precision() of a supernodal factor is
//   within 1e-5 of solve() (the factor of A: CHOLMOD's supernodal
//   choice on this 3D operator is checked);
// - in rotated frames whose first rows are unit normals n_a of those nodes
//   (NodeFrame::with_normal()), on their normal slots: S_N is the inverse
//   of W_NN = N^T A^{-1} N, checked by N^T A^{-1} N (S_N x) = x with one
//   solve with a factorisation of A;
// - with contact states (set_contact_states(): some contacts open, some
//   sticking, some sliding with a skew mu d), the product inverts K =
//   H_C^T A^{-1} H_s on the closed normals and sticking tangents, checked
//   the same way with the skewed directions H_s = n + mu d_1 t_1 + mu d_2
//   t_2 of the sliding ones; without states it is S_N's again;
// - NodeFrame::with_normal() gives orthonormal frames (2D and 3D, normals
//   along an axis or not) and refuses a normal that is not a unit vector;
// - frames over unknowns with different couplings are refused (false, and
//   the object is left empty).

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <impactfe/dynamics/schur_complement.h>
#include <impactfe/dynamics/sparse_cholesky.h>

#include <cmath>
#include <string>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;

namespace
{
  const unsigned int m = 9; // grid points per direction

  unsigned int
  node(const unsigned int i, const unsigned int j, const unsigned int k)
  {
    return i + m * (j + m * k);
  }

  // The largest deviation of a frame's rows from an orthonormal basis.
  double
  orthonormality_error(const SparseSchurComplement::NodeFrame &frame)
  {
    const std::size_t d     = frame.dofs.size();
    double            error = 0.;
    for (std::size_t k = 0; k < d; ++k)
      for (std::size_t l = 0; l < d; ++l)
        {
          double dot = 0.;
          for (std::size_t p = 0; p < d; ++p)
            dot += frame.rotation[k][p] * frame.rotation[l][p];
          error = std::max(error, std::abs(dot - (k == l ? 1. : 0.)));
        }
    return error;
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  const unsigned int n_nodes = m * m * m, n = 3 * n_nodes;
  const double B[3][3] = {{2., 0.5, 0.2}, {0.5, 1.5, 0.3}, {0.2, 0.3, 1.}};

  // L: 7-point couplings of the nodes; A = L (x) B + shift.
  std::vector<std::vector<std::pair<unsigned int, double>>> L(n_nodes);
  for (unsigned int k = 0; k < m; ++k)
    for (unsigned int j = 0; j < m; ++j)
      for (unsigned int i = 0; i < m; ++i)
        {
          const unsigned int p = node(i, j, k);
          L[p].push_back({p, 6.2 + 0.01 * (p % 5)});
          auto couple = [&](const unsigned int q) {
            L[p].push_back({q, -1.});
            L[q].push_back({p, -1.});
          };
          if (i + 1 < m)
            couple(node(i + 1, j, k));
          if (j + 1 < m)
            couple(node(i, j + 1, k));
          if (k + 1 < m)
            couple(node(i, j, k + 1));
        }
  DynamicSparsityPattern dsp(n, n);
  for (unsigned int p = 0; p < n_nodes; ++p)
    for (const auto &[q, value] : L[p])
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          dsp.add(3 * p + a, 3 * q + b);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> A(pattern);
  for (unsigned int p = 0; p < n_nodes; ++p)
    for (const auto &[q, value] : L[p])
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          A.add(3 * p + a, 3 * q + b, value * B[a][b]);
  for (unsigned int i = 0; i < n; ++i)
    A.add(i, i, 0.05 * (i % 3));
  SparseCholesky full;
  full.factorize(A, "A");
  {
    Vector<double> b(n), b_single(n);
    for (unsigned int i = 0; i < n; ++i)
      b[i] = std::cos(0.1 * i);
    b_single = b;
    full.solve(b);
    full.solve_single_precision(b_single);
    b_single -= b;
    check(!full.simplicial() &&
            b_single.linfty_norm() <= 1e-5 * b.linfty_norm() &&
            b_single.linfty_norm() > 0.,
          "supernodal factor: the single-precision solve within 1e-5 of "
          "solve(), not equal");
  }

  // The face k = 0: every unknown of its nodes.
  std::vector<types::global_dof_index> face_dofs;
  std::vector<unsigned int>            face_nodes;
  for (unsigned int j = 0; j < m; ++j)
    for (unsigned int i = 0; i < m; ++i)
      {
        face_nodes.push_back(node(i, j, 0));
        for (unsigned int a = 0; a < 3; ++a)
          face_dofs.push_back(3 * node(i, j, 0) + a);
      }
  SparseSchurComplement sparse;
  check(sparse.initialize(A, face_dofs, "A"), "initialize() on the face");
  DenseSchurComplement dense;
  dense.compute(A, face_dofs, "A");
  Vector<double> y(n), out(n), work(n);
  for (const auto d : face_dofs)
    y[d] = std::sin(1. + 0.7 * d);
  sparse.vmult(y, out, work);
  const auto         &C = dense.dofs();
  std::vector<double> y_c(C.size()), S_y(C.size());
  for (std::size_t a = 0; a < C.size(); ++a)
    y_c[a] = y[C[a]];
  dense.vmult(y_c.data(), S_y.data());
  double error = 0., scale = 0.;
  for (std::size_t a = 0; a < C.size(); ++a)
    {
      error = std::max(error, std::abs(out[C[a]] - S_y[a]));
      scale = std::max(scale, std::abs(S_y[a]));
    }
  check(error <= 1e-12 * scale, "S y equals the dense Schur complement's");

  // The preconditioner's product: A_II solved in single precision.
  Vector<double> out_single(n);
  sparse.vmult_single_precision(y, out_single, work);
  double single_error = 0.;
  for (const auto d : C)
    single_error = std::max(single_error, std::abs(out_single[d] - out[d]));
  check(single_error <= 1e-5 * scale && single_error > 0.,
        "S y with A_II^{-1} in single precision: within 1e-5, not equal");

  // Rotated frames, unit normals varying over the face; C = normal slots.
  std::vector<SparseSchurComplement::NodeFrame> frames;
  std::vector<types::global_dof_index>          normal_dofs;
  double                                        frame_error = 0.;
  for (std::size_t a = 0; a < face_nodes.size(); ++a)
    {
      const double        t = 0.3 * a, s = 0.2 + 0.1 * std::cos(1.3 * a);
      std::vector<double> normal{std::sin(s) * std::cos(t),
                                 std::sin(s) * std::sin(t),
                                 std::cos(s)};
      const unsigned int  p = face_nodes[a];
      frames.push_back(SparseSchurComplement::NodeFrame::with_normal(
        {3 * p, 3 * p + 1, 3 * p + 2}, normal));
      frame_error = std::max(frame_error, orthonormality_error(frames.back()));
      normal_dofs.push_back(3 * p);
    }
  SparseSchurComplement normal_schur;
  check(normal_schur.initialize(A, normal_dofs, "A", frames),
        "initialize() in rotated frames");
  Vector<double> x(n), S_N_x(n);
  for (const auto d : normal_dofs)
    x[d] = std::cos(0.4 + 0.3 * d);
  normal_schur.vmult(x, S_N_x, work);
  // N^T A^{-1} N (S_N x) = x
  Vector<double> forces(n);
  for (std::size_t a = 0; a < frames.size(); ++a)
    for (unsigned int p = 0; p < 3; ++p)
      forces[frames[a].dofs[p]] =
        frames[a].rotation[0][p] * S_N_x[frames[a].dofs[0]];
  full.solve(forces);
  error = scale = 0.;
  for (std::size_t a = 0; a < frames.size(); ++a)
    {
      double normal_velocity = 0.;
      for (unsigned int p = 0; p < 3; ++p)
        normal_velocity += frames[a].rotation[0][p] * forces[frames[a].dofs[p]];
      error = std::max(error, std::abs(normal_velocity - x[frames[a].dofs[0]]));
      scale = std::max(scale, std::abs(x[frames[a].dofs[0]]));
    }
  check(error <= 1e-11 * scale, "rotated frames: S_N = (N^T A^{-1} N)^{-1}");

  // Contact states: every fourth contact open (its normal slot joins the
  // interior), every fourth sticking (its tangents closed as well), the
  // others sliding, two thirds of them with a skew mu d of |mu d| up to 3.
  // The product must invert K = H_C^T A^{-1} H_s on C' (closed normals,
  // sticking tangents): the impulses lambda along H_s,a = n_a + s_a1 t1_a
  // + s_a2 t2_a (sliding) or n_a, t1_a, t2_a (sticking), applied through a
  // solve with A, give the velocities x on C'.
  SparseSchurComplement state_schur;
  check(state_schur.initialize(A, normal_dofs, "A", frames, true),
        "initialize() for contact states");
  std::vector<unsigned char>         states(frames.size());
  std::vector<std::array<double, 3>> skew(frames.size(), {{0., 0., 0.}});
  Vector<double>                     x_closed(n);
  for (std::size_t a = 0; a < frames.size(); ++a)
    {
      states[a] = a % 4 == 1 ? SparseSchurComplement::open_state :
                  a % 4 == 3 ? SparseSchurComplement::stick_state :
                               SparseSchurComplement::slide_state;
      if (states[a] == SparseSchurComplement::slide_state && a % 3 != 0)
        {
          const double angle = 0.9 * a, size = 3. * std::abs(std::sin(a));
          skew[a][1] = size * std::cos(angle);
          skew[a][2] = size * std::sin(angle);
        }
      if (states[a] != SparseSchurComplement::open_state)
        x_closed[frames[a].dofs[0]] = x[frames[a].dofs[0]];
      if (states[a] == SparseSchurComplement::stick_state)
        for (unsigned int l = 1; l < 3; ++l)
          x_closed[frames[a].dofs[l]] = std::sin(0.3 + 0.2 * a + l);
    }
  state_schur.set_contact_states(states, skew);
  Vector<double> lambda(n);
  state_schur.vmult(x_closed, lambda, work);
  forces = 0.;
  for (std::size_t a = 0; a < frames.size(); ++a)
    for (unsigned int p = 0; p < 3; ++p)
      {
        const auto  &R        = frames[a].rotation;
        const double lambda_n = lambda[frames[a].dofs[0]];
        if (states[a] == SparseSchurComplement::slide_state)
          forces[frames[a].dofs[p]] =
            lambda_n * (R[0][p] + skew[a][1] * R[1][p] + skew[a][2] * R[2][p]);
        else if (states[a] == SparseSchurComplement::stick_state)
          forces[frames[a].dofs[p]] = lambda_n * R[0][p] +
                                      lambda[frames[a].dofs[1]] * R[1][p] +
                                      lambda[frames[a].dofs[2]] * R[2][p];
      }
  full.solve(forces);
  error = scale = 0.;
  for (std::size_t a = 0; a < frames.size(); ++a)
    for (unsigned int l = 0; l < 3; ++l)
      if ((l == 0 && states[a] != SparseSchurComplement::open_state) ||
          states[a] == SparseSchurComplement::stick_state)
        {
          double velocity = 0.;
          for (unsigned int p = 0; p < 3; ++p)
            velocity += frames[a].rotation[l][p] * forces[frames[a].dofs[p]];
          error =
            std::max(error, std::abs(velocity - x_closed[frames[a].dofs[l]]));
          scale = std::max(scale, std::abs(x_closed[frames[a].dofs[l]]));
        }
  check(state_schur.inverts_contact_states() && error <= 1e-11 * scale,
        "contact states: the products invert K on the closed normals and "
        "sticking tangents");
  // A lag (the active set method's `Exact normal rows state lag`): two
  // contacts change, a sliding one opens and another sticks. Allowed two
  // contacts behind, the products keep the factorised states and are
  // unchanged to the last bit; allowed one, they are factorised again.
  std::vector<unsigned char> lagging = states;
  lagging[0]                         = SparseSchurComplement::open_state;
  lagging[4]                         = SparseSchurComplement::stick_state;
  Vector<double> kept(n);
  const bool     refactorised_two =
    state_schur.set_contact_states(lagging, skew, 0., 2);
  state_schur.vmult(x_closed, kept, work);
  kept -= lambda;
  check(states[0] == SparseSchurComplement::slide_state &&
          states[4] == SparseSchurComplement::slide_state &&
          !refactorised_two && state_schur.factored_states() == states &&
          kept.linfty_norm() == 0.,
        "a lag of two contacts keeps the factorised states and products");
  check(state_schur.set_contact_states(lagging, skew, 0., 1) &&
          state_schur.factored_states() == lagging,
        "a lag of one contact factorises the new states");
  // no states: S_N again
  state_schur.set_contact_states({}, {});
  state_schur.vmult(x, lambda, work);
  lambda -= S_N_x;
  check(!state_schur.inverts_contact_states() &&
          lambda.linfty_norm() <= 1e-13 * S_N_x.linfty_norm(),
        "contact states cleared: the products are S_N's again");

  // Frames: orthonormal in 3D and 2D, along an axis or not.
  const auto axis =
    SparseSchurComplement::NodeFrame::with_normal({0, 1, 2}, {0., -1., 0.});
  const auto plane =
    SparseSchurComplement::NodeFrame::with_normal({0, 1}, {0.6, -0.8});
  check(frame_error < 1e-15 && orthonormality_error(axis) < 1e-15 &&
          orthonormality_error(plane) < 1e-15 && axis.rotation[0][1] == -1. &&
          plane.rotation[0][0] == 0.6,
        "with_normal(): orthonormal frames, the normal first");
  try
    {
      SparseSchurComplement::NodeFrame::with_normal({0, 1}, {1., 1.});
      check(false, "with_normal() refuses a normal of length sqrt(2)");
    }
  catch (const std::exception &e)
    {
      check(std::string(e.what()).find("unit normal") != std::string::npos,
            "with_normal() refuses a normal of length sqrt(2)");
    }

  // Unknowns with different couplings in one frame: refused.
  SparseSchurComplement::NodeFrame apart = frames[0];
  apart.dofs[2]                          = 3 * node(5, 5, 5);
  SparseSchurComplement refused;
  check(!refused.initialize(A, {apart.dofs[0]}, "A", {apart}) &&
          refused.dofs().empty() && refused.n_factor_entries() == 0,
        "a frame over unknowns with different couplings is refused");
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
