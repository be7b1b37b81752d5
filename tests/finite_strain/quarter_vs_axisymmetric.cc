// The 3D quarter of the finite-strain cylinder against the axisymmetric
// model (issue 13: "the 3D run checks it").
//
// 1. The elastic limit with nu = 0 (copper at 1 m/s, Hencky with lambda =
//    0): tau = 2 G ln V is uniaxial, so a bar whose cross-sections move
//    rigidly along z is an exact solution of both discrete models. Each
//    node's internal force and lumped mass are then the same multiple of
//    its share of the cross-section, whatever that cross-section's mesh.
//    The two models must give the same length and the same wall force per
//    unit initial momentum at every step, to the Newton tolerance (per unit
//    momentum, as the quarter disc's area, integrated on cells mapped to the
//    cylinder, is pi r0^2 only to quadrature accuracy).
// 2. Finite strain (copper at 227 m/s, 10 us): the models differ only by
//    their cross-section meshes (the refined quarter disc against uniform
//    rings), 2 cells across the radius here. Refined across the radius
//    (25 cells along), the 3D footprints are 5.126, 5.098, 5.087 mm at 2,
//    4, 8 cells and the axisymmetric ones 5.043, 5.054 mm at 2, 4: the
//    models approach each other from both sides, 1.6 % apart at 2 cells;
//    the plastic work differs by 0.04 % of E_kin(0) and the length by less
//    than 0.01 mm. The bounds are twice those or more: the footprint radii
//    agree to 3 %, the plastic work to 0.5 % of E_kin(0), the lengths to
//    0.5 %. Each run must pass its own balances: wall impulse = change of
//    momentum, no energy created by the contact, an energy balance error
//    below 2 %.

#include <impactfe/finite_strain/finite_strain_impact.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;
using impactfe_tests::rounded;

namespace
{
  MaterialParameters
  copper(const double poissons_ratio)
  {
    MaterialParameters material;
    material.youngs_modulus = 117e9;
    material.poissons_ratio = poissons_ratio;
    material.density        = 8930.;
    return material;
  }



  FiniteStrainImpact::Settings
  settings(const FiniteStrainImpact::Model model,
           const double                    speed,
           const double                    end_time,
           const double                    theta)
  {
    FiniteStrainImpact::Settings s;
    s.model     = model;
    s.n_radial  = 2;
    s.n_axial   = 25;
    s.speed     = speed;
    s.end_time  = end_time;
    s.time_step = 2e-7;
    s.theta     = theta;
    return s;
  }



  void
  check_elastic_limit()
  {
    const PlasticityParameters plasticity;
    auto                       axisymmetric = FiniteStrainImpact::create(
      settings(FiniteStrainImpact::Model::axisymmetric, 1., 24e-6, 0.5),
      copper(0.),
      plasticity);
    auto quarter = FiniteStrainImpact::create(
      settings(FiniteStrainImpact::Model::three_dimensional, 1., 24e-6, 0.5),
      copper(0.),
      plasticity);
    const double p_axisymmetric = -axisymmetric->axial_momentum(),
                 p_quarter      = -quarter->axial_momentum();
    double largest_force = 0., force_difference = 0., length_difference = 0.;
    const unsigned int n_steps =
      settings(FiniteStrainImpact::Model::axisymmetric, 1., 24e-6, 0.5)
        .n_steps();
    for (unsigned int step = 0; step < n_steps; ++step)
      {
        const double f_axisymmetric =
          axisymmetric->do_time_step().normal_impulse / p_axisymmetric;
        const double f_quarter =
          quarter->do_time_step().normal_impulse / p_quarter;
        largest_force = std::max(largest_force, std::abs(f_axisymmetric));
        force_difference =
          std::max(force_difference, std::abs(f_quarter - f_axisymmetric));
        length_difference = std::max(length_difference,
                                     std::abs(quarter->current_length() -
                                              axisymmetric->current_length()));
      }
    deallog << "elastic limit: " << n_steps
            << " steps, wall impulse / p0: axisymmetric "
            << rounded(axisymmetric->totals().wall_impulse / p_axisymmetric, 4)
            << ", 3D quarter "
            << rounded(quarter->totals().wall_impulse / p_quarter, 4)
            << std::endl;
    check(force_difference <= 1e-7 * largest_force,
          "elastic limit: wall force per unit momentum, step by step, to "
          "1e-7 of its peak",
          std::to_string(force_difference / largest_force));
    check(length_difference <= 1e-9 * 32.4e-3,
          "elastic limit: length, step by step, to 1e-9 L0",
          std::to_string(length_difference));
    check(std::abs(quarter->footprint_radius() - 3.2e-3) < 1e-12,
          "elastic limit: the 3D quarter's radius does not change");
  }



  void
  check_finite_strain()
  {
    const PlasticityParameters          plasticity;
    std::unique_ptr<FiniteStrainImpact> runs[2] = {
      FiniteStrainImpact::create(
        settings(FiniteStrainImpact::Model::axisymmetric, 227., 10e-6, 1.),
        copper(0.35),
        plasticity),
      FiniteStrainImpact::create(
        settings(FiniteStrainImpact::Model::three_dimensional, 227., 10e-6, 1.),
        copper(0.35),
        plasticity)};
    const std::string names[2] = {"axisymmetric", "3D quarter"};
    double            length[2], footprint[2], plastic[2];
    for (unsigned int m = 0; m < 2; ++m)
      {
        FiniteStrainImpact &bar         = *runs[m];
        const double        p0          = bar.axial_momentum();
        double              worst_error = 0.;
        for (unsigned int step = 0; step < 50; ++step)
          {
            bar.do_time_step();
            worst_error =
              std::max(worst_error, std::abs(bar.energy_balance_error()));
          }
        length[m]    = 1e3 * bar.current_length();
        footprint[m] = 1e3 * bar.footprint_radius();
        plastic[m]   = bar.plastic_work() / bar.initial_energy();
        deallog << names[m] << ": length " << rounded(length[m], 4)
                << " mm, footprint radius " << rounded(footprint[m], 3)
                << " mm, plastic work / E_kin(0) " << rounded(plastic[m], 3)
                << std::endl;
        const FiniteStrainRunTotals &t = bar.totals();
        check(std::abs(t.wall_impulse - (bar.axial_momentum() - p0)) <
                1e-8 * std::abs(p0),
              names[m] + ": wall impulse = change of momentum");
        check(t.contact_dissipation >= -1e-9 * bar.initial_energy(),
              names[m] + ": the contact creates no energy");
        check(worst_error < 0.02,
              names[m] + ": energy balance error below 2 %",
              std::to_string(worst_error));
        check(t.worst_contact_violation < 1e-8,
              names[m] + ": contact solutions verified");
      }
    check(std::abs(length[1] - length[0]) < 5e-3 * length[0],
          "finite strain: lengths agree to 0.5 %");
    check(std::abs(footprint[1] - footprint[0]) < 0.03 * footprint[0],
          "finite strain: footprint radii agree to 3 %");
    check(std::abs(plastic[1] - plastic[0]) < 0.005,
          "finite strain: plastic work agrees to 0.5 % of E_kin(0)");
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  check_elastic_limit();
  check_finite_strain();
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
