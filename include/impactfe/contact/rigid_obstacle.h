#ifndef impactfe_contact_rigid_obstacle_h
#define impactfe_contact_rigid_obstacle_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>

#include <memory>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * A rigid, fixed obstacle described by its signed distance: positive on
   * the side where the bodies are, zero on its surface. For each contact
   * candidate the library evaluates, at the node's reference position, the
   * initial gap (the signed distance) and the contact normal (the unit
   * vector pointing from the obstacle towards the body). Under the small
   * perturbation hypothesis both stay fixed during the run; for a plane
   * this is exact, for a curved obstacle it holds while the contact point
   * moves little compared with the radius of curvature.
   */
  template <int dim>
  class RigidObstacle
  {
  public:
    virtual ~RigidObstacle() = default;

    /** Signed distance of @p x to the surface (> 0 outside) [m]. */
    virtual double
    signed_distance(const Point<dim> &x) const = 0;

    /** Unit normal at the surface point nearest to @p x, towards the body. */
    virtual Tensor<1, dim>
    normal(const Point<dim> &x) const = 0;

    /** What the obstacle is, for messages ("plane through (0, 0) ..."). */
    virtual std::string
    description() const = 0;
  };



  /** Half-space {x : (x - p) . n >= 0}. */
  template <int dim>
  class PlaneObstacle : public RigidObstacle<dim>
  {
  public:
    PlaneObstacle(const Point<dim> &point, const Tensor<1, dim> &normal);
    double
    signed_distance(const Point<dim> &x) const override;
    Tensor<1, dim>
    normal(const Point<dim> &x) const override;
    std::string
    description() const override;

  private:
    Point<dim>     point;
    Tensor<1, dim> unit_normal;
  };



  /** A rigid disc (2D) or ball (3D): the bodies are outside it. */
  template <int dim>
  class BallObstacle : public RigidObstacle<dim>
  {
  public:
    BallObstacle(const Point<dim> &center, const double radius);
    double
    signed_distance(const Point<dim> &x) const override;
    /** The radius of the disc or ball [m]. */
    double
    ball_radius() const;
    Tensor<1, dim>
    normal(const Point<dim> &x) const override;
    std::string
    description() const override;

  private:
    Point<dim> center;
    double     radius;
  };



  /**
   * An obstacle given by a level-set function phi (a deal.II
   * FunctionParser expression in x, y, z), phi > 0 where the bodies are.
   * The gap is the first-order distance phi / |grad phi| and the normal
   * grad phi / |grad phi|; the gradient is taken by central differences.
   * Exact for a plane; for a signed distance function, exact too.
   */
  template <int dim>
  class LevelSetObstacle : public RigidObstacle<dim>
  {
  public:
    LevelSetObstacle(const std::string &expression, const double length_scale);
    double
    signed_distance(const Point<dim> &x) const override;
    Tensor<1, dim>
    normal(const Point<dim> &x) const override;
    std::string
    description() const override;

  private:
    std::string         expression;
    FunctionParser<dim> phi;
    double              step;

    Tensor<1, dim>
    gradient(const Point<dim> &x) const;
  };



  /**
   * Parameter subsection `Obstacle`: which rigid obstacle the bodies hit.
   */
  struct ObstacleParameters
  {
    enum class Type
    {
      plane,
      ball,
      level_set
    };
    Type                type = Type::plane;
    std::vector<double> point{0., 0., 0.};
    std::vector<double> normal{0., 1., 0.};
    std::vector<double> center{0., 0., 0.};
    double              radius               = 1.;
    std::string         expression           = "y";
    double              friction_coefficient = 0.;

    /**
     * @p default_point and @p default_normal are the scene's plane (comma
     * separated coordinates); the defaults of the other entries are
     * neutral.
     */
    static void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &default_point,
                       const std::string &default_normal,
                       const std::string &default_friction);
    void
    parse_parameters(ParameterHandler &prm, const unsigned int dim);

    /** The obstacle; @p length_scale sets the finite-difference step. */
    template <int dim>
    std::unique_ptr<RigidObstacle<dim>>
    create(const double length_scale) const;
  };
} // namespace impactfe

#endif
