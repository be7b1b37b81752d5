#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <impactfe/contact/rigid_obstacle.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <sstream>

namespace impactfe
{
  namespace
  {
    template <int dim>
    std::string
    format_point(const Tensor<1, dim> &x)
    {
      std::ostringstream out;
      out << "(";
      for (unsigned int d = 0; d < dim; ++d)
        out << (d > 0 ? ", " : "") << x[d];
      out << ")";
      return out.str();
    }
  } // namespace



  // @sect3{Plane}
  template <int dim>
  PlaneObstacle<dim>::PlaneObstacle(const Point<dim>     &point,
                                    const Tensor<1, dim> &normal)
    : point(point)
  {
    AssertThrow(normal.norm() > 0.,
                ExcMessage("Obstacle: the plane's normal must not be zero."));
    unit_normal = normal / normal.norm();
  }

  template <int dim>
  double
  PlaneObstacle<dim>::signed_distance(const Point<dim> &x) const
  {
    return (x - point) * unit_normal;
  }

  template <int dim>
  Tensor<1, dim>
  PlaneObstacle<dim>::normal(const Point<dim> &) const
  {
    return unit_normal;
  }

  template <int dim>
  std::string
  PlaneObstacle<dim>::description() const
  {
    return "plane through " + format_point<dim>(point) + " with normal " +
           format_point<dim>(unit_normal);
  }



  // @sect3{Disc or ball}
  template <int dim>
  BallObstacle<dim>::BallObstacle(const Point<dim> &center, const double radius)
    : center(center)
    , radius(radius)
  {
    require_positive(radius, "Obstacle", "Radius");
  }

  template <int dim>
  double
  BallObstacle<dim>::signed_distance(const Point<dim> &x) const
  {
    return (x - center).norm() - radius;
  }

  template <int dim>
  Tensor<1, dim>
  BallObstacle<dim>::normal(const Point<dim> &x) const
  {
    const Tensor<1, dim> r = x - center;
    AssertThrow(r.norm() > 0.,
                ExcMessage("Obstacle: a contact node lies at the centre of "
                           "the ball, where the normal is undefined."));
    return r / r.norm();
  }

  template <int dim>
  double
  BallObstacle<dim>::ball_radius() const
  {
    return radius;
  }



  template <int dim>
  std::string
  BallObstacle<dim>::description() const
  {
    return std::string(dim == 2 ? "disc" : "ball") + " of radius " +
           format_number(radius) + " centred at " + format_point<dim>(center);
  }



  // @sect3{Level set}
  template <int dim>
  LevelSetObstacle<dim>::LevelSetObstacle(const std::string &expression,
                                          const double       length_scale)
    : expression(expression)
    , step(1e-6 * length_scale)
  {
    const std::string variables = dim == 1 ? "x" : (dim == 2 ? "x,y" : "x,y,z");
    // The parser may only complain at the first evaluation: do one here,
    // so that a bad expression is reported with the entry's name.
    std::string problem;
    try
      {
        // muParser's own report goes to std::cerr; the message below
        // carries it
        std::ostringstream printed;
        const CerrCapture  capture(printed);
        phi.initialize(variables, expression, std::map<std::string, double>());
        phi.value(Point<dim>());
      }
    catch (const std::exception &error)
      {
        problem = exception_text(error);
      }
    AssertThrow(problem.empty(),
                ExcMessage("Obstacle: 'Level set' = '" + expression +
                           "' is not a valid expression in " + variables +
                           ": " + problem));
  }

  template <int dim>
  Tensor<1, dim>
  LevelSetObstacle<dim>::gradient(const Point<dim> &x) const
  {
    Tensor<1, dim> g;
    for (unsigned int d = 0; d < dim; ++d)
      {
        Point<dim> plus = x, minus = x;
        plus[d] += step;
        minus[d] -= step;
        g[d] = (phi.value(plus) - phi.value(minus)) / (2. * step);
      }
    AssertThrow(g.norm() > 0. && std::isfinite(g.norm()),
                ExcMessage("Obstacle: the gradient of the level set '" +
                           expression + "' vanishes or is not finite at " +
                           format_point<dim>(x) + "."));
    return g;
  }

