#include <deal.II/base/exceptions.h>

#include <impactfe/bodies/constitutive_model.h>

namespace impactfe
{
  template <int dim>
  unsigned int
  ConstitutiveModel<dim>::n_internal_variables() const
  {
    return 0;
  }



  template <int dim>
  void
  ConstitutiveModel<dim>::initialize(std::vector<double> &internal) const
  {
    internal.assign(n_internal_variables(), 0.);
  }



  template <int dim>
  SymmetricTensor<4, dim>
  ConstitutiveModel<dim>::elasticity_tensor() const
  {
    AssertThrow(false,
                ExcMessage("Material: the law '" + name() +
                           "' is nonlinear and has no constant elasticity "
                           "tensor; it needs a nonlinear step."));
    return {};
  }



  template <int dim>
  SymmetricTensor<4, dim>
  ConstitutiveModel<dim>::viscosity_tensor() const
  {
    AssertThrow(false,
                ExcMessage("Material: the law '" + name() +
                           "' is nonlinear and has no constant viscosity "
                           "tensor; it needs a nonlinear step."));
    return {};
  }



  template <int dim>
  KelvinVoigtModel<dim>::KelvinVoigtModel(const MaterialParameters &material)
    : elasticity(material.elasticity_tensor<dim>())
    , relaxation_time(material.viscosity / material.youngs_modulus)
  {}



  template <int dim>
  std::string
  KelvinVoigtModel<dim>::name() const
  {
    return relaxation_time > 0. ? "Kelvin-Voigt" : "linear elastic";
  }



  template <int dim>
  bool
  KelvinVoigtModel<dim>::is_linear() const
  {
    return true;
  }



  // P = C : sym(F - I) + t_r C : sym(dF/dt); the tangents are C and t_r C
  // written as full fourth-order tensors (with the minor symmetries of C),
  // so that P = A : (F - I) + A_v : dF/dt holds for any F.
  template <int dim>
  void
  KelvinVoigtModel<dim>::evaluate(const MaterialPointKinematics<dim> &kin,
                                  const std::vector<double> &,
                                  std::vector<double>        &new_internal,
                                  MaterialPointResponse<dim> &response) const
  {
    new_internal.clear();
    const SymmetricTensor<2, dim> strain =
      symmetrize(kin.deformation_gradient - unit_symmetric_tensor<dim>());
    const SymmetricTensor<2, dim> strain_rate =
      symmetrize(kin.deformation_gradient_rate);
    response.stress =
      Tensor<2, dim>(elasticity * (strain + relaxation_time * strain_rate));
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            {
              response.tangent[i][j][k][l] = elasticity[i][j][k][l];
              response.viscous_tangent[i][j][k][l] =
                relaxation_time * elasticity[i][j][k][l];
            }
  }



  template <int dim>
  SymmetricTensor<4, dim>
  KelvinVoigtModel<dim>::elasticity_tensor() const
  {
    return elasticity;
  }



  template <int dim>
  SymmetricTensor<4, dim>
  KelvinVoigtModel<dim>::viscosity_tensor() const
  {
    return relaxation_time * elasticity;
  }



  template <int dim>
  std::unique_ptr<ConstitutiveModel<dim>>
  create_constitutive_model(const MaterialParameters &material)
  {
    return std::make_unique<KelvinVoigtModel<dim>>(material);
  }



  template class ConstitutiveModel<1>;
  template class ConstitutiveModel<2>;
  template class ConstitutiveModel<3>;
  template class KelvinVoigtModel<1>;
  template class KelvinVoigtModel<2>;
  template class KelvinVoigtModel<3>;
  template std::unique_ptr<ConstitutiveModel<1>>
  create_constitutive_model<1>(const MaterialParameters &);
  template std::unique_ptr<ConstitutiveModel<2>>
  create_constitutive_model<2>(const MaterialParameters &);
  template std::unique_ptr<ConstitutiveModel<3>>
  create_constitutive_model<3>(const MaterialParameters &);
} // namespace impactfe
