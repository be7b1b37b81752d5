// The scenes of programs/contact_mpi, on a distributed mesh (issue 14,
// doc/parallel.md): an elastic block (2D or 3D) sliding on a rigid plane
// under gravity with Coulomb friction, a body read from a mesh file thrown
// at a rigid obstacle (the cylinder and the plate), at a second body (the
// two bars; a block on another on a plane), or any number of bodies
// (three bars in a row).
#ifndef impactfe_parallel_distributed_scene_h
#define impactfe_parallel_distributed_scene_h

#include <deal.II/base/conditional_ostream.h>

#include <impactfe/bodies/mesh_input.h>
#include <impactfe/dynamics/stability_monitor.h>
#include <impactfe/output/output.h>
#include <impactfe/parallel/distributed_dynamics.h>
#include <impactfe/scenes/contact_scene.h>
#include <impactfe/scenes/rigid_block.h>

#include <array>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace impactfe
{
  namespace distributed
  {
    /**
     * The parameters of contact_mpi: every entry of block_sliding_3d
     * (the scene's, the obstacle's, the material's and the common ones), so
     * that its files run here too, plus `Dimension`, `Scene`, `Initial
     * conditions/Initial velocity` and `Parallel solver`.
     */
    struct DistributedSceneParameters
    {
      unsigned int dimension = 3;
      /// The sliding box, checked against the rigid block; or a body from
      /// `Mesh file` thrown at the obstacle with initial_velocity (impact);
      /// or that body thrown at the body of `Mesh of the second body`
      /// (impact and two_bodies); or the bodies of subsection `Bodies`
      /// (impact and several_bodies).
      bool impact = false, two_bodies = false, several_bodies = false;
      /// Scene = two bodies: the second body's mesh and uniform initial
      /// velocity, how the contact between the bodies is discretised, the
      /// contact normal of node-to-node pairs (from the second body towards
      /// the first) and the friction coefficient between the bodies.
      MeshParameters      second_mesh;
      std::vector<double> second_velocity, contact_normal;
      std::string         discretization          = "node-to-node";
      double              friction_between_bodies = 0.;
      /// Scene = two bodies: the boundary ids of the first and the second
      /// body's nodes that can touch the obstacle (-1: none).
      std::array<int, 2> obstacle_boundary_ids{{-1, -1}};
      /// A contact pair between bodies: the nodes of body_a on boundary_a
      /// (side A) against body_b's boundary_b (side B); bodies from 0.
      /// and its Coulomb coefficient.
      struct BodyPair
      {
        unsigned int       body_a = 0, body_b = 1;
        types::boundary_id boundary_a = 0, boundary_b = 0;
        double             friction_coefficient = 0.;
      };
      /// The nodes of @p body on @p boundary against the obstacle, with
      /// their Coulomb coefficient.
      struct ObstacleContact
      {
        unsigned int       body                 = 0;
        types::boundary_id boundary             = 0;
        double             friction_coefficient = 0.;
      };
      /// Scene = two bodies or bodies (multibody()), in one form: every
      /// body's mesh and uniform initial velocity (empty: at rest), the
      /// pairs between them (discretization for all) and the boundaries
      /// that touch the obstacle, each with its friction coefficient.
      std::vector<MeshParameters>      body_meshes;
      std::vector<std::vector<double>> body_velocities;
      /// body_a or body_b numbers::invalid_unsigned_int: 'all' (every
      /// body, within search_distance [m]).
      std::vector<BodyPair> body_pairs;
      double                search_distance = 0.;
      /// Steps between two contact searches during the run (0: once).
      unsigned int                 search_interval = 0;
      std::vector<ObstacleContact> obstacle_contacts;
      /// Whether any pair or obstacle contact has friction.
      bool
      multibody_friction() const;
      /// Whether the scene holds several bodies (two bodies or bodies).
      bool
      multibody() const
      {
        return !body_meshes.empty();
      }
      /// Whether the second body has its own material, and that material.
      bool               second_body_has_own_material = false;
      MaterialParameters second_material;
      /// Scene = two bodies with `Own material`, or bodies with per-body
      /// values in subsection Bodies: each body's material (material id =
      /// body); empty: every body is of subsection Material's.
      std::vector<MaterialParameters> body_materials;
      /// 2D: the out-of-plane thickness [m].
      double                   thickness = 1.;
      std::vector<double>      initial_velocity;
      SceneParameters          scene;
      MeshParameters           mesh;
      ObstacleParameters       obstacle;
      MaterialParameters       material;
      ParallelSolverParameters linear_solver;
      /// The scene: the box (2D: its section), v0, phi, g, the bounds.
      SlidingBoxParameters box;

      /// Every entry of contact_mpi's parameter files.
      static void
      declare_parameters(dealii::ParameterHandler &prm);

      /// Declare every entry, read @p file and check the values (throws with
      /// the entry named).
      void
      read(const std::string &file);

    private:
      /// Scene = bodies: subsection Bodies into the multibody lists and
      /// body_materials (and checks that it is empty otherwise). Needs
      /// `material` parsed.
      void
      parse_bodies(ParameterHandler &prm);
    };



    /**
     * The scene of contact_mpi in the shape of a deal.II tutorial
     * program: make_grid(), setup_system(), the time loop of
     * DistributedImpactSolver, output_results() (history.csv on rank 0 with
     * block_sliding_3d's columns, partitioned VTU and their .pvtu/.pvd
     * records), report_results() (the checks, summary.json, the RESULT
     * line). Every member function is collective.
     */
    template <int dim>
    class DistributedScene
    {
    public:
      DistributedScene(const DistributedSceneParameters &parameters,
                       const std::string                &file);
      void
      run();

    private:
      void
      make_grid();
      /// Scene = two bodies or bodies: the candidates on the bodies' own
      /// meshes (serial_bodies), as they are; @p during_run: a contact
      /// search during the run (named pairs within the search distance).
      std::unique_ptr<ContactSet>
      find_candidates(const bool during_run) const;
      /// What the searches during the run need (setup_system()).
      void
      prepare_contact_searches();
      /// The candidates found again in the current configuration.
      void
      search_contacts();
      void
      setup_system();
      void
      output_results(const unsigned int step);
      void
      report_results();

      Tensor<1, dim>
      direction() const
      {
        Tensor<1, dim> s;
        s[0] = std::cos(parameters.box.phi);
        if (dim == 3)
          s[dim - 1] = std::sin(parameters.box.phi);
        return s;
      }

      /// The body's (the first body's) uniform velocity at t = 0.
      Tensor<1, dim>
      launch_velocity() const
      {
        Tensor<1, dim> v = parameters.box.speed * direction();
        if (parameters.impact)
          for (unsigned int d = 0; d < dim; ++d)
            v[d] = parameters.initial_velocity[d];
        return v;
      }

      /// Body @p b's uniform velocity at t = 0 (the body's when there is
      /// one).
      Tensor<1, dim>
      body_launch_velocity(const unsigned int b) const
      {
        if (!parameters.multibody())
          return launch_velocity();
        Tensor<1, dim>             v;
        const std::vector<double> &given = parameters.body_velocities[b];
        for (unsigned int d = 0; d < given.size(); ++d)
          v[d] = given[d];
        return v;
      }

      /// The bodies of the scene: one, or several (material id = body).
      unsigned int
      n_bodies() const
      {
        return parameters.multibody() ? parameters.body_meshes.size() : 1;
      }

      /// The momentum of body @p b (the whole mesh when there is one).
      Tensor<1, dim>
      body_momentum(const DistributedVector &velocity, const unsigned int b);

      /// The largest extent of the mesh (the obstacle's length scale).
      double
      body_size() const;

      const DistributedSceneParameters parameters;
      /// The time stepping of the run: the parameter file's, with theta
      /// set from the mesh's Courant number in setup_system() when
      /// 'Theta rule = courant'.
      TimeSteppingParameters      time_stepping;
      const std::string           parameter_file;
      MPI_Comm                    comm;
      const unsigned int          n_ranks;
      ConditionalOStream          pcout;
      DistributedElasticBody<dim> body;
      DistributedContact<dim>     contact;
      /// Scene = two bodies: the candidates between the bodies and against
      /// the obstacle on the bodies' own meshes (the serial ContactSet),
      /// and where each body's vertices start in the merged mesh.
      std::unique_ptr<ContactSet> serial_candidates;
      std::vector<unsigned int>   vertex_offsets;
      /// The bodies' own meshes (kept for contact searches during the run),
      /// and the merged mesh's vertices whose DoFs this rank owns.
      std::vector<std::unique_ptr<ElasticBody<dim>>> serial_bodies;
      std::vector<std::vector<Point<dim>>>           reference_vertices;
      std::map<unsigned int, std::array<types::global_dof_index, dim>>
        owned_vertex_dofs;
      /// The contact searches during the run: how many, the candidates
      /// they added and dropped, the fewest and most candidates after one,
      /// and their wall seconds.
      struct
      {
        unsigned int searches = 0, new_candidates = 0, dropped_candidates = 0,
                     fewest = std::numeric_limits<unsigned int>::max(),
                     most   = 0;
        double seconds      = 0.;
      } search_statistics;
      std::unique_ptr<RigidObstacle<dim>>           obstacle;
      std::unique_ptr<DistributedImpactSolver<dim>> solver;
      std::unique_ptr<HistoryWriter>                history;
      std::unique_ptr<RigidBlockTracker<dim>>       tracker;
      std::vector<std::pair<double, std::string>>   vtu_records;
      Tensor<1, dim>                                normal;
      DistributedStepReport                         last_report;
      DistributedVector                             work;
      double normal_impulse = 0., tangential_impulse = 0., balance_error = 0.,
             largest_turn = 0.;
      /// Small sliding: DistributedContact::largest_slide_off() over the
      /// run.
      double largest_slide_off = 0.;
      /// Scene = impact: kinetic + elastic energy minus the loads' work,
      /// at t = 0 and at the last step, its largest increase in a step, the
      /// largest kinetic + elastic energy (the scale when the body starts
      /// at rest, as in ContactMonitor), and the largest penetration.
      double initial_energy = 0., last_energy = 0., largest_increase = 0.,
             largest_stored_energy = 0., largest_penetration = 0.;
      std::vector<double> gaps;
      double              setup_seconds = 0., loop_seconds = 0.;
      /// Steps h in the run, steps taken (a free-flight step is k steps
      /// h), and the step of the last VTU output.
      unsigned int n_steps = 0, n_steps_taken = 0, last_vtu_step = 0;
    };
  } // namespace distributed
} // namespace impactfe

#endif
