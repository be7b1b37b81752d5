// ContactSet::add_node_to_segment (2D, an R-tree of B's segments) against
// a loop over all of B's segments written here. Body B: a disc of radius
// 1 (deal.II's hyper_ball refined three times: 32 boundary segments, a
// polygon inside the circle). Body A: a ring of radii 1.02 and 1.3 around
// it (hyper_shell, 12 cells refined once, turned by 3 degrees so that no
// node of its inner side lies in the wedge beyond a corner of B's
// polygon); its 24 inner nodes are the candidates. For every node, the
// loop here takes the segment with the smallest distance among those that
// the node projects on (xi in [0, 1]), the first one on a tie. Checks:
// - without a search distance: 24 candidates, each paired with the
//   loop's segment, weights (1 - xi, xi) and gap g0 = the loop's distance,
//   the normal the segment's outward unit normal;
// - with a search distance of 0.022 m: exactly the nodes the loop finds
//   within 0.022 m (some of them: the polygon's corners lie on the circle,
//   its edges' middles 0.995 from the centre), with the same pairs;
// - the same search through a disc shifted into the ring (it overlaps A):
//   a node of A lies inside B and the search stops with a message naming
//   it.

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_tools.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/contact_set.h>

#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "../tests.h"

using namespace dealii;
using namespace impactfe;
using impactfe_tests::check;

namespace
{
  std::unique_ptr<ElasticBody<2>>
  make_body(const std::string &name)
  {
    MaterialParameters material;
    material.youngs_modulus = 1e6;
    material.density        = 1000.;
    material.poissons_ratio = 0.3;
    return std::make_unique<ElasticBody<2>>(name,
                                            material,
                                            DiscretizationParameters(),
                                            1.);
  }

  struct BoundarySegment
  {
    unsigned int v1, v2;
    Point<2>     p1, p2;
    Tensor<1, 2> normal;
  };

  // B's boundary segments with id 0 in cell order, outward normals.
  std::vector<BoundarySegment>
  segments_of(const ElasticBody<2> &body)
  {
    std::vector<BoundarySegment> segments;
    for (const auto &cell : body.triangulation().active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 0)
          {
            BoundarySegment s;
            s.v1                 = cell->face(f)->vertex_index(0);
            s.v2                 = cell->face(f)->vertex_index(1);
            s.p1                 = cell->face(f)->vertex(0);
            s.p2                 = cell->face(f)->vertex(1);
            const Tensor<1, 2> t = s.p2 - s.p1;
            s.normal             = Tensor<1, 2>({-t[1], t[0]}) / t.norm();
            if ((cell->center() - s.p1) * s.normal > 0.)
              s.normal *= -1.;
            segments.push_back(s);
          }
    return segments;
  }

  // The loop: the closest segment that x projects on, its xi and distance.
  struct Pairing
  {
    int    segment  = -1;
    double xi       = 0.;
    double distance = 0.;
  };

  Pairing
  closest_segment(const std::vector<BoundarySegment> &segments,
                  const Point<2>                     &x)
  {
    Pairing best;
    for (unsigned int k = 0; k < segments.size(); ++k)
      {
        const BoundarySegment &s  = segments[k];
        const Tensor<1, 2>     t  = s.p2 - s.p1;
        const double           xi = ((x - s.p1) * t) / t.norm_square();
        if (xi < 0. || xi > 1.)
          continue;
        const double distance = (x - s.p1) * s.normal;
        if (distance < 0.)
          continue;
        if (best.segment < 0 || distance < best.distance)
          best = {static_cast<int>(k), xi, distance};
      }
    return best;
  }

  // Each candidate against the loop; returns the largest deviation.
  double
  compare(const ContactSet                   &contacts,
          const std::vector<BoundarySegment> &segments,
          const std::vector<Pairing>         &expected,
          const std::vector<Point<2>>        &nodes,
          unsigned int                       &mismatched_pairs)
  {
    double worst     = 0.;
    mismatched_pairs = 0;
    for (const ContactCandidate &c : contacts.candidates())
      {
        const Point<2> x(c.position[0], c.position[1]);
        unsigned int   i = 0;
        while (i < nodes.size() && nodes[i].distance(x) > 1e-14)
          ++i;
        if (i == nodes.size() || expected[i].segment < 0)
          {
            ++mismatched_pairs;
            continue;
          }
        const BoundarySegment &s = segments[expected[i].segment];
        if (c.n_vertices_b != 2 || c.vertices_b[0] != s.v1 ||
            c.vertices_b[1] != s.v2)
          {
            ++mismatched_pairs;
            continue;
          }
        worst = std::max({worst,
                          std::abs(c.weights_b[0] - (1. - expected[i].xi)),
                          std::abs(c.weights_b[1] - expected[i].xi),
                          std::abs(c.initial_gap - expected[i].distance),
                          std::abs(c.frame[0][0] - s.normal[0]),
                          std::abs(c.frame[0][1] - s.normal[1])});
      }
    return worst;
  }
} // namespace



