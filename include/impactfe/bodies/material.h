#ifndef impactfe_bodies_material_h
#define impactfe_bodies_material_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <string>

namespace impactfe
{
  using namespace dealii;

  /**
   * How a two-dimensional model represents the third direction.
   */
  enum class PlaneModel
  {
    plane_strain,
    plane_stress
  };

  /**
   * Linear viscoelastic material: isotropic Hooke's law plus Kelvin--Voigt
   * viscous moduli, and optional Rayleigh damping. Parameter subsection
   * `Material`.
   *
   * The Kelvin--Voigt viscous moduli are taken proportional to the elastic
   * ones (same Poisson's ratio, viscous Young's modulus `Viscosity`), so the
   * damping matrix is C = (eta/E) K + a M + b K.
   */
  struct MaterialParameters
  {
    double     youngs_modulus     = 1.;
    double     density            = 1.;
    double     poissons_ratio     = 0.;
    double     viscosity          = 0.;
    double     rayleigh_mass      = 0.;
    double     rayleigh_stiffness = 0.;
    PlaneModel plane_model        = PlaneModel::plane_strain;

    /**
     * Declare the entries for a model of dimension @p dim. The plane model
     * exists only in 2D; Poisson's ratio is declared everywhere (in 1D it
     * has no effect, and its help text says so). A scene whose bodies are
     * of different materials declares one subsection per material, e.g.
     * `Material` and `Material of body 2`.
     */
    static void
    declare_parameters(ParameterHandler  &prm,
                       const unsigned int dim,
                       const std::string &subsection = "Material");
    /**
     * Read the entries of @p subsection and check() them. If @p in_use
     * (the scene has a body of this material), Young's modulus and the
     * density must have been set by the file (they have no default); the
     * subsection of a body that is not in the scene is read and range-
     * checked only.
     */
    void
    parse_parameters(ParameterHandler  &prm,
                     const unsigned int dim,
                     const std::string &subsection = "Material",
                     const bool         in_use     = true);

    /**
     * Throw, naming @p where and the entry, if a value is out of its range
     * (E > 0, rho > 0, nu in [0, 0.5), viscosity and Rayleigh coefficients
     * >= 0). parse_parameters() calls it.
     */
    void
    check(const std::string &where) const;

    /**
     * The entries, with their values and units, that the "mass",
     * "stiffness" or "damping" matrix is made of: for a message about
     * that matrix.
     */
    std::string
    entries_of_matrix(const std::string &matrix) const;

    /** Kelvin--Voigt relaxation time eta/E plus the Rayleigh stiffness term. */
    double
    stiffness_damping_factor() const
    {
      return viscosity / youngs_modulus + rayleigh_stiffness;
    }

    bool
    has_damping() const
    {
      return viscosity > 0. || rayleigh_mass > 0. || rayleigh_stiffness > 0.;
    }

    /** Longitudinal (P) wave speed of the model in dimension @p dim. */
    template <int dim>
    double
    longitudinal_wave_speed() const;

    /**
     * The elasticity tensor of the model in dimension @p dim: uniaxial stress
     * in 1D, plane strain or plane stress in 2D, isotropic 3D.
     */
    template <int dim>
    SymmetricTensor<4, dim>
    elasticity_tensor() const;
  };
} // namespace impactfe

#endif
