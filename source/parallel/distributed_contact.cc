#include <deal.II/base/mpi.h>

#include <impactfe/contact/contact_set.h>
#include <impactfe/parallel/distributed_contact.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>

namespace impactfe
{
  namespace distributed
  {
    // @sect3{The candidates}
    template <int dim>
    void
    DistributedContact<dim>::start_setup(
      const DistributedElasticBody<dim> &body,
      const double                       friction_coefficient)
    {
      AssertThrow(friction_coefficient >= 0.,
                  ExcMessage("Contact: the friction coefficient must be >= "
                             "0."));
      communicator = body.communicator();
      this_rank    = Utilities::MPI::this_mpi_process(communicator);
      mu           = friction_coefficient;
      directions   = mu > 0. ? dim : 1;
      bodies       = 1;
      candidate_list.clear();
    }



    // Each rank lists the nodes of the boundary whose DoFs it owns (a
    // node's DoFs have one owner), as numbers: position, DoFs, rank. The
    // all-gather gives every rank the same list.
    template <int dim>
    std::vector<typename DistributedContact<dim>::Node>
    DistributedContact<dim>::gather_boundary_nodes(
      const DistributedElasticBody<dim> &body,
      const types::boundary_id           boundary_id,
      std::vector<Point<dim>>           &positions) const
    {
      const IndexSet                   &owned = body.locally_owned_dofs();
      std::set<types::global_dof_index> seen;
      std::vector<double>               mine;
      // ghost cells too: a node this rank owns may lie on a boundary face
      // of a neighbour's cell only (meshes read from files)
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == boundary_id)
              for (const unsigned int v : face->vertex_indices())
                {
                  const types::global_dof_index first =
                    face->vertex_dof_index(v, 0);
                  if (!owned.is_element(first) || !seen.insert(first).second)
                    continue;
                  const Point<dim> x = face->vertex(v);
                  for (unsigned int d = 0; d < dim; ++d)
                    mine.push_back(x[d]);
                  for (unsigned int d = 0; d < dim; ++d)
                    mine.push_back(
                      static_cast<double>(face->vertex_dof_index(v, d)));
                  mine.push_back(this_rank);
                }
      const std::vector<std::vector<double>> all =
        Utilities::MPI::all_gather(communicator, mine);

      std::vector<Node> nodes;
      positions.clear();
      const unsigned int record = 2 * dim + 1;
      for (const std::vector<double> &list : all)
        for (std::size_t i = 0; i + record <= list.size(); i += record)
          {
            Node       node;
            Point<dim> x;
            for (unsigned int d = 0; d < dim; ++d)
              {
                x[d] = list[i + d];
                node.dofs[d] =
                  static_cast<types::global_dof_index>(list[i + dim + d]);
              }
            node.owner = static_cast<unsigned int>(list[i + 2 * dim]);
            nodes.push_back(node);
            positions.push_back(x);
          }
      return nodes;
    }



    template <int dim>
    void
    DistributedContact<dim>::finish_setup(const std::string &where)
    {
      AssertThrow(!candidate_list.empty(),
                  ExcMessage("Contact: " + where +
                             ", so the contact boundary is empty."));
      // stable: a node may be side A of two candidates (an obstacle and
      // another body), kept in the given order
      std::stable_sort(candidate_list.begin(),
                       candidate_list.end(),
                       [](const Candidate &a, const Candidate &b) {
                         for (unsigned int d = 0; d < dim; ++d)
                           if (a.position[d] != b.position[d])
                             return a.position[d] < b.position[d];
                         return false;
                       });
    }



    template <int dim>
    void
    DistributedContact<dim>::setup(const DistributedElasticBody<dim> &body,
                                   const types::boundary_id  boundary_id,
                                   const RigidObstacle<dim> &obstacle,
                                   const double friction_coefficient)
    {
      start_setup(body, friction_coefficient);
      std::vector<Point<dim>> positions;
      const std::vector<Node> nodes =
        gather_boundary_nodes(body, boundary_id, positions);
      for (unsigned int i = 0; i < nodes.size(); ++i)
        {
          Candidate c;
          c.position             = positions[i];
          c.nodes[0]             = nodes[i];
          c.frame                = contact_frame(obstacle.normal(c.position));
          c.initial_gap          = obstacle.signed_distance(c.position);
          c.friction_coefficient = friction_coefficient;
          candidate_list.push_back(c);
        }
      finish_setup("the body has no vertex on boundary id " +
                   std::to_string(boundary_id));
    }



