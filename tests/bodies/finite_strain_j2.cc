// Finite-strain J2 plasticity (Hencky elasticity, exponential map, linear
// isotropic hardening) at one material point, against results derived here
// independently of the return mapping:
// - uniaxial stress, loading and unloading: the Kirchhoff stress against the
//   logarithmic strain is the bilinear curve sigma_y + E H/(E + H)(eps -
//   sigma_y/E), unloading with slope E, and the lateral log strain is
//   -nu tau/E - alpha/2 (isochoric flow). The lateral stretches are the
//   unknowns of a Newton iteration on P_22 = P_33 = 0 with the law's
//   tangent, whose convergence must be quadratic;
// - det C_p = 1 (isochoric plastic flow);
// - the work int P : dF along the path equals the stored energy plus the
//   plastic work int (sigma_y + H alpha) dalpha (the stress derives from
//   the energy, and the dissipation is the flow's);
// - objectivity: rigid rotations up to 170 degrees of the plastically
//   deformed point change tau to Q tau Q^T and nothing else;
// - the small-strain limit: P and dP/dF at F = I + 1e-7 G are Lame's
//   stress and elasticity tensor (3D and plane strain);
// - the closed-form consistent tangent equals central differences of the
//   update in F (on the branch taken) at elastic and plastic points, with
//   distinct, two equal and three equal eigenvalues of b_trial.

#include <deal.II/base/tensor.h>

#include <deal.II/physics/transformations.h>

#include <impactfe/bodies/finite_strain_plasticity.h>

#include <cmath>
#include <random>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::rounded;

namespace
{
  const double E = 117e9, nu = 0.35, sigma_y = 400e6, H = 100e6;

  MaterialParameters
  copper()
  {
    MaterialParameters material;
    material.youngs_modulus = E;
    material.poissons_ratio = nu;
    material.density        = 8930.;
    return material;
  }

  PlasticityParameters
  hardening()
  {
    PlasticityParameters plasticity;
    plasticity.yield_stress      = sigma_y;
    plasticity.hardening_modulus = H;
    return plasticity;
  }

  struct UniaxialState
  {
    Tensor<2, 3>        F;
    std::vector<double> internal;
  };

  // Axial stretch @p stretch; Newton on the lateral stretches F_22, F_33 for
  // P_22 = P_33 = 0. Returns the largest r_{k+1} / r_k^2 (relative residuals)
  // seen while r_k < 1e-3 and r_{k+1} > 1e-9, and sets @p converged.
  double
  uniaxial_step(const FiniteStrainJ2Model<3> &law,
                UniaxialState                &state,
                const double                  stretch,
                std::vector<double>          &new_internal,
                bool                         &converged)
  {
    state.F[0][0]           = stretch;
    double       worst_rate = 0., previous = -1.;
    Tensor<2, 3> P;
    Tensor<4, 3> tangent;
    converged = false;
    for (unsigned int it = 0; it < 12; ++it)
      {
        law.evaluate_3d(state.F, state.internal, new_internal, P, &tangent);
        const double residual =
          std::hypot(P[1][1], P[2][2]) / sigma_y; // relative residual
        if (previous > 0. && previous < 1e-3 && residual > 1e-9)
          worst_rate = std::max(worst_rate, residual / (previous * previous));
        previous = residual;
        if (residual < 1e-11)
          {
            converged = true;
            break;
          }
        const double a = tangent[1][1][1][1], b = tangent[1][1][2][2],
                     c = tangent[2][2][1][1], d = tangent[2][2][2][2];
        const double det = a * d - b * c;
        state.F[1][1] -= (d * P[1][1] - b * P[2][2]) / det;
        state.F[2][2] -= (-c * P[1][1] + a * P[2][2]) / det;
      }
    return worst_rate;
  }