int
main()
{
  impactfe_tests::initlog();
  auto ring = make_body("ring");
  GridGenerator::hyper_shell(
    ring->triangulation(), Point<2>(), 1.02, 1.3, 12, true);
  ring->triangulation().refine_global(1);
  GridTools::rotate(3. * numbers::PI / 180., ring->triangulation());
  ring->setup();
  auto disc = make_body("disc");
  GridGenerator::hyper_ball(disc->triangulation());
  disc->triangulation().refine_global(3);
  disc->setup();
  const std::vector<const ElasticBody<2> *> bodies{ring.get(), disc.get()};

  const std::vector<BoundarySegment> segments = segments_of(*disc);
  check(segments.size() == 32, "the disc has 32 boundary segments");
  // the ring's inner nodes (boundary id 0 of hyper_shell)
  std::vector<Point<2>> nodes;
  for (const auto &v : ring->triangulation().get_vertices())
    if (std::abs(v.norm() - 1.02) < 1e-12)
      nodes.push_back(v);
  check(nodes.size() == 24, "the ring's inner side has 24 nodes");
  std::vector<Pairing> expected;
  unsigned int         within = 0;
  for (const Point<2> &x : nodes)
    {
      expected.push_back(closest_segment(segments, x));
      within +=
        expected.back().segment >= 0 && expected.back().distance <= 0.022;
    }
  bool all_project = true;
  for (const Pairing &p : expected)
    all_project = all_project && p.segment >= 0;
  check(all_project, "every inner node of the ring projects on a segment");

  ContactSet   contacts(2);
  unsigned int mismatched = 0;
  check(contacts.add_node_to_segment(bodies, 0, 0, 1, 0) == 24,
        "24 candidates without a search distance");
  double worst = compare(contacts, segments, expected, nodes, mismatched);
  check(mismatched == 0,
        "each node paired with the loop's closest segment",
        std::to_string(mismatched) + " mismatched");
  check(worst < 1e-14,
        "weights, gap and normal equal the loop's",
        std::to_string(worst));

  // a search: only the nodes within its distance; some but not all
  std::vector<Pairing> expected_within = expected;
  for (Pairing &p : expected_within)
    if (p.distance > 0.022)
      p.segment = -1;
  ContactSet         search(2);
  const unsigned int n_found =
    search.add_node_to_segment(bodies, 0, 0, 1, 0, 0., 0.022);
  check(n_found == within && within > 0 && within < 24,
        "a search within 0.022 m finds the loop's nodes within it (" +
          std::to_string(within) + " of 24)");
  worst = compare(search, segments, expected_within, nodes, mismatched);
  check(mismatched == 0 && worst < 1e-14,
        "and pairs them as the loop does",
        std::to_string(worst));

  // a disc moved into the ring: a node of the ring lies inside it
  auto shifted = make_body("shifted disc");
  GridGenerator::hyper_ball(shifted->triangulation(), Point<2>(0.1, 0.));
  shifted->triangulation().refine_global(3);
  shifted->setup();
  try
    {
      ContactSet overlap(2);
      overlap.add_node_to_segment<2>(
        {ring.get(), shifted.get()}, 0, 0, 1, 0, 0., 0.05);
      check(false, "a search through overlapping bodies stops");
    }
  catch (const std::exception &e)
    {
      const std::string message = impactfe_tests::one_line(e);
      check(message.find("'ring'") != std::string::npos &&
              message.find("lies inside body 'shifted disc'") !=
                std::string::npos,
            "a search through overlapping bodies stops, naming the node",
            message);
    }

  // A search during a run (max_penetration = 1e-3 m, distance 0.05 m)
  // against the two sides of the reflex corner of an L (deal.II's hyper_L,
  // [-1, 1]^2 without (0, 1]^2; id 5 on the sides x = 0, y > 0 and y = 0,
  // x > 0). A square [-1e-4, 0.1]^2: its corners (0.1, -1e-4) and
  // (-1e-4, 0.1) sank 1e-4 into one side each (paired at g0 = -1e-4);
  // (-1e-4, -1e-4) sank into the corner, past the end of both sides
  // (skipped); (0.1, 0.1) is 0.1 from both (skipped). The same square
  // 0.01 lower has a corner 0.01 deep behind the side y = 0: an overlap.
  auto ell = make_body("L");
  GridGenerator::hyper_L(ell->triangulation());
  ell->triangulation().refine_global(2);
  for (const auto &cell : ell->triangulation().active_cell_iterators())
    for (const unsigned int f : cell->face_indices())
      if (cell->face(f)->at_boundary())
        {
          const Point<2> c = cell->face(f)->center();
          if ((c[0] > 0. && std::abs(c[1]) < 1e-12) ||
              (c[1] > 0. && std::abs(c[0]) < 1e-12))
            cell->face(f)->set_boundary_id(5);
        }
  ell->setup();
  const auto square = [&](const double low) {
    auto body = make_body("square");
    GridGenerator::hyper_rectangle(body->triangulation(),
                                   Point<2>(-1e-4, low),
                                   Point<2>(0.1, low + 0.1 + 1e-4));
    body->setup();
    return body;
  };
  auto               sunk = square(-1e-4);
  ContactSet         run_search(2);
  const unsigned int n_sunk = run_search.add_node_to_segment<2>(
    {sunk.get(), ell.get()}, 0, 0, 1, 5, 0., 0.05, 1e-3);
  double worst_gap = 0.;
  for (const ContactCandidate &c : run_search.candidates())
    worst_gap = std::max(worst_gap, std::abs(c.initial_gap + 1e-4));
  check(n_sunk == 2 && worst_gap < 1e-15,
        "a run's search pairs the two nodes sunk 1e-4 m into a side, at "
        "g0 = -1e-4 m, and skips the one in the reflex corner",
        std::to_string(n_sunk) + " candidates, gap error " +
          std::to_string(worst_gap));
  auto deep = square(-0.01);
  try
    {
      ContactSet deep_search(2);
      deep_search.add_node_to_segment<2>(
        {deep.get(), ell.get()}, 0, 0, 1, 5, 0., 0.05, 1e-3);
      check(false, "a node 0.01 m inside the L stops a run's search");
    }
  catch (const std::exception &e)
    {
      const std::string message = impactfe_tests::one_line(e);
      check(message.find("lies inside body 'L': the bodies overlap by more "
                         "than 0.001 m") != std::string::npos,
            "a node 0.01 m inside the L stops a run's search, naming it",
            message);
    }
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
