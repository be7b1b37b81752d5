#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/numerics/data_out.h>

#include <impactfe/dynamics/contact_monitor.h>
#include <impactfe/parallel/distributed_scene.h>
#include <impactfe/utilities/mpi_errors.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <tuple>
#include <type_traits>

namespace impactfe
{
  namespace distributed
  {
    namespace
    {
      // The per-body material lists of subsection Bodies: the entry, its
      // unit and the member of MaterialParameters it sets.
      struct PerBodyMaterialEntry
      {
        const char *name;
        const char *unit;
        double MaterialParameters::*member;
      };
      const PerBodyMaterialEntry per_body_material_entries[] = {
        {"Young's moduli", "Pa", &MaterialParameters::youngs_modulus},
        {"Densities", "kg/m^3", &MaterialParameters::density},
        {"Poisson's ratios", "-", &MaterialParameters::poissons_ratio},
        {"Viscosities", "Pa s", &MaterialParameters::viscosity},
        {"Rayleigh mass coefficients",
         "1/s",
         &MaterialParameters::rayleigh_mass},
        {"Rayleigh stiffness coefficients",
         "s",
         &MaterialParameters::rayleigh_stiffness}};



      // @p text as a finite number (double or int), or a throw with
      // @p message ("nan" and "inf" are doubles to string_to_double()).
      template <typename Number>
      Number
      number_or_throw(const std::string &text, const std::string &message)
      {
        Number value = Number();
        try
          {
            if constexpr (std::is_same_v<Number, int>)
              value = Utilities::string_to_int(text);
            else
              value = Utilities::string_to_double(text);
          }
        catch (...)
          {
            AssertThrow(false, ExcMessage(message));
          }
        AssertThrow(std::isfinite(double(value)), ExcMessage(message));
        return value;
      }



      // A token of subsection Bodies' @p entry without its optional
      // suffix ' with friction x', and x (-1 without it: the entry's
      // default).
      std::pair<std::string, double>
      without_friction(const std::string &token, const std::string &entry)
      {
        const std::string suffix = " with friction ";
        const std::size_t at     = token.find(suffix);
        if (at == std::string::npos)
          return {token, -1.};
        const std::string value =
          Utilities::trim(token.substr(at + suffix.size()));
        const std::string message =
          "Bodies: '" + entry + "' has '" + token +
          "': the friction coefficient after 'with friction' must be a "
          "number >= 0, got '" +
          value + "'.";
        const double mu = number_or_throw<double>(value, message);
        AssertThrow(mu >= 0., ExcMessage(message));
        require_friction_coefficient(mu, "Bodies", entry);
        return {Utilities::trim(token.substr(0, at)), mu};
      }



      // 'b:i' of subsection Bodies' @p entry: body b of @p n_bodies (from
      // 1; returned from 0) and boundary id i; with @p allow_all also
      // 'all:i' (every body: numbers::invalid_unsigned_int).
      std::pair<unsigned int, types::boundary_id>
      body_and_boundary(const std::string &token,
                        const unsigned int n_bodies,
                        const std::string &entry,
                        const bool         allow_all = false)
      {
        const auto fail = [&](const std::string &why) {
          AssertThrow(false,
                      ExcMessage("Bodies: '" + entry + "' has '" + token +
                                 "': " + why + "."));
        };
        const std::vector<std::string> parts =
          Utilities::split_string_list(token, ':');
        if (parts.size() != 2)
          fail("expected 'body:boundary id'");
        const std::string integers =
          "Bodies: '" + entry + "' has '" + token + "': expected " +
          (allow_all ? "'body:boundary id' or 'all:boundary id'" :
                       "'body:boundary id'") +
          " with integers.";
        const bool all  = allow_all && parts[0] == "all";
        const int  body = all ? 1 : number_or_throw<int>(parts[0], integers);
        const int  boundary = number_or_throw<int>(parts[1], integers);
        if (body < 1 || body > static_cast<int>(n_bodies))
          fail("the bodies are 1 to " + std::to_string(n_bodies));
        if (boundary < 0 || boundary > 255)
          fail("a boundary id is 0 to 255");
        return {all ? numbers::invalid_unsigned_int : body - 1,
                static_cast<types::boundary_id>(boundary)};
      }
    } // namespace



    // Scene = bodies: subsection Bodies into the multibody lists; the
    // pairs are node-to-segment (2D) or node-to-face (3D).
    void
    DistributedSceneParameters::parse_bodies(ParameterHandler &prm)
    {
      prm.enter_subsection("Bodies");
      const std::vector<std::string> files =
        Utilities::split_string_list(prm.get("Mesh files"));
      const std::string velocities = prm.get("Initial velocities");
      const std::string pairs      = prm.get("Contact pairs");
      const std::string contacts   = prm.get("Obstacle contacts");
      const double      mu         = prm.get_double("Friction coefficient");
      search_distance              = prm.get_double("Contact search distance");
      search_interval              = prm.get_integer("Contact search interval");
      // each body's value of a material entry (empty: Material's for all)
      std::vector<std::vector<double>> per_body;
      for (const auto &entry : per_body_material_entries)
        {
          per_body.emplace_back();
          for (const std::string &v :
               Utilities::split_string_list(prm.get(entry.name)))
            per_body.back().push_back(
              parse_list_number(v, "Bodies", entry.name));
        }
      prm.leave_subsection();
      bool has_material_lists = false;
      for (const auto &values : per_body)
        has_material_lists = has_material_lists || !values.empty();
      // Scene = bodies: Material's Young's modulus and density (no
      // default) are needed unless a list here gives every body its own
      if (several_bodies)
        {
          std::vector<std::string> needed;
          for (unsigned int e = 0; e < per_body.size(); ++e)
            if (per_body[e].empty())
              {
                const auto member = per_body_material_entries[e].member;
                if (member == &MaterialParameters::youngs_modulus)
                  needed.emplace_back("Young's modulus");
                else if (member == &MaterialParameters::density)
                  needed.emplace_back("Density");
              }
          require_entries_set(prm, "Material", needed);
        }
      if (!several_bodies)
        {
          AssertThrow(files.empty() && velocities.empty() && pairs.empty() &&
                        contacts.empty() && mu == 0. && !has_material_lists &&
                        search_distance == 0. && search_interval == 0,
                      ExcMessage("The subsection 'Bodies' is for Scene = "
                                 "bodies."));
          return;
        }
      AssertThrow(files.size() >= 2,
                  ExcMessage("Bodies: 'Mesh files' must name at least two "
                             "files, got " +
                             std::to_string(files.size()) + "."));
      require_friction_coefficient(mu, "Bodies", "Friction coefficient");
      AssertThrow(friction_between_bodies == 0. &&
                    discretization == "node-to-node",
                  ExcMessage("The subsections 'Second body', 'Mesh of the "
                             "second body' and 'Obstacle contact' are for "
                             "Scene = two bodies."));
      const unsigned int n = files.size();
      for (const std::string &file : files)
        {
          MeshParameters body_mesh;
          body_mesh.file_name = file;
          body_meshes.push_back(body_mesh);
        }
      body_velocities.assign(n, {});
      if (!velocities.empty())
        {
          const std::vector<std::string> list =
            Utilities::split_string_list(velocities, ';');
          AssertThrow(list.size() == n,
                      ExcMessage("Bodies: 'Initial velocities' must give " +
                                 std::to_string(n) +
                                 " velocities separated by ';' (one per "
                                 "body), got '" +
                                 velocities + "'."));
          for (unsigned int b = 0; b < n; ++b)
            {
              for (const std::string &v : Utilities::split_string_list(list[b]))
                {
                  body_velocities[b].push_back(number_or_throw<double>(
                    v,
                    "Bodies: 'Initial velocities' has '" + v + "' for body " +
                      std::to_string(b + 1) +
                      ", which is not a finite number."));
                }
              AssertThrow(body_velocities[b].size() == dimension,
                          ExcMessage("Bodies: 'Initial velocities' must give " +
                                     std::to_string(dimension) +
                                     " components for each body, got '" +
                                     list[b] + "' for body " +
                                     std::to_string(b + 1) + "."));
            }
        }
      for (const std::string &token : Utilities::split_string_list(pairs))
        {
          const auto [pair, pair_mu] = without_friction(token, "Contact pairs");
          const std::size_t at       = pair.find(" against ");
          AssertThrow(at != std::string::npos,
                      ExcMessage("Bodies: 'Contact pairs' has '" + pair +
                                 "': expected 'a:i against b:j'."));
          // 'all:i': every body (the contact search of make_grid())
          const auto a = body_and_boundary(Utilities::trim(pair.substr(0, at)),
                                           n,
                                           "Contact pairs",
                                           true);
          const auto b = body_and_boundary(Utilities::trim(pair.substr(at + 9)),
                                           n,
                                           "Contact pairs",
                                           true);
          AssertThrow(a.first != b.first ||
                        a.first == numbers::invalid_unsigned_int,
                      ExcMessage("Bodies: 'Contact pairs' has '" + pair +
                                 "': a body against itself."));
          AssertThrow((a.first != numbers::invalid_unsigned_int &&
                       b.first != numbers::invalid_unsigned_int) ||
                        search_distance > 0.,
                      ExcMessage("Bodies: 'Contact pairs' has '" + pair +
                                 "': a pair with 'all' needs 'Contact search "
                                 "distance' > 0."));
          // twice, the pair's candidates would be made twice (each
          // node's impulse split between them, two coefficients mixed)
          AssertThrow(std::none_of(body_pairs.begin(),
                                   body_pairs.end(),
                                   [&](const BodyPair &p) {
                                     return p.body_a == a.first &&
                                            p.boundary_a == a.second &&
                                            p.body_b == b.first &&
                                            p.boundary_b == b.second;
                                   }),
                      ExcMessage("Bodies: 'Contact pairs' names '" + pair +
                                 "' twice."));
          body_pairs.push_back({a.first,
                                b.first,
                                a.second,
                                b.second,
                                pair_mu >= 0. ? pair_mu : mu});
        }
      AssertThrow(!body_pairs.empty() || !contacts.empty(),
                  ExcMessage("Bodies: neither 'Contact pairs' nor 'Obstacle "
                             "contacts' names a contact."));
      AssertThrow(search_distance == 0. || search_interval > 0 ||
                    std::any_of(body_pairs.begin(),
                                body_pairs.end(),
                                [](const BodyPair &pair) {
                                  return pair.body_a ==
                                           numbers::invalid_unsigned_int ||
                                         pair.body_b ==
                                           numbers::invalid_unsigned_int;
                                }),
                  ExcMessage("Bodies: 'Contact search distance' is for "
                             "'Contact pairs' with 'all' or 'Contact search "
                             "interval' > 0, and there is neither."));
      // the obstacle's coefficient is filled in once it is read (-1 here)
      for (const std::string &token : Utilities::split_string_list(contacts))
        {
          const auto [contact, contact_mu] =
            without_friction(token, "Obstacle contacts");
          const auto [b, boundary] =
            body_and_boundary(contact, n, "Obstacle contacts");
          AssertThrow(std::none_of(obstacle_contacts.begin(),
                                   obstacle_contacts.end(),
                                   [&, b = b, boundary = boundary](
                                     const ObstacleContact &c) {
                                     return c.body == b &&
                                            c.boundary == boundary;
                                   }),
                      ExcMessage("Bodies: 'Obstacle contacts' names '" +
                                 contact + "' twice."));
          obstacle_contacts.push_back({b, boundary, contact_mu});
        }
      discretization = dimension == 2 ? "node-to-segment" : "node-to-face";
      friction_between_bodies = mu;

      // per-body materials: Material's law with the listed values
      if (!has_material_lists)
        return;
      body_materials.assign(n, material);
      for (unsigned int e = 0; e < per_body.size(); ++e)
        {
          const std::vector<double> &values = per_body[e];
          const auto                &entry  = per_body_material_entries[e];
          if (values.empty())
            continue;
          AssertThrow(values.size() == n,
                      ExcMessage("Bodies: '" + std::string(entry.name) +
                                 "' must give " + std::to_string(n) +
                                 " values (one per body) or none, got " +
                                 std::to_string(values.size()) + "."));
          for (unsigned int b = 0; b < n; ++b)
            body_materials[b].*entry.member = values[b];
        }
      // the ranges of subsection Material, for each body
      for (unsigned int b = 0; b < n; ++b)
        body_materials[b].check("Bodies, body " + std::to_string(b + 1) +
                                " (Material with its values)");
    }