  void
  check_uniaxial_stress()
  {
    deallog << "Uniaxial stress, copper (E = 117 GPa, nu = 0.35, sigma_y = "
               "400 MPa, H = 100 MPa)"
            << std::endl;
    const FiniteStrainJ2Model<3> law(copper(), hardening());
    UniaxialState                state;
    state.F = unit_symmetric_tensor<3>();
    law.initialize(state.internal);
    std::vector<double> new_internal;

    const double eps_max         = std::log(1.5);
    const double tangent_modulus = E * H / (E + H);
    double       stress_error = 0., lateral_error = 0., worst_rate = 0.;
    double       work = 0., max_det_error = 0.;
    bool         all_converged = true;
    Tensor<2, 3> P_old;
    // 200 loading increments to eps = ln 1.5, one of them ending at the
    // yield point (the work's trapezoidal rule needs no kink inside an
    // increment), and 100 unloading ones.
    std::vector<double> path;
    for (unsigned int i = 1; i <= 200; ++i)
      path.push_back(eps_max * i / 200.);
    path[0]              = sigma_y / E;
    const double tau_max = sigma_y + tangent_modulus * (eps_max - sigma_y / E);
    const double eps_unloaded = eps_max - tau_max / E;
    for (unsigned int i = 1; i <= 100; ++i)
      path.push_back(eps_max - (eps_max - eps_unloaded) * i / 100.);

    for (unsigned int step = 0; step < path.size(); ++step)
      {
        const double       eps   = path[step];
        const Tensor<2, 3> F_old = state.F;
        bool               converged;
        worst_rate = std::max(
          worst_rate,
          uniaxial_step(law, state, std::exp(eps), new_internal, converged));
        all_converged = all_converged && converged;
        Tensor<2, 3> P;
        law.evaluate_3d(state.F, state.internal, new_internal, P, nullptr);
        state.internal = new_internal;
        work += 0.5 * scalar_product(P + P_old, state.F - F_old);
        P_old = P;

        const double tau =
          FiniteStrainJ2Model<3>::kirchhoff_stress(state.F, P)[0][0];
        const double alpha =
          FiniteStrainJ2Model<3>::equivalent_plastic_strain(state.internal);
        const double exact =
          step < 200 ? (eps <= sigma_y / E ?
                          E * eps :
                          sigma_y + tangent_modulus * (eps - sigma_y / E)) :
                       tau_max - E * (eps_max - eps);
        stress_error = std::max(stress_error, std::abs(tau - exact) / sigma_y);
        const double lateral = -nu * exact / E - 0.5 * alpha;
        lateral_error        = std::max({lateral_error,
                                         std::abs(std::log(state.F[1][1]) - lateral),
                                         std::abs(std::log(state.F[2][2]) - lateral)});
        Tensor<2, 3> Cp_inverse;
        Cp_inverse[0][0] = state.internal[0];
        Cp_inverse[1][1] = state.internal[1];
        Cp_inverse[2][2] = state.internal[2];
        max_det_error =
          std::max(max_det_error, std::abs(determinant(Cp_inverse) - 1.));
        if (step == 199 || step == 299)
          deallog << (step == 199 ? "  loaded:   " : "  unloaded: ")
                  << "eps = " << rounded(eps, 6)
                  << ", tau_11 = " << rounded(tau / 1e6, 6, 1e-6)
                  << " MPa (exact " << rounded(exact / 1e6, 6, 1e-6)
                  << "), alpha = " << rounded(alpha, 6) << std::endl;
      }
    const double alpha =
      FiniteStrainJ2Model<3>::equivalent_plastic_strain(state.internal);
    const double stored = law.stored_energy(state.F, state.internal);
    const double energy = stored + law.plastic_work(alpha);
    deallog << "  every Newton iteration converged: "
            << (all_converged ? "yes" : "no") << std::endl;
    deallog << "  tau_11 vs the bilinear curve, max error / sigma_y < 1e-9: "
            << (stress_error < 1e-9 ? "yes" : "no") << std::endl;
    deallog << "  lateral log strain vs -nu tau/E - alpha/2, error < 1e-11: "
            << (lateral_error < 1e-11 ? "yes" : "no") << std::endl;
    deallog << "  |det C_p^{-1} - 1| < 1e-12: "
            << (max_det_error < 1e-12 ? "yes" : "no") << std::endl;
    deallog << "  Newton quadratic (r_k+1 <= 10 r_k^2 near the solution): "
            << (worst_rate < 10. ? "yes" : "no") << std::endl;
    deallog << "  work int P:dF = " << rounded(work / 1e6, 4)
            << " MJ/m^3, stored + plastic work = " << rounded(energy / 1e6, 4)
            << " MJ/m^3, relative difference < 1e-5: "
            << (std::abs(work - energy) < 1e-5 * energy ? "yes" : "no")
            << std::endl;
    deallog << "  stored elastic energy after unloading (residual lateral "
               "stresses are zero): "
            << rounded(stored / 1e6, 3) << " MJ/m^3" << std::endl;
  }

