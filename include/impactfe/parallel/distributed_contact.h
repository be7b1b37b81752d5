// The contact candidates of a distributed body: its nodes against a rigid
// obstacle, or the candidates of a serial ContactSet between the parts of
// its mesh (bodies) and against obstacles. Each
// candidate is owned by the rank that owns its first node's DoFs, and the
// candidate data the contact problem needs (frames, gaps, local velocities) are
// replicated on every rank (issue 14, doc/parallel.md).
#ifndef impactfe_parallel_distributed_contact_h
#define impactfe_parallel_distributed_contact_h

#include <impactfe/contact/contact_set.h>
#include <impactfe/contact/rigid_obstacle.h>
#include <impactfe/parallel/distributed_body.h>

#include <array>
#include <map>
#include <optional>
#include <vector>

namespace impactfe
{
  namespace distributed
  {
    /**
     * Contact candidates with the serial ContactSet's conventions: side A
     * is a node of the body, side B a rigid obstacle or a point of another
     * part of the mesh (a node, or a point of a segment or face that moves
     * with its nodes); the frame (contact_frame()) has its normal n
     * pointing from B towards A, and g(u) = g_0 + n . (u_A - u_B),
     * V = frame . (v_A - v_B), the impulse P acts on A and -P on B. Small
     * perturbations: frames, g_0 and the pairs are fixed at the reference
     * configuration. The candidates are numbered in the order of side A's
     * reference positions (x, then y, then z), whatever the partition, so
     * runs on different numbers of ranks pose the same problem. A product
     * with H or H^T touches the DoFs this rank owns only, and the replicated
     * values are summed over the ranks: no ghost exchange, also when the
     * nodes of a pair have different owners.
     */
    template <int dim>
    class DistributedContact
    {
    public:
      /// The most nodes of a candidate: a node and a face's four.
      static constexpr unsigned int max_nodes = 5;

      /// A node of a candidate: its DoFs, the rank that owns them, and its
      /// weight in H (1 for side A; minus the interpolation weight of the
      /// contact point for each of side B's nodes).
      struct Node
      {
        std::array<types::global_dof_index, dim> dofs{};
        unsigned int                             owner  = 0;
        double                                   weight = 1.;
      };
      struct Candidate
      {
        /// Side A's reference position.
        Point<dim>                           position;
        std::array<std::array<double, 3>, 3> frame{};
        double                               initial_gap          = 0.;
        double                               friction_coefficient = 0.;
        /// ContactCandidate::tangential_extent (between bodies).
        std::array<std::array<double, 2>, 2> tangential_extent{};
        /// The bodies (parts of the mesh) of sides A and B; B is
        /// numbers::invalid_unsigned_int for a rigid obstacle.
        unsigned int body_a = 0, body_b = numbers::invalid_unsigned_int;
        /// Side A's node, then side B's (one node, a segment's two or a
        /// face's four).
        unsigned int                n_nodes = 1;
        std::array<Node, max_nodes> nodes{};
      };

      /**
       * The candidates: every node of @p boundary_id against @p obstacle.
       * The local directions are 1 (frictionless: no tangential unknowns)
       * or dim.
       */
      void
      setup(const DistributedElasticBody<dim> &body,
            const types::boundary_id           boundary_id,
            const RigidObstacle<dim>          &obstacle,
            const double                       friction_coefficient);

      /**
       * The candidates of bodies held in the body's mesh as parts
       * (merge_body_meshes(), material id = body): @p pairs are a serial
       * ContactSet's candidates (node-to-node, node-to-segment or
       * node-to-face between bodies, node-to-obstacle), built on the
       * bodies' own coarse meshes (so that the pairing, the frames, the
       * gaps and the friction coefficients are the serial programs'), whose
       * vertex v of body b is vertex @p vertex_offsets[b] + v of the merged
       * mesh. Each rank finds the DoFs of the vertices it owns; all are
       * gathered. The local directions are the set's. With @p allow_empty
       * (a contact search during the run) the set may be empty. Collective;
       * it replaces the candidates.
       */
      void
      setup_from_contact_set(const DistributedElasticBody<dim> &body,
                             const ContactSet                  &pairs,
                             const std::vector<unsigned int>   &vertex_offsets,
                             const bool allow_empty = false);

      /**
       * The nodes of the merged mesh's @p vertices (all the vertices that
       * a contact search during the run may pair): the substructured
       * solver keeps their DoFs in its contact Schur complement, so that
       * new candidates among them need no new factorisation. Collective;
       * call after the set-up.
       */
      void
      set_potential_contact_vertices(const DistributedElasticBody<dim> &body,
                                     const std::vector<unsigned int> &vertices);
      /// The nodes set_potential_contact_vertices() listed, by vertex of
      /// the merged mesh (empty if none).
      const std::map<unsigned int, Node> &
      potential_contact_nodes() const;

      unsigned int
      n_candidates() const;
      unsigned int
      n_directions() const;
      /// The largest friction coefficient of the candidates.
      double
      friction_coefficient() const;
      /// The bodies the candidates name (1 for setup()).
      unsigned int
      n_bodies() const;
      const Candidate &
      candidate(const unsigned int c) const;
      /// Whether this rank owns candidate @p c (its side A node).
      bool
      owns(const unsigned int c) const;

      /// Per candidate, g_0 + n . u (replicated).
      void
      gaps(const DistributedVector &displacement,
           std::vector<double>     &gap) const;
      /**
       * Small sliding keeps the pairs of the set-up: how far a node between
       * bodies has slid off side B's contact boundary at the displacement
       * @p u, the largest over the candidates and tangents of the distance
       * of its slide outside ContactCandidate::tangential_extent, as a
       * fraction of that extent's length (0 while every node stays within;
       * obstacles do not count). Collective.
       */
      double
      largest_slide_off(const DistributedVector &u) const;
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
       * (n_directions() per candidate): each rank adds the nodal forces on
       * the nodes it owns.
       */
      void
      add_impulses(const std::vector<unsigned int> &candidates,
                   const std::vector<double>       &x,
                   DistributedVector               &target) const;

    private:
      /// The friction coefficient, directions and communicator.
      void
      start_setup(const DistributedElasticBody<dim> &body,
                  const double                       friction_coefficient);
      /// The owned nodes on @p boundary_id, gathered on every rank.
      std::vector<Node>
      gather_boundary_nodes(const DistributedElasticBody<dim> &body,
                            const types::boundary_id           boundary_id,
                            std::vector<Point<dim>>           &positions) const;
      /// The nodes of the merged mesh's vertices @p needed (with side A's
      /// reference position to check the numbering, if given).
      std::map<unsigned int, Node>
      gather_vertex_nodes(
        const DistributedElasticBody<dim>                       &body,
        const std::map<unsigned int, std::optional<Point<dim>>> &needed) const;
      /// Sort by side A's position and check that there are candidates.
      void
      finish_setup(const std::string &where);
      /// Sum over the candidate's nodes that this rank owns of
      /// weight * frame[k] . field at the node.
      double
      owned_part(const Candidate         &candidate,
                 const unsigned int       direction,
                 const DistributedVector &field) const;

      MPI_Comm                     communicator = MPI_COMM_SELF;
      unsigned int                 directions   = 1;
      unsigned int                 this_rank    = 0;
      unsigned int                 bodies       = 1;
      double                       mu           = 0.;
      std::vector<Candidate>       candidate_list;
      std::map<unsigned int, Node> node_of_vertex;
      mutable std::vector<double>  partial;
    };
  } // namespace distributed
} // namespace impactfe

#endif
