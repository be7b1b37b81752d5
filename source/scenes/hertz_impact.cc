#include <impactfe/scenes/hertz_impact.h>

#include <cmath>

namespace impactfe
{
  double
  HertzImpact::effective_modulus() const
  {
    double compliance = (1. - poissons_ratio * poissons_ratio) / youngs_modulus;
    if (std::isfinite(flat_youngs_modulus))
      compliance +=
        (1. - flat_poissons_ratio * flat_poissons_ratio) / flat_youngs_modulus;
    return 1. / compliance;
  }



  double
  HertzImpact::max_approach() const
  {
    return std::pow(15. * mass * velocity * velocity /
                      (16. * effective_modulus() * std::sqrt(radius)),
                    0.4);
  }



  double
  HertzImpact::force(const double approach) const
  {
    return 4. / 3. * effective_modulus() * std::sqrt(radius) *
           std::pow(std::max(approach, 0.), 1.5);
  }



  double
  HertzImpact::peak_force() const
  {
    return force(max_approach());
  }



  double
  HertzImpact::max_contact_radius() const
  {
    return std::sqrt(radius * max_approach());
  }



  // int_0^1 (1 - x^(5/2))^(-1/2) dx = (2/5) B(2/5, 1/2) with x^(5/2) = y.
  double
  HertzImpact::contact_duration() const
  {
    const double beta = std::tgamma(0.4) * std::tgamma(0.5) / std::tgamma(0.9);
    return 2. * 0.4 * beta * max_approach() / velocity;
  }
} // namespace impactfe