  void
  check_objectivity()
  {
    deallog << "Objectivity" << std::endl;
    const FiniteStrainJ2Model<3> law(copper(), hardening());
    std::vector<double>          internal, updated;
    law.initialize(internal);
    // A plastic, non-coaxial deformation in five increments.
    Tensor<2, 3> G;
    G[0][0] = 0.2, G[0][1] = 0.15, G[1][2] = -0.1, G[2][0] = 0.05,
    G[2][2] = -0.12;
    Tensor<2, 3> F, P;
    for (unsigned int i = 1; i <= 5; ++i)
      {
        F = Tensor<2, 3>(unit_symmetric_tensor<3>()) + (i / 5.) * G;
        law.evaluate_3d(F, internal, updated, P, nullptr);
        internal = updated;
      }
    const Tensor<2, 3> tau0 = FiniteStrainJ2Model<3>::kirchhoff_stress(F, P);
    const double       alpha0 =
      FiniteStrainJ2Model<3>::equivalent_plastic_strain(internal);
    const double energy0 = law.stored_energy(F, internal);
    Tensor<1, 3> axis;
    axis[0] = 1., axis[1] = 2., axis[2] = 3.;
    axis /= axis.norm();
    double stress_error = 0., alpha_error = 0., energy_error = 0.;
    for (unsigned int i = 1; i <= 17; ++i)
      {
        const double       angle = i * 10. * numbers::PI / 180.;
        const Tensor<2, 3> Q =
          Physics::Transformations::Rotations::rotation_matrix_3d(axis, angle);
        const Tensor<2, 3> F_rotated = Q * F;
        law.evaluate_3d(F_rotated, internal, updated, P, nullptr);
        internal = updated;
        const Tensor<2, 3> tau =
          FiniteStrainJ2Model<3>::kirchhoff_stress(F_rotated, P);
        stress_error =
          std::max(stress_error,
                   (tau - Q * tau0 * transpose(Q)).norm() / tau0.norm());
        alpha_error = std::max(
          alpha_error,
          std::abs(FiniteStrainJ2Model<3>::equivalent_plastic_strain(internal) -
                   alpha0));
        energy_error =
          std::max(energy_error,
                   std::abs(law.stored_energy(F_rotated, internal) - energy0) /
                     energy0);
      }
    deallog << "  plastic before the rotations: "
            << (alpha0 > 0.01 ? "yes" : "no") << std::endl;
    deallog << "  rotations to 170 degrees: |tau - Q tau0 Q^T|/|tau0| < 1e-10: "
            << (stress_error < 1e-10 ? "yes" : "no")
            << ", alpha unchanged (< 1e-13): "
            << (alpha_error < 1e-13 ? "yes" : "no")
            << ", stored energy unchanged (< 1e-10): "
            << (energy_error < 1e-10 ? "yes" : "no") << std::endl;
  }

