// Newton's method of the finite-strain cylinder converges quadratically
// near the solution (issue 13). With the closed-form consistent tangent,
// a residual below 1e-3 (relative to max(M) v0) must be followed by one
// below 10 times its square, except at iterates where a Gauss point
// crosses the yield surface or a contact opens or closes (the problem is
// only piecewise smooth there). The first 20 us of the Taylor bar, with
// a Newton tolerance of 1e-12 so that each step shows several iterates
// near the solution: at least 80 % of the pairs must be quadratic, in the
// axisymmetric and in the 3D model, and every step must converge without
// substeps; and the closed-form tangent must take, step by step, the
// iterations that the tangent by central differences takes. The counts
// themselves are not printed (they are iteration counts).

#include <impactfe/finite_strain/finite_strain_impact.h>

#include <string>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;

int
main()
{
  impactfe_tests::initlog();
  MaterialParameters material;
  material.youngs_modulus = 117e9;
  material.poissons_ratio = 0.35;
  material.density        = 8930.;
  for (const auto model : {FiniteStrainImpact::Model::axisymmetric,
                           FiniteStrainImpact::Model::three_dimensional})
    {
      FiniteStrainImpact::Settings settings;
      settings.model = model;
      const bool three_d =
        model == FiniteStrainImpact::Model::three_dimensional;
      settings.n_radial         = three_d ? 2 : 5;
      settings.n_axial          = three_d ? 25 : 50;
      settings.end_time         = 20e-6;
      settings.newton_tolerance = 1e-12;
      auto bar =
        FiniteStrainImpact::create(settings, material, PlasticityParameters());
      // The same run with the tangent by central differences of the cell
      // forces (accurate to about 1e-9), in lockstep: a wrong closed form
      // would change Newton's path, so every step must take the same
      // number of iterations.
      FiniteStrainImpact::Settings differences = settings;
      differences.closed_form_tangent          = false;
      auto         reference = FiniteStrainImpact::create(differences,
                                                  material,
                                                  PlasticityParameters());
      unsigned int steps_with_other_iterations = 0;
      for (unsigned int step = 0; step < settings.n_steps(); ++step)
        steps_with_other_iterations +=
          bar->do_time_step().newton_iterations !=
              reference->do_time_step().newton_iterations ?
            1 :
            0;
      const FiniteStrainRunTotals &t = bar->totals();
      const std::string name         = three_d ? "3D quarter" : "axisymmetric";
      check(t.pairs_near_solution >= settings.n_steps(),
            name +
              ": at least one pair of iterates per step near the solution");
      check(t.quadratic_fraction() >= 0.8,
            name + ": at least 80 % of them quadratic",
            std::to_string(t.quadratic_fraction()));
      check(t.step_reductions == 0, name + ": no step needed substeps");
      check(steps_with_other_iterations == 0,
            name + ": the tangent by central differences takes the same "
                   "iterations in every step",
            std::to_string(steps_with_other_iterations));
    }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
