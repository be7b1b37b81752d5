#ifndef impactfe_bodies_constitutive_model_h
#define impactfe_bodies_constitutive_model_h

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <impactfe/bodies/material.h>

#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /** What a constitutive model sees at one quadrature point. */
  template <int dim>
  struct MaterialPointKinematics
  {
    /// F = I + Grad u (reference configuration).
    Tensor<2, dim> deformation_gradient = unit_symmetric_tensor<dim>();
    /// dF/dt = Grad v.
    Tensor<2, dim> deformation_gradient_rate;
    /// Length of the step the internal variables are advanced over [s].
    double time_step = 0.;
  };



  /** What a constitutive model returns at one quadrature point. */
  template <int dim>
  struct MaterialPointResponse
  {
    /// First Piola-Kirchhoff stress P [Pa] (the Cauchy stress at small
    /// strain).
    Tensor<2, dim> stress;
    /// dP/dF, consistent with the update of the internal variables.
    Tensor<4, dim> tangent;
    /// dP/d(dF/dt): the viscous tangent.
    Tensor<4, dim> viscous_tangent;
  };



  /**
   * The internal variables of one quadrature point (plastic strain,
   * hardening variables, ...): their values at the start of the step, and
   * at the current iterate. ElasticBody keeps one per quadrature point in
   * deal.II's CellDataStorage; accept_step() copies the current values to
   * the start-of-step values once a step is accepted.
   */
  struct MaterialPointHistory
  {
    std::vector<double> old_values;
    std::vector<double> new_values;
  };



  /**
   * A constitutive law: the stress and its consistent tangents from the
   * kinematics and the internal variables of a quadrature point. The
   * stepper does not know the law; it asks is_linear(): a linear law's
   * matrices (K and C of M v' + C v + K u = F) are assembled once from
   * elasticity_tensor() and viscosity_tensor(); a nonlinear one (e.g.
   * finite-strain J2 plasticity) is evaluated at every Newton iterate
   * through evaluate().
   */
  template <int dim>
  class ConstitutiveModel
  {
  public:
    virtual ~ConstitutiveModel() = default;

    virtual std::string
    name() const = 0;

    /** Whether P is linear in (F - I, dF/dt), with no internal variable. */
    virtual bool
    is_linear() const = 0;

    /** Internal variables per quadrature point (0 for elastic laws). */
    virtual unsigned int
    n_internal_variables() const;

    /** Their values in the undeformed, unloaded state (default 0). */
    virtual void
    initialize(std::vector<double> &internal_variables) const;

    /**
     * P, dP/dF and dP/d(dF/dt) at @p kinematics, with the internal
     * variables @p old_internal at the start of the step; writes the
     * updated ones to @p new_internal.
     */
    virtual void
    evaluate(const MaterialPointKinematics<dim> &kinematics,
             const std::vector<double>          &old_internal,
             std::vector<double>                &new_internal,
             MaterialPointResponse<dim>         &response) const = 0;

    /**
     * Linear laws: the small-strain elasticity tensor C and the viscosity
     * tensor C_v of sigma = C : eps(u) + C_v : eps(v). A nonlinear law
     * throws.
     */
    virtual SymmetricTensor<4, dim>
    elasticity_tensor() const;
    virtual SymmetricTensor<4, dim>
    viscosity_tensor() const;
  };



  /**
   * Hooke's law with Kelvin--Voigt viscosity at small strain:
   * sigma = C : eps(u) + (eta/E) C : eps(v), eps = sym(F - I) and its rate.
   * C is isotropic (uniaxial stress in 1D, plane strain or plane stress in
   * 2D, see MaterialParameters); eta = 0 gives linear elasticity. Linear,
   * no internal variable. (Rayleigh damping is not a constitutive law: the
   * body adds a M + b K to C.)
   */
  template <int dim>
  class KelvinVoigtModel : public ConstitutiveModel<dim>
  {
  public:
    explicit KelvinVoigtModel(const MaterialParameters &material);

    std::string
    name() const override;
    bool
    is_linear() const override;
    void
    evaluate(const MaterialPointKinematics<dim> &kinematics,
             const std::vector<double>          &old_internal,
             std::vector<double>                &new_internal,
             MaterialPointResponse<dim>         &response) const override;
    SymmetricTensor<4, dim>
    elasticity_tensor() const override;
    SymmetricTensor<4, dim>
    viscosity_tensor() const override;

  private:
    SymmetricTensor<4, dim> elasticity;
    double                  relaxation_time;
  };



  /** The law that the parameters of subsection `Material` describe. */
  template <int dim>
  std::unique_ptr<ConstitutiveModel<dim>>
  create_constitutive_model(const MaterialParameters &material);
} // namespace impactfe

#endif