  // Lame's stress and elasticity tensor (plane strain in 2D), written out.
  template <int dim>
  void
  check_small_strain_limit()
  {
    const FiniteStrainJ2Model<dim> law(copper(), hardening());
    const double lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    const double mu     = E / (2. * (1. + nu));
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1., 1.);
    double stress_error = 0., tangent_error = 0.;
    for (unsigned int sample = 0; sample < 5; ++sample)
      {
        Tensor<2, dim> G;
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            G[i][j] = 1e-7 * u(rng);
        MaterialPointKinematics<dim> kinematics;
        kinematics.deformation_gradient =
          Tensor<2, dim>(unit_symmetric_tensor<dim>()) + G;
        std::vector<double> internal, updated;
        law.initialize(internal);
        MaterialPointResponse<dim> response;
        law.evaluate(kinematics, internal, updated, response);
        const Tensor<2, dim> eps = 0.5 * (G + transpose(G));
        const Tensor<2, dim> lame =
          lambda * trace(eps) * Tensor<2, dim>(unit_symmetric_tensor<dim>()) +
          2. * mu * eps;
        stress_error =
          std::max(stress_error, (response.stress - lame).norm() / lame.norm());
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int j = 0; j < dim; ++j)
            for (unsigned int k = 0; k < dim; ++k)
              for (unsigned int l = 0; l < dim; ++l)
                {
                  const double C =
                    lambda * (i == j) * (k == l) +
                    mu * ((i == k) * (j == l) + (i == l) * (j == k));
                  tangent_error =
                    std::max(tangent_error,
                             std::abs(response.tangent[i][j][k][l] - C) / E);
                }
      }
    deallog << "Small-strain limit, dim = " << dim
            << (dim == 2 ? " (plane strain)" : "")
            << ": P vs Lame's stress < 1e-5: "
            << (stress_error < 1e-5 ? "yes" : "no")
            << ", dP/dF vs Lame's tensor < 1e-6 E: "
            << (tangent_error < 1e-6 ? "yes" : "no") << std::endl;
  }


  // The closed-form tangent against central differences of P: at F = I
  // (three equal eigenvalues), a uniaxial stretch (two equal), a general
  // F, that F rotated and a small general F (elastic from a virgin
  // point), each from a virgin and from a plastically
  // deformed point. The step 1e-6 leaves a difference error of about 1e-9
  // relative; the bound is 1e-6 of the largest entry.
  void
  check_closed_form_tangent()
  {
    const FiniteStrainJ2Model<3> law(copper(), hardening());
    std::vector<double>          virgin, deformed, scratch;
    law.initialize(virgin);
    Tensor<2, 3> P;
    {
      Tensor<2, 3> F;
      F[0][0] = 1.3;
      F[1][1] = F[2][2] = 1. / std::sqrt(1.3);
      F[0][1]           = 0.2;
      law.evaluate_3d(F, virgin, deformed, P, nullptr);
    }
    const double rotation = 0.7;
    Tensor<2, 3> R;
    R[0][0] = R[1][1] = std::cos(rotation);
    R[0][1]           = -std::sin(rotation);
    R[1][0]           = std::sin(rotation);
    R[2][2]           = 1.;
    std::vector<Tensor<2, 3>> gradients(5, unit_symmetric_tensor<3>());
    gradients[1][0][0]     = 1.01;
    gradients[2]           = gradients[1];
    gradients[2][0][1]     = 0.003;
    gradients[2][2][1]     = -0.004;
    gradients[2][1][1]     = 0.998;
    gradients[3]           = R * gradients[2];
    gradients[4][0][0]     = 1.0005;
    gradients[4][0][1]     = 0.0003;
    gradients[4][2][2]     = 0.9998;
    unsigned int n_plastic = 0, n_elastic = 0;
    double       worst = 0.;
    for (const auto *internal : {&virgin, &deformed})
      for (const Tensor<2, 3> &F : gradients)
        {
          Tensor<4, 3> tangent;
          const bool   plastic =
            law.evaluate_3d(F, *internal, scratch, P, &tangent);
          ++(plastic ? n_plastic : n_elastic);
          const auto branch  = plastic ?
                                 FiniteStrainJ2Model<3>::Branch::plastic :
                                 FiniteStrainJ2Model<3>::Branch::elastic;
          double     largest = 0., difference = 0.;
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int l = 0; l < 3; ++l)
              {
                Tensor<2, 3> F_plus = F, F_minus = F, P_plus, P_minus;
                F_plus[k][l] += 1e-6;
                F_minus[k][l] -= 1e-6;
                law.evaluate_3d(
                  F_plus, *internal, scratch, P_plus, nullptr, branch);
                law.evaluate_3d(
                  F_minus, *internal, scratch, P_minus, nullptr, branch);
                for (unsigned int i = 0; i < 3; ++i)
                  for (unsigned int j = 0; j < 3; ++j)
                    {
                      const double numerical =
                        (P_plus[i][j] - P_minus[i][j]) / 2e-6;
                      largest = std::max(largest, std::abs(numerical));
                      difference =
                        std::max(difference,
                                 std::abs(numerical - tangent[i][j][k][l]));
                    }
              }
          worst = std::max(worst, difference / largest);
        }
    deallog << "Closed-form tangent at " << n_elastic << " elastic and "
            << n_plastic << " plastic points = central differences to 1e-6: "
            << (worst < 1e-6 ? "yes" : "no") << std::endl;
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  check_uniaxial_stress();
  check_objectivity();
  check_small_strain_limit<3>();
  check_small_strain_limit<2>();
  check_closed_form_tangent();
  try
    {
      const FiniteStrainJ2Model<1> law(copper(), hardening());
    }
  catch (const std::exception &e)
    {
      deallog << "1D: "
              << (std::string(e.what()).find("not available in 1D") !=
                      std::string::npos ?
                    "refused with a message" :
                    "wrong message")
              << std::endl;
    }
}
