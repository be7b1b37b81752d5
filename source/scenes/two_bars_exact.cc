#include <impactfe/scenes/two_bars_exact.h>

#include <cmath>

namespace impactfe
{
  TwoBarsExactSolution::TwoBarsExactSolution(const double impact_velocity,
                                             const double initial_gap,
                                             const double bar_length,
                                             const double wave_speed,
                                             const double density,
                                             const double area)
    : v0(impact_velocity)
    , t_contact(initial_gap / impact_velocity)
    , duration(2. * bar_length / wave_speed)
    , contact_force(0.5 * density * wave_speed * impact_velocity * area)
    , velocity_jump(0.5 * impact_velocity)
  {}



  TwoBarsExactSolution
  TwoBarsExactSolution::against_rigid_wall(const double impact_velocity,
                                           const double initial_gap,
                                           const double bar_length,
                                           const double wave_speed,
                                           const double density,
                                           const double area)
  {
    TwoBarsExactSolution wall(
      impact_velocity, initial_gap, bar_length, wave_speed, density, area);
    wall.contact_force *= 2.;
    wall.velocity_jump = impact_velocity;
    wall.rigid_wall    = true;
    return wall;
  }



  double
  TwoBarsExactSolution::contact_velocity(const double t) const
  {
    if (t < t_contact)
      return v0;
    if (rigid_wall)
      return t < t_contact + duration ? 0. : -v0;
    return t < t_contact + duration ? 0.5 * v0 : 0.;
  }



  double
  TwoBarsExactSolution::target_velocity(const double t) const
  {
    return rigid_wall ? 0. : v0 - contact_velocity(t);
  }



  double
  TwoBarsExactSolution::normal_force(const double t) const
  {
    return (t >= t_contact && t < t_contact + duration) ? contact_force : 0.;
  }



  TwoBarsErrors::TwoBarsErrors(const TwoBarsExactSolution &exact)
    : exact(exact)
  {}



  void
  TwoBarsErrors::add(const double       t,
                     const double       contact_velocity,
                     const double       normal_force,
                     const unsigned int n_steps)
  {
    sum_v += n_steps * std::abs(contact_velocity - exact.contact_velocity(t)) /
             exact.velocity_jump;
    sum_f += n_steps * std::abs(normal_force - exact.normal_force(t)) /
             exact.contact_force;
    n += n_steps;
  }



  double
  TwoBarsErrors::err_v() const
  {
    return n > 0 ? sum_v / n : 0.;
  }



  double
  TwoBarsErrors::err_f() const
  {
    return n > 0 ? sum_f / n : 0.;
  }



  unsigned int
  TwoBarsErrors::n_steps() const
  {
    return n;
  }
} // namespace impactfe
