#include <deal.II/base/bounding_box.h>
#include <deal.II/base/exceptions.h>

#include <deal.II/numerics/rtree.h>

#include <impactfe/contact/contact_set.h>
#include <impactfe/utilities/program.h>

#include <deal.II/boost_adaptors/bounding_box.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <sstream>

namespace impactfe
{
  ContactSet::ContactSet(const unsigned int n_directions)
    : directions(n_directions)
  {
    AssertThrow(n_directions >= 1 && n_directions <= 3,
                ExcMessage("A contact set has 1, 2 or 3 local directions."));
  }

  unsigned int
  ContactSet::n_directions() const
  {
    return directions;
  }

  unsigned int
  ContactSet::n_candidates() const
  {
    return candidate_list.size();
  }

  unsigned int
  ContactSet::n_columns() const
  {
    return candidate_list.size() * directions;
  }

  const ContactCandidate &
  ContactSet::candidate(const unsigned int c) const
  {
    return candidate_list[c];
  }

  const std::vector<ContactCandidate> &
  ContactSet::candidates() const
  {
    return candidate_list;
  }



  void
  ContactSet::refer_to_reference_configuration(
    const std::function<std::array<double, 3>(unsigned int, unsigned int)>
      &displacement)
  {
    for (ContactCandidate &c : candidate_list)
      {
        // u_A - sum_k w_k u_Bk (an obstacle does not move)
        std::array<double, 3> relative = displacement(c.body_a, c.vertex_a);
        for (unsigned int d = 0; d < 3; ++d)
          c.position[d] -= relative[d];
        for (unsigned int k = 0; k < c.n_vertices_b; ++k)
          {
            const std::array<double, 3> u_b =
              displacement(c.body_b, c.vertices_b[k]);
            for (unsigned int d = 0; d < 3; ++d)
              relative[d] -= c.weights_b[k] * u_b[d];
          }
        for (unsigned int d = 0; d < 3; ++d)
          c.initial_gap -= c.frame[0][d] * relative[d];
        // the extent holds the slide from the contact point found here
        for (unsigned int k = 1; k < 3; ++k)
          for (unsigned int d = 0; d < 3; ++d)
            for (double &bound : c.tangential_extent[k - 1])
              bound += c.frame[k][d] * relative[d];
      }
  }



  namespace
  {
    // Vertices of a body on the boundary with the given id.
    template <int dim>
    std::set<unsigned int>
    boundary_vertices(const ElasticBody<dim> &body, const types::boundary_id id)
    {
      std::set<unsigned int> vertices;
      for (const auto &cell : body.triangulation().active_cell_iterators())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() &&
              cell->face(f)->boundary_id() == id)
            for (const unsigned int v : cell->face(f)->vertex_indices())
              vertices.insert(cell->face(f)->vertex_index(v));
      return vertices;
    }

    template <int dim>
    Point<dim>
    vertex_position(const ElasticBody<dim> &body, const unsigned int vertex)
    {
      return body.triangulation().get_vertices()[vertex];
    }

    // A contact search found node @p x of body @p A behind a side of body
    // @p B: if it lies inside B, the bodies overlap, which the search must
    // not hide by leaving the node out.
    template <int dim>
    void
    check_not_inside(const ElasticBody<dim> &A,
                     const ElasticBody<dim> &B,
                     const Point<dim>       &x,
                     const std::string      &how = "at t = 0")
    {
      // most nodes behind a side lie outside the other body's box
      if (!BoundingBox<dim>(B.triangulation().get_vertices()).point_inside(x))
        return;
      for (const auto &cell : B.triangulation().active_cell_iterators())
        if (cell->point_inside(x))
          {
            std::ostringstream where;
            for (unsigned int d = 0; d < dim; ++d)
              where << (d == 0 ? "(" : ", ") << x[d];
            AssertThrow(false,
                        ExcMessage("Contact search: the node of body '" +
                                   A.name() + "' at " + where.str() +
                                   ") lies inside body '" + B.name() +
                                   "': the bodies overlap " + how + "."));
          }
    }

    // Whether a point lies inside body B, from B's cells in an R-tree of
    // their boxes. A search during a run (max_penetration >= 0) stops at a
    // node that nothing pairs and that lies inside B farther than
    // max_penetration from every side of the searched boundary, however
    // far from them: the bodies overlap. Used only by such searches, and
    // made at the first point in B's box (most searches never ask).
    template <int dim>
    class CellsOfBody
    {
    public:
      CellsOfBody(const ElasticBody<dim> &B, const bool needed)
        : body(B)
        , needed(needed)
      {}

      // Inside a cell of B (false if not needed).
      bool
      contains(const Point<dim> &x) const
      {
        if (!needed)
          return false;
        if (!box)
          box.emplace(body.triangulation().get_vertices());
        if (!box->point_inside(x))
          return false;
        if (cells.empty())
          {
            std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
            for (const auto &cell :
                 body.triangulation().active_cell_iterators())
              {
                boxes.emplace_back(cell->bounding_box(), cells.size());
                cells.push_back(cell);
              }
            tree = pack_rtree(boxes);
          }
        std::vector<std::pair<BoundingBox<dim>, unsigned int>> hits;
        tree.query(boost::geometry::index::intersects(
                     BoundingBox<dim>(std::make_pair(x, x))),
                   std::back_inserter(hits));
        for (const auto &hit : hits)
          if (cells[hit.second]->point_inside(x))
            return true;
        return false;
      }

