#include <deal.II/base/exceptions.h>
#include <deal.II/base/symmetric_tensor.h>

#include <impactfe/bodies/finite_strain_plasticity.h>
#include <impactfe/utilities/program.h>

#include <cmath>

namespace impactfe
{
  void
  PlasticityParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Plasticity");
    prm.declare_entry("Yield stress",
                      "400e6",
                      Patterns::Double(),
                      "Initial uniaxial yield stress sigma_y of J2 "
                      "plasticity [Pa] (Kirchhoff stress). Must be > 0.");
    prm.declare_entry("Hardening modulus",
                      "100e6",
                      Patterns::Double(),
                      "Linear isotropic hardening modulus H [Pa]: the yield "
                      "stress is sigma_y + H alpha, alpha the equivalent "
                      "plastic strain. Must be >= 0.");
    prm.leave_subsection();
  }



  void
  PlasticityParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Plasticity");
    yield_stress      = prm.get_double("Yield stress");
    hardening_modulus = prm.get_double("Hardening modulus");
    prm.leave_subsection();
    require_positive(yield_stress, "Plasticity", "Yield stress");
    require_non_negative(hardening_modulus, "Plasticity", "Hardening modulus");
  }



  namespace
  {
    // Symmetric 3x3 tensor <-> the storage order xx, yy, zz, xy, xz, yz.
    SymmetricTensor<2, 3>
    unpack(const std::vector<double> &v)
    {
      SymmetricTensor<2, 3> t;
      t[0][0] = v[0];
      t[1][1] = v[1];
      t[2][2] = v[2];
      t[0][1] = v[3];
      t[0][2] = v[4];
      t[1][2] = v[5];
      return t;
    }

    void
    pack(const SymmetricTensor<2, 3> &t, std::vector<double> &v)
    {
      v[0] = t[0][0];
      v[1] = t[1][1];
      v[2] = t[2][2];
      v[3] = t[0][1];
      v[4] = t[0][2];
      v[5] = t[1][2];
    }
  } // namespace



  template <int dim>
  FiniteStrainJ2Model<dim>::FiniteStrainJ2Model(
    const MaterialParameters   &material,
    const PlasticityParameters &plasticity)
    : bulk_modulus(material.youngs_modulus /
                   (3. * (1. - 2. * material.poissons_ratio)))
    , shear_modulus(material.youngs_modulus /
                    (2. * (1. + material.poissons_ratio)))
    , yield_stress(plasticity.yield_stress)
    , hardening_modulus(plasticity.hardening_modulus)
  {
    AssertThrow(dim > 1,
                ExcMessage("Material: finite-strain J2 plasticity needs a "
                           "2D (plane strain), axisymmetric or 3D model; "
                           "it is not available in 1D."));
  }



  template <int dim>
  std::string
  FiniteStrainJ2Model<dim>::name() const
  {
    return "finite strain J2 plasticity";
  }



  template <int dim>
  bool
  FiniteStrainJ2Model<dim>::is_linear() const
  {
    return false;
  }



  template <int dim>
  unsigned int
  FiniteStrainJ2Model<dim>::n_internal_variables() const
  {
    return n_variables;
  }



  template <int dim>
  void
  FiniteStrainJ2Model<dim>::initialize(std::vector<double> &internal) const
  {
    internal.assign(n_variables, 0.);
    internal[0] = internal[1] = internal[2] = 1.; // C_p^{-1} = I
  }



  template <int dim>
  double
  FiniteStrainJ2Model<dim>::equivalent_plastic_strain(
    const std::vector<double> &internal)
  {
    return internal[6];
  }



  template <int dim>
  typename FiniteStrainJ2Model<dim>::Principal
  FiniteStrainJ2Model<dim>::trial_state(
    const Tensor<2, 3>        &F,
    const std::vector<double> &internal) const
  {
    AssertThrow(determinant(F) > 0.,
                ExcMessage("Finite-strain J2 plasticity: det F = " +
                           std::to_string(determinant(F)) +
                           " <= 0 (an element is inverted)."));
    const Tensor<2, 3> b = F * Tensor<2, 3>(unpack(internal)) * transpose(F);
    const auto         eigen =
      eigenvectors(symmetrize(b), SymmetricTensorEigenvectorMethod::jacobi);
    Principal principal;
    for (unsigned int i = 0; i < 3; ++i)
      {
        principal.log_strain[i] = 0.5 * std::log(eigen[i].first);
        principal.direction[i]  = eigen[i].second;
      }
    return principal;
  }



  template <int dim>
  bool
  FiniteStrainJ2Model<dim>::evaluate_3d(const Tensor<2, 3>        &F,
                                        const std::vector<double> &old_internal,
                                        std::vector<double>       &new_internal,
                                        Tensor<2, 3>              &P,
                                        Tensor<4, 3>              *tangent,
                                        const Branch               branch) const
  {
    AssertDimension(old_internal.size(), n_variables);
    Principal    state = trial_state(F, old_internal);
    const double volumetric =
      state.log_strain[0] + state.log_strain[1] + state.log_strain[2];
    std::array<double, 3> deviator;
    double                norm = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      {
        deviator[i] =
          2. * shear_modulus * (state.log_strain[i] - volumetric / 3.);
        norm += deviator[i] * deviator[i];
      }
    norm = std::sqrt(norm);
    // The trial state, for the tangent.
    const double                trial_norm     = norm;
    const std::array<double, 3> trial_deviator = deviator;
    std::array<double, 3>       trial_b;
    for (unsigned int i = 0; i < 3; ++i)
      trial_b[i] = std::exp(2. * state.log_strain[i]);
    double       plastic_multiplier = 0.;
    const double alpha_old          = old_internal[6];
    const double yield =
      std::sqrt(2. / 3.) * (yield_stress + hardening_modulus * alpha_old);
    double     alpha = alpha_old;
    const bool plastic =
      norm > 0. && (branch == Branch::automatic ? norm - yield > 0. :
                                                  branch == Branch::plastic);
    if (plastic)
      {
        // Radial return: exact for linear hardening, in logarithmic strain.
        const double dgamma =
          (norm - yield) / (2. * shear_modulus + 2. / 3. * hardening_modulus);
        plastic_multiplier = dgamma;
        for (unsigned int i = 0; i < 3; ++i)
          {
            const double flow = deviator[i] / norm;
            state.log_strain[i] -= dgamma * flow;
            deviator[i] -= 2. * shear_modulus * dgamma * flow;
          }
        alpha += std::sqrt(2. / 3.) * dgamma;
      }

    SymmetricTensor<2, 3> elastic_b, tau;
    for (unsigned int i = 0; i < 3; ++i)
      {
        const SymmetricTensor<2, 3> nn =
          symmetrize(outer_product(state.direction[i], state.direction[i]));
        elastic_b += std::exp(2. * state.log_strain[i]) * nn;
        tau += (bulk_modulus * volumetric + deviator[i]) * nn;
      }
    const Tensor<2, 3> F_inverse = invert(F);
    new_internal.resize(n_variables);
    pack(symmetrize(F_inverse * Tensor<2, 3>(elastic_b) * transpose(F_inverse)),
         new_internal);
    new_internal[6] = alpha;
    P               = Tensor<2, 3>(tau) * transpose(F_inverse);

    if (tangent != nullptr)
      {
        // The consistent tangent in closed form (Simo 1992), on the branch
        // taken: P = tau F^{-T} with tau = A(eps_trial), eps_trial =
        // ln(b_trial)/2 and b_trial = F C_p^{-1} F^T. For each direction dF,
        //   db   = dF C_p^{-1} F^T + F C_p^{-1} dF^T,
        //   deps = (1/2) D ln(b)[db], in the eigenbasis of b the divided
        //          differences (ln b_i - ln b_j)/(b_i - b_j) times db_ij
        //          (Daleckii-Krein; 1/b_i for equal eigenvalues),
        //   dtau = K tr(deps) I + 2 G beta dev(deps) - 2 G gamma (n : deps) n,
        //          beta = 1 - 2 G dgamma/|s_trial|, gamma = 1/(1 + H/(3 G))
        //          - (1 - beta), n = s_trial/|s_trial| (the radial return's
        //          algorithmic modulus; beta = 1, gamma = 0 if elastic),
        //   dP   = dtau F^{-T} - tau F^{-T} dF^T F^{-T}.
        const Tensor<2, 3> C_p_inverse(unpack(old_internal));
        const Tensor<2, 3> F_inverse_transpose = transpose(F_inverse);
        const Tensor<2, 3> tau_full(tau);
        Tensor<2, 3>       Q; // columns: the eigenvectors of b_trial
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int d = 0; d < 3; ++d)
            Q[d][i] = state.direction[i][d];
        std::array<std::array<double, 3>, 3> divided;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            {
              const double bi = trial_b[i], bj = trial_b[j];
              const double mean = 0.5 * (bi + bj), x = (bi - bj) / mean;
              divided[i][j] = std::abs(x) < 1e-4 ?
                                (1. + x * x / 12.) / mean :
                                (std::log(bi) - std::log(bj)) / (bi - bj);
            }
        double       beta = 1., gamma = 0.;
        Tensor<2, 3> flow_direction;
        if (plastic)
          {
            beta  = 1. - 2. * shear_modulus * plastic_multiplier / trial_norm;
            gamma = 1. / (1. + hardening_modulus / (3. * shear_modulus)) -
                    (1. - beta);
            for (unsigned int i = 0; i < 3; ++i)
              flow_direction +=
                (trial_deviator[i] / trial_norm) *
                outer_product(state.direction[i], state.direction[i]);
          }
        const Tensor<2, 3> FC = F * C_p_inverse;
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int l = 0; l < 3; ++l)
            {
              // db for dF = e_k (x) e_l: (dF C F^T)_ij = delta_ik (F C)_jl.
              Tensor<2, 3> db;
              for (unsigned int j = 0; j < 3; ++j)
                {
                  db[k][j] += FC[j][l];
                  db[j][k] += FC[j][l];
                }
              Tensor<2, 3> deps = transpose(Q) * db * Q;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  deps[i][j] *= 0.5 * divided[i][j];
              deps                     = Q * deps * transpose(Q);
              const double trace       = deps[0][0] + deps[1][1] + deps[2][2];
              const double flow_amount = scalar_product(flow_direction, deps);
              Tensor<2, 3> dtau        = 2. * shear_modulus * beta * deps;
              for (unsigned int i = 0; i < 3; ++i)
                dtau[i][i] +=
                  (bulk_modulus - 2. * shear_modulus * beta / 3.) * trace;
              dtau -= 2. * shear_modulus * gamma * flow_amount * flow_direction;
              // F^{-T} dF^T F^{-T} for dF = e_k (x) e_l.
              Tensor<2, 3> dF_inverse_transpose;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  dF_inverse_transpose[i][j] =
                    F_inverse_transpose[i][l] * F_inverse_transpose[k][j];
              const Tensor<2, 3> dP =
                dtau * F_inverse_transpose - tau_full * dF_inverse_transpose;
              for (unsigned int i = 0; i < 3; ++i)
                for (unsigned int j = 0; j < 3; ++j)
                  (*tangent)[i][j][k][l] = dP[i][j];
            }
      }
    return plastic;
  }



  template <int dim>
  void
  FiniteStrainJ2Model<dim>::evaluate(const MaterialPointKinematics<dim> &kin,
                                     const std::vector<double>  &old_internal,
                                     std::vector<double>        &new_internal,
                                     MaterialPointResponse<dim> &response) const
  {
    // Plane strain: F_zz = 1, the other out-of-plane components zero.
    Tensor<2, 3> F;
    F[2][2] = 1.;
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        F[i][j] = kin.deformation_gradient[i][j];
    Tensor<2, 3> P;
    Tensor<4, 3> tangent;
    evaluate_3d(F, old_internal, new_internal, P, &tangent);
    response.viscous_tangent = Tensor<4, dim>();
    for (unsigned int i = 0; i < dim; ++i)
      for (unsigned int j = 0; j < dim; ++j)
        {
          response.stress[i][j] = P[i][j];
          for (unsigned int k = 0; k < dim; ++k)
            for (unsigned int l = 0; l < dim; ++l)
              response.tangent[i][j][k][l] = tangent[i][j][k][l];
        }
  }



  template <int dim>
  Tensor<2, 3>
  FiniteStrainJ2Model<dim>::kirchhoff_stress(const Tensor<2, 3> &F,
                                             const Tensor<2, 3> &P)
  {
    return P * transpose(F);
  }



  template <int dim>
  double
  FiniteStrainJ2Model<dim>::stored_energy(
    const Tensor<2, 3>        &F,
    const std::vector<double> &internal) const
  {
    // With the updated C_p^{-1}, F C_p^{-1} F^T is the elastic b_e.
    const Principal state = trial_state(F, internal);
    const double    volumetric =
      state.log_strain[0] + state.log_strain[1] + state.log_strain[2];
    double deviatoric = 0.;
    for (unsigned int i = 0; i < 3; ++i)
      deviatoric += std::pow(state.log_strain[i] - volumetric / 3., 2);
    return 0.5 * bulk_modulus * volumetric * volumetric +
           shear_modulus * deviatoric;
  }



  template <int dim>
  double
  FiniteStrainJ2Model<dim>::plastic_work(const double alpha) const
  {
    return yield_stress * alpha + 0.5 * hardening_modulus * alpha * alpha;
  }



  template class FiniteStrainJ2Model<1>;
  template class FiniteStrainJ2Model<2>;
  template class FiniteStrainJ2Model<3>;
} // namespace impactfe