    // Each rank lists the needed vertices whose DoFs it owns (vertex, DoFs,
    // rank); the all-gather gives every rank the same map.
    template <int dim>
    std::map<unsigned int, typename DistributedContact<dim>::Node>
    DistributedContact<dim>::gather_vertex_nodes(
      const DistributedElasticBody<dim>                       &body,
      const std::map<unsigned int, std::optional<Point<dim>>> &needed) const
    {
      const IndexSet        &owned = body.locally_owned_dofs();
      std::vector<double>    mine;
      std::set<unsigned int> seen;
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const unsigned int v : cell->vertex_indices())
            {
              const unsigned int vertex = cell->vertex_index(v);
              const auto         found  = needed.find(vertex);
              if (found == needed.end() ||
                  !owned.is_element(cell->vertex_dof_index(v, 0)) ||
                  !seen.insert(vertex).second)
                continue;
              // side A's nodes carry their position: check the numbering
              AssertThrow(!found->second ||
                            found->second->distance(cell->vertex(v)) <=
                              1e-12 * (1. + found->second->norm()),
                          ExcMessage("Contact: the merged mesh does not "
                                     "keep the bodies' vertex numbers."));
              mine.push_back(vertex);
              for (unsigned int d = 0; d < dim; ++d)
                mine.push_back(
                  static_cast<double>(cell->vertex_dof_index(v, d)));
              mine.push_back(this_rank);
            }
      std::map<unsigned int, Node> nodes;
      const unsigned int           record = dim + 2;
      for (const std::vector<double> &list :
           Utilities::MPI::all_gather(communicator, mine))
        for (std::size_t i = 0; i + record <= list.size(); i += record)
          {
            Node node;
            for (unsigned int d = 0; d < dim; ++d)
              node.dofs[d] =
                static_cast<types::global_dof_index>(list[i + 1 + d]);
            node.owner = static_cast<unsigned int>(list[i + 1 + dim]);
            nodes[static_cast<unsigned int>(list[i])] = node;
          }
      return nodes;
    }



    template <int dim>
    void
    DistributedContact<dim>::set_potential_contact_vertices(
      const DistributedElasticBody<dim> &body,
      const std::vector<unsigned int>   &vertices)
    {
      std::map<unsigned int, std::optional<Point<dim>>> needed;
      for (const unsigned int v : vertices)
        needed.emplace(v, std::nullopt);
      node_of_vertex = gather_vertex_nodes(body, needed);
      AssertThrow(node_of_vertex.size() == needed.size(),
                  ExcMessage(
                    "Contact: " +
                    std::to_string(needed.size() - node_of_vertex.size()) +
                    " vertices of the contact boundaries have no "
                    "owned DoFs."));
    }



    template <int dim>
    const std::map<unsigned int, typename DistributedContact<dim>::Node> &
    DistributedContact<dim>::potential_contact_nodes() const
    {
      return node_of_vertex;
    }



    // The merged mesh keeps each body's vertices in order after its offset
    // (merge_body_meshes()); the positions are compared to make sure.
    template <int dim>
    void
    DistributedContact<dim>::setup_from_contact_set(
      const DistributedElasticBody<dim> &body,
      const ContactSet                  &pairs,
      const std::vector<unsigned int>   &vertex_offsets,
      const bool                         allow_empty)
    {
      double largest_mu = 0.;
      for (const ContactCandidate &c : pairs.candidates())
        largest_mu = std::max(largest_mu, c.friction_coefficient);
      start_setup(body, largest_mu);
      // the set's directions (dim if any candidate has friction; a search
      // during the run may find only frictionless pairs of a scene that
      // has frictional ones)
      directions = pairs.n_directions();
      AssertThrow(largest_mu == 0. || directions == dim,
                  ExcMessage("Contact: the candidate set has " +
                             std::to_string(pairs.n_directions()) +
                             " local directions for a largest mu = " +
                             format_number(largest_mu) + "."));
      bodies                   = vertex_offsets.size();
      const auto merged_vertex = [&](const unsigned int b,
                                     const unsigned int v) {
        AssertThrow(b < vertex_offsets.size(),
                    ExcMessage("Contact: a candidate names body " +
                               std::to_string(b) + " of " +
                               std::to_string(vertex_offsets.size()) + "."));
        return vertex_offsets[b] + v;
      };
      // vertex -> its position if known (side A's)
      std::map<unsigned int, std::optional<Point<dim>>> needed;
      for (const ContactCandidate &c : pairs.candidates())
        {
          Point<dim> x;
          for (unsigned int d = 0; d < dim; ++d)
            x[d] = c.position[d];
          needed[merged_vertex(c.body_a, c.vertex_a)] = x;
          for (unsigned int k = 0; k < c.n_vertices_b; ++k)
            needed.emplace(merged_vertex(c.body_b, c.vertices_b[k]),
                           std::nullopt);
        }

      // the searches during a run pair only vertices whose nodes
      // set_potential_contact_vertices() found: no gathering then
      const bool known =
        !node_of_vertex.empty() &&
        std::all_of(needed.begin(), needed.end(), [&](const auto &entry) {
          return node_of_vertex.count(entry.first) > 0;
        });
      std::map<unsigned int, Node> gathered;
      if (!known)
        gathered = gather_vertex_nodes(body, needed);
      const std::map<unsigned int, Node> &nodes =
        known ? node_of_vertex : gathered;
      AssertThrow(known || nodes.size() == needed.size(),
                  ExcMessage(
                    "Contact: " + std::to_string(needed.size() - nodes.size()) +
                    " contact vertices have no owned DoFs."));

      for (const ContactCandidate &pair : pairs.candidates())
        {
          Candidate c;
          for (unsigned int d = 0; d < dim; ++d)
            c.position[d] = pair.position[d];
          c.frame                = pair.frame;
          c.initial_gap          = pair.initial_gap;
          c.friction_coefficient = pair.friction_coefficient;
          c.tangential_extent    = pair.tangential_extent;
          c.body_a               = pair.body_a;
          c.body_b               = pair.body_b;
          c.nodes[0] = nodes.at(merged_vertex(pair.body_a, pair.vertex_a));
          c.n_nodes  = 1 + pair.n_vertices_b;
          for (unsigned int k = 0; k < pair.n_vertices_b; ++k)
            {
              c.nodes[1 + k] =
                nodes.at(merged_vertex(pair.body_b, pair.vertices_b[k]));
              c.nodes[1 + k].weight = -pair.weights_b[k];
            }
          candidate_list.push_back(c);
        }
      if (!allow_empty)
        finish_setup("the candidate set is empty");
      else if (!candidate_list.empty())
        finish_setup("");
    }



    template <int dim>
    unsigned int
    DistributedContact<dim>::n_candidates() const
    {
      return candidate_list.size();
    }



    template <int dim>
    unsigned int
    DistributedContact<dim>::n_directions() const
    {
      return directions;
    }



    template <int dim>
    double
    DistributedContact<dim>::friction_coefficient() const
    {
      return mu;
    }



    template <int dim>
    unsigned int
    DistributedContact<dim>::n_bodies() const
    {
      return bodies;
    }



    template <int dim>
    const typename DistributedContact<dim>::Candidate &
    DistributedContact<dim>::candidate(const unsigned int c) const
    {
      return candidate_list[c];
    }



    template <int dim>
    bool
    DistributedContact<dim>::owns(const unsigned int c) const
    {
      return candidate_list[c].nodes[0].owner == this_rank;
    }



    // @sect3{Replicated values}
    // Each rank writes the part of each candidate's value that the nodes
    // it owns give into a zeroed array, and the ranks sum it: against an
    // obstacle one term per entry (the sum is exact); a pair's two nodes
    // may have different owners.
    template <int dim>
    double
    DistributedContact<dim>::owned_part(const Candidate         &candidate,
                                        const unsigned int       direction,
                                        const DistributedVector &field) const
    {
      double value = 0.;
      for (unsigned int i = 0; i < candidate.n_nodes; ++i)
        {
          const Node &node = candidate.nodes[i];
          if (node.owner != this_rank)
            continue;
          double along = 0.;
          for (unsigned int d = 0; d < dim; ++d)
            along += candidate.frame[direction][d] * field[node.dofs[d]];
          value += node.weight * along;
        }
      return value;
    }



    template <int dim>
    void
    DistributedContact<dim>::gaps(const DistributedVector &u,
                                  std::vector<double>     &gap) const
    {
      partial.assign(candidate_list.size(), 0.);
      for (unsigned int c = 0; c < candidate_list.size(); ++c)
        partial[c] = (owns(c) ? candidate_list[c].initial_gap : 0.) +
                     owned_part(candidate_list[c], 0, u);
      gap.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, gap);
    }



    // Per candidate between bodies and tangent, the slide s = t_k . (u_A -
    // sum w u_B) from the contact point of the set-up; how far it lies
    // outside the candidate's tangential_extent, as a fraction of the
    // extent's length (side B's contact boundary along t_k).
    template <int dim>
    double
    DistributedContact<dim>::largest_slide_off(const DistributedVector &u) const
    {
      partial.assign(candidate_list.size() * (dim - 1), 0.);
      for (unsigned int c = 0; c < candidate_list.size(); ++c)
        if (candidate_list[c].body_b != numbers::invalid_unsigned_int)
          for (unsigned int k = 1; k < dim; ++k)
            partial[c * (dim - 1) + k - 1] =
              owned_part(candidate_list[c], k, u);
      std::vector<double> slide(partial.size());
      Utilities::MPI::sum(partial, communicator, slide);
      double largest = 0.;
      for (unsigned int c = 0; c < candidate_list.size(); ++c)
        if (candidate_list[c].body_b != numbers::invalid_unsigned_int)
          for (unsigned int k = 1; k < dim; ++k)
            largest = std::max(
              largest,
              slide_off_fraction(candidate_list[c].tangential_extent[k - 1],
                                 slide[c * (dim - 1) + k - 1]));
      return largest;
    }



    template <int dim>
    void
    DistributedContact<dim>::normal_velocities(
      const DistributedVector &v,
      std::vector<double>     &normal_velocity) const
    {
      partial.assign(candidate_list.size(), 0.);
      for (unsigned int c = 0; c < candidate_list.size(); ++c)
        partial[c] = owned_part(candidate_list[c], 0, v);
      normal_velocity.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, normal_velocity);
    }



    template <int dim>
    void
    DistributedContact<dim>::local_velocities(const DistributedVector &v,
                                              std::vector<double> &local) const
    {
      const unsigned int n = candidate_list.size();
      partial.assign(n * directions, 0.);
      for (unsigned int c = 0; c < n; ++c)
        for (unsigned int k = 0; k < directions; ++k)
          partial[c * directions + k] = owned_part(candidate_list[c], k, v);
      local.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, local);
    }



    template <int dim>
    void
    DistributedContact<dim>::local_values(
      const DistributedVector         &field,
      const std::vector<unsigned int> &candidates,
      std::vector<double>             &local) const
    {
      partial.assign(candidates.size() * directions, 0.);
      for (unsigned int a = 0; a < candidates.size(); ++a)
        for (unsigned int k = 0; k < directions; ++k)
          partial[a * directions + k] =
            owned_part(candidate_list[candidates[a]], k, field);
      local.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, local);
    }



    template <int dim>
    void
    DistributedContact<dim>::add_impulses(
      const std::vector<unsigned int> &candidates,
      const std::vector<double>       &x,
      DistributedVector               &target) const
    {
      for (unsigned int a = 0; a < candidates.size(); ++a)
        {
          const Candidate &cand = candidate_list[candidates[a]];
          for (unsigned int i = 0; i < cand.n_nodes; ++i)
            {
              const Node &node = cand.nodes[i];
              if (node.owner != this_rank)
                continue;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  double f = 0.;
                  for (unsigned int k = 0; k < directions; ++k)
                    f += cand.frame[k][d] * x[a * directions + k];
                  if (f != 0.)
                    target[node.dofs[d]] += node.weight * f;
                }
            }
        }
      target.compress(VectorOperation::add);
    }



    template class DistributedContact<2>;
    template class DistributedContact<3>;
  } // namespace distributed
} // namespace impactfe
