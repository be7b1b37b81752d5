#ifndef impactfe_contact_contact_set_h
#define impactfe_contact_contact_set_h

#include <deal.II/base/bounding_box.h>
#include <deal.II/base/point.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <deal.II/lac/block_vector.h>
#include <deal.II/lac/sparse_matrix.h>

#include <impactfe/bodies/elastic_body.h>
#include <impactfe/contact/rigid_obstacle.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * One contact candidate: a node of a body (side A) against a node of
   * another body (node-to-node), a point of a boundary segment or face of
   * another body (node-to-segment, node-to-face: two or four nodes of side
   * B with the interpolation weights there), or a rigid obstacle. The
   * local frame is
   * (n, t1, t2) with n pointing from side B towards side A, so that
   *   g = (x_A - x_B) . n >= 0 when open,
   *   V_N = (v_A - v_B) . n, and the impulse P_N n acts on A, -P_N n on B.
   */
  /**
   * The local frame of a contact with normal @p normal (not necessarily of
   * unit length): row 0 the unit normal, then the tangents (2D: the normal
   * turned by +90 degrees; 3D: t1 from the axis least aligned with n,
   * t2 = n x t1, a right-handed frame). Padded to 3 coordinates.
   */
  template <int dim>
  std::array<std::array<double, 3>, 3>
  contact_frame(const Tensor<1, dim> &normal);

  /**
   * How far a tangential slide @p slide lies outside @p range (a
   * ContactCandidate::tangential_extent), as a fraction of the range's
   * length: 0 inside, and for an unbounded range.
   */
  inline double
  slide_off_fraction(const std::array<double, 2> &range, const double slide)
  {
    const double length = range[1] - range[0];
    if (!(length > 0.) || !std::isfinite(length))
      return 0.;
    return std::max(
      {0., (slide - range[1]) / length, (range[0] - slide) / length});
  }

  struct ContactCandidate
  {
    unsigned int body_a   = 0;
    unsigned int vertex_a = 0;
    /// numbers::invalid_unsigned_int for a rigid obstacle.
    unsigned int body_b = numbers::invalid_unsigned_int;
    /// Side B's nodes around the contact point (one for node-to-node, a
    /// segment's two, a face's four) and the point's weights among them
    /// (the shape functions there; they sum to 1).
    unsigned int                n_vertices_b = 0;
    std::array<unsigned int, 4> vertices_b{{numbers::invalid_unsigned_int,
                                            numbers::invalid_unsigned_int,
                                            numbers::invalid_unsigned_int,
                                            numbers::invalid_unsigned_int}};
    std::array<double, 4>       weights_b{{0., 0., 0., 0.}};
    /// Reference position of the node of side A (3 coordinates, padded).
    std::array<double, 3> position{{0., 0., 0.}};
    /// Frame: direction 0 is the normal, then the tangents.
    std::array<std::array<double, 3>, 3> frame{};
    double                               initial_gap          = 0.;
    double                               friction_coefficient = 0.;
    /// Between two bodies: per tangent k (frame rows 1, 2), the range of
    /// t_k . (x - x_c) over the bounding box of side B's contact boundary,
    /// x_c the contact point, where the candidate was made: how far side A
    /// may slide from the contact point before it has certainly left side
    /// B's contact boundary (small sliding keeps the pair of t = 0, whose
    /// side B is then extrapolated). Unbounded against an obstacle.
    std::array<std::array<double, 2>, 2> tangential_extent{
      {{{-std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::infinity()}},
       {{-std::numeric_limits<double>::infinity(),
         std::numeric_limits<double>::infinity()}}}};

    bool
    against_rigid_obstacle() const
    {
      return body_b == numbers::invalid_unsigned_int;
    }
  };



  /**
   * The contact candidates of a scene and the linear operator H that maps
   * local impulses (per candidate: normal, then tangents) to nodal forces
   * in the global block vector of all bodies. Small perturbations: H, the
   * frames and g0 are fixed, and g(u) = g0 + H_N^T u.
   *
   * The number of local directions per candidate is 1 for frictionless
   * scenes (whatever the dimension: only what the scene needs) and dim with
   * friction.
   */
  class ContactSet
  {
  public:
    /** @p n_directions: 1 (frictionless) or the space dimension. */
    explicit ContactSet(const unsigned int n_directions = 1);

    unsigned int
    n_directions() const;
    unsigned int
    n_candidates() const;
    /** n_candidates() * n_directions(): the columns of H. */
    unsigned int
    n_columns() const;
    const ContactCandidate &
    candidate(const unsigned int c) const;
    const std::vector<ContactCandidate> &
    candidates() const;

    /**
     * Node-to-rigid-plane candidates: every vertex of body @p body_index on
     * the boundary with id @p boundary_id, against the plane through
     * @p plane_point with unit normal @p plane_normal pointing to the side
     * where the body is. Returns how many candidates were added; throws if
     * the boundary has no vertex.
     */
    template <int dim>
    unsigned int
    add_node_to_plane(const std::vector<const ElasticBody<dim> *> &bodies,
                      const unsigned int                           body_index,
                      const types::boundary_id                     boundary_id,
                      const Point<dim>                            &plane_point,
                      const Tensor<1, dim>                        &plane_normal,
                      const double friction_coefficient = 0.);

    /**
     * Node-to-obstacle candidates: every vertex of body @p body_index on the
     * boundary with id @p boundary_id, against a rigid obstacle. The gap and
     * the normal are the obstacle's at the node's reference position.
     * Returns how many candidates were added; throws if the boundary has no
     * vertex.
     */
    template <int dim>
    unsigned int
    add_node_to_obstacle(const std::vector<const ElasticBody<dim> *> &bodies,
                         const unsigned int        body_index,
                         const types::boundary_id  boundary_id,
                         const RigidObstacle<dim> &obstacle,
                         const double              friction_coefficient = 0.);

    /**
     * Node-to-segment candidates (2D) between two bodies whose interface
     * meshes need not match: each vertex of body A on @p boundary_a is
     * projected on the nearest boundary segment of body B on
     * @p boundary_b; the normal is that segment's, pointing from B towards
     * A, and the relative motion of the projection point interpolates the
     * segment's two nodes linearly. A is the "slave" side, B the "master".
     * Throws if a node projects on no segment. The segments come from an
     * R-tree of their bounding boxes (deal.II's pack_rtree): a node is
     * compared with those within its search distance, or within the
     * distance of the nearest box's segment, and with all of them only if
     * none of those is at least as close; ties go to the segment met first
     * in B's cell order, as in a loop over all of them.
     *
     * With a finite @p max_distance (a contact search between bodies that
     * may not face each other): only the nodes within @p max_distance of
     * the outer side of a segment become candidates (a node behind a
     * segment, by more than 1e-6 max_distance, is not paired with it: the
     * bodies do not overlap at the reference configuration; if such a node
     * lies inside body B, it throws, naming the node); the others and a
     * missing boundary id on either body are skipped without a message.
     * A @p max_penetration >= 0 replaces that 1e-6 max_distance: a search
     * in a deformed configuration (during a run) pairs a node that has
     * sunk into a side by up to @p max_penetration with it, at a negative
     * gap; a node that lies inside body B and farther than
     * @p max_penetration from every side of @p boundary_b throws, naming
     * it (add_node_to_face() likewise). A node that sank by less past the
     * end of the sides it could project on (into a reflex corner) is
     * skipped.
     * Returns the number of candidates added.
     */
    template <int dim>
    unsigned int
    add_node_to_segment(
      const std::vector<const ElasticBody<dim> *> &bodies,
      const unsigned int                           body_a,
      const types::boundary_id                     boundary_a,
      const unsigned int                           body_b,
      const types::boundary_id                     boundary_b,
      const double                                 friction_coefficient = 0.,
      const double max_distance    = std::numeric_limits<double>::infinity(),
      const double max_penetration = -1.);

    /**
     * Node-to-face candidates (3D) between two bodies whose interface
     * meshes need not match: each vertex of body A on @p boundary_a is
     * projected (closest point, Newton's method on the bilinear face) on
     * the boundary faces of body B with id @p boundary_b that a bounding-box
     * search (deal.II's R-tree) finds near it; the nearest projection
     * inside a face wins. The contact point moves with the face's four
     * nodes weighted by the bilinear shape functions there. The normal is
     * the bilinear interpolation of B's nodal normals (the average of the
     * normals of the faces around each node), pointing from B towards A:
     * continuous across face edges, so a node on an edge gets the same
     * normal from either face. A node farther from B than the widened boxes
     * is projected on all the faces. Throws if a node projects on no face.
     * A finite @p max_distance makes it a search, as add_node_to_segment().
     */
    template <int dim>
    unsigned int
    add_node_to_face(
      const std::vector<const ElasticBody<dim> *> &bodies,
      const unsigned int                           body_a,
      const types::boundary_id                     boundary_a,
      const unsigned int                           body_b,
      const types::boundary_id                     boundary_b,
      const double                                 friction_coefficient = 0.,
      const double max_distance    = std::numeric_limits<double>::infinity(),
      const double max_penetration = -1.);

    /**
     * Node-to-node candidates between two bodies with matching interface
     * nodes: each vertex of body A on @p boundary_a is paired with the vertex
     * of body B on @p boundary_b that lies on the same normal line (through
     * the interface normal @p normal, pointing from B towards A). The initial
     * gap is the distance along n. Throws if a node has no partner.
     */
    template <int dim>
    unsigned int
    add_node_to_node(const std::vector<const ElasticBody<dim> *> &bodies,
                     const unsigned int                           body_a,
                     const types::boundary_id                     boundary_a,
                     const unsigned int                           body_b,
                     const types::boundary_id                     boundary_b,
                     const Tensor<1, dim>                        &normal,
                     const double friction_coefficient = 0.);

    /**
     * For candidates found on displaced meshes (a contact search in the
     * current configuration, the vertices at X + u): refer them to the
     * reference configuration, keeping the pairing, the frames and the
     * weights. Side A's position becomes X_A = x_A - u_A, and the initial
     * gap g_0 = g - n . (u_A - sum_k w_k u_Bk), so that g_0 + H_N^T u is the
     * gap found at the current u (and H_N^T u keeps measuring from the
     * reference). @p displacement(body, vertex) gives a vertex's u (3
     * components, padded).
     */
    void
    refer_to_reference_configuration(
      const std::function<std::array<double, 3>(unsigned int, unsigned int)>
        &displacement);

    /**
     * Fix the global DoF layout (the block sizes of the bodies) and build
     * H. Call after all candidates are added and the bodies are set up.
     */
    template <int dim>
    void
    build_operator(const std::vector<const ElasticBody<dim> *> &bodies);

    /**
     * Small sliding keeps the pairs of the set-up: the largest distance
     * by which a node between bodies has slid, at the displacement @p u,
     * outside its ContactCandidate::tangential_extent, as a fraction of
     * that extent's length (0 while every node stays over side B's contact
     * boundary; obstacles do not count). After build_operator().
     */
    double
    largest_slide_off(const BlockVector<double> &u) const;

    /** g_c = g0_c + H_N,c^T u for every candidate. */
    void
    gaps(const BlockVector<double> &displacement, std::vector<double> &g) const;
    /**
     * g_c = g0_c + H_N,c^T (u + a v), the gaps at a predicted displacement,
     * read at the candidates' DoFs only (u + a v is not formed). Each term
     * is rounded as the same sum over a vector u + a v would be.
     */
    void
    gaps(const BlockVector<double> &u,
         const double               a,
         const BlockVector<double> &v,
         std::vector<double>       &g) const;
    /** V_N,c = H_N,c^T v. */
    void
    normal_velocities(const BlockVector<double> &velocity,
                      std::vector<double>       &normal_velocity) const;
    /** All local components H^T v, ordered per candidate. */
    void
    local_velocities(const BlockVector<double> &velocity,
                     std::vector<double>       &local_velocity) const;
    /** H_j^T v for one column j = c * n_directions + k. */
    double
    column_dot(const unsigned int column, const BlockVector<double> &v) const;
    /** f += alpha H_j for one column j. */
    void
    add_column(const unsigned int   column,
               const double         alpha,
               BlockVector<double> &f) const;

    /**
     * c_j ~ 1 / W_jj for the columns of the candidates @p candidates
     * (ordered as their local unknowns, per candidate [N, T...]), W = H^T
     * A^{-1} H with A block diagonal, one @p block_matrices entry per body
     * (A = M~ in the time loop): H_j^T A H_j for a candidate against a rigid
     * obstacle (exact for a lumped, mass-dominated A), 1 / (H_j^T
     * diag(A)^{-1} H_j) for one between two bodies (the pair's reduced
     * mass). The active set method's complementarity constants.
     */
    void
    inverse_delassus_diagonal(
      const std::vector<const SparseMatrix<double> *> &block_matrices,
      const std::vector<unsigned int>                 &candidates,
      std::vector<double>                             &c) const;
    /**
     * Per body (block), the DoFs in the columns of the candidates against
     * rigid obstacles, sorted: the contact DoFs C of the Schur complement
     * preconditioner of the active set method (MultibodySystem).
     */
    std::vector<std::vector<types::global_dof_index>>
    obstacle_contact_dofs(const unsigned int n_blocks) const;

  private:
    /// The last candidate's tangential_extent, side B's contact boundary
    /// having the bounding box @p box_of_b.
    template <int dim>
    void
    set_tangential_extent(const ElasticBody<dim> &B,
                          const BoundingBox<dim> &box_of_b);

    struct Entry
    {
      unsigned int            block;
      types::global_dof_index dof;
      double                  coefficient;
    };

    unsigned int                  directions;
    std::vector<ContactCandidate> candidate_list;
    /// Column j of H as (block, dof, coefficient) entries.
    std::vector<std::vector<Entry>> columns;
    /// Per candidate between bodies and tangent k (2 c + k - 1), the row
    /// t_k . (u_A - sum_j w_j u_Bj) (largest_slide_off()).
    std::vector<std::vector<Entry>> slide_rows;

    template <int dim>
    void
    set_frame(ContactCandidate &candidate, const Tensor<1, dim> &normal) const;
    /// Complete @p candidate (its bodies, side A's node and side B's nodes
    /// set) with side A's reference position @p x, the frame of @p normal,
    /// the initial gap and the friction coefficient, and add it.
    template <int dim>
    void
    add_candidate(ContactCandidate      candidate,
                  const Point<dim>     &x,
                  const Tensor<1, dim> &normal,
                  const double          initial_gap,
                  const double          friction_coefficient);
  };
} // namespace impactfe

#endif
