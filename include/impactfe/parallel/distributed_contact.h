// Node-to-obstacle contact candidates of a distributed body: each
// candidate is owned by the rank that owns its node's DoFs, and the
// candidate data the contact problem needs (frames, gaps, local
// velocities) are replicated on every rank (issue 14, doc/parallel.md).
#ifndef impactfe_parallel_distributed_contact_h
#define impactfe_parallel_distributed_contact_h

#include <impactfe/contact/rigid_obstacle.h>
#include <impactfe/parallel/distributed_body.h>

#include <array>
#include <vector>

namespace impactfe
{
  namespace distributed
  {
    /**
     * The nodes of a body's boundary @p boundary_id against a rigid
     * obstacle, with the serial ContactSet's conventions: the frame
     * (contact_frame()) and the initial gap at the reference position,
     * g(u) = g_0 + n . u, V = frame . v. The candidates are numbered in the
     * order of their reference positions (x, then y, then z), whatever the
     * partition, so runs on different numbers of ranks pose the same
     * problem. A product with H or H^T touches the owned candidates only;
     * the replicated values are summed over the ranks (each candidate has
     * one owner, so the sum is exact).
     */
    template <int dim>
    class DistributedObstacleContact
    {
    public:
      struct Candidate
      {
        Point<dim>                           position;
        std::array<std::array<double, 3>, 3> frame{};
        double                               initial_gap = 0.;
        /// The rank that owns the node, and its DoFs there.
        unsigned int                             owner = 0;
        std::array<types::global_dof_index, dim> dofs{};
      };

      /**
       * The candidates: every node of @p boundary_id. @p n_directions is 1
       * (frictionless: no tangential unknowns) or dim.
       */
      void
      setup(const DistributedElasticBody<dim> &body,
            const types::boundary_id           boundary_id,
            const RigidObstacle<dim>          &obstacle,
            const double                       friction_coefficient);

      unsigned int
      n_candidates() const;
      unsigned int
      n_directions() const;
      double
      friction_coefficient() const;
      const Candidate &
      candidate(const unsigned int c) const;
      /// Whether this rank owns candidate @p c.
      bool
      owns(const unsigned int c) const;

      /// Per candidate, g_0 + n . u (replicated).
      void
      gaps(const DistributedVector &displacement,
           std::vector<double>     &gap) const;
      /// Per candidate, n . v (replicated).
      void
      normal_velocities(const DistributedVector &velocity,
                        std::vector<double>     &normal_velocity) const;
      /// Per candidate and direction, frame . v (replicated).
      void
      local_velocities(const DistributedVector &velocity,
                       std::vector<double>     &local) const;
      /**
       * Local values of @p field at the candidates listed in @p candidates
       * (n_directions() per candidate, replicated).
       */
      void
      local_values(const DistributedVector         &field,
                   const std::vector<unsigned int> &candidates,
                   std::vector<double>             &local) const;
      /**
       * target += H x for the local impulses @p x of @p candidates
       * (n_directions() per candidate): each rank adds its owned
       * candidates' nodal forces.
       */
      void
      add_impulses(const std::vector<unsigned int> &candidates,
                   const std::vector<double>       &x,
                   DistributedVector               &target) const;

    private:
      MPI_Comm                    communicator = MPI_COMM_SELF;
      unsigned int                directions   = 1;
      unsigned int                this_rank    = 0;
      double                      mu           = 0.;
      std::vector<Candidate>      candidate_list;
      mutable std::vector<double> partial;
    };
  } // namespace distributed
} // namespace impactfe

#endif
