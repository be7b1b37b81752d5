// @sect3{The four time schemes}
//
// Each scheme is written at the velocity level (see time_integrator.h and
// ../shared/spec/schemes.md): it gives the step matrix coefficients, the free
// right-hand side, the gap term b_N of its discrete Signorini condition
// w_N = V_N^{i+1} + b_N >= 0 _|_ P_N >= 0, and the displacement update.
// The external load is constant in time, so h (theta F^{i+1} + (1-theta)
// F^i) = h F.

#include <deal.II/base/exceptions.h>

#include <impactfe/contact/contact_set.h>
#include <impactfe/output/output.h>
#include <impactfe/time_integration/time_integrator.h>
#include <impactfe/utilities/program.h>
#include <impactfe/utilities/vectorized_kernel.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace impactfe
{
  std::string
  to_string(const Scheme scheme)
  {
    switch (scheme)
      {
        case Scheme::theta:
          return "theta";
        case Scheme::theta_euler:
          return "theta-euler";
        case Scheme::modified_theta:
          return "modified-theta";
        case Scheme::newmark:
          return "newmark";
      }
    return "unknown";
  }



  void
  TimeSteppingParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Time stepping");
    prm.declare_entry(
      "Scheme",
      "theta-euler",
      Patterns::Selection("theta|theta-euler|modified-theta|newmark"),
      "Time scheme: theta (Moreau-Jean theta-method, gap from the theta "
      "displacement update), theta-euler (u^{i+1} = u^i + h v^{i+1}), "
      "modified-theta (theta dynamics, gap at u + h(1-theta) v), or newmark "
      "(displacement-level Signorini; the baseline).");
    prm.declare_entry("Theta",
                      "0.55",
                      Patterns::Double(),
                      "theta of the theta-schemes [-], in [0.5, 1]. 0.5 is "
                      "the trapezoidal rule; larger values damp.");
    prm.declare_entry(
      "Theta rule",
      "fixed",
      Patterns::Selection("fixed|courant"),
      "fixed: theta is the entry 'Theta'. courant: theta = 1/2 + kappa / C "
      "(at most 1), C = c_p h / dx the Courant number of the mesh (c_p the "
      "P-wave speed, dx = (volume / number of cells)^(1/dim), the body with "
      "the shortest dx / c_p), kappa the entry 'Theta damping'; the entry "
      "'Theta' is then not used (the programs print theta and say so), so "
      "that the rule can be chosen in a file that includes another with a "
      "Theta. Free-flight steps of k h use the theta of h. The scheme's numerical damping, that of a "
      "stiffness-proportional damping (theta - 1/2) h, is then kappa dx / "
      "c_p at every time step: less damping at large steps (where "
      "theta = 0.55 damps the physical modes), more at small ones (where "
      "theta = 1/2 leaves the mesh's ringing in the contact forces). "
      "Theta-schemes only.");
    prm.declare_entry("Theta damping",
                      "0.025",
                      Patterns::Double(),
                      "kappa of 'Theta rule = courant' [-], > 0: the "
                      "numerical damping coefficient (theta - 1/2) h in units "
                      "of the cell transit time dx / c_p.");
    prm.declare_entry(
      "Newmark beta",
      "0.25",
      Patterns::Double(),
      "Newmark beta [-], in [gamma / 2, 0.5] (unconditionally stable).");
    prm.declare_entry("Newmark gamma",
                      "0.5",
                      Patterns::Double(),
                      "Newmark gamma [-], in [0.5, 1].");
    // h and T have no default: a placeholder step would run a scene at
    // a step unrelated to it (parse_parameters() asks for both)
    prm.declare_entry("Time step",
                      "1e-3",
                      Patterns::Double(),
                      "Time step h [s]. Must be > 0. No default: the file "
                      "must set it.",
                      true);
    prm.declare_entry("End time",
                      "1",
                      Patterns::Double(),
                      "End time T [s]. Must be >= the time step. The run "
                      "makes ceil(T / h) steps: it ends at the first "
                      "multiple of h at or after T. No default: the file "
                      "must set it.",
                      true);
    prm.declare_entry(
      "Free-flight step factor",
      "1",
      Patterns::Integer(1),
      "1 <= k <= 1000 [-]: a step in which no contact is active and no candidate "
      "can touch is made k times longer (k h), with its own factorised "
      "step matrix; it is kept only if its free velocities close no gap "
      "(the Signorini condition of k h), otherwise the step is made with h. "
      "Coarse steps end on the grid of h, so the end time and the output "
      "times are those of h. 1: every step is h.");
    prm.leave_subsection();
  }



  void
  TimeSteppingParameters::parse_parameters(ParameterHandler &prm)
  {
    require_entries_set(prm, "Time stepping", {"Time step", "End time"});
    prm.enter_subsection("Time stepping");
    const std::string name  = prm.get("Scheme");
    scheme                  = name == "theta"          ? Scheme::theta :
                              name == "theta-euler"    ? Scheme::theta_euler :
                              name == "modified-theta" ? Scheme::modified_theta :
                                                         Scheme::newmark;
    theta                   = prm.get_double("Theta");
    theta_entry             = theta;
    theta_from_courant      = prm.get("Theta rule") == "courant";
    theta_damping           = prm.get_double("Theta damping");
    newmark_beta            = prm.get_double("Newmark beta");
    newmark_gamma           = prm.get_double("Newmark gamma");
    time_step               = prm.get_double("Time step");
    end_time                = prm.get_double("End time");
    free_flight_step_factor = prm.get_integer("Free-flight step factor");
    prm.leave_subsection();

    // Below 1/2 the schemes are only conditionally stable: a step above
    // the limit gives energies of 1e18 and no error.
    AssertThrow(theta >= 0.5 && theta <= 1.,
                ExcMessage("Time stepping: 'Theta' must be in [0.5, 1] (the "
                           "schemes are unconditionally stable there), got " +
                           format_input(theta) + "."));
    AssertThrow(!theta_from_courant || scheme != Scheme::newmark,
                ExcMessage("Time stepping: 'Theta rule = courant' needs a "
                           "theta-scheme, got 'Scheme = newmark'."));
    AssertThrow(theta_damping > 0. && std::isfinite(theta_damping),
                ExcMessage("Time stepping: 'Theta damping' must be > 0, got " +
                           format_input(theta_damping) + "."));
    AssertThrow(newmark_beta > 0. && newmark_beta <= 0.5,
                ExcMessage("Time stepping: 'Newmark beta' must be in "
                           "(0, 0.5], got " +
                           format_input(newmark_beta) + "."));
    AssertThrow(newmark_gamma >= 0.5 && newmark_gamma <= 1.,
                ExcMessage("Time stepping: 'Newmark gamma' must be in "
                           "[0.5, 1], got " +
                           format_input(newmark_gamma) + "."));
    // Below gamma/2 Newmark is only conditionally stable, and the steps of
    // the contact benchmarks are far above its limit.
    AssertThrow(newmark_beta >= 0.5 * newmark_gamma,
                ExcMessage("Time stepping: 'Newmark beta' = " +
                           format_input(newmark_beta) +
                           " is below 'Newmark gamma' / 2 = " +
                           format_input(0.5 * newmark_gamma) +
                           ": that Newmark scheme is only conditionally "
                           "stable; take beta >= gamma / 2."));
    AssertThrow(free_flight_step_factor <= 1000,
                ExcMessage("Time stepping: 'Free-flight step factor' must be "
                           "at most 1000, got " +
                           std::to_string(free_flight_step_factor) + "."));
    require_positive(time_step, "Time stepping", "Time step");
    require_positive(end_time, "Time stepping", "End time");
    AssertThrow(time_step <= end_time,
                ExcMessage(
                  "Time stepping: 'Time step' = " + format_number(time_step) +
                  " s is longer than 'End time' = " + format_number(end_time) +
                  " s."));
    AssertThrow(end_time / time_step < 1e9,
                ExcMessage("Time stepping: 'End time' / 'Time step' = " +
                           format_number(end_time / time_step) +
                           " steps is more than this program will run."));
  }



  unsigned int
  TimeSteppingParameters::n_steps() const
  {
    return static_cast<unsigned int>(std::ceil(end_time / time_step - 1e-9));
  }



  void
  TimeSteppingParameters::apply_theta_rule(const double cell_transit_time)
  {
    const bool valid =
      cell_transit_time > 0. && std::isfinite(cell_transit_time);
    if (valid)
      courant_number = time_step / cell_transit_time;
    // The step matrix M + theta^2 h^2 K has a condition number near
    // (theta C)^2: beyond C = 1e6 (1e12) its solves keep too few digits for
    // the impulse balance and the contact checks, and the run's answer
    // would depend on the solver (a density of 1e-20 kg/m^3 gave an
    // impulse balance error of 196 on one rank and an indefinite
    // factorisation on two). The benchmarks go up to C ~ 1e3.
    // (a free-flight step k h has k times the Courant number)
    AssertThrow(courant_number * free_flight_step_factor <= 1e6,
                ExcMessage(
                  "Time stepping: the Courant number c_p h / dx = " +
                  format_number(courant_number) +
                  (free_flight_step_factor > 1 ?
                     " (" +
                       format_number(courant_number * free_flight_step_factor) +
                       " for the free-flight steps of 'Free-flight step "
                       "factor' h)" :
                     std::string()) +
                  ", with the fastest wave's speed c_p from 'Young's "
                  "modulus' and 'Density', and dx the cells' mean size, is "
                  "above 1e6: the step matrix M + theta^2 h^2 K would be too "
                  "ill-conditioned for double precision. Lower 'Time step' "
                  "(or 'Free-flight step factor'), or check 'Density' and "
                  "'Young's modulus'."));
    if (!theta_from_courant)
      return;
    AssertThrow(valid,
                ExcMessage("Time stepping: 'Theta rule = courant' needs the "
                           "cells' wave transit time dx / c_p > 0, got " +
                           format_number(cell_transit_time) + " s."));
    theta = std::min(1., 0.5 + theta_damping / courant_number);
  }



  TimeSteppingParameters
  TimeSteppingParameters::free_flight_parameters() const
  {
    TimeSteppingParameters coarse = *this;
    coarse.time_step *= free_flight_step_factor;
    coarse.courant_number *= free_flight_step_factor;
    // theta stays that of h, also under the Courant rule: theta = 1/2 +
    // kappa / (k C) for k h (the damping coefficient of a step of h) gave
    // energies 0.05-0.85 % closer to 1 but err_v larger at 38 of 40 points
    // of the 1D bars, by up to 10 % (the ringing left after the impact is
    // damped less), and the same 2D force errors (doc/work_precision.md,
    // 2026-12-03).
    return coarse;
  }



  std::string
  TimeSteppingParameters::scheme_description() const
  {
    std::ostringstream text;
    text << to_string(scheme);
    if (scheme == Scheme::newmark)
      text << " (beta = " << newmark_beta << ", gamma = " << newmark_gamma
           << ")";
    else if (theta_from_courant)
      text << " (theta = " << theta << " from the Courant number "
           << courant_number << "; the entry 'Theta' = " << theta_entry
           << " is not used)";
    else
      text << " (theta = " << theta << ")";
    return text.str();
  }



  void
  TimeSteppingParameters::add_to_summary(JsonObject &summary) const
  {
    summary.add("scheme", to_string(scheme))
      .add("theta", theta)
      .add("theta_rule", std::string(theta_from_courant ? "courant" : "fixed"))
      .add("courant_number", courant_number)
      .add("time_step", time_step);
  }



  TimeIntegrator::TimeIntegrator(const TimeSteppingParameters &parameters)
    : parameters(parameters)
    , h(parameters.time_step)
  {}

  Scheme
  TimeIntegrator::scheme() const
  {
    return parameters.scheme;
  }

  double
  TimeIntegrator::time_step() const
  {
    return h;
  }

  double
  TimeIntegrator::force_per_impulse() const
  {
    return massless_contact_nodes ? 1. / (h * parameters.theta) : 1. / h;
  }

  double
  TimeIntegrator::contact_force_weight() const
  {
    return massless_contact_nodes ? parameters.theta : 1.;
  }

  void
  TimeIntegrator::set_massless_contact_nodes(const bool massless)
  {
    AssertThrow(!massless || parameters.scheme != Scheme::newmark,
                ExcMessage("Discretization: 'Mass redistribution = true' "
                           "needs a theta-scheme; Newmark's initial "
                           "acceleration needs an invertible mass matrix."));
    massless_contact_nodes = massless;
  }

  double
  TimeIntegrator::slip_velocity_carry() const
  {
    return 0.;
  }

  double
  TimeIntegrator::massless_impulse_carry() const
  {
    return massless_contact_nodes ? (1. - parameters.theta) / parameters.theta :
                                    0.;
  }

  bool
  TimeIntegrator::needs_initial_acceleration() const
  {
    return false;
  }

  std::pair<const BlockVector<double> *, const BlockVector<double> *>
  TimeIntegrator::free_rhs_arguments(const MechanicalState &state) const
  {
    return {&state.velocity, &state.displacement};
  }

  void
  TimeIntegrator::free_rhs(const FreeRhsOperator         &op,
                           const MechanicalState         &state,
                           BlockVector<double>           &rhs,
                           FreeRhsOperator::Translations &translation) const
  {
    const auto [x, y] = free_rhs_arguments(state);
    op.apply(*x, *y, rhs, translation);
  }



  ThetaStepRule
  TimeIntegrator::theta_step_rule() const
  {
    AssertThrow(false,
                ExcMessage("The scheme '" + to_string(scheme()) +
                           "' has no theta-step rule: its step needs the "
                           "acceleration (choose a theta-scheme)."));
    return {};
  }

  NewmarkStepRule
  TimeIntegrator::newmark_step_rule() const
  {
    AssertThrow(false,
                ExcMessage("The scheme '" + to_string(scheme()) +
                           "' has no Newmark step rule."));
    return {};
  }

  void
  TimeIntegrator::gap_term(const ContactSet      &contacts,
                           const MechanicalState &s,
                           std::vector<double>   &b) const
  {
    const ThetaStepRule rule = theta_step_rule();
    if (rule.gap_prediction != 0.)
      contacts.gaps(s.displacement, h * rule.gap_prediction, s.velocity, b);
    else
      contacts.gaps(s.displacement, b);
    if (rule.gap_velocity != 0.)
      {
        contacts.normal_velocities(s.velocity, rule_normal_velocity);
        for (unsigned int c = 0; c < b.size(); ++c)
          b[c] = b[c] / rule.gap_divisor +
                 rule.gap_velocity * rule_normal_velocity[c];
      }
    else
      for (double &bc : b)
        bc /= rule.gap_divisor;
  }

  namespace
  {
    // u_new = u_old + a v_new + b v_old, entry by entry (b = 0: u_old + a
    // v_new, as deal.II's add(a, v) would round it).
    IMPACTFE_VECTORIZED_KERNEL void
    displacement_update(const std::size_t n,
                        const double     *u_old,
                        const double      a,
                        const double     *v_new,
                        const double      b,
                        const double     *v_old,
                        double *__restrict u_new)
    {
      if (b == 0.)
        for (std::size_t i = 0; i < n; ++i)
          u_new[i] = u_old[i] + a * v_new[i];
      else
        for (std::size_t i = 0; i < n; ++i)
          u_new[i] = u_old[i] + a * v_new[i] + b * v_old[i];
    }
  } // namespace



  void
  TimeIntegrator::complete_step(const MechanicalState &old_state,
                                MechanicalState       &new_state) const
  {
    // u^{i+1} = u^i + h w v^{i+1} + h (1 - w) v^i in one pass (a copy and
    // an add() were two); rounded as deal.II's add(a, v, b, w).
    AssertThrow(new_state.displacement.size() == old_state.displacement.size(),
                dealii::ExcDimensionMismatch(new_state.displacement.size(),
                                             old_state.displacement.size()));
    const double w = theta_step_rule().new_velocity_weight;
    for (unsigned int k = 0; k < new_state.displacement.n_blocks(); ++k)
      displacement_update(new_state.displacement.block(k).size(),
                          old_state.displacement.block(k).data(),
                          h * w,
                          new_state.velocity.block(k).data(),
                          h * (1. - w),
                          old_state.velocity.block(k).data(),
                          new_state.displacement.block(k).data());
  }



  namespace
  {
    // @sect4{theta-method (Moreau--Jean)}
    // u^{i+1} = u^i + h (theta v^{i+1} + (1-theta) v^i);
    // g^{i+1} = g^i + h theta V_N^{i+1} + h (1-theta) V_N^i, so Signorini on
    // g^{i+1}/(h theta) gives b_N = g^i/(h theta) + (1-theta)/theta V_N^i.
    class ThetaMethod : public TimeIntegrator
    {
    public:
      using TimeIntegrator::TimeIntegrator;

      double
      damping_coefficient() const override
      {
        return h * parameters.theta;
      }

      double
      stiffness_coefficient() const override
      {
        return h * h * parameters.theta * parameters.theta;
      }

      // F~ = M v - h (1-theta) C v - h^2 theta (1-theta) K v - h K u + h F
      FreeRhsCoefficients
      free_rhs_coefficients() const override
      {
        const double theta = parameters.theta;
        return {-h * (1. - theta), -h * h * theta * (1. - theta), -h, h};
      }

      ThetaStepRule
      theta_step_rule() const override
      {
        const double theta = parameters.theta;
        return {theta, 0., h * theta, (1. - theta) / theta};
      }

      double
      slip_velocity_carry() const override
      {
        return massless_contact_nodes ?
                 (1. - parameters.theta) / parameters.theta :
                 0.;
      }
    };



    // @sect4{Modified theta-method}
    // Same dynamics and displacement update as the theta-method; the gap is
    // taken at the estimate u^ = u + h (1-theta) v, which moves with
    // h V_N^{i+1} exactly: b_N = g(u^i + h (1-theta) v^i) / h. A gap that is
    // closed and stays closed gives V_N^{i+1} = 0 (paper, section 4).
    class ModifiedThetaMethod : public ThetaMethod
    {
    public:
      using ThetaMethod::ThetaMethod;

      ThetaStepRule
      theta_step_rule() const override
      {
        const double theta = parameters.theta;
        return {theta, 1. - theta, h, 0.};
      }
    };



    // @sect4{theta-Euler method}
    // u^{i+1} = u^i + h v^{i+1}; the momentum balance keeps the theta
    // weighting of the forces. Then g^{i+1} = g^i + h V_N^{i+1} and
    // b_N = g^i / h.
    class ThetaEulerMethod : public TimeIntegrator
    {
    public:
      using TimeIntegrator::TimeIntegrator;

      double
      damping_coefficient() const override
      {
        return h * parameters.theta;
      }

      double
      stiffness_coefficient() const override
      {
        return h * h * parameters.theta;
      }

      // F~ = M v - h (1-theta) C v - h K u + h F
      FreeRhsCoefficients
      free_rhs_coefficients() const override
      {
        return {-h * (1. - parameters.theta), 0., -h, h};
      }

      ThetaStepRule
      theta_step_rule() const override
      {
        return {1., 0., h, 0.};
      }
    };



    // @sect4{Newmark}
    // Predictors u~ = u + h v + h^2 (1/2 - beta) a, v~ = v + h (1-gamma) a;
    // then u^{i+1} = u~ + h^2 beta a^{i+1}, v^{i+1} = v~ + h gamma a^{i+1}.
    // Eliminating a^{i+1} = (v^{i+1} - v~)/(h gamma) gives the velocity
    // form with M~ = M + h gamma C + h^2 beta K and the impulse P = h gamma
    // r^{i+1}. Signorini holds on the displacement, g(u^{i+1}) >= 0, which
    // is g(u~) + (h beta/gamma)(V_N^{i+1} - V~_N) >= 0, hence
    // b_N = gamma g(u~) / (h beta) - V~_N.
    class NewmarkMethod : public TimeIntegrator
    {
    public:
      using TimeIntegrator::TimeIntegrator;

      double
      damping_coefficient() const override
      {
        return h * parameters.newmark_gamma;
      }

      double
      stiffness_coefficient() const override
      {
        return h * h * parameters.newmark_beta;
      }

      // F~ = M v~ + h^2 beta K v~ - h gamma K u~ + h gamma F (no C v~:
      // hgamma C multiplies v^{i+1} itself, in M~)
      FreeRhsCoefficients
      free_rhs_coefficients() const override
      {
        return {0.,
                h * h * parameters.newmark_beta,
                -h * parameters.newmark_gamma,
                h * parameters.newmark_gamma};
      }

      std::pair<const BlockVector<double> *, const BlockVector<double> *>
      free_rhs_arguments(const MechanicalState &s) const override
      {
        predict(s);
        return {&predicted_velocity, &predicted_displacement};
      }

      NewmarkStepRule
      newmark_step_rule() const override
      {
        const double beta  = parameters.newmark_beta,
                     gamma = parameters.newmark_gamma;
        NewmarkStepRule rule;
        rule.time_step                           = h;
        rule.predicted_displacement_acceleration = h * h * (0.5 - beta);
        rule.predicted_velocity_acceleration     = h * (1. - gamma);
        rule.gap_factor                          = gamma / (h * beta);
        rule.acceleration_divisor                = h * gamma;
        rule.displacement_acceleration           = h * h * beta;
        return rule;
      }

      void
      gap_term(const ContactSet      &contacts,
               const MechanicalState &s,
               std::vector<double>   &b) const override
      {
        const NewmarkStepRule rule = newmark_step_rule();
        predict(s);
        contacts.gaps(predicted_displacement, b);
        contacts.normal_velocities(predicted_velocity, normal_velocity);
        for (unsigned int c = 0; c < b.size(); ++c)
          b[c] = rule.gap_factor * b[c] - normal_velocity[c];
      }

      void
      complete_step(const MechanicalState &old_state,
                    MechanicalState       &new_state) const override
      {
        const NewmarkStepRule rule = newmark_step_rule();
        predict(old_state);
        new_state.acceleration = new_state.velocity;
        new_state.acceleration -= predicted_velocity;
        new_state.acceleration *= 1. / rule.acceleration_divisor;
        new_state.displacement = predicted_displacement;
        new_state.displacement.add(rule.displacement_acceleration,
                                   new_state.acceleration);
      }

      double
      force_per_impulse() const override
      {
        return 1. / (h * parameters.newmark_gamma);
      }

      double
      contact_force_weight() const override
      {
        return parameters.newmark_gamma;
      }

      bool
      needs_initial_acceleration() const override
      {
        return true;
      }

    private:
      mutable BlockVector<double> predicted_displacement;
      mutable BlockVector<double> predicted_velocity;
      mutable std::vector<double> normal_velocity;

      void
      predict(const MechanicalState &s) const
      {
        const NewmarkStepRule rule = newmark_step_rule();
        predicted_displacement     = s.displacement;
        predicted_displacement.add(h,
                                   s.velocity,
                                   rule.predicted_displacement_acceleration,
                                   s.acceleration);
        predicted_velocity = s.velocity;
        predicted_velocity.add(rule.predicted_velocity_acceleration,
                               s.acceleration);
      }
    };
  } // namespace



  std::unique_ptr<TimeIntegrator>
  create_time_integrator(const TimeSteppingParameters &parameters)
  {
    switch (parameters.scheme)
      {
        case Scheme::theta:
          return std::make_unique<ThetaMethod>(parameters);
        case Scheme::theta_euler:
          return std::make_unique<ThetaEulerMethod>(parameters);
        case Scheme::modified_theta:
          return std::make_unique<ModifiedThetaMethod>(parameters);
        case Scheme::newmark:
          return std::make_unique<NewmarkMethod>(parameters);
      }
    AssertThrow(false, ExcInternalError());
    return nullptr;
  }
} // namespace impactfe
