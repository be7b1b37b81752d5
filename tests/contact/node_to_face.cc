// ContactSet::add_node_to_face on non-matching, warped faces, against a
// brute-force search. Body B: 2 x 2 x 1 hexahedra on [0, 1]^2 x [0, 0.5]
// whose top face (boundary id 5) is warped by lifting its middle node by
// 0.1, so its four faces are non-planar bilinear patches. Body A: 3 x 3 x 1
// hexahedra on [0.05, 0.95]^2 x [0.65, 0.8] above it; its bottom face
// (id 4) has 16 nodes, none above a node of B but the middle one. For each
// candidate:
// - the weights are in [0, 1] and sum to 1;
// - the contact point y = sum w_k p_k is B's closest point to the node: no
//   point of a 400 x 400 grid on each of B's top faces is closer (the grid
//   spacing bounds how much closer the true minimum can be);
// - the frame is orthonormal and its normal points from B to A, the gap
//   g0 = (x - y) . n is positive, and n is the bilinear interpolation of
//   unit nodal normals (so |n| = 1 after normalisation and n_z > 0.9 here).
// A body beside B (no face under its nodes) gets a message naming it, and
// a run's search stops at a node deep inside B.

#include <deal.II/grid/grid_generator.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_set.h>

#include <cmath>
#include <memory>
#include <string>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;

namespace
{
  std::unique_ptr<ElasticBody<3>>
  make_block(const std::string &name,
             const Point<3>    &low,
             const Point<3>    &high,
             const unsigned int n)
  {
    MaterialParameters material;
    material.youngs_modulus = 1e6;
    material.density        = 1000.;
    material.poissons_ratio = 0.3;
    auto body               = std::make_unique<ElasticBody<3>>(name,
                                                 material,
                                                 DiscretizationParameters(),
                                                 1.);
    GridGenerator::subdivided_hyper_rectangle(body->triangulation(),
                                              std::vector<unsigned int>{n,
                                                                        n,
                                                                        1},
                                              low,
                                              high,
                                              true);
    return body;
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  auto lower =
    make_block("lower", Point<3>(0., 0., 0.), Point<3>(1., 1., .5), 2);
  for (auto &cell : lower->triangulation().active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      if (cell->vertex(v).distance(Point<3>(0.5, 0.5, 0.5)) < 1e-12)
        cell->vertex(v)[2] = 0.6;
  lower->setup();
  auto upper =
    make_block("upper", Point<3>(0.05, 0.05, 0.65), Point<3>(.95, .95, .8), 3);
  upper->setup();
  const std::vector<const ElasticBody<3> *> bodies{upper.get(), lower.get()};

  ContactSet         contacts(3);
  const unsigned int n = contacts.add_node_to_face(bodies, 0, 4, 1, 5);
  check(n == 16, "16 candidates on the upper body's bottom face");

  const auto &vertices_b = lower->triangulation().get_vertices();
  // B's top faces, for the brute-force search.
  std::vector<std::array<Point<3>, 4>> faces;
  for (const auto &cell : lower->triangulation().active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 5)
        faces.push_back({{cell->face(f)->vertex(0),
                          cell->face(f)->vertex(1),
                          cell->face(f)->vertex(2),
                          cell->face(f)->vertex(3)}});
  double worst_weight = 0., worst_closest = -1., worst_frame = 0.;
  bool   normals_up = true, gaps_positive = true;
  for (const ContactCandidate &c : contacts.candidates())
    {
      const Point<3> x(c.position[0], c.position[1], c.position[2]);
      double         sum = 0.;
      Point<3>       y;
      for (unsigned int k = 0; k < c.n_vertices_b; ++k)
        {
          sum += c.weights_b[k];
          worst_weight =
            std::max({worst_weight, -c.weights_b[k], c.weights_b[k] - 1.});
          y += c.weights_b[k] * Tensor<1, 3>(vertices_b[c.vertices_b[k]]);
        }
      worst_weight       = std::max(worst_weight, std::abs(sum - 1.));
      double brute_force = 1e300;
      for (const auto &p : faces)
        for (unsigned int i = 0; i <= 400; ++i)
          for (unsigned int j = 0; j <= 400; ++j)
            {
              const double   s = i / 400., t = j / 400.;
              const Point<3> z =
                (1. - s) * (1. - t) * p[0] + Tensor<1, 3>(s * (1. - t) * p[1]) +
                Tensor<1, 3>((1. - s) * t * p[2]) + Tensor<1, 3>(s * t * p[3]);
              brute_force = std::min(brute_force, x.distance(z));
            }
      worst_closest = std::max(worst_closest, x.distance(y) - brute_force);
      Tensor<1, 3> frame[3];
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int d = 0; d < 3; ++d)
          frame[a][d] = c.frame[a][d];
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int b = 0; b < 3; ++b)
          worst_frame =
            std::max(worst_frame, std::abs(frame[a] * frame[b] - (a == b)));
      normals_up    = normals_up && frame[0][2] > 0.9;
      gaps_positive = gaps_positive && c.initial_gap > 0. &&
                      std::abs(c.initial_gap - (x - y) * frame[0]) < 1e-14;
    }
  check(worst_weight < 1e-14, "weights in [0, 1], summing to 1");
  check(worst_closest <= 1e-12,
        "the contact point is B's closest point (no grid point closer)",
        std::to_string(worst_closest));
  check(worst_frame < 1e-14, "orthonormal frames");
  check(normals_up, "normals from B towards A");
  check(gaps_positive, "g0 = (x - y) . n > 0");

  auto beside =
    make_block("beside", Point<3>(2., 0., 0.65), Point<3>(3., 1., 0.8), 1);
  beside->setup();
  try
    {
      contacts.add_node_to_face<3>({beside.get(), lower.get()}, 0, 4, 1, 5);
      check(false, "a node beside B is refused");
    }
  catch (const std::exception &e)
    {
      // (deal.II wraps the message's lines.)
      const std::string message = e.what();
      check(message.find("'beside'") != std::string::npos &&
              message.find("'lower'") != std::string::npos &&
              message.find("projects on no") != std::string::npos,
            "a node beside B is refused with a message naming the bodies");
    }

  // A search during a run (distance 0.05 m, max_penetration 1e-3 m) from
  // a small block whose nodes lie 2.4-2.5 m deep inside a block 5 m tall:
  // farther from B's top than its faces' widened boxes reach, so no face
  // is near; they lie inside B, and the search stops, naming a node.
  auto tall = make_block("tall", Point<3>(0., 0., 0.), Point<3>(1., 1., 5.), 2);
  tall->setup();
  auto sunk =
    make_block("sunk", Point<3>(0.3, 0.3, 2.5), Point<3>(0.4, 0.4, 2.6), 1);
  sunk->setup();
  try
    {
      ContactSet search(3);
      search.add_node_to_face<3>(
        {sunk.get(), tall.get()}, 0, 4, 1, 5, 0., 0.05, 1e-3);
      check(false, "a node deep inside B stops a run's search");
    }
  catch (const std::exception &e)
    {
      const std::string message = impactfe_tests::one_line(e);
      check(message.find("'sunk'") != std::string::npos &&
              message.find("lies inside body 'tall'") != std::string::npos,
            "a node deep inside B stops a run's search, naming it",
            message);
    }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