  template <int dim>
  double
  LevelSetObstacle<dim>::signed_distance(const Point<dim> &x) const
  {
    const double value = phi.value(x);
    AssertThrow(std::isfinite(value),
                ExcMessage("Obstacle: the level set '" + expression +
                           "' is not finite at " + format_point<dim>(x) + "."));
    // The gap is fixed by the level set near x only; the surface it stands
    // for must exist where the node would touch it, at the first-order
    // foot point x - phi grad(phi) / |grad(phi)|^2. (A level set that is
    // NaN there, say y + 0 * sqrt(y - 1) with the nodes above y = 1, would
    // otherwise give a plausible gap to a surface that is not defined.)
    const Tensor<1, dim> g        = gradient(x);
    const double         distance = value / g.norm();
    const Point<dim>     foot     = x - (distance / g.norm()) * g;
    AssertThrow(std::isfinite(phi.value(foot)),
                ExcMessage("Obstacle: the level set '" + expression +
                           "' is not finite at " + format_point<dim>(foot) +
                           ", the point to which the gap of the node at " +
                           format_point<dim>(x) +
                           " is measured (x - phi grad(phi) / "
                           "|grad(phi)|^2): define the level set wherever "
                           "the bodies can reach its surface."));
    return distance;
  }

  template <int dim>
  Tensor<1, dim>
  LevelSetObstacle<dim>::normal(const Point<dim> &x) const
  {
    const Tensor<1, dim> g = gradient(x);
    return g / g.norm();
  }

  template <int dim>
  std::string
  LevelSetObstacle<dim>::description() const
  {
    return "level set " + expression + " = 0";
  }



  // @sect3{Parameters}
  void
  ObstacleParameters::declare_parameters(ParameterHandler  &prm,
                                         const std::string &default_point,
                                         const std::string &default_normal,
                                         const std::string &default_friction)
  {
    prm.enter_subsection("Obstacle");
    prm.declare_entry("Type",
                      "plane",
                      Patterns::Selection("plane|ball|level set"),
                      "The rigid obstacle: 'plane' (Point on plane, Normal), "
                      "'ball' (a disc in 2D, a ball in 3D: Center, Radius; "
                      "the bodies are outside), or 'level set', the zero "
                      "level set of a function (Level set; positive on the "
                      "bodies' side).");
    prm.declare_entry("Point on plane",
                      default_point,
                      Patterns::List(Patterns::Double(), 1, 3),
                      "A point of the plane, comma-separated coordinates [m].");
    prm.declare_entry("Normal",
                      default_normal,
                      Patterns::List(Patterns::Double(), 1, 3),
                      "Normal of the plane, pointing towards the bodies [-]. "
                      "Need not be unit.");
    prm.declare_entry("Center",
                      default_point,
                      Patterns::List(Patterns::Double(), 1, 3),
                      "Centre of the disc or ball [m].");
    prm.declare_entry("Radius",
                      "1",
                      Patterns::Double(),
                      "Radius of the disc or ball [m]. Must be > 0.");
    // the default plane as a level set, so that switching 'Type' keeps
    // the scene's obstacle (y = 0 in most scenes, z = 0 for the ball)
    std::string plane;
    {
      const auto normal = Utilities::split_string_list(default_normal);
      const auto point  = Utilities::split_string_list(default_point);
      const char axes[] = {'x', 'y', 'z'};
      double     offset = 0.;
      for (unsigned int d = 0; d < normal.size() && d < 3; ++d)
        {
          const double n = Utilities::string_to_double(normal[d]);
          if (n == 0.)
            continue;
          if (d < point.size())
            offset += n * Utilities::string_to_double(point[d]);
          plane += (plane.empty() ? "" : " + ") +
                   (n == 1. ? std::string() : normal[d] + "*") + axes[d];
        }
      if (offset != 0.)
        plane += " - (" + format_number(offset) + ")";
    }
    prm.declare_entry("Level set",
                      plane,
                      Patterns::Anything(),
                      "Function phi(x, y, z) whose zero level set is the "
                      "obstacle's surface, phi > 0 on the bodies' side [m]. "
                      "The default is the default plane.");
    prm.declare_entry("Friction coefficient",
                      default_friction,
                      Patterns::Double(),
                      "Coulomb friction coefficient mu between the bodies "
                      "and the obstacle [-]. Must be >= 0; 0 means a "
                      "frictionless scene (normal unknowns only).");
    prm.leave_subsection();
  }



