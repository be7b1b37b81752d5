#include <deal.II/base/exceptions.h>

#include <impactfe/bodies/material.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace impactfe
{
  void
  MaterialParameters::declare_parameters(ParameterHandler  &prm,
                                         const unsigned int dim,
                                         const std::string &subsection)
  {
    const bool with_plane_model = dim == 2;
    prm.enter_subsection(subsection);
    // E and rho have no default: a placeholder (1 Pa, 1 kg/m^3) would give
    // a silent wrong answer (parse_parameters() asks for both)
    prm.declare_entry("Young's modulus",
                      "1",
                      Patterns::Double(),
                      "Young's modulus E of the bodies [Pa]. Must be > 0. "
                      "No default: the file must set it.",
                      true);
    prm.declare_entry("Density",
                      "1",
                      Patterns::Double(),
                      "Mass density rho [kg/m^3]. Must be > 0. No default: "
                      "the file must set it.",
                      true);
    prm.declare_entry("Poisson's ratio",
                      "0",
                      Patterns::Double(),
                      dim == 1 ? "Poisson's ratio nu [-], in [0, 0.5). No "
                                 "effect in 1D (uniaxial stress)." :
                                 "Poisson's ratio nu [-], in [0, 0.5).");
    prm.declare_entry(
      "Viscosity",
      "0",
      Patterns::Double(),
      "Kelvin-Voigt viscous Young's modulus eta [Pa s]: the viscous stress is "
      "eta/E times the elastic stress computed from the strain rate. 0 for an "
      "elastic body.");
    prm.declare_entry(
      "Rayleigh mass coefficient",
      "0",
      Patterns::Double(),
      "Rayleigh damping: coefficient a of C = a M + b K [1/s].");
    prm.declare_entry("Rayleigh stiffness coefficient",
                      "0",
                      Patterns::Double(),
                      "Rayleigh damping: coefficient b of C = a M + b K [s].");
    if (with_plane_model)
      prm.declare_entry("Plane model",
                        "plane strain",
                        Patterns::Selection("plane strain|plane stress"),
                        "Two-dimensional models only: plane strain (thick "
                        "body, zero out-of-plane strain) or plane stress "
                        "(thin plate, zero out-of-plane stress).");
    prm.leave_subsection();
  }



  void
  MaterialParameters::parse_parameters(ParameterHandler  &prm,
                                       const unsigned int dim,
                                       const std::string &subsection,
                                       const bool         in_use)
  {
    if (in_use)
      require_entries_set(prm, subsection, {"Young's modulus", "Density"});
    prm.enter_subsection(subsection);
    youngs_modulus = prm.get_double("Young's modulus");
    density        = prm.get_double("Density");
    poissons_ratio = prm.get_double("Poisson's ratio");
    if (dim == 2)
      plane_model = (prm.get("Plane model") == "plane stress") ?
                      PlaneModel::plane_stress :
                      PlaneModel::plane_strain;
    viscosity          = prm.get_double("Viscosity");
    rayleigh_mass      = prm.get_double("Rayleigh mass coefficient");
    rayleigh_stiffness = prm.get_double("Rayleigh stiffness coefficient");
    prm.leave_subsection();
    check(subsection);
  }



  void
  MaterialParameters::check(const std::string &where) const
  {
    require_positive(youngs_modulus, where, "Young's modulus");
    require_positive(density, where, "Density");
    AssertThrow(poissons_ratio >= 0. && poissons_ratio < 0.5,
                ExcMessage(where +
                           ": 'Poisson's ratio' must be in [0, 0.5), "
                           "got " +
                           format_input(poissons_ratio) + "."));
    require_non_negative(viscosity, where, "Viscosity");
    AssertThrow(rayleigh_mass >= 0. && rayleigh_stiffness >= 0.,
                ExcMessage(where +
                           ": the Rayleigh coefficients must be >= 0."));
  }


  std::string
  MaterialParameters::entries_of_matrix(const std::string &matrix) const
  {
    if (matrix == "mass")
      return "'Density' = " + format_number(density) + " kg/m^3";
    if (matrix == "stiffness")
      return "'Young's modulus' = " + format_number(youngs_modulus) +
             " Pa, 'Poisson's ratio' = " + format_number(poissons_ratio);
    return "'Viscosity' = " + format_number(viscosity) +
           " Pa s, 'Rayleigh mass coefficient' = " +
           format_number(rayleigh_mass) +
           " 1/s, 'Rayleigh stiffness coefficient' = " +
           format_number(rayleigh_stiffness) + " s";
  }



  template <int dim>
  SymmetricTensor<4, dim>
  MaterialParameters::elasticity_tensor() const
  {
    const double E      = youngs_modulus;
    const double nu     = poissons_ratio;
    double       lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    const double mu     = E / (2. * (1. + nu));
    if (dim == 2 && plane_model == PlaneModel::plane_stress)
      lambda = 2. * lambda * mu / (lambda + 2. * mu);

    SymmetricTensor<4, dim> C;
    if (dim == 1)
      {
        // Uniaxial stress: sigma = E epsilon, whatever nu is.
        C[0][0][0][0] = E;
        return C;
      }
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        for (unsigned int k = 0; k < dim; ++k)
          for (unsigned int l = 0; l < dim; ++l)
            C[i][j][k][l] = (i == j && k == l ? lambda : 0.) +
                            ((i == k && j == l) ? mu : 0.) +
                            ((i == l && j == k) ? mu : 0.);
    return C;
  }



  template <int dim>
  double
  MaterialParameters::longitudinal_wave_speed() const
  {
    // The P-wave modulus is C_0000 of the model's elasticity tensor.
    return std::sqrt(elasticity_tensor<dim>()[0][0][0][0] / density);
  }



  template SymmetricTensor<4, 1>
  MaterialParameters::elasticity_tensor<1>() const;
  template SymmetricTensor<4, 2>
  MaterialParameters::elasticity_tensor<2>() const;
  template SymmetricTensor<4, 3>
  MaterialParameters::elasticity_tensor<3>() const;
  template double
  MaterialParameters::longitudinal_wave_speed<1>() const;
  template double
  MaterialParameters::longitudinal_wave_speed<2>() const;
  template double
  MaterialParameters::longitudinal_wave_speed<3>() const;
} // namespace impactfe