    private:
      const ElasticBody<dim>                 &body;
      const bool                              needed;
      mutable std::optional<BoundingBox<dim>> box;
      mutable std::vector<typename Triangulation<dim>::active_cell_iterator>
                                                               cells;
      mutable RTree<std::pair<BoundingBox<dim>, unsigned int>> tree;
    };

    // What a search (a finite max_distance) pairs: a node behind a side by
    // at most `sunk` (1e-6 max_distance at t = 0, max_penetration during a
    // run), and how an overlap is reported.
    struct SearchRules
    {
      SearchRules(const double max_distance, const double max_penetration)
        : searching(max_distance < std::numeric_limits<double>::max())
        , sunk(max_penetration >= 0. ? max_penetration : 1e-6 * max_distance)
        , overlap(max_penetration >= 0. ?
                    "by more than " + format_number(max_penetration) + " m" :
                    "at t = 0")
      {}
      const bool        searching;
      const double      sunk;
      const std::string overlap;
    };

    // The checks of every candidate set between two bodies, and the nodes
    // of side A (@p kind names the set in the messages).
    template <int dim>
    std::set<unsigned int>
    side_a_vertices(const std::vector<const ElasticBody<dim> *> &bodies,
                    const unsigned int                           body_a,
                    const types::boundary_id                     boundary_a,
                    const unsigned int                           body_b,
                    const double       friction_coefficient,
                    const std::string &kind,
                    const bool         searching = false)
    {
      AssertThrow(
        body_a < bodies.size() && body_b < bodies.size() && body_a != body_b,
        ExcMessage("Contact: " + kind + " needs two distinct bodies."));
      AssertThrow(friction_coefficient >= 0.,
                  ExcMessage(
                    "Contact: the friction coefficient must be >= 0."));
      const auto vertices = boundary_vertices(*bodies[body_a], boundary_a);
      AssertThrow(searching || !vertices.empty(),
                  ExcMessage("Contact: body '" + bodies[body_a]->name() +
                             "' has no vertex on boundary id " +
                             std::to_string(boundary_a) + "."));
      return vertices;
    }
  } // namespace



  // @sect3{Local frames}
  // The normal is direction 0. In 2D the tangent is the normal turned by
  // +90 degrees; in 3D two orthonormal tangents complete a right-handed
  // frame.
  template <int dim>
  std::array<std::array<double, 3>, 3>
  contact_frame(const Tensor<1, dim> &normal)
  {
    const double norm = normal.norm();
    AssertThrow(norm > 0., ExcMessage("A contact normal must not be zero."));
    std::array<std::array<double, 3>, 3> frame{};
    std::array<double, 3>                n{{0., 0., 0.}};
    for (unsigned int d = 0; d < dim; ++d)
      n[d] = normal[d] / norm;
    frame[0] = n;
    if (dim == 2)
      frame[1] = {{-n[1], n[0], 0.}};
    if (dim == 3)
      {
        // t1: the unit vector orthogonal to n built from the axis least
        // aligned with n; t2 = n x t1.
        std::array<double, 3> a{{0., 0., 0.}};
        const unsigned int    axis = (std::abs(n[0]) <= std::abs(n[1]) &&
                                   std::abs(n[0]) <= std::abs(n[2])) ?
                                       0 :
                                     (std::abs(n[1]) <= std::abs(n[2])) ? 1 :
                                                                          2;
        a[axis]                    = 1.;
        std::array<double, 3> t1{{a[1] * n[2] - a[2] * n[1],
                                  a[2] * n[0] - a[0] * n[2],
                                  a[0] * n[1] - a[1] * n[0]}};
        const double          l =
          std::sqrt(t1[0] * t1[0] + t1[1] * t1[1] + t1[2] * t1[2]);
        for (double &x : t1)
          x /= l;
        frame[1] = t1;
        frame[2] = {{n[1] * t1[2] - n[2] * t1[1],
                     n[2] * t1[0] - n[0] * t1[2],
                     n[0] * t1[1] - n[1] * t1[0]}};
      }
    return frame;
  }



  template <int dim>
  void
  ContactSet::set_frame(ContactCandidate     &candidate,
                        const Tensor<1, dim> &normal) const
  {
    candidate.frame = contact_frame(normal);
  }



  template <int dim>
  unsigned int
  ContactSet::add_node_to_plane(
    const std::vector<const ElasticBody<dim> *> &bodies,
    const unsigned int                           body_index,
    const types::boundary_id                     boundary_id,
    const Point<dim>                            &plane_point,
    const Tensor<1, dim>                        &plane_normal,
    const double                                 friction_coefficient)
  {
    return add_node_to_obstacle(bodies,
                                body_index,
                                boundary_id,
                                PlaneObstacle<dim>(plane_point, plane_normal),
                                friction_coefficient);
  }



  template <int dim>
  unsigned int
  ContactSet::add_node_to_obstacle(
    const std::vector<const ElasticBody<dim> *> &bodies,
    const unsigned int                           body_index,
    const types::boundary_id                     boundary_id,
    const RigidObstacle<dim>                    &obstacle,
    const double                                 friction_coefficient)
  {
    AssertThrow(body_index < bodies.size(),
                ExcMessage("Contact: body index out of range."));
    AssertThrow(friction_coefficient >= 0.,
                ExcMessage("Contact: the friction coefficient must be >= 0."));
    const auto &body     = *bodies[body_index];
    const auto  vertices = boundary_vertices(body, boundary_id);
    AssertThrow(!vertices.empty(),
                ExcMessage("Contact: body '" + body.name() +
                           "' has no vertex on boundary id " +
                           std::to_string(boundary_id) +
                           ", so the contact boundary is empty."));
    for (const unsigned int v : vertices)
      {
        ContactCandidate candidate;
        candidate.body_a   = body_index;
        candidate.vertex_a = v;
        const Point<dim> x = vertex_position(body, v);
        add_candidate(candidate,
                      x,
                      obstacle.normal(x),
                      obstacle.signed_distance(x),
                      friction_coefficient);
      }
    return vertices.size();
  }



  template <int dim>
  void
  ContactSet::add_candidate(ContactCandidate      candidate,
                            const Point<dim>     &x,
                            const Tensor<1, dim> &normal,
                            const double          initial_gap,
                            const double          friction_coefficient)
  {
    for (unsigned int d = 0; d < dim; ++d)
      candidate.position[d] = x[d];
    set_frame(candidate, normal);
    candidate.initial_gap          = initial_gap;
    candidate.friction_coefficient = friction_coefficient;
    candidate_list.push_back(candidate);
  }



  // The box's corners bound every point of side B's boundary, so their
  // projections on a tangent bound the slide that keeps side A above it.
  template <int dim>
  void
  ContactSet::set_tangential_extent(const ElasticBody<dim> &B,
                                    const BoundingBox<dim> &box_of_b)
  {
    ContactCandidate &c = candidate_list.back();
    Point<dim>        contact_point;
    for (unsigned int k = 0; k < c.n_vertices_b; ++k)
      contact_point +=
        c.weights_b[k] * (vertex_position(B, c.vertices_b[k]) - Point<dim>());
    for (unsigned int k = 1; k < dim; ++k)
      {
        auto &range = c.tangential_extent[k - 1];
        range       = {{std::numeric_limits<double>::max(),
                        std::numeric_limits<double>::lowest()}};
        for (unsigned int corner = 0; corner < (1u << dim); ++corner)
          {
            double s = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              s += c.frame[k][d] * (((corner >> d) & 1u) ?
                                      box_of_b.get_boundary_points().second[d] :
                                      box_of_b.get_boundary_points().first[d]) -
                   c.frame[k][d] * contact_point[d];
            range[0] = std::min(range[0], s);
            range[1] = std::max(range[1], s);
          }
      }
  }



  namespace
  {
    // The bounding box of a body's vertices on a boundary id.
    template <int dim>
    BoundingBox<dim>
    boundary_box(const ElasticBody<dim> &body, const types::boundary_id id)
    {
      std::vector<Point<dim>> points;
      for (const unsigned int v : boundary_vertices(body, id))
        points.push_back(vertex_position(body, v));
      return points.empty() ? BoundingBox<dim>() : BoundingBox<dim>(points);
    }
  } // namespace



  // @sect3{Node-to-segment}
  // Each slave node is projected on the master segments; the nearest
  // segment whose parameter xi lies in [0, 1] (up to a small tolerance,
  // then clamped) wins. The outward normal of the master segment is taken
  // away from its cell's centre.
  template <int dim>
  unsigned int
  ContactSet::add_node_to_segment(
    const std::vector<const ElasticBody<dim> *> &bodies,
    const unsigned int                           body_a,
    const types::boundary_id                     boundary_a,
    const unsigned int                           body_b,
    const types::boundary_id                     boundary_b,
    const double                                 friction_coefficient,
    const double                                 max_distance,
    const double                                 max_penetration)
  {
    AssertThrow(dim == 2,
                ExcMessage("Contact: node-to-segment candidates are "
                           "implemented in 2D only."));
    const SearchRules      rules(max_distance, max_penetration);
    const bool             searching  = rules.searching;
    const auto             vertices_a = side_a_vertices(bodies,
                                            body_a,
                                            boundary_a,
                                            body_b,
                                            friction_coefficient,
                                            "node-to-segment",
                                            searching);
    const auto            &A          = *bodies[body_a];
    const auto            &B          = *bodies[body_b];
    const BoundingBox<dim> box_of_b   = boundary_box(B, boundary_b);

    struct Segment
    {
      unsigned int   v1, v2;
      Point<dim>     p1, p2;
      Tensor<1, dim> normal;
    };
    std::vector<Segment>                                   segments;
    std::vector<std::pair<BoundingBox<dim>, unsigned int>> boxes;
    for (const auto &cell : B.triangulation().active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary() &&
            cell->face(f)->boundary_id() == boundary_b)
          {
            Segment s;
            s.v1                   = cell->face(f)->vertex_index(0);
            s.v2                   = cell->face(f)->vertex_index(1);
            s.p1                   = vertex_position(B, s.v1);
            s.p2                   = vertex_position(B, s.v2);
            const Tensor<1, dim> t = s.p2 - s.p1;
            if constexpr (dim == 2)
              s.normal = Tensor<1, dim>({-t[1], t[0]}) / t.norm();
            if ((cell->center() - s.p1) * s.normal > 0.)
              s.normal *= -1.;
            boxes.emplace_back(BoundingBox<dim>(
                                 std::vector<Point<dim>>{{s.p1, s.p2}}),
                               segments.size());
            segments.push_back(s);
          }
    AssertThrow(searching || !segments.empty(),
                ExcMessage("Contact: body '" + B.name() +
                           "' has no boundary segment with id " +
                           std::to_string(boundary_b) + "."));
    if (segments.empty())
      return 0;
    // The segments' boxes in an R-tree: a node is compared with the
    // segments whose boxes come within a distance of it, not with all of
    // them (the search was O(nodes x segments): 0.29 s per search with
    // 8 000 nodes against 16 000 segments).
    const auto tree = pack_rtree(boxes);
    std::vector<std::pair<BoundingBox<dim>, unsigned int>> near;
    const auto segments_within = [&](const Point<dim> &x, const double r) {
      Point<dim> lower = x, upper = x;
      for (unsigned int d = 0; d < dim; ++d)
        {
          lower[d] -= r;
          upper[d] += r;
        }
      near.clear();
      tree.query(boost::geometry::index::intersects(
                   BoundingBox<dim>(std::make_pair(lower, upper))),
                 std::back_inserter(near));
      // the order of the loop over all segments, so that ties go the same
      std::sort(near.begin(), near.end(), [](const auto &a, const auto &b) {
        return a.second < b.second;
      });
    };
    const CellsOfBody<dim> cells_of_b(B, searching && max_penetration >= 0.);
    // unpaired x inside B, farther than max_penetration from every segment
    const auto sunk_deeper = [&](const Point<dim> &x) {
      if (!cells_of_b.contains(x))
        return false;
      segments_within(x, max_penetration);
      for (const auto &hit : near)
        {
          const Segment       &s = segments[hit.second];
          const Tensor<1, dim> t = s.p2 - s.p1;
          const double         xi =
            std::clamp(((x - s.p1) * t) / t.norm_square(), 0., 1.);
          if (x.distance(s.p1 + xi * t) <= max_penetration)
            return false;
        }
      return true;
    };

    unsigned int n_added = 0;
    for (const unsigned int va : vertices_a)
      {
        const Point<dim> x       = vertex_position(A, va);
        const Segment   *best    = nullptr;
        double           best_xi = 0., best_distance = 0.;
        bool             behind = false;
        // Every segment closer than r has its box within r of x. A search
        // needs those within its distance; a pairing without one the
        // closest at any distance: r is the distance to the farther end of
        // the segment whose box is nearest, which bounds the closest one's.
        double r = max_distance;
        if (!searching)
          {
            std::vector<std::pair<BoundingBox<dim>, unsigned int>> nearest;
            tree.query(boost::geometry::index::nearest(x, 1),
                       std::back_inserter(nearest));
            const Segment &s = segments[nearest.front().second];
            r                = std::max(x.distance(s.p1), x.distance(s.p2));
          }
        segments_within(x, r);
        const auto try_segment = [&](const Segment &s) {
          const Tensor<1, dim> t  = s.p2 - s.p1;
          const double         xi = ((x - s.p1) * t) / t.norm_square();
          if (xi < -1e-8 || xi > 1. + 1e-8)
            return;
          const double signed_distance = (x - s.p1) * s.normal;
          // a search pairs a node only with the outer side of a segment:
          // the bodies do not overlap at the reference configuration
          // (in a search during the run, max_penetration >= 0, a node
          // deeper than that is checked; see sunk_deeper too)
          if (searching && signed_distance < -rules.sunk)
            {
              behind = behind || -signed_distance <= max_distance ||
                       max_penetration >= 0.;
              return;
            }
          const double distance = std::abs(signed_distance);
          if (best == nullptr || distance < best_distance)
            {
              best          = &s;
              best_xi       = std::clamp(xi, 0., 1.);
              best_distance = distance;
            }
        };
        for (const auto &hit : near)
          try_segment(segments[hit.second]);
        // No segment within r that x projects on (x beyond a corner of
        // the nearest one), or only farther ones, which a segment outside
        // the boxes might beat: all of them, as before.
        if (!searching && (best == nullptr || best_distance > r))
          {
            best   = nullptr;
            behind = false;
            for (const Segment &s : segments)
              try_segment(s);
          }
        const bool paired =
          best != nullptr && (!searching || best_distance <= max_distance);
        // Behind a side within the search distance, or (a run's search)
        // unpaired and inside B deeper than max_penetration: an overlap if
        // x is inside B. A node that sank into B by less, beyond the end
        // of the sides it projects on (a reflex corner), is skipped.
        if (behind || (!paired && sunk_deeper(x)))
          check_not_inside(A, B, x, rules.overlap);
        if (searching && !paired)
          continue;
        AssertThrow(best != nullptr,
                    ExcMessage(
                      "Contact: the node of body '" + A.name() +
                      "' at boundary id " + std::to_string(boundary_a) +
                      " projects on no segment of body '" + B.name() +
                      "' (boundary id " + std::to_string(boundary_b) + ")."));
        ContactCandidate candidate;
        candidate.body_a       = body_a;
        candidate.vertex_a     = va;
        candidate.body_b       = body_b;
        candidate.n_vertices_b = 2;
        candidate.vertices_b   = {{best->v1,
                                   best->v2,
                                   numbers::invalid_unsigned_int,
                                   numbers::invalid_unsigned_int}};
        candidate.weights_b    = {{1. - best_xi, best_xi, 0., 0.}};
        const Point<dim> projection =
          best->p1 + best_xi * (best->p2 - best->p1);
        add_candidate(candidate,
                      x,
                      best->normal,
                      (x - projection) * best->normal,
                      friction_coefficient);
        set_tangential_extent(B, box_of_b);
        ++n_added;
      }
    return n_added;
  }



  // @sect3{Node-to-face candidates (3D)}
  //
  // B's faces with the boundary id, their vertices in deal.II's face order
  // (bilinear shape functions N0 = (1 - xi)(1 - eta), N1 = xi (1 - eta),
  // N2 = (1 - xi) eta, N3 = xi eta), an R-tree of their bounding boxes
  // widened by the face's size, and for each node of A the closest point
  // on the faces the tree returns.
  template <int dim>
  unsigned int
  ContactSet::add_node_to_face(
    const std::vector<const ElasticBody<dim> *> &bodies,
    const unsigned int                           body_a,
    const types::boundary_id                     boundary_a,
    const unsigned int                           body_b,
    const types::boundary_id                     boundary_b,
    const double                                 friction_coefficient,
    const double                                 max_distance,
    const double                                 max_penetration)
  {
    AssertThrow(dim == 3,
                ExcMessage("Contact: node-to-face candidates are 3D only "
                           "(node-to-segment in 2D)."));
    const SearchRules      rules(max_distance, max_penetration);
    const bool             searching  = rules.searching;
    const auto             vertices_a = side_a_vertices(bodies,
                                            body_a,
                                            boundary_a,
                                            body_b,
                                            friction_coefficient,
                                            "node-to-face",
                                            searching);
    unsigned int           n_added    = 0;
    const auto            &A          = *bodies[body_a];
    const auto            &B          = *bodies[body_b];
    const BoundingBox<dim> box_of_b   = boundary_box(B, boundary_b);
    if constexpr (dim == 3)
      {
        struct Face
        {
          std::array<unsigned int, 4> v;
          std::array<Point<3>, 4>     p;
        };
        std::vector<Face>                                    faces;
        std::map<unsigned int, Tensor<1, 3>>                 nodal_normals;
        std::vector<std::pair<BoundingBox<3>, unsigned int>> boxes;
        for (const auto &cell : B.triangulation().active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() == boundary_b)
              {
                Face face;
                for (unsigned int k = 0; k < 4; ++k)
                  {
                    face.v[k] = cell->face(f)->vertex_index(k);
                    face.p[k] = vertex_position(B, face.v[k]);
                  }
                // Outward (away from B's cell): twice the area times the
                // unit normal for a flat face.
                Tensor<1, 3> normal = cross_product_3d(face.p[3] - face.p[0],
                                                       face.p[2] - face.p[1]);
                if ((cell->center() - face.p[0]) * normal > 0.)
                  normal *= -1.;
                for (const unsigned int v : face.v)
                  nodal_normals[v] += normal;
                BoundingBox<3> box(
                  std::vector<Point<3>>(face.p.begin(), face.p.end()));
                // a search reaches max_distance within the boxes
                box.extend(std::max(box.side_length(0) + box.side_length(1) +
                                      box.side_length(2),
                                    searching ? max_distance : 0.));
                boxes.emplace_back(box, faces.size());
                faces.push_back(face);
              }
        AssertThrow(searching || !faces.empty(),
                    ExcMessage("Contact: body '" + B.name() +
                               "' has no boundary face with id " +
                               std::to_string(boundary_b) + "."));
        if (faces.empty())
          return 0;
        const auto tree = pack_rtree(boxes);

        // The closest point of a face to x: Newton's method on (xi, eta)
        // for (y - x) . dy/dxi = (y - x) . dy/deta = 0. Its weights, or
        // nothing if Newton's method does not converge to a minimum
        // (det > 0) inside the face.
        const auto project =
          [](const Face     &face,
             const Point<3> &x) -> std::optional<std::array<double, 4>> {
          double             xi = 0.5, eta = 0.5;
          bool               converged = false;
          const Tensor<1, 3> y_xi_eta =
            face.p[0] - face.p[1] - face.p[2] + face.p[3];
          for (unsigned int it = 0; it < 30 && !converged; ++it)
            {
              const Point<3> y = face.p[0] + xi * (face.p[1] - face.p[0]) +
                                 eta * (face.p[2] - face.p[0]) +
                                 xi * eta * y_xi_eta;
              const Tensor<1, 3> y_xi  = face.p[1] - face.p[0] + eta * y_xi_eta;
              const Tensor<1, 3> y_eta = face.p[2] - face.p[0] + xi * y_xi_eta;
              const Tensor<1, 3> r     = y - x;
              const double       g1 = r * y_xi, g2 = r * y_eta;
              const double a11 = y_xi * y_xi, a12 = y_xi * y_eta + r * y_xi_eta,
                           a22 = y_eta * y_eta;
              const double det = a11 * a22 - a12 * a12;
              if (!(det > 0.))
                return std::nullopt;
              const double d_xi  = (a22 * g1 - a12 * g2) / det,
                           d_eta = (a11 * g2 - a12 * g1) / det;
              xi -= d_xi;
              eta -= d_eta;
              converged = std::abs(d_xi) + std::abs(d_eta) < 1e-14;
            }
          if (!converged || !std::isfinite(xi) || !std::isfinite(eta) ||
              xi < -1e-8 || xi > 1. + 1e-8 || eta < -1e-8 || eta > 1. + 1e-8)
            return std::nullopt;
          // On an edge or a corner: exactly there.
          const auto snap = [](const double t) {
            return t < 1e-8 ? 0. : (t > 1. - 1e-8 ? 1. : t);
          };
          xi  = snap(xi);
          eta = snap(eta);
          return std::array<double, 4>{{(1. - xi) * (1. - eta),
                                        xi * (1. - eta),
                                        (1. - xi) * eta,
                                        xi * eta}};
        };

        // The point of a face with bilinear weights w, and there the
        // interpolated nodal normal (not normalised).
        const auto interpolate =
          [&nodal_normals](const Face &face, const std::array<double, 4> &w) {
            std::pair<Point<3>, Tensor<1, 3>> point_and_normal;
            for (unsigned int k = 0; k < 4; ++k)
              {
                const Tensor<1, 3> &nodal = nodal_normals[face.v[k]];
                if (nodal.norm() > 0.)
                  point_and_normal.second += w[k] * nodal / nodal.norm();
                point_and_normal.first += w[k] * Tensor<1, 3>(face.p[k]);
              }
            return point_and_normal;
          };

        // The closest point of the face's edges (p0 p1, p2 p3, p0 p2,
        // p1 p3, straight on a bilinear face) to x, as bilinear weights.
        const auto closest_edge_point = [](const Face     &face,
                                           const Point<3> &x) {
          constexpr unsigned int edges[4][2] = {{0, 1}, {2, 3}, {0, 2}, {1, 3}};
          std::array<double, 4>  best_w{};
          double                 best_d = std::numeric_limits<double>::max();
          for (const auto &e : edges)
            {
              const Tensor<1, 3> ab = face.p[e[1]] - face.p[e[0]];
              const double       t =
                std::clamp((x - face.p[e[0]]) * ab / (ab * ab), 0., 1.);
              const double d = x.distance(face.p[e[0]] + t * ab);
              if (d < best_d)
                {
                  best_d       = d;
                  best_w       = {{0., 0., 0., 0.}};
                  best_w[e[0]] = 1. - t;
                  best_w[e[1]] = t;
                }
            }
          return best_w;
        };

        // unpaired x inside B, farther than max_penetration from every
        // face (as in 2D)
        const CellsOfBody<3> cells_of_b(B, searching && max_penetration >= 0.);
        const auto           sunk_deeper = [&](const Point<3> &x) {
          if (!cells_of_b.contains(x))
            return false;
          std::vector<std::pair<BoundingBox<3>, unsigned int>> close;
          tree.query(
            boost::geometry::index::intersects(BoundingBox<3>(std::make_pair(
              x +
                Point<3>(-max_penetration, -max_penetration, -max_penetration),
              x +
                Point<3>(max_penetration, max_penetration, max_penetration)))),
            std::back_inserter(close));
          for (const auto &hit : close)
            {
              const Face &face = faces[hit.second];
              auto        w    = project(face, x);
              if (!w)
                w = closest_edge_point(face, x);
              if (x.distance(interpolate(face, *w).first) <= max_penetration)
                return false;
            }
          return true;
        };

        for (const unsigned int va : vertices_a)
          {
            const Point<3> x = vertex_position(A, va);
            std::vector<std::pair<BoundingBox<3>, unsigned int>> near;
            tree.query(boost::geometry::index::intersects(
                         BoundingBox<3>(std::make_pair(x, x))),
                       std::back_inserter(near));
            double                best_distance = -1.;
            const Face           *best          = nullptr;
            std::array<double, 4> best_weights{};
            bool                  behind   = false;
            const auto            try_face = [&](const Face &face) {
              auto w = project(face, x);
              // No minimum inside the face: the face's closest point is on
              // its boundary (its four straight edges). Over a convex edge
              // of the master surface, e.g. a ball's, a node at some
              // distance has its closest point there, and no face's
              // interior projection exists. Such a point counts only if the
              // node lies along the surface's interpolated normal there
              // (within 60 degrees), not beside the master surface.
              const bool on_edge = !w;
              if (on_edge)
                w = closest_edge_point(face, x);
              const auto [y, n] = interpolate(face, *w);
              if (on_edge && !((x - y) * n >= 0.5 * n.norm() * x.distance(y)))
                return;
              // a search: only the outer side of the face (as in 2D)
              if (searching && (x - y) * n < -rules.sunk * n.norm())
                {
                  behind = behind || x.distance(y) <= max_distance ||
                           max_penetration >= 0.;
                  return;
                }
              if (best == nullptr || x.distance(y) < best_distance)
                {
                  best          = &face;
                  best_distance = x.distance(y);
                  best_weights  = *w;
                }
            };
            for (const auto &hit : near)
              try_face(faces[hit.second]);
            // Farther than the widened boxes (a large initial gap): all
            // the faces; a search skips the node instead.
            if (best == nullptr && !searching)
              for (const Face &face : faces)
                try_face(face);
            const bool paired =
              best != nullptr && (!searching || best_distance <= max_distance);
            if (behind || (!paired && sunk_deeper(x)))
              check_not_inside(A, B, Point<dim>(x), rules.overlap);
            if (searching && !paired)
              continue;
            AssertThrow(best != nullptr,
                        ExcMessage("Contact: the node of body '" + A.name() +
                                   "' at (" + format_number(x[0]) + ", " +
                                   format_number(x[1]) + ", " +
                                   format_number(x[2]) + ") on boundary id " +
                                   std::to_string(boundary_a) +
                                   " projects on no face of body '" + B.name() +
                                   "' (boundary id " +
                                   std::to_string(boundary_b) + ")."));
            ContactCandidate candidate;
            candidate.body_a       = body_a;
            candidate.vertex_a     = va;
            candidate.body_b       = body_b;
            candidate.n_vertices_b = 4;
            for (unsigned int k = 0; k < 4; ++k)
              {
                candidate.vertices_b[k] = best->v[k];
                candidate.weights_b[k]  = best_weights[k];
                AssertThrow(nodal_normals[best->v[k]].norm() > 0.,
                            ExcMessage("Contact: the faces of body '" +
                                       B.name() + "' with boundary id " +
                                       std::to_string(boundary_b) +
                                       " around a node have opposite "
                                       "normals (a thin part?)."));
              }
            auto [y, normal] = interpolate(*best, best_weights);
            normal /= normal.norm();
            add_candidate(candidate,
                          Point<dim>(x),
                          Tensor<1, dim>(normal),
                          (x - y) * normal,
                          friction_coefficient);
            set_tangential_extent(B, box_of_b);
            ++n_added;
          }
      }
    return n_added;
  }



  template <int dim>
  unsigned int
  ContactSet::add_node_to_node(
    const std::vector<const ElasticBody<dim> *> &bodies,
    const unsigned int                           body_a,
    const types::boundary_id                     boundary_a,
    const unsigned int                           body_b,
    const types::boundary_id                     boundary_b,
    const Tensor<1, dim>                        &normal,
    const double                                 friction_coefficient)
  {
    const auto vertices_a = side_a_vertices(
      bodies, body_a, boundary_a, body_b, friction_coefficient, "node-to-node");
    const auto            &A          = *bodies[body_a];
    const auto            &B          = *bodies[body_b];
    const BoundingBox<dim> box_of_b   = boundary_box(B, boundary_b);
    const auto             vertices_b = boundary_vertices(B, boundary_b);
    AssertThrow(!vertices_b.empty(),
                ExcMessage("Contact: body '" + B.name() +
                           "' has no vertex on boundary id " +
                           std::to_string(boundary_b) + "."));
    const Tensor<1, dim> n = normal / normal.norm();

    // Size scale for the matching tolerance.
    double scale = 0.;
    for (const unsigned int v : vertices_b)
      scale = std::max(scale, vertex_position(B, v).norm());
    const double tolerance = 1e-8 * std::max(scale, 1.);

    for (const unsigned int va : vertices_a)
      {
        const Point<dim> xa      = vertex_position(A, va);
        unsigned int     partner = numbers::invalid_unsigned_int;
        for (const unsigned int vb : vertices_b)
          {
            const Tensor<1, dim> d = xa - vertex_position(B, vb);
            if ((d - (d * n) * n).norm() <= tolerance)
              {
                partner = vb;
                break;
              }
          }
        if (partner == numbers::invalid_unsigned_int)
          {
            std::ostringstream where;
            for (unsigned int d = 0; d < dim; ++d)
              where << (d > 0 ? ", " : "") << xa[d];
            AssertThrow(false,
                        ExcMessage(
                          "Contact: the node at (" + where.str() +
                          ") of body '" + A.name() + "' at boundary id " +
                          std::to_string(boundary_a) +
                          " has no matching node on body '" + B.name() +
                          "'. Node-to-node contact needs matching "
                          "interface meshes."));
          }
        ContactCandidate candidate;
        candidate.body_a        = body_a;
        candidate.vertex_a      = va;
        candidate.body_b        = body_b;
        candidate.n_vertices_b  = 1;
        candidate.vertices_b[0] = partner;
        candidate.weights_b[0]  = 1.;
        add_candidate(candidate,
                      xa,
                      n,
                      (xa - vertex_position(B, partner)) * n,
                      friction_coefficient);
        set_tangential_extent(B, box_of_b);
      }
    return vertices_a.size();
  }



  // @sect3{The H operator}
  // Column (c, k) of H holds +e_k on the DoFs of node A and -e_k on those of
  // node B (split as -w_j e_k over a master segment's or face's nodes, w_j
  // the contact point's weights), e_k being direction k of the candidate's
  // frame.
  template <int dim>
  void
  ContactSet::build_operator(
    const std::vector<const ElasticBody<dim> *> &bodies)
  {
    AssertThrow(directions == 1 || directions == dim,
                ExcMessage("Contact: the number of local directions must be 1 "
                           "(frictionless) or the space dimension."));
    // frame row k . (u_A - sum_j w_j u_Bj) as entries
    const auto frame_row = [&](const ContactCandidate &cand,
                               const unsigned int      k) {
      std::vector<Entry> row;
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double e = cand.frame[k][d];
          if (e == 0.)
            continue;
          row.push_back({cand.body_a,
                         bodies[cand.body_a]->vertex_dof(cand.vertex_a, d),
                         e});
          if (cand.against_rigid_obstacle())
            continue;
          for (unsigned int j = 0; j < cand.n_vertices_b; ++j)
            if (cand.weights_b[j] != 0.)
              row.push_back(
                {cand.body_b,
                 bodies[cand.body_b]->vertex_dof(cand.vertices_b[j], d),
                 -cand.weights_b[j] * e});
        }
      return row;
    };
    columns.assign(n_columns(), {});
    slide_rows.assign(2 * candidate_list.size(), {});
    for (unsigned int c = 0; c < candidate_list.size(); ++c)
      {
        const ContactCandidate &cand = candidate_list[c];
        for (unsigned int k = 0; k < directions; ++k)
          columns[c * directions + k] = frame_row(cand, k);
        if (!cand.against_rigid_obstacle())
          for (unsigned int k = 1; k < dim; ++k)
            slide_rows[2 * c + k - 1] = frame_row(cand, k);
      }
  }



  double
  ContactSet::largest_slide_off(const BlockVector<double> &u) const
  {
    double largest = 0.;
    for (unsigned int c = 0; c < candidate_list.size(); ++c)
      for (unsigned int k = 0; k < 2; ++k)
        if (!slide_rows.empty() && !slide_rows[2 * c + k].empty())
          {
            double slide = 0.;
            for (const Entry &e : slide_rows[2 * c + k])
              slide += e.coefficient * u.block(e.block)(e.dof);
            largest =
              std::max(largest,
                       slide_off_fraction(
                         candidate_list[c].tangential_extent[k], slide));
          }
    return largest;
  }



  double
  ContactSet::column_dot(const unsigned int         column,
                         const BlockVector<double> &v) const
  {
    double sum = 0.;
    for (const Entry &e : columns[column])
      sum += e.coefficient * v.block(e.block)(e.dof);
    return sum;
  }



  void
  ContactSet::add_column(const unsigned int   column,
                         const double         alpha,
                         BlockVector<double> &f) const
  {
    for (const Entry &e : columns[column])
      f.block(e.block)(e.dof) += alpha * e.coefficient;
  }



  void
  ContactSet::gaps(const BlockVector<double> &u, std::vector<double> &g) const
  {
    g.resize(candidate_list.size());
    for (unsigned int c = 0; c < candidate_list.size(); ++c)
      g[c] = candidate_list[c].initial_gap + column_dot(c * directions, u);
  }



  void
  ContactSet::gaps(const BlockVector<double> &u,
                   const double               a,
                   const BlockVector<double> &v,
                   std::vector<double>       &g) const
  {
    g.resize(candidate_list.size());
    for (unsigned int c = 0; c < candidate_list.size(); ++c)
      {
        double sum = 0.;
        for (const Entry &e : columns[c * directions])
          sum += e.coefficient *
                 (u.block(e.block)(e.dof) + a * v.block(e.block)(e.dof));
        g[c] = candidate_list[c].initial_gap + sum;
      }
  }



  void
  ContactSet::normal_velocities(const BlockVector<double> &v,
                                std::vector<double> &normal_velocity) const
  {
    normal_velocity.resize(candidate_list.size());
    for (unsigned int c = 0; c < candidate_list.size(); ++c)
      normal_velocity[c] = column_dot(c * directions, v);
  }



  void
  ContactSet::local_velocities(const BlockVector<double> &v,
                               std::vector<double>       &local_velocity) const
  {
    local_velocity.resize(n_columns());
    for (unsigned int j = 0; j < n_columns(); ++j)
      local_velocity[j] = column_dot(j, v);
  }



  void
  ContactSet::inverse_delassus_diagonal(
    const std::vector<const SparseMatrix<double> *> &A,
    const std::vector<unsigned int>                 &candidates,
    std::vector<double>                             &c) const
  {
    const unsigned int nd = directions;
    c.resize(candidates.size() * nd);
    for (unsigned int i = 0; i < c.size(); ++i)
      {
        const unsigned int cand = candidates[i / nd];
        const auto        &H    = columns[cand * nd + i % nd];
        double             sum  = 0.;
        if (candidate_list[cand].against_rigid_obstacle())
          {
            for (const Entry &e : H)
              for (const Entry &f : H)
                if (e.block == f.block)
                  sum += e.coefficient * A[e.block]->el(e.dof, f.dof) *
                         f.coefficient;
          }
        else
          {
            double inverse = 0.;
            for (const Entry &e : H)
              inverse +=
                e.coefficient * e.coefficient / A[e.block]->diag_element(e.dof);
            sum = inverse > 0. ? 1. / inverse : 0.;
          }
        c[i] = sum;
      }
  }



  std::vector<std::vector<types::global_dof_index>>
  ContactSet::obstacle_contact_dofs(const unsigned int n_blocks) const
  {
    std::vector<std::vector<types::global_dof_index>> dofs(n_blocks);
    for (unsigned int c = 0; c < candidate_list.size(); ++c)
      if (candidate_list[c].against_rigid_obstacle())
        for (unsigned int k = 0; k < directions; ++k)
          for (const Entry &e : columns[c * directions + k])
            dofs[e.block].push_back(e.dof);
    for (auto &block : dofs)
      {
        std::sort(block.begin(), block.end());
        block.erase(std::unique(block.begin(), block.end()), block.end());
      }
    return dofs;
  }



