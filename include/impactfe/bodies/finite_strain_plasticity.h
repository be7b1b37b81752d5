// Finite-strain J2 plasticity with isotropic linear hardening: the
// multiplicative split F = F_e F_p, Hencky (logarithmic) elasticity and the
// exponential-map return mapping in principal stretches (Simo, CMAME 99,
// 1992; Simo & Hughes, Computational Inelasticity, 1998, ch. 9). The
// material point of issue 13 (the Taylor bar), behind ConstitutiveModel.
#ifndef impactfe_bodies_finite_strain_plasticity_h
#define impactfe_bodies_finite_strain_plasticity_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/tensor.h>

#include <impactfe/bodies/constitutive_model.h>
#include <impactfe/bodies/material.h>

#include <array>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * Parameter subsection `Plasticity`: the yield stress and the linear
   * isotropic hardening modulus of J2 plasticity. The elastic constants come
   * from subsection `Material`.
   */
  struct PlasticityParameters
  {
    /// Initial yield stress sigma_y [Pa] (Kirchhoff stress, uniaxial).
    double yield_stress = 400e6;
    /// Linear hardening modulus H [Pa]: yield stress sigma_y + H alpha.
    double hardening_modulus = 100e6;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);
  };



  /**
   * J2 plasticity at finite strain. The internal variables of a quadrature
   * point are the inverse plastic right Cauchy--Green tensor C_p^{-1}
   * (components xx, yy, zz, xy, xz, yz) and the equivalent plastic strain
   * alpha. A step:
   *
   *   b_e^trial = F C_p^{-1} F^T = sum_i lambda_i^2 n_i (x) n_i,
   *   eps_i = ln lambda_i,  tau_i = K sum_j eps_j + 2 G dev(eps)_i,
   *   f = |dev tau| - sqrt(2/3) (sigma_y + H alpha_n);
   *   if f > 0: dgamma = f / (2 G + 2 H / 3), eps_i -= dgamma dev(tau)_i/|dev
   *   tau|, alpha = alpha_n + sqrt(2/3) dgamma (the radial return, exact for
   *   linear hardening); then b_e = sum_i exp(2 eps_i) n_i (x) n_i,
   *   C_p^{-1} = F^{-1} b_e F^{-T}, and P = tau F^{-T}.
   *
   * The plastic flow is isochoric (det C_p = 1). In uniaxial stress the
   * Kirchhoff stress against the logarithmic strain is exactly the
   * small-strain bilinear curve; tests/bodies/finite_strain_j2 checks that,
   * objectivity under large rotations, and the small-strain limit.
   *
   * The tangent dP/dF is the derivative of this algorithmic update (the
   * consistent tangent), in closed form: the radial return's algorithmic
   * modulus (Simo & Hughes 1998, box 3.2) composed with the derivative of
   * the matrix logarithm in the eigenbasis of b_trial (divided differences
   * of ln b_i, their limit for equal eigenvalues) and of tau F^{-T}.
   * tests/bodies/finite_strain_j2 compares it with central differences.
   *
   * dim = 3 is the law itself; dim = 2 is plane strain (F_zz = 1); the
   * axisymmetric case uses evaluate_3d() with F = diag(F_rz, F_thth). dim = 1
   * is not available (uniaxial stress needs the lateral stretch as an
   * unknown) and throws.
   */
  template <int dim>
  class FiniteStrainJ2Model : public ConstitutiveModel<dim>
  {
  public:
    static constexpr unsigned int n_variables = 7;

    FiniteStrainJ2Model(const MaterialParameters   &material,
                        const PlasticityParameters &plasticity);

    std::string
    name() const override;
    bool
    is_linear() const override;
    unsigned int
    n_internal_variables() const override;
    void
    initialize(std::vector<double> &internal_variables) const override;
    void
    evaluate(const MaterialPointKinematics<dim> &kinematics,
             const std::vector<double>          &old_internal,
             std::vector<double>                &new_internal,
             MaterialPointResponse<dim>         &response) const override;

    /// Which branch of the return mapping an update takes: the one the
    /// yield condition chooses, or a given one (for a tangent by finite
    /// differences that must not straddle the yield surface).
    enum class Branch
    {
      automatic,
      elastic,
      plastic
    };

    /**
     * The update in three dimensions; the tangent only if asked for (the
     * derivative of the update on the branch it took). Returns whether the
     * plastic branch was taken.
     */
    bool
    evaluate_3d(const Tensor<2, 3>        &deformation_gradient,
                const std::vector<double> &old_internal,
                std::vector<double>       &new_internal,
                Tensor<2, 3>              &first_piola_kirchhoff,
                Tensor<4, 3>              *tangent,
                const Branch               branch = Branch::automatic) const;

    /** The Kirchhoff stress tau = P F^T of the last update of @p F. */
    static Tensor<2, 3>
    kirchhoff_stress(const Tensor<2, 3> &F, const Tensor<2, 3> &P);

    /**
     * Stored elastic energy per reference volume [J/m^3] at @p F with the
     * updated internal variables: K/2 (tr eps_e)^2 + G |dev eps_e|^2.
     */
    double
    stored_energy(const Tensor<2, 3>        &deformation_gradient,
                  const std::vector<double> &internal) const;

    /**
     * Plastic work per reference volume [J/m^3] to reach @p alpha:
     * int_0^alpha (sigma_y + H a) da.
     */
    double
    plastic_work(const double alpha) const;

    /** The equivalent plastic strain alpha of @p internal. */
    static double
    equivalent_plastic_strain(const std::vector<double> &internal);

  private:
    /// Principal logarithmic elastic strains and directions of b_e.
    struct Principal
    {
      std::array<double, 3>       log_strain;
      std::array<Tensor<1, 3>, 3> direction;
    };

    Principal
    trial_state(const Tensor<2, 3>        &F,
                const std::vector<double> &internal) const;

    double bulk_modulus;
    double shear_modulus;
    double yield_stress;
    double hardening_modulus;
  };
} // namespace impactfe

#endif