  void
  ObstacleParameters::parse_parameters(ParameterHandler  &prm,
                                       const unsigned int dim)
  {
    prm.enter_subsection("Obstacle");
    const std::string type_name = prm.get("Type");
    type                        = type_name == "plane" ? Type::plane :
                                  type_name == "ball"  ? Type::ball :
                                                         Type::level_set;
    // Only the entries of the chosen type must have dim coordinates.
    const auto read_vector = [&](const std::string &entry, const bool used) {
      const std::vector<std::string> parts =
        Utilities::split_string_list(prm.get(entry));
      AssertThrow(!used || parts.size() == dim,
                  ExcMessage("Obstacle: '" + entry + "' needs " +
                             std::to_string(dim) + " coordinates, got '" +
                             prm.get(entry) + "'."));
      std::vector<double> values(3, 0.);
      for (unsigned int d = 0; d < std::min<std::size_t>(parts.size(), 3); ++d)
        values[d] = parse_list_number(parts[d], "Obstacle", entry);
      return values;
    };
    point = read_vector("Point on plane", type == Type::plane);
    const std::string normal_text = prm.get("Normal");
    normal                        = read_vector("Normal", type == Type::plane);
    center                        = read_vector("Center", type == Type::ball);
    radius                        = prm.get_double("Radius");
    expression                    = prm.get("Level set");
    friction_coefficient          = prm.get_double("Friction coefficient");
    prm.leave_subsection();

    double normal_norm = 0.;
    for (const double x : normal)
      normal_norm += x * x;
    AssertThrow(type != Type::plane || normal_norm > 0.,
                ExcMessage("Obstacle: 'Normal' must not be zero, nor so "
                           "short that its squared length is 0 in double "
                           "precision; got '" +
                           normal_text + "'."));
    if (type == Type::ball)
      require_positive(radius, "Obstacle", "Radius");
    require_friction_coefficient(friction_coefficient,
                                 "Obstacle",
                                 "Friction coefficient");
  }



  template <int dim>
  std::unique_ptr<RigidObstacle<dim>>
  ObstacleParameters::create(const double length_scale) const
  {
    Point<dim>     p, c;
    Tensor<1, dim> n;
    for (unsigned int d = 0; d < dim; ++d)
      {
        p[d] = point[d];
        n[d] = normal[d];
        c[d] = center[d];
      }
    switch (type)
      {
        case Type::plane:
          return std::make_unique<PlaneObstacle<dim>>(p, n);
        case Type::ball:
          return std::make_unique<BallObstacle<dim>>(c, radius);
        default:
          return std::make_unique<LevelSetObstacle<dim>>(expression,
                                                         length_scale);
      }
  }



  template class PlaneObstacle<1>;
  template class PlaneObstacle<2>;
  template class PlaneObstacle<3>;
  template class BallObstacle<1>;
  template class BallObstacle<2>;
  template class BallObstacle<3>;
  template class LevelSetObstacle<1>;
  template class LevelSetObstacle<2>;
  template class LevelSetObstacle<3>;
  template std::unique_ptr<RigidObstacle<1>>
  ObstacleParameters::create<1>(const double) const;
  template std::unique_ptr<RigidObstacle<2>>
  ObstacleParameters::create<2>(const double) const;
  template std::unique_ptr<RigidObstacle<3>>
  ObstacleParameters::create<3>(const double) const;
} // namespace impactfe