    bool
    DistributedSceneParameters::multibody_friction() const
    {
      bool friction = false;
      for (const BodyPair &pair : body_pairs)
        friction = friction || pair.friction_coefficient > 0.;
      for (const ObstacleContact &contact : obstacle_contacts)
        friction = friction || contact.friction_coefficient > 0.;
      return friction;
    }



    // @sect3{Parameters}
    void
    DistributedSceneParameters::declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Dimension",
                        "3",
                        Patterns::Integer(2, 3),
                        "The scene's dimension [-]. Scene = sliding block: "
                        "2, the block's section in the x-y plane, sliding "
                        "along x; 3, the box. 2D bodies take their "
                        "material's 'Plane model'.");
      prm.declare_entry(
        "Scene",
        "sliding block",
        Patterns::Selection("sliding block|impact|two bodies|bodies"),
        "sliding block: the box of subsection Geometry (or the mesh of "
        "subsection Mesh) launched along the plane, checked against the "
        "rigid-block model. impact: the body of 'Mesh file' thrown at the "
        "obstacle with 'Initial velocity', checked by its impulse balance "
        "and the contact verification (the cylinder and the plate). two "
        "bodies: that body thrown at the body of subsection 'Mesh of the "
        "second body' (subsection 'Second body': the contact between "
        "them), and either or both against the obstacle if subsection "
        "'Obstacle contact' names their boundaries (the bars in 2D and 3D; "
        "a block on another on a plane). bodies: any number of bodies, "
        "their pairs and their contacts with the obstacle listed in "
        "subsection 'Bodies' (three bars in a row).");
      prm.enter_subsection("Geometry");
      prm.declare_entry("Thickness",
                        "1",
                        Patterns::Double(),
                        "Dimension = 2: the out-of-plane thickness of the "
                        "body (plane strain or stress) [m]. Must be > 0.");
      prm.leave_subsection();
      prm.enter_subsection("Initial conditions");
      prm.declare_entry("Initial velocity",
                        "",
                        Patterns::List(Patterns::Double(), 0, 3),
                        "Scene = impact: the body's uniform initial "
                        "velocity, one component per dimension [m/s].");
      prm.leave_subsection();
      prm.enter_subsection("Second body");
      prm.declare_entry("Initial velocity",
                        "",
                        Patterns::List(Patterns::Double(), 0, 3),
                        "Scene = two bodies: the second body's uniform "
                        "initial velocity, one component per dimension; "
                        "empty: at rest [m/s].");
      prm.declare_entry(
        "Contact discretization",
        "node-to-node",
        Patterns::Selection("node-to-node|node-to-segment|node-to-face"),
        "Scene = two bodies: node-to-node (matching interface meshes: each "
        "contact node of the first body against the second body's node on "
        "its line along 'Contact normal'), node-to-segment (2D) or "
        "node-to-face (3D): each contact node of the first body against the "
        "nearest point of the second body's contact boundary, as the serial "
        "programs' ContactSet.");
      prm.declare_entry("Contact normal",
                        "",
                        Patterns::List(Patterns::Double(), 0, 3),
                        "Scene = two bodies, node-to-node: the direction "
                        "from the second body's contact face towards the "
                        "first body's, one component per dimension "
                        "(normalised) [-].");
      prm.declare_entry("Friction coefficient",
                        "0",
                        Patterns::Double(),
                        "Scene = two bodies: Coulomb's coefficient between "
                        "the bodies [-]. Must be >= 0; 0: no tangential "
                        "unknowns.");
      prm.declare_entry("Own material",
                        "false",
                        Patterns::Bool(),
                        "Scene = two bodies: true: the second body is made "
                        "of the material of subsection 'Material of the "
                        "second body' (linear laws); false: of the first "
                        "body's.");
      prm.leave_subsection();
      prm.enter_subsection("Bodies");
      prm.declare_entry("Mesh files",
                        "",
                        Patterns::List(Patterns::FileName(), 0),
                        "Scene = bodies: one mesh file per body (body 1, 2, "
                        "...), relative to the directory of the parameter "
                        "file that sets it (an included file's own) [-].");
      prm.declare_entry("Initial velocities",
                        "",
                        Patterns::Anything(),
                        "Scene = bodies: each body's uniform initial "
                        "velocity, one component per dimension, the bodies "
                        "separated by ';' (e.g. '1, 0; 0, 0; 0, 0'); empty: "
                        "all at rest [m/s].");
      prm.declare_entry("Contact pairs",
                        "",
                        Patterns::Anything(),
                        "Scene = bodies: the pairs between bodies, "
                        "comma-separated, each 'a:i against b:j': the nodes "
                        "of body a on boundary id i against the boundary id "
                        "j of body b (node-to-segment in 2D, node-to-face in "
                        "3D; 'all' in place of a body: every body, within "
                        "'Contact search distance'), with 'Friction "
                        "coefficient', or with its own "
                        "coefficient after ' with friction' (e.g. '1:2 "
                        "against 2:3 with friction 0.3') [-].");
      prm.declare_entry("Contact search distance",
                        "0",
                        Patterns::Double(0.),
                        "Scene = bodies: for 'Contact pairs' with 'all' in "
                        "place of a body ('all:2 against all:3': every "
                        "body's nodes on boundary id 2 against every other "
                        "body's boundary id 3), the largest distance of a "
                        "node from the other body's boundary at which it "
                        "becomes a candidate; with 'Contact search "
                        "interval' > 0 (which needs it) also for the named "
                        "pairs [m].");
      prm.declare_entry(
        "Contact search interval",
        "0",
        Patterns::Integer(0),
        "Scene = bodies: every this many steps the pairs are made again in "
        "the current configuration (the vertices at X + u): large sliding, "
        "and bodies that start apart; 0: once, at t = 0 (small sliding). A "
        "pair with 'all' must then reach, with 'Contact search distance', "
        "what the bodies approach in this many steps. With mass "
        "redistribution every node of the named boundaries is massless "
        "[-].");
      prm.declare_entry("Friction coefficient",
                        "0",
                        Patterns::Double(),
                        "Scene = bodies: Coulomb's coefficient of every "
                        "pair between bodies that does not give its own "
                        "[-]. Must be >= 0.");
      prm.declare_entry("Obstacle contacts",
                        "",
                        Patterns::Anything(),
                        "Scene = bodies: the boundaries that touch the "
                        "obstacle of subsection Obstacle, comma-separated, "
                        "each 'b:i' (body b, boundary id i), with the "
                        "obstacle's 'Friction coefficient' or with its own "
                        "after ' with friction' (e.g. '1:2 with friction "
                        "0.2') [-].");
      for (const auto &entry : per_body_material_entries)
        prm.declare_entry(entry.name,
                          "",
                          Patterns::List(Patterns::Double(), 0),
                          "Scene = bodies: one value per body, "
                          "comma-separated, in place of subsection "
                          "Material's (whose law and plane model every body "
                          "keeps); empty: "
                          "Material's for every body [" +
                            std::string(entry.unit) + "].");
      prm.leave_subsection();
      prm.enter_subsection("Obstacle contact");
      for (const std::string body : {"first", "second"})
        prm.declare_entry("Boundary id of the " + body + " body",
                          "-1",
                          Patterns::Integer(-1, 255),
                          "Scene = two bodies: the boundary id of the " + body +
                            " body's nodes that can touch the obstacle of "
                            "subsection Obstacle (node-to-obstacle, with its "
                            "friction coefficient); -1: the " +
                            body + " body does not touch it [-].");
      prm.leave_subsection();
      MaterialParameters::declare_parameters(prm,
                                             2,
                                             "Material of the second body");
      SceneParameters::declare_parameters(prm, "results/contact_mpi", true);
      MeshParameters::declare_parameters(prm, "Mesh", 2);
      MeshParameters::declare_parameters(prm, "Mesh of the second body", 0);
      ObstacleParameters::declare_parameters(prm, "0, 0, 0", "0, 1, 0", "0.5");
      MaterialParameters::declare_parameters(prm, 2); // 2D: a superset
      ParallelSolverParameters::declare_parameters(prm);
      SlidingBoxParameters::declare_parameters(prm);
    }



    void
    DistributedSceneParameters::read(const std::string &file)
    {
      ParameterHandler prm;
      declare_parameters(prm);
      read_parameter_file(prm, file);
      dimension      = prm.get_integer("Dimension");
      two_bodies     = prm.get("Scene") == "two bodies";
      several_bodies = prm.get("Scene") == "bodies";
      impact = prm.get("Scene") == "impact" || two_bodies || several_bodies;
      prm.enter_subsection("Geometry");
      thickness = prm.get_double("Thickness");
      prm.leave_subsection();
      require_positive(thickness, "Geometry", "Thickness");
      AssertThrow(dimension == 2 || thickness == 1.,
                  ExcMessage("Geometry: 'Thickness' is for Dimension = 2, "
                             "got " +
                             format_number(thickness) + " in 3D."));
      prm.enter_subsection("Initial conditions");
      const std::string velocity = prm.get("Initial velocity");
      prm.leave_subsection();
      const auto numbers = [](const std::string &list,
                              const std::string &subsection,
                              const std::string &entry) {
        std::vector<double> values;
        for (const std::string &v : Utilities::split_string_list(list))
          values.push_back(parse_list_number(v, subsection, entry));
        return values;
      };
      initial_velocity =
        numbers(velocity, "Initial conditions", "Initial velocity");
      prm.enter_subsection("Second body");
      const std::string second_velocity_text = prm.get("Initial velocity");
      const std::string normal_text          = prm.get("Contact normal");
      discretization = prm.get("Contact discretization");
      second_velocity =
        numbers(second_velocity_text, "Second body", "Initial velocity");
      contact_normal = numbers(normal_text, "Second body", "Contact normal");
      friction_between_bodies      = prm.get_double("Friction coefficient");
      second_body_has_own_material = prm.get_bool("Own material");
      prm.leave_subsection();
      prm.enter_subsection("Obstacle contact");
      obstacle_boundary_ids = {
        {static_cast<int>(prm.get_integer("Boundary id of the first body")),
         static_cast<int>(prm.get_integer("Boundary id of the second body"))}};
      prm.leave_subsection();
      // with Scene = bodies, parse_bodies() asks for what its lists leave
      material.parse_parameters(prm, dimension, "Material", !several_bodies);
      parse_bodies(prm);
      const bool touches_obstacle = obstacle_boundary_ids[0] >= 0 ||
                                    obstacle_boundary_ids[1] >= 0 ||
                                    !obstacle_contacts.empty();
      // Read and range-checked even when unused ('Own material' = false or
      // another scene): a wrong value there must not pass unnoticed.
      second_material.parse_parameters(prm,
                                       dimension,
                                       "Material of the second body",
                                       two_bodies &&
                                         second_body_has_own_material);
      require_friction_coefficient(friction_between_bodies,
                                   "Second body",
                                   "Friction coefficient");
      second_mesh.parse_parameters(prm, "Mesh of the second body");
      scene.parse_parameters(prm);
      mesh.parse_parameters(prm, "Mesh");
      // bodies read the obstacle only if they touch it
      if (!(two_bodies || several_bodies) || touches_obstacle)
        obstacle.parse_parameters(prm, dimension);
      linear_solver.parse_parameters(prm);
      box.parse_parameters(prm);
      AssertThrow(search_interval == 0 || search_distance > 0.,
                  ExcMessage("Bodies: 'Contact search interval' = " +
                             std::to_string(search_interval) +
                             " needs 'Contact search distance' > 0 (how far "
                             "from the other body a node becomes a "
                             "candidate)."));
      if (several_bodies)
        {
          AssertThrow(initial_velocity.empty() && !mesh.from_file(),
                      ExcMessage("Scene = bodies: the bodies' meshes and "
                                 "velocities are in subsection 'Bodies', not "
                                 "in 'Mesh' and 'Initial conditions'."));
        }
      else if (impact)
        {
          AssertThrow(initial_velocity.size() == dimension,
                      ExcMessage("Initial conditions: 'Initial velocity' "
                                 "must have " +
                                 std::to_string(dimension) +
                                 " components with Scene = impact, got '" +
                                 velocity + "'."));
          AssertThrow(mesh.from_file(),
                      ExcMessage("Scene = " + prm.get("Scene") +
                                 ": set 'Mesh file' in subsection Mesh (the "
                                 "body to throw)."));
        }
      else
        AssertThrow(initial_velocity.empty(),
                    ExcMessage("Initial conditions: 'Initial velocity' is "
                               "for Scene = impact; the sliding block uses "
                               "'Sliding speed' and 'Sliding direction'."));
      if (two_bodies)
        {
          AssertThrow(second_mesh.from_file(),
                      ExcMessage("Scene = two bodies: set 'Mesh file' in "
                                 "subsection 'Mesh of the second body'."));
          AssertThrow(second_velocity.empty() ||
                        second_velocity.size() == dimension,
                      ExcMessage("Second body: 'Initial velocity' must be "
                                 "empty (at rest) or have " +
                                 std::to_string(dimension) +
                                 " components, got '" + second_velocity_text +
                                 "'."));
          AssertThrow(discretization == "node-to-node" ||
                        discretization ==
                          (dimension == 2 ? "node-to-segment" : "node-to-face"),
                      ExcMessage("Second body: 'Contact discretization' "
                                 "cannot be " +
                                 discretization + " in " +
                                 std::to_string(dimension) +
                                 "D (node-to-segment is for 2D, "
                                 "node-to-face for 3D)."));
          double length = 0.;
          for (const double n : contact_normal)
            length += n * n;
          length = std::sqrt(length);
          if (discretization == "node-to-node")
            {
              AssertThrow(contact_normal.size() == dimension && length > 0.,
                          ExcMessage("Second body: 'Contact normal' must be "
                                     "a non-zero vector of " +
                                     std::to_string(dimension) +
                                     " components for node-to-node "
                                     "contact, got '" +
                                     normal_text + "'."));
              for (double &n : contact_normal)
                n /= length;
            }
          else
            AssertThrow(contact_normal.empty(),
                        ExcMessage("Second body: 'Contact normal' is for "
                                   "node-to-node contact; " +
                                   discretization +
                                   " takes the second body's normals."));
        }
      else
        AssertThrow(!second_mesh.from_file() && second_velocity.empty() &&
                      contact_normal.empty() &&
                      (several_bodies || friction_between_bodies == 0.) &&
                      (several_bodies || discretization == "node-to-node") &&
                      !second_body_has_own_material &&
                      obstacle_boundary_ids[0] < 0 &&
                      obstacle_boundary_ids[1] < 0,
                    ExcMessage("The subsections 'Second body', 'Mesh of "
                               "the second body' and 'Obstacle contact' are "
                               "for Scene = two bodies."));
      // two bodies in the multibody form
      if (two_bodies)
        {
          body_meshes     = {mesh, second_mesh};
          body_velocities = {initial_velocity, second_velocity};
          body_pairs      = {{0,
                              1,
                              mesh.contact_boundary_id,
                              second_mesh.contact_boundary_id,
                              friction_between_bodies}};
          for (unsigned int b = 0; b < 2; ++b)
            if (obstacle_boundary_ids[b] >= 0)
              obstacle_contacts.push_back(
                {b,
                 static_cast<types::boundary_id>(obstacle_boundary_ids[b]),
                 -1.});
          if (second_body_has_own_material)
            body_materials = {material, second_material};
        }
      // an obstacle contact without its own coefficient: the obstacle's
      for (ObstacleContact &contact : obstacle_contacts)
        if (contact.friction_coefficient < 0.)
          contact.friction_coefficient = obstacle.friction_coefficient;
      scene.output.refuse_mesh_output(
        "contact_mpi reads the serial programs' meshes; its own come from "
        "files or the built-in box");
      // contact_mpi writes no shapes.csv
      scene.output.check_shape_times(false, 0, 0.);
      AssertThrow(dimension == 3 || std::abs(std::sin(box.phi)) < 1e-12,
                  ExcMessage("Initial conditions: 'Sliding direction' must "
                             "be 0 or pi in 2D (the block slides along x), "
                             "got " +
                             format_number(box.phi) + "."));
    }



    template <int dim>
    DistributedScene<dim>::DistributedScene(
      const DistributedSceneParameters &parameters,
      const std::string                &file)
      : parameters(parameters)
      , time_stepping(parameters.scene.time_stepping)
      , parameter_file(file)
      , comm(MPI_COMM_WORLD)
      , n_ranks(Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD))
      , pcout(std::cout, Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0)
      , body(MPI_COMM_WORLD,
             parameters.material,
             parameters.scene.discretization,
             dim == 2 ? parameters.thickness : 1.)
    {}



    // @sect3{The mesh}
    // The box (or its section) on the plane y = 0, centred in x (and z),
    // colorized: its lower face has boundary id 2. A file (subsection
    // `Mesh`) is read on every rank as the coarse mesh and partitioned.
    // Two bodies are two files, held side by side in one mesh (material
    // ids 0 and 1, merge_body_meshes()), so that p4est partitions them
    // together; the candidates between them are the serial ContactSet's on
    // the bodies' own meshes (the same pairs, frames and gaps as the
    // serial programs).
    template <int dim>
    void
    DistributedScene<dim>::make_grid()
    {
      auto &tria = body.triangulation();
      if (parameters.multibody())
        {
          const double       thickness = dim == 2 ? parameters.thickness : 1.;
          const unsigned int n         = n_bodies();
          std::vector<const Triangulation<dim> *> meshes;
          serial_bodies.clear();
          vertex_offsets.clear();
          for (unsigned int b = 0; b < n; ++b)
            {
              const std::string name =
                parameters.two_bodies ?
                  (b == 0 ? "first body" : "second body") :
                  "body " + std::to_string(b + 1);
              serial_bodies.push_back(std::make_unique<ElasticBody<dim>>(
                name,
                parameters.material,
                parameters.scene.discretization,
                thickness));
              parameters.body_meshes[b].read(
                serial_bodies.back()->triangulation(), parameter_file);
              vertex_offsets.push_back(b == 0 ? 0 :
                                                vertex_offsets.back() +
                                                  meshes.back()->n_vertices());
              meshes.push_back(&serial_bodies.back()->triangulation());
            }
          merge_body_meshes<dim>(meshes, tria);

          // the obstacle, if a body touches it (its size: the bodies')
          if (!parameters.obstacle_contacts.empty())
            obstacle = parameters.obstacle.create<dim>(body_size());
          serial_candidates = find_candidates(false);
          // the bodies' meshes are needed again only to search
          if (parameters.search_interval == 0)
            serial_bodies.clear();
        }
      else if (parameters.mesh.from_file())
        parameters.mesh.read(tria, parameter_file);
      else if (dim == 3)
        GridGenerator::subdivided_hyper_rectangle(
          tria,
          {parameters.box.nx, parameters.box.ny, parameters.box.nz},
          Point<dim>(-0.5 * parameters.box.length,
                     0.,
                     -0.5 * parameters.box.width),
          Point<dim>(0.5 * parameters.box.length,
                     parameters.box.height,
                     0.5 * parameters.box.width),
          true);
      else
        GridGenerator::subdivided_hyper_rectangle(
          tria,
          {parameters.box.nx, parameters.box.ny},
          Point<dim>(-0.5 * parameters.box.length, 0.),
          Point<dim>(0.5 * parameters.box.length, parameters.box.height),
          true);
      AssertThrow(tria.n_global_active_cells() >= n_ranks,
                  ExcMessage(
                    "The mesh has " +
                    std::to_string(tria.n_global_active_cells()) +
                    (tria.n_global_active_cells() == 1 ? " cell" : " cells") +
                    " for " + std::to_string(n_ranks) +
                    " MPI ranks: use at most one rank per cell."));
    }



    // The obstacle's finite differences need the body's size: the box's
    // length, or the extent of the mesh read from a file, over all ranks.
    // @sect3{The contact candidates}
    // The pairs between the bodies and the obstacle contacts, by the serial
    // ContactSet on the bodies' own meshes (at t = 0 the reference
    // configuration; in a contact search during the run the current one,
    // search_contacts()).
    template <int dim>
    std::unique_ptr<ContactSet>
    DistributedScene<dim>::find_candidates(const bool during_run) const
    {
      const unsigned int                    n = n_bodies();
      std::vector<const ElasticBody<dim> *> bodies;
      for (const auto &serial_body : serial_bodies)
        bodies.push_back(serial_body.get());
      auto candidates =
        std::make_unique<ContactSet>(parameters.multibody_friction() ? dim : 1);
      // pairs with 'all': every ordered pair of bodies whose bounding
      // boxes come within the search distance (a body against itself
      // never; 'all:i against all:i' makes only the lower numbered body
      // side A, so that no two bodies are paired twice)
      const double                  reach = parameters.search_distance;
      std::vector<BoundingBox<dim>> boxes;
      for (const auto *serial_body : bodies)
        {
          BoundingBox<dim> box(serial_body->triangulation().get_vertices());
          box.extend(reach);
          boxes.push_back(box);
        }
      // One pair of bodies: the candidates of body a's boundary against
      // body b's, within @p distance (infinite: every node of a named
      // pair, which must project).
      const auto add_pair = [&](const auto        &pair,
                                const unsigned int a,
                                const unsigned int b,
                                const double       distance) {
        const double mu = pair.friction_coefficient;
        // in the deformed configuration a closed contact may have sunk
        // into the other side (a corner sliding onto a segment the other
        // body has not pressed down): pair it if it lies within
        // 'Maximum penetration' (if given; else a tenth of the search
        // distance); a node deeper inside stops the run
        const double bound = parameters.scene.verification.max_penetration;
        const double sunk  = !during_run ? -1. :
                             bound >= 0. ? std::min(bound, distance) :
                                           0.1 * distance;
        if (parameters.discretization == "node-to-segment")
          return candidates->add_node_to_segment(
            bodies, a, pair.boundary_a, b, pair.boundary_b, mu, distance, sunk);
        if (parameters.discretization == "node-to-face")
          return candidates->add_node_to_face(
            bodies, a, pair.boundary_a, b, pair.boundary_b, mu, distance, sunk);
        Tensor<1, dim> normal_of_pair;
        for (unsigned int d = 0; d < dim; ++d)
          normal_of_pair[d] = parameters.contact_normal[d];
        return candidates->add_node_to_node(
          bodies, a, pair.boundary_a, b, pair.boundary_b, normal_of_pair, mu);
      };
      const auto all = numbers::invalid_unsigned_int;
      for (const auto &pair : parameters.body_pairs)
        {
          // a named pair: every node, which must project; with searches
          // during the run those within the search distance (a node may
          // slide off the other body, the bodies may start apart)
          if (pair.body_a != all && pair.body_b != all)
            {
              add_pair(pair,
                       pair.body_a,
                       pair.body_b,
                       parameters.search_interval > 0 ?
                         reach :
                         std::numeric_limits<double>::infinity());
              continue;
            }
          unsigned int found = 0;
          for (unsigned int a = 0; a < n; ++a)
            for (unsigned int b = 0; b < n; ++b)
              if (a != b && (pair.body_a == all || pair.body_a == a) &&
                  (pair.body_b == all || pair.body_b == b) &&
                  !(pair.body_a == all && pair.body_b == all &&
                    pair.boundary_a == pair.boundary_b && b < a) &&
                  boxes[a].get_neighbor_type(boxes[b]) !=
                    NeighborType::not_neighbors)
                found += add_pair(pair, a, b, reach);
          // with searches during the run, bodies may start apart
          AssertThrow(found > 0 || parameters.search_interval > 0,
                      ExcMessage(
                        "Bodies: 'Contact pairs' with 'all' found no node "
                        "on boundary id " +
                        std::to_string(pair.boundary_a) +
                        " within 'Contact search distance' = " +
                        format_number(reach) + " m of a boundary id " +
                        std::to_string(pair.boundary_b) + " of another body."));
        }
      for (const auto &contact : parameters.obstacle_contacts)
        candidates->add_node_to_obstacle(bodies,
                                         contact.body,
                                         contact.boundary,
                                         *obstacle,
                                         contact.friction_coefficient);
      return candidates;
    }



    // What a contact search during the run needs: the DoFs of the
    // vertices this rank owns (to gather u), and the nodes it may pair,
    // every vertex on a boundary that a pair or an obstacle contact names
    // (the substructured solver's contact DoFs).
    template <int dim>
    void
    DistributedScene<dim>::prepare_contact_searches()
    {
      const IndexSet &owned = body.locally_owned_dofs();
      owned_vertex_dofs.clear();
      for (const auto &cell : body.dof_handler().active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          for (const unsigned int v : cell->vertex_indices())
            if (owned.is_element(cell->vertex_dof_index(v, 0)))
              for (unsigned int d = 0; d < dim; ++d)
                owned_vertex_dofs[cell->vertex_index(v)][d] =
                  cell->vertex_dof_index(v, d);

      reference_vertices.clear();
      for (const auto &serial_body : serial_bodies)
        reference_vertices.push_back(
          serial_body->triangulation().get_vertices());

      std::set<unsigned int> vertices;
      const auto             add_boundary = [&](const unsigned int       b,
                                    const types::boundary_id boundary) {
        for (const auto &cell :
             serial_bodies[b]->triangulation().active_cell_iterators())
          for (const auto &face : cell->face_iterators())
            if (face->at_boundary() && face->boundary_id() == boundary)
              for (const unsigned int i : face->vertex_indices())
                vertices.insert(vertex_offsets[b] + face->vertex_index(i));
      };
      const auto all = numbers::invalid_unsigned_int;
      for (const auto &pair : parameters.body_pairs)
        for (unsigned int b = 0; b < n_bodies(); ++b)
          {
            if (pair.body_a == all || pair.body_a == b)
              add_boundary(b, pair.boundary_a);
            if (pair.body_b == all || pair.body_b == b)
              add_boundary(b, pair.boundary_b);
          }
      for (const auto &touching : parameters.obstacle_contacts)
        add_boundary(touching.body, touching.boundary);
      contact.set_potential_contact_vertices(
        body, std::vector<unsigned int>(vertices.begin(), vertices.end()));
    }



    // @sect4{Contact search during the run}
    // Every `Contact search interval` steps: the bodies' meshes are moved
    // to X + u (u gathered at every vertex on every rank), the candidates
    // are found there as at t = 0, referred back to the reference
    // configuration (ContactSet::refer_to_reference_configuration(): the
    // same gaps, frames of the current configuration), and replace the
    // old ones; a candidate of the same node of body a against body b
    // keeps its predecessor's contact state. The substructured solver's
    // factors stay: its contact DoFs hold every node of the searched
    // boundaries (setup_system()).
    template <int dim>
    void
    DistributedScene<dim>::search_contacts()
    {
      const auto start = std::chrono::steady_clock::now();
      // u at every vertex of the merged mesh, on every rank
      std::vector<double> vertex_displacement(
        body.triangulation().n_vertices() * dim, 0.);
      const DistributedVector &u = solver->displacement();
      for (const auto &[vertex, dofs] : owned_vertex_dofs)
        for (unsigned int d = 0; d < dim; ++d)
          vertex_displacement[vertex * dim + d] = u[dofs[d]];
      Utilities::MPI::sum(vertex_displacement, comm, vertex_displacement);
      const auto displacement = [&](const unsigned int b,
                                    const unsigned int v) {
        std::array<double, 3> x{{0., 0., 0.}};
        for (unsigned int d = 0; d < dim; ++d)
          x[d] = vertex_displacement[(vertex_offsets[b] + v) * dim + d];
        return x;
      };
      // to X + u, or back to X exactly (no drift over many searches)
      const auto move_meshes = [&](const bool displaced) {
        for (unsigned int b = 0; b < serial_bodies.size(); ++b)
          for (const auto &cell :
               serial_bodies[b]->triangulation().active_cell_iterators())
            for (const unsigned int i : cell->vertex_indices())
              {
                const unsigned int          v = cell->vertex_index(i);
                const std::array<double, 3> w = displacement(b, v);
                cell->vertex(i)               = reference_vertices[b][v];
                if (displaced)
                  for (unsigned int d = 0; d < dim; ++d)
                    cell->vertex(i)[d] += w[d];
              }
      };

      move_meshes(true);
      std::unique_ptr<ContactSet> found;
      try
        {
          found = find_candidates(true);
        }
      catch (const ExceptionBase &e)
        {
          AssertThrow(false,
                      ExcMessage("The contact search at t = " +
                                 format_number(solver->time()) +
                                 " s failed: " + exception_text(e)));
        }
      move_meshes(false);
      found->refer_to_reference_configuration(displacement);

      // each new candidate's predecessor: the same node of body a against
      // body b (the k-th of them the k-th, should a node meet a body twice)
      using Key =
        std::tuple<unsigned int, types::global_dof_index, unsigned int>;
      std::map<Key, std::vector<unsigned int>> old_candidates;
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        {
          const auto &candidate = contact.candidate(c);
          old_candidates[{candidate.body_a,
                          candidate.nodes[0].dofs[0],
                          candidate.body_b}]
            .push_back(c);
        }
      const unsigned int old_count = contact.n_candidates();
      contact.setup_from_contact_set(body, *found, vertex_offsets, true);
      std::map<Key, unsigned int> seen;
      std::vector<unsigned int>   previous(contact.n_candidates(),
                                         numbers::invalid_unsigned_int);
      unsigned int                kept = 0;
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        {
          const auto        &candidate = contact.candidate(c);
          const Key          key{candidate.body_a,
                        candidate.nodes[0].dofs[0],
                        candidate.body_b};
          const auto         list = old_candidates.find(key);
          const unsigned int k    = seen[key]++;
          if (list != old_candidates.end() && k < list->second.size())
            {
              previous[c] = list->second[k];
              ++kept;
            }
        }
      solver->candidates_changed(previous);
      ++search_statistics.searches;
      search_statistics.new_candidates += contact.n_candidates() - kept;
      search_statistics.dropped_candidates += old_count - kept;
      search_statistics.fewest =
        std::min(search_statistics.fewest, contact.n_candidates());
      search_statistics.most =
        std::max(search_statistics.most, contact.n_candidates());
      search_statistics.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
    }



    template <int dim>
    double
    DistributedScene<dim>::body_size() const
    {
      if (!parameters.impact)
        return parameters.box.length;
      double extent = 0.;
      for (unsigned int d = 0; d < dim; ++d)
        {
          double lowest  = std::numeric_limits<double>::max(),
                 highest = std::numeric_limits<double>::lowest();
          for (const auto &cell : body.triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              for (const unsigned int v : cell->vertex_indices())
                {
                  lowest  = std::min(lowest, cell->vertex(v)[d]);
                  highest = std::max(highest, cell->vertex(v)[d]);
                }
          extent = std::max(extent,
                            Utilities::MPI::max(highest, comm) +
                              Utilities::MPI::max(-lowest, comm));
        }
      return extent;
    }



    // @sect3{Set-up}
    template <int dim>
    void
    DistributedScene<dim>::setup_system()
    {
      make_grid();
      Tensor<1, dim> g;
      g[1] = -parameters.box.gravity;
      body.set_gravity(g);
      for (unsigned int b = 0; b < parameters.body_materials.size(); ++b)
        body.set_part_material(b, parameters.body_materials[b]);
      body.setup();
      time_stepping.apply_theta_rule(body.cell_transit_time());
      if (parameters.multibody())
        {
          contact.setup_from_contact_set(body,
                                         *serial_candidates,
                                         vertex_offsets,
                                         parameters.search_interval > 0);
          serial_candidates.reset();
          if (parameters.search_interval > 0)
            prepare_contact_searches();
        }
      else
        {
          obstacle = parameters.obstacle.create<dim>(body_size());
          contact.setup(body,
                        parameters.mesh.contact_boundary_id,
                        *obstacle,
                        parameters.obstacle.friction_coefficient);
        }
      // The bodies must not overlap at t = 0: a candidate that starts
      // inside the other side would be pushed out in the first step, an
      // impulse no physics asked for (e.g. a pair of the wrong sides)
      {
        const double size = body_size();
        for (unsigned int c = 0; c < contact.n_candidates(); ++c)
          {
            const auto &candidate = contact.candidate(c);
            if (!(candidate.initial_gap < -1e-9 * size))
              continue;
            std::ostringstream where;
            for (unsigned int d = 0; d < dim; ++d)
              where << (d == 0 ? "(" : ", ") << candidate.position[d];
            where << ")";
            const std::string side_a =
              parameters.multibody() ?
                "body " + std::to_string(candidate.body_a + 1) :
                "the body";
            const std::string side_b =
              candidate.body_b == numbers::invalid_unsigned_int ?
                "the obstacle" :
                "body " + std::to_string(candidate.body_b + 1);
            AssertThrow(false,
                        ExcMessage("The contact candidate of " + side_a +
                                   " at " + where.str() + " starts " +
                                   format_number(-candidate.initial_gap) +
                                   " m inside " + side_b +
                                   ": the bodies overlap at t = 0 (check the "
                                   "meshes, the contact pairs and the "
                                   "obstacle)."));
          }
      }
      // Mass redistribution: every candidate's nodes, on both sides, lose
      // their mass (as ContactScene::redistribute_mass())
      // (with searches during the run: every node a search may pair, so
      // that the mass matrix stays that of the set-up)
      if (parameters.scene.discretization.mass_redistribution)
        {
          std::vector<types::global_dof_index> massless;
          const auto                           add = [&](const auto &node) {
            massless.insert(massless.end(), node.dofs.begin(), node.dofs.end());
          };
          for (const auto &[vertex, node] : contact.potential_contact_nodes())
            add(node);
          for (unsigned int c = 0; c < contact.n_candidates(); ++c)
            for (unsigned int i = 0; i < contact.candidate(c).n_nodes; ++i)
              add(contact.candidate(c).nodes[i]);
          body.redistribute_mass(massless);
        }
      solver = std::make_unique<DistributedImpactSolver<dim>>(
        body,
        contact,
        time_stepping,
        parameters.scene.contact_solver,
        parameters.linear_solver);
      solver->set_dump_directory(parameters.scene.output.directory);
      solver->setup();
      work.reinit(body.locally_owned_dofs(), comm);
      if (parameters.multibody())
        for (unsigned int b = 0; b < n_bodies(); ++b)
          solver->set_initial_velocity(body_launch_velocity(b), b);
      else
        solver->set_initial_velocity(launch_velocity());
      normal[1] = 1.;
      if (!parameters.impact)
        {
          tracker =
            std::make_unique<RigidBlockTracker<dim>>(normal,
                                                     direction(),
                                                     time_stepping.time_step);
          tracker->start(launch_velocity());
        }

      std::vector<std::string> columns = {"time",
                                          "normal_force",
                                          "tangential_force"};
      const char              *axes[]  = {"x", "y", "z"};
      for (unsigned int d = 0; d < dim; ++d)
        columns.push_back(std::string("force_") + axes[d]);
      for (unsigned int d = 0; d < dim; ++d)
        columns.push_back(std::string("momentum_") + axes[d]);
      for (const char *c :
           {"kinetic_energy", "elastic_energy", "active_contacts"})
        columns.push_back(c);
      // several bodies: force_* is the sum over the bodies (zero without
      // an obstacle, as in the serial programs), and each body has its
      // own columns
      if (parameters.multibody())
        for (unsigned int b = 1; b <= n_bodies(); ++b)
          for (const char *quantity : {"_force_", "_momentum_"})
            for (unsigned int d = 0; d < dim; ++d)
              columns.push_back("body_" + std::to_string(b) + quantity +
                                axes[d]);
      // A launch velocity whose kinetic energy overflows (1e308 m/s, say)
      // is refused here, before an earlier run's files are removed; every
      // rank has the same sum, so all stop together.
      {
        require_representable_mass(body.total_mass(), "the bodies");
        const DistributedVector &v = solver->velocity();
        body.mass_matrix().vmult(work, v);
        const double kinetic_energy = 0.5 * (work * v);
        AssertThrow(std::isfinite(kinetic_energy),
                    ExcMessage("Initial conditions: the kinetic energy at "
                               "t = 0 overflows double precision (largest "
                               "initial velocity " +
                               format_number(v.linfty_norm()) +
                               " m/s): the run is not started."));
      }
      on_rank_zero(comm, [&]() {
        create_output_directory(parameters.scene.output.directory);
        // an earlier run's summary and its .pvd/.pvtu/.vtu records, which
        // a run on fewer ranks or with fewer steps would leave beside its own
        // (the broadcast in on_rank_zero() orders this before any rank
        // writes)
        remove_previous_run_output(parameters.scene.output.directory,
                                   {},
                                   {"solution"});
        history = std::make_unique<HistoryWriter>(
          parameters.scene.output.directory + "/history.csv", columns);
      });
    }



    // @sect3{Output}
    // history.csv (rank 0) at every step; the partitioned VTU files and
    // their .pvtu/.pvd records every `Output interval` steps.
    template <int dim>
    void
    DistributedScene<dim>::output_results(const unsigned int step)
    {
      const DistributedVector &u = solver->displacement();
      const DistributedVector &v = solver->velocity();
      body.mass_matrix().vmult(work, v);
      const double kinetic_energy = 0.5 * (work * v);
      body.stiffness_matrix().vmult(work, u);
      const double                elastic_energy = 0.5 * (work * u);
      const Tensor<1, dim>        p = body.momentum(v); // collective
      std::vector<Tensor<1, dim>> per_body;
      if (parameters.multibody())
        for (unsigned int b = 0; b < n_bodies(); ++b)
          per_body.push_back(body_momentum(v, b));
      if (parameters.impact)
        {
          const double energy =
            kinetic_energy + elastic_energy - body.external_force() * u;
          if (step == 0)
            initial_energy = energy;
          else
            largest_increase = std::max(largest_increase, energy - last_energy);
          last_energy = energy;
          largest_stored_energy =
            std::max(largest_stored_energy, kinetic_energy + elastic_energy);
          contact.gaps(u, gaps);
          for (const double g : gaps)
            largest_penetration = std::max(largest_penetration, -g);
        }
      // the row on every rank (its values are the same there), written by
      // rank 0 in on_rank_zero(): its error stops every rank, not rank 0
      // alone, which would leave the others in a collective call
      {
        const double per_impulse = solver->integrator().force_per_impulse();
        // the contact force on body b (none before the first step)
        const auto force = [&](const unsigned int b, const unsigned int d) {
          return b < last_report.body_impulse.size() ?
                   last_report.body_impulse[b][d] * per_impulse :
                   0.;
        };
        std::vector<double> row = {solver->time(),
                                   last_report.normal_impulse * per_impulse,
                                   last_report.tangential_impulse *
                                     per_impulse};
        // the total: the obstacle's reaction (zero between bodies alone)
        for (unsigned int d = 0; d < dim; ++d)
          {
            double total = 0.;
            for (unsigned int b = 0; b < contact.n_bodies(); ++b)
              total += force(b, d);
            row.push_back(total + 0.); // not -0
          }
        for (unsigned int d = 0; d < dim; ++d)
          row.push_back(p[d]);
        row.push_back(kinetic_energy);
        row.push_back(elastic_energy);
        row.push_back(last_report.active_contacts);
        for (unsigned int b = 0; b < per_body.size(); ++b)
          {
            for (unsigned int d = 0; d < dim; ++d)
              row.push_back(force(b, d) + 0.); // not -0
            for (unsigned int d = 0; d < dim; ++d)
              row.push_back(per_body[b][d]);
          }
        on_rank_zero(comm, [&]() { history->add_row(row); });
      }
      // every `Output interval` steps h (a free-flight step may cross a
      // multiple of it)
      const unsigned int interval = parameters.scene.output.output_interval;
      if (!parameters.scene.output.vtu_output ||
          (step > 0 && step / interval == last_vtu_step / interval))
        return;
      last_vtu_step = step;
      // the nodal contact force of the last step: H P times the scheme's
      // force per impulse (the serial programs' contact_force)
      solver->contact_impulse_field(work);
      work *= solver->integrator().force_per_impulse();
      DistributedVector u_ghost, v_ghost, force_ghost;
      for (DistributedVector *ghosted : {&u_ghost, &v_ghost, &force_ghost})
        ghosted->reinit(body.locally_owned_dofs(),
                        body.locally_relevant_dofs(),
                        comm);
      u_ghost     = u;
      v_ghost     = v;
      force_ghost = work;
      DataOut<dim> data_out;
      data_out.attach_dof_handler(body.dof_handler());
      const std::vector<
        DataComponentInterpretation::DataComponentInterpretation>
        vector_field(dim,
                     DataComponentInterpretation::component_is_part_of_vector);
      data_out.add_data_vector(u_ghost,
                               std::vector<std::string>(dim, "displacement"),
                               DataOut<dim>::type_dof_data,
                               vector_field);
      data_out.add_data_vector(v_ghost,
                               std::vector<std::string>(dim, "velocity"),
                               DataOut<dim>::type_dof_data,
                               vector_field);
      data_out.add_data_vector(force_ghost,
                               std::vector<std::string>(dim, "contact_force"),
                               DataOut<dim>::type_dof_data,
                               vector_field);
      Vector<float> subdomain(body.triangulation().n_active_cells());
      for (unsigned int i = 0; i < subdomain.size(); ++i)
        subdomain(i) = body.triangulation().locally_owned_subdomain();
      data_out.add_data_vector(subdomain, "subdomain");
      // several bodies: each cell's body, numbered from 1 as in the
      // parameter file and history.csv
      Vector<float> body_number(body.triangulation().n_active_cells());
      if (parameters.multibody())
        {
          for (const auto &cell : body.triangulation().active_cell_iterators())
            if (cell->is_locally_owned())
              body_number(cell->active_cell_index()) = cell->material_id() + 1;
          data_out.add_data_vector(body_number, "body");
        }
      data_out.build_patches();
      const std::string record = data_out.write_vtu_with_pvtu_record(
        parameters.scene.output.directory + "/", "solution", step, comm, 4);
      vtu_records.emplace_back(solver->time(), record);
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        {
          std::ofstream pvd(parameters.scene.output.directory +
                            "/solution.pvd");
          DataOutBase::write_pvd_record(pvd, vtu_records);
        }
    }



    template <int dim>
    Tensor<1, dim>
    DistributedScene<dim>::body_momentum(const DistributedVector &velocity,
                                         const unsigned int       b)
    {
      return parameters.multibody() ? body.momentum(velocity, b) :
                                      body.momentum(velocity);
    }



    // @sect3{The run}
    // The loop's wall time is measured between barriers (a step is
    // collective). Each step's momentum change of each body is compared
    // with the loads' and the contact impulses (the rigid translations are
    // in the kernel of K, so the balance is exact up to the solves'
    // tolerance); between two bodies the impulse on the first is the
    // opposite of that on the second.
    template <int dim>
    void
    DistributedScene<dim>::run()
    {
      using Clock = std::chrono::steady_clock;
      MPI_Barrier(comm);
      auto start = Clock::now();
      setup_system();
      output_results(0);
      MPI_Barrier(comm);
      setup_seconds =
        std::chrono::duration<double>(Clock::now() - start).count();

      const unsigned int          n_b = n_bodies();
      std::vector<Tensor<1, dim>> load(n_b), p0(n_b), impulses(n_b);
      double                      largest_momentum = 0.;
      for (unsigned int b = 0; b < n_b; ++b)
        {
          for (unsigned int d = 0; d < dim; ++d)
            {
              Tensor<1, dim> e;
              e[d] = 1.;
              work = 0.;
              body.fill_uniform(work,
                                e,
                                parameters.multibody() ?
                                  b :
                                  numbers::invalid_material_id);
              load[b][d] = work * body.external_force();
            }
          p0[b]            = body_momentum(solver->velocity(), b);
          largest_momentum = std::max(largest_momentum, p0[b].norm());
        }
      n_steps = time_stepping.n_steps();
      // the impulses are summed as h F per step, F the step's contact force,
      // as in the serial ContactMonitor: P / w with w the contact force
      // weight (w < 1 for Newmark and massless contact nodes, whose
      // impulse acts over this step and, (1 - w)/w of it, over the next)
      const double w = solver->integrator().contact_force_weight();
      unsigned int steps_since_search = 0;
      // a free-flight step makes k steps h at once, never past the end
      for (unsigned int step = 0; step < n_steps;)
        {
          MPI_Barrier(comm);
          start = Clock::now();
          // searches before the step (the output of a step shows the
          // impulses of its own candidates); a free-flight step never
          // jumps past the next search
          unsigned int most_substeps = n_steps - step;
          if (parameters.search_interval > 0)
            {
              if (steps_since_search >= parameters.search_interval)
                {
                  search_contacts();
                  steps_since_search = 0;
                }
              most_substeps =
                std::min(most_substeps,
                         parameters.search_interval - steps_since_search);
            }
          last_report = solver->do_time_step(most_substeps);
          step += last_report.n_substeps;
          ++n_steps_taken;
          // small sliding keeps the pairs of t = 0: watch that no node
          // slides off the other body's contact boundary
          if (parameters.multibody() && parameters.search_interval == 0)
            largest_slide_off =
              std::max(largest_slide_off,
                       contact.largest_slide_off(solver->displacement()));
          steps_since_search += last_report.n_substeps;
          MPI_Barrier(comm);
          loop_seconds +=
            std::chrono::duration<double>(Clock::now() - start).count();
          normal_impulse += last_report.normal_impulse / w;
          tangential_impulse += last_report.tangential_impulse / w;
          for (unsigned int b = 0; b < n_b; ++b)
            {
              for (unsigned int d = 0; d < dim; ++d)
                impulses[b][d] += last_report.load_coefficient * load[b][d] +
                                  last_report.body_impulse[b][d] +
                                  last_report.carried_impulse[b][d];
              const Tensor<1, dim> p = body_momentum(solver->velocity(), b);
              largest_momentum       = std::max(largest_momentum, p.norm());
              balance_error =
                std::max(balance_error, (p - p0[b] - impulses[b]).norm());
            }
          output_results(step);
          if (!tracker)
            continue;
          const Tensor<1, dim> mean =
            body.momentum(solver->velocity()) / body.total_mass();
          tracker->record(solver->time(),
                          mean,
                          last_report.active_contacts > 0);
          // the direction of sliding until the block first stops, while it
          // slides faster than 1 % of v0 (near the stop the mean velocity is
          // the vibration's; a tall block may rock after it)
          const Tensor<1, dim> s      = direction();
          const double         along  = mean * s;
          const double         across = (mean - along * s).norm();
          if (tracker->stop_time() < 0. &&
              std::hypot(along, across) > 0.01 * parameters.box.speed)
            largest_turn = std::max(largest_turn, std::atan2(across, along));
        }
      // a body that never moves: no momentum to compare with
      balance_error /=
        std::max(largest_momentum, std::numeric_limits<double>::min());
      report_results();
    }



    // @sect3{The report}
    template <int dim>
    void
    DistributedScene<dim>::report_results()
    {
      const DistributedRunStatistics &stats = solver->statistics();
      unsigned int                    owned = 0;
      for (unsigned int c = 0; c < contact.n_candidates(); ++c)
        owned += contact.owns(c) ? 1 : 0;
      const auto owned_range = Utilities::MPI::min_max_avg(double(owned), comm);
      const double mass      = body.total_mass();
      const double speed     = body.momentum(solver->velocity()).norm() / mass;
      const double along =
        body.momentum(solver->velocity()) * direction() / mass;
      const double distance =
        body.momentum(solver->displacement()) * direction() / mass;
      const auto &ts = time_stepping;
      // the friction coefficients of the pairs and obstacle contacts, in
      // the order of the parameter file
      std::string pair_frictions, obstacle_frictions;
      for (const auto &pair : parameters.body_pairs)
        pair_frictions += (pair_frictions.empty() ? "" : ", ") +
                          format_number(pair.friction_coefficient);
      for (const auto &contact : parameters.obstacle_contacts)
        obstacle_frictions += (obstacle_frictions.empty() ? "" : ", ") +
                              format_number(contact.friction_coefficient);
      if (!parameters.multibody())
        obstacle_frictions =
          format_number(parameters.obstacle.friction_coefficient);
      // mass-proportional damping a M acts on the momentum (as in the
      // serial programs, the balance is then not checked)
      bool mass_damping = parameters.material.rayleigh_mass > 0.;
      for (const MaterialParameters &m : parameters.body_materials)
        mass_damping = mass_damping || m.rayleigh_mass > 0.;
      if (parameters.second_body_has_own_material)
        mass_damping =
          mass_damping || parameters.second_material.rayleigh_mass > 0.;
      std::ostringstream out;
      out << (parameters.multibody() ?
                "Impact of " + std::to_string(n_bodies()) + " bodies in " :
              parameters.impact ? "Impact on an obstacle in " :
                                  "Block sliding on a plane in ")
          << dim << "D on " << n_ranks << " MPI rank"
          << (n_ranks > 1 ? "s" : "") << ", scheme " << ts.scheme_description()
          << ", h = " << ts.time_step << " s, " << n_steps << " steps"
          << (stats.free_flight_steps > 0 ?
                " (" + std::to_string(n_steps_taken) + " taken, " +
                  std::to_string(stats.free_flight_steps) + " of them " +
                  std::to_string(ts.free_flight_step_factor) + " h long)" :
                std::string())
          << "\n"
          << "  Mesh: " << body.triangulation().n_global_active_cells()
          << " Q1 cells, " << body.dof_handler().n_dofs() << " DoFs, "
          << contact.n_candidates() << " contact candidates; "
          << (parameters.multibody() && !parameters.body_pairs.empty() ?
                parameters.discretization + " between the bodies, mu = " +
                  pair_frictions + (obstacle ? "; " : "") :
                std::string())
          << (obstacle ? "obstacle: " + obstacle->description() +
                           ", mu = " + obstacle_frictions :
                         std::string())
          << "\n"
          << "  Contact candidates owned per rank: " << owned_range.min
          << " to " << owned_range.max << "\n";
      const auto &searched = search_statistics;
      if (parameters.search_interval > 0)
        out << "  Contact searches: " << searched.searches << " (every "
            << parameters.search_interval << " steps); they added "
            << searched.new_candidates << " candidates and dropped "
            << searched.dropped_candidates << "; "
            << (searched.searches > 0 ?
                  std::to_string(searched.fewest) + " to " +
                    std::to_string(searched.most) +
                    " candidates after a search" :
                  std::string("none made"))
            << "\n";
      double speed_scale = 0.;
      for (unsigned int b = 0; b < n_bodies(); ++b)
        speed_scale = std::max(speed_scale, body_launch_velocity(b).norm());
      if (parameters.multibody())
        for (unsigned int b = 0; b < n_bodies(); ++b)
          {
            const double         m_b = body.part_mass(b);
            const Tensor<1, dim> p_b = body_momentum(solver->velocity(), b);
            const Tensor<1, dim> v_b = body_launch_velocity(b);
            out << "  Body " << b + 1 << ": mass " << format_figure(m_b, 1e-9)
                << " kg, initial velocity (";
            for (unsigned int d = 0; d < dim; ++d)
              out << (d > 0 ? ", " : "") << v_b[d];
            out << ") m/s, mean velocity at the end (";
            for (unsigned int d = 0; d < dim; ++d)
              out << (d > 0 ? ", " : "")
                  << format_figure(p_b[d] / m_b, 1e-9 * speed_scale);
            out << ") m/s\n";
          }
      else if (parameters.impact)
        {
          const Tensor<1, dim> p = body.momentum(solver->velocity());
          out << "  Mass " << format_figure(mass, 1e-9)
              << " kg; initial velocity (";
          for (unsigned int d = 0; d < dim; ++d)
            out << (d > 0 ? ", " : "") << launch_velocity()[d];
          out << ") m/s, mean velocity at the end (";
          for (unsigned int d = 0; d < dim; ++d)
            out << (d > 0 ? ", " : "") << format_figure(p[d] / mass, 1e-9);
          out << ") m/s\n";
        }
      else
        out << "  Mass " << format_figure(mass, 1e-9) << " kg; launched at "
            << parameters.box.speed
            << " m/s in the direction phi = " << parameters.box.phi << " rad\n"
            << "  Largest angle between the mean sliding velocity and the "
               "launch direction: "
            << format_figure(largest_turn, 1e-6) << " rad\n"
            << "  Mean velocity at the end: " << format_figure(speed, 1e-6)
            << " m/s\n";
      out << "  Normal impulse " << format_figure(normal_impulse, 1e-9)
          << ", tangential impulse " << format_figure(tangential_impulse, 1e-9)
          << "\n"
          << (mass_damping ?
                std::string("  Impulse balance: not checked "
                            "(mass-proportional damping acts on the "
                            "momentum)") :
                "  Impulse balance: max |p(t) - p(0) - impulses| / max |p| = " +
                  format_figure(balance_error, 1e-12))
          << "\n"
          << "  Contact problems: " << stats.contact_problems << ", "
          << stats.fallbacks << " fell back to Lemke's method; "
          << "largest violations (Signorini, cone, sliding): "
          << format_figure(stats.largest_signorini, 1e-12) << ", "
          << format_figure(stats.largest_cone, 1e-12) << ", "
          << format_figure(stats.largest_sliding, 1e-12) << "\n";
      if (stats.fallbacks > 0)
        out << "  Last fallback: " << stats.last_fallback_reason << "\n";
      const double largest_violation = std::max(
        {stats.largest_signorini, stats.largest_cone, stats.largest_sliding});
      bool ok = check_figures_are_numbers(
        out,
        {{"impulse balance error", mass_damping ? 0. : balance_error},
         {"contact verification", largest_violation}});
      if (!mass_damping)
        ok &=
          print_check(out,
                      "impulse balance error",
                      balance_error,
                      "<=",
                      parameters.scene.verification.max_impulse_balance_error);
      ok &=
        print_check(out, "contact verification", largest_violation, "<=", 1e-8);
      // a node past the end of the other body's contact boundary is held
      // by that boundary extended (a block sliding on in the air): not a
      // failed check, since small sliding is the scene's own choice, but
      // never silent
      if (parameters.multibody() && parameters.search_interval == 0)
        {
          out << "  Small sliding (the pairs of t = 0): largest slide of a "
                 "node off the other body's contact boundary "
              << format_figure(largest_slide_off, 1e-12)
              << " of that boundary's length\n";
          if (largest_slide_off > 0.01)
            out << "  Warning: nodes slid off the other body's contact "
                   "boundary by more than 1 % of its length; the pairs of "
                   "t = 0 hold them on that boundary extended. "
                << (parameters.several_bodies ?
                      "Set 'Bodies/Contact search interval' to make the "
                      "pairs again during the run.\n" :
                      "Scene = bodies with 'Contact search interval' makes "
                      "the pairs again during the run.\n");
        }
      // relative to the initial energy, or to the largest stored one when
      // the body starts at rest
      const double energy_scale =
        initial_energy > 0. ?
          initial_energy :
          std::max(largest_stored_energy, std::numeric_limits<double>::min());
      const double energy_ratio =
        initial_energy > 0. ?
          last_energy / initial_energy :
          1. + (last_energy - initial_energy) / energy_scale;
      if (parameters.impact)
        {
          const ContactVerificationParameters &bounds =
            parameters.scene.verification;
          out << "  Signorini: largest penetration "
              << format_figure(largest_penetration, 1e-12) << "\n"
              << "  Energy (kinetic + elastic - work of the loads): final / "
                 "initial = "
              << format_figure(energy_ratio, 1e-12)
              << ", largest increase in a step = "
              << format_figure(largest_increase / energy_scale, 1e-12)
              << " of the initial energy\n";
          ok &= check_figures_are_numbers(out,
                                          {{"penetration", largest_penetration},
                                           {"energy increase in a step",
                                            largest_increase / energy_scale},
                                           {"energy ratio", energy_ratio}});
          ok &= print_check(out,
                            "penetration",
                            largest_penetration,
                            "<=",
                            bounds.max_penetration);
          ok &= print_check(out,
                            "energy increase in a step",
                            largest_increase / energy_scale,
                            "<=",
                            bounds.max_energy_increase);
          ok &= print_check(
            out, "energy ratio", energy_ratio, ">=", bounds.min_energy_ratio);
          ok &= print_check(
            out, "energy ratio", energy_ratio, "<=", bounds.max_energy_ratio);
        }
      const RigidSliding rigid(parameters.box.speed,
                               0.,
                               parameters.box.gravity,
                               contact.friction_coefficient(),
                               ts.end_time);
      JsonObject         sliding;
      if (tracker)
        ok &= tracker->report_sliding(out,
                                      rigid,
                                      distance,
                                      along,
                                      ts.end_time,
                                      parameters.box.bounds,
                                      sliding);
      if (parameters.scene.output.print_performance)
        out << "  Wall seconds: set-up " << setup_seconds << ", time loop "
            << loop_seconds << " (" << loop_seconds / n_steps_taken
            << " per step taken); " << stats.active_set_iterations
            << " active set iterations, " << stats.products << " products W x, "
            << stats.cg_iterations << " CG iterations; solves with M~ "
            << stats.solve_seconds << " s, contact problems "
            << stats.contact_problem_seconds << " s (rank 0)"
            << (searched.searches > 0 ?
                  "; contact searches " + format_number(searched.seconds) +
                    " s (rank 0)" :
                  std::string())
            << (stats.contact_schur_groups > 1 ?
                  "; contact Schur complement in " +
                    std::to_string(stats.contact_schur_groups) +
                    " uncoupled blocks" :
                  std::string())
            << (stats.contact_operator == "sparse" ?
                  "; sparse contact operator, preconditioned by its " +
                    stats.contact_preconditioner :
                  std::string())
            << "\n";
      pcout << out.str();

      JsonObject summary;
      summary.add("program", "contact_mpi")
        .add("scene",
             parameters.two_bodies     ? "two bodies" :
             parameters.several_bodies ? "bodies" :
             parameters.impact         ? "impact" :
                                         "sliding block")
        .add("dimension", double(dim))
        .add("ranks", double(n_ranks));
      ts.add_to_summary(summary);
      summary.add("cells", double(body.triangulation().n_global_active_cells()))
        .add("dofs", double(body.dof_handler().n_dofs()))
        .add("contact_candidates", double(contact.n_candidates()))
        .add("n_steps", double(n_steps))
        .add("steps_taken", double(n_steps_taken))
        .add("free_flight_steps", double(stats.free_flight_steps))
        .add("setup_wall_seconds", setup_seconds)
        .add("loop_wall_seconds", loop_seconds)
        .add("final_speed", speed)
        .add("largest_turn", largest_turn)
        .add("normal_impulse", normal_impulse)
        .add("tangential_impulse", tangential_impulse)
        .add("impulse_balance_error", balance_error)
        .add("energy_ratio", energy_ratio)
        .add("max_penetration", largest_penetration)
        .add("contact_problems", double(stats.contact_problems))
        .add("fallbacks", double(stats.fallbacks))
        .add("products", double(stats.products))
        .add("active_set_iterations", double(stats.active_set_iterations))
        .add("cg_iterations", double(stats.cg_iterations))
        .add("solve_wall_seconds", stats.solve_seconds)
        .add("contact_problem_wall_seconds", stats.contact_problem_seconds)
        .add("contact_schur_groups", double(stats.contact_schur_groups))
        .add("contact_operator", stats.contact_operator)
        .add("contact_preconditioner", stats.contact_preconditioner)
        .add("largest_slide_off", largest_slide_off)
        .add("contact_search_interval", double(parameters.search_interval))
        .add("contact_searches", double(searched.searches))
        .add("contact_search_new_candidates", double(searched.new_candidates))
        .add("contact_search_dropped_candidates",
             double(searched.dropped_candidates))
        .add("contact_search_wall_seconds", searched.seconds)
        .add("largest_violation", largest_violation)
        .add("checks_passed", ok ? "yes" : "no");
      if (tracker)
        summary.add("sliding", sliding);
      on_rank_zero(comm, [&]() {
        summary.write(parameters.scene.output.directory + "/summary.json");
        history->close();
        report_output_files(std::cout,
                            parameters.scene.output,
                            parameters.scene.output.vtu_output ?
                              "history.csv, summary.json, solution.pvd" :
                              "history.csv, summary.json",
                            {"normal_force",
                             "tangential_force",
                             "kinetic_energy"},
                            "contact_mpi, " + std::to_string(dim) + "D, " +
                              std::to_string(n_ranks) + " ranks");
      });
      if (parameters.scene.output.print_performance)
        pcout << "RESULT program=contact_mpi dim=" << dim
              << " ranks=" << n_ranks << " dofs=" << body.dof_handler().n_dofs()
              << " contacts=" << contact.n_candidates() << " steps=" << n_steps
              << " seconds_per_step=" << loop_seconds / n_steps_taken
              << " fallbacks=" << stats.fallbacks
              << " searches=" << searched.searches
              << " largest_violation=" << largest_violation << std::endl;
      AssertThrow(ok, ExcMessage("contact_mpi: a check failed (see above)."));
    }


    template class DistributedScene<2>;
    template class DistributedScene<3>;
  } // namespace distributed
} // namespace impactfe
