#include <deal.II/base/mpi.h>

#include <impactfe/contact/contact_set.h>
#include <impactfe/parallel/distributed_contact.h>

#include <algorithm>
#include <set>

namespace impactfe
{
  namespace distributed
  {
    // @sect3{The candidates}
    // Each rank lists the nodes of the contact boundary whose DoFs it owns
    // (a node's DoFs have one owner), as numbers: position, DoFs, rank.
    // After an all-gather every rank sorts the same list by position.
    template <int dim>
    void
    DistributedObstacleContact<dim>::setup(
      const DistributedElasticBody<dim> &body,
      const types::boundary_id           boundary_id,
      const RigidObstacle<dim>          &obstacle,
      const double                       friction_coefficient)
    {
      AssertThrow(friction_coefficient >= 0.,
                  ExcMessage("Contact: the friction coefficient must be >= "
                             "0."));
      communicator = body.communicator();
      this_rank    = Utilities::MPI::this_mpi_process(communicator);
      mu           = friction_coefficient;
      directions   = mu > 0. ? dim : 1;

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

      candidate_list.clear();
      const unsigned int record = 2 * dim + 1;
      for (const std::vector<double> &list : all)
        for (std::size_t i = 0; i + record <= list.size(); i += record)
          {
            Candidate c;
            for (unsigned int d = 0; d < dim; ++d)
              {
                c.position[d] = list[i + d];
                c.dofs[d] =
                  static_cast<types::global_dof_index>(list[i + dim + d]);
              }
            c.owner       = static_cast<unsigned int>(list[i + 2 * dim]);
            c.frame       = contact_frame(obstacle.normal(c.position));
            c.initial_gap = obstacle.signed_distance(c.position);
            candidate_list.push_back(c);
          }
      AssertThrow(!candidate_list.empty(),
                  ExcMessage("Contact: the body has no vertex on boundary id " +
                             std::to_string(boundary_id) +
                             ", so the contact boundary is empty."));
      std::sort(candidate_list.begin(),
                candidate_list.end(),
                [](const Candidate &a, const Candidate &b) {
                  for (unsigned int d = 0; d < dim; ++d)
                    if (a.position[d] != b.position[d])
                      return a.position[d] < b.position[d];
                  return false;
                });
    }



    template <int dim>
    unsigned int
    DistributedObstacleContact<dim>::n_candidates() const
    {
      return candidate_list.size();
    }



    template <int dim>
    unsigned int
    DistributedObstacleContact<dim>::n_directions() const
    {
      return directions;
    }



    template <int dim>
    double
    DistributedObstacleContact<dim>::friction_coefficient() const
    {
      return mu;
    }



    template <int dim>
    const typename DistributedObstacleContact<dim>::Candidate &
    DistributedObstacleContact<dim>::candidate(const unsigned int c) const
    {
      return candidate_list[c];
    }



    template <int dim>
    bool
    DistributedObstacleContact<dim>::owns(const unsigned int c) const
    {
      return candidate_list[c].owner == this_rank;
    }



    // @sect3{Replicated values}
    // Each owner writes its candidates' values into a zeroed array, and the
    // ranks sum it: one value per entry, so the sum is exact.
    template <int dim>
    void
    DistributedObstacleContact<dim>::gaps(const DistributedVector &u,
                                          std::vector<double>     &gap) const
    {
      partial.assign(candidate_list.size(), 0.);
      for (unsigned int c = 0; c < candidate_list.size(); ++c)
        if (owns(c))
          {
            const Candidate &cand = candidate_list[c];
            double           g    = cand.initial_gap;
            for (unsigned int d = 0; d < dim; ++d)
              g += cand.frame[0][d] * u[cand.dofs[d]];
            partial[c] = g;
          }
      gap.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, gap);
    }



    template <int dim>
    void
    DistributedObstacleContact<dim>::normal_velocities(
      const DistributedVector &v,
      std::vector<double>     &normal_velocity) const
    {
      partial.assign(candidate_list.size(), 0.);
      for (unsigned int c = 0; c < candidate_list.size(); ++c)
        if (owns(c))
          for (unsigned int d = 0; d < dim; ++d)
            partial[c] +=
              candidate_list[c].frame[0][d] * v[candidate_list[c].dofs[d]];
      normal_velocity.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, normal_velocity);
    }



    template <int dim>
    void
    DistributedObstacleContact<dim>::local_velocities(
      const DistributedVector &v,
      std::vector<double>     &local) const
    {
      const unsigned int n = candidate_list.size();
      partial.assign(n * directions, 0.);
      for (unsigned int c = 0; c < n; ++c)
        if (owns(c))
          for (unsigned int k = 0; k < directions; ++k)
            for (unsigned int d = 0; d < dim; ++d)
              partial[c * directions + k] +=
                candidate_list[c].frame[k][d] * v[candidate_list[c].dofs[d]];
      local.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, local);
    }



    template <int dim>
    void
    DistributedObstacleContact<dim>::local_values(
      const DistributedVector         &field,
      const std::vector<unsigned int> &candidates,
      std::vector<double>             &local) const
    {
      partial.assign(candidates.size() * directions, 0.);
      for (unsigned int a = 0; a < candidates.size(); ++a)
        if (owns(candidates[a]))
          {
            const Candidate &cand = candidate_list[candidates[a]];
            for (unsigned int k = 0; k < directions; ++k)
              for (unsigned int d = 0; d < dim; ++d)
                partial[a * directions + k] +=
                  cand.frame[k][d] * field[cand.dofs[d]];
          }
      local.resize(partial.size());
      Utilities::MPI::sum(partial, communicator, local);
    }



    template <int dim>
    void
    DistributedObstacleContact<dim>::add_impulses(
      const std::vector<unsigned int> &candidates,
      const std::vector<double>       &x,
      DistributedVector               &target) const
    {
      for (unsigned int a = 0; a < candidates.size(); ++a)
        if (owns(candidates[a]))
          {
            const Candidate &cand = candidate_list[candidates[a]];
            for (unsigned int d = 0; d < dim; ++d)
              {
                double f = 0.;
                for (unsigned int k = 0; k < directions; ++k)
                  f += cand.frame[k][d] * x[a * directions + k];
                if (f != 0.)
                  target[cand.dofs[d]] += f;
              }
          }
      target.compress(VectorOperation::add);
    }



    template class DistributedObstacleContact<2>;
    template class DistributedObstacleContact<3>;
  } // namespace distributed
} // namespace impactfe