#define IMPACTFE_INSTANTIATE(dim)                                   \
  template std::array<std::array<double, 3>, 3> contact_frame<dim>( \
    const Tensor<1, dim> &);                                        \
  template unsigned int ContactSet::add_node_to_plane<dim>(         \
    const std::vector<const ElasticBody<dim> *> &,                  \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const Point<dim> &,                                             \
    const Tensor<1, dim> &,                                         \
    const double);                                                  \
  template unsigned int ContactSet::add_node_to_obstacle<dim>(      \
    const std::vector<const ElasticBody<dim> *> &,                  \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const RigidObstacle<dim> &,                                     \
    const double);                                                  \
  template unsigned int ContactSet::add_node_to_segment<dim>(       \
    const std::vector<const ElasticBody<dim> *> &,                  \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const double,                                                   \
    const double,                                                   \
    const double);                                                  \
  template unsigned int ContactSet::add_node_to_face<dim>(          \
    const std::vector<const ElasticBody<dim> *> &,                  \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const double,                                                   \
    const double,                                                   \
    const double);                                                  \
  template unsigned int ContactSet::add_node_to_node<dim>(          \
    const std::vector<const ElasticBody<dim> *> &,                  \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const unsigned int,                                             \
    const types::boundary_id,                                       \
    const Tensor<1, dim> &,                                         \
    const double);                                                  \
  template void ContactSet::build_operator<dim>(                    \
    const std::vector<const ElasticBody<dim> *> &);

  IMPACTFE_INSTANTIATE(1)
  IMPACTFE_INSTANTIATE(2)
  IMPACTFE_INSTANTIATE(3)
#undef IMPACTFE_INSTANTIATE
} // namespace impactfe
