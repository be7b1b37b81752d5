// Bad input gets one clear message naming the entry or value, and a
// non-zero exit: run the programs on broken parameter files and record
// their exit status and the message they print.

#include <impactfe/lcp/problem_io.h>

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "../tests.h"

namespace
{
  // The message between "Exception on processing:" and "Aborting!".
  std::string
  message_of(const std::string &file)
  {
    std::ifstream in(file);
    std::string   line, message;
    bool          inside = false;
    while (std::getline(in, line))
      {
        if (line.find("Aborting!") != std::string::npos)
          break;
        if (inside && !line.empty())
          message += "  " + line + "\n";
        if (line.find("Exception on processing:") != std::string::npos)
          inside = true;
      }
    return message;
  }

  // A message that ends with a figure of this machine (its memory) is
  // recorded up to @p cut_at.
  void
  run_case(const std::string &name,
           const std::string &prm_text,
           const std::string &executable    = TWO_BARS_1D_EXECUTABLE,
           const std::string &cut_at        = "",
           const std::string &extension     = ".prm",
           const bool         fill_required = true)
  {
    const std::string prm = name + extension;
    // Young's modulus, the density, the time step and the end time have no
    // default (a file that leaves them out is refused): the cases that do
    // not set them get the values they ran with when those were the
    // defaults, at the end of the file so that line numbers stay.
    // taylor_bar has its own subsections and defaults (copper's).
    const auto sets = [&prm_text](const std::string &subsection,
                                  const std::string &entry) {
      const std::string opening = "subsection " + subsection + "\n";
      for (auto at = prm_text.find(opening); at != std::string::npos;
           at      = prm_text.find(opening, at + 1))
        {
               const auto end = prm_text.find("\nend", at);
               if (prm_text.substr(at, end - at).find("set " + entry) !=
              std::string::npos)
            return true;
        }
      return false;
    };
    std::string filled;
    if (fill_required && extension == ".prm" &&
        executable.find("taylor_bar") == std::string::npos)
      for (const auto &[subsection, entries] : std::vector<
             std::pair<std::string,
                       std::vector<std::pair<std::string, std::string>>>>{
             {"Material", {{"Young's modulus", "1"}, {"Density", "1"}}},
             {"Time stepping", {{"Time step", "1e-3"}, {"End time", "1"}}}})
        {
          std::string lines;
          for (const auto &[entry, value] : entries)
            if (!sets(subsection, entry))
              lines += "  set " + entry + " = " + value + "\n";
          if (!lines.empty())
            filled += "subsection " + subsection + "\n" + lines + "end\n";
        }
    if (!prm_text.empty())
      std::ofstream(prm) << prm_text << filled;
    const std::string command =
      executable + " " + prm + " > " + name + ".log 2>&1";
    const int   status  = std::system(command.c_str());
    const int   code    = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::string message = message_of(name + ".log");
    if (!cut_at.empty() && message.find(cut_at) != std::string::npos)
      message = message.substr(0, message.find(cut_at)) + cut_at + "...\n";
    dealii::deallog << name << ": exit code " << code << "\n" << message;
    impactfe_tests::check(code == 1 && !message.empty(),
                          name + ": non-zero exit with a message");
  }

  // Nothing but the message block on the screen: deal.II's readers print
  // inner errors (muParser's, the ABAQUS conversion's stack trace) to
  // std::cerr before they throw.
  void
  check_only_the_message(const std::string &name)
  {
    std::ifstream      in(name + ".log");
    std::ostringstream text;
    text << in.rdbuf();
    const std::string before =
      text.str().substr(0, text.str().find("Exception on processing:"));
    impactfe_tests::check(before.find_first_not_of("-\n") == std::string::npos,
                          name + ": nothing printed before the message");
  }

  // A valid, small run with one entry replaced.
  std::string
  with(const std::string &subsection, const std::string &entry)
  {
    std::ostringstream s;
    s << "subsection Output\n  set Output directory = results\n"
      << "  set VTU output = false\n  set Plot = false\nend\n"
      << "subsection " << subsection << "\n  set " << entry << "\nend\n";
    return s.str();
  }
} // namespace

int
main()
{
  impactfe_tests::initlog();
  run_case("unknown_scheme", with("Time stepping", "Scheme = runge-kutta"));
  run_case("theta_zero", with("Time stepping", "Theta = 0"));
  run_case("theta_above_one", with("Time stepping", "Theta = 1.5"));
  // below 1/2 only conditionally stable; the value is printed as given
  run_case("theta_below_half", with("Time stepping", "Theta = 0.3"));
  run_case("theta_just_above_one", with("Time stepping", "Theta = 1.0000001"));
  // no step would end within the run (it used to make 0 steps, exit 0)
  run_case("time_step_longer_than_end_time",
           with("Time stepping", "Time step = 0.1\n  set End time = 0.02"));
  run_case("theta_not_a_number", with("Time stepping", "Theta = abc"));
  // the Courant rule: kappa must be positive, and Newmark has no theta
  run_case("theta_rule_unknown", with("Time stepping", "Theta rule = auto"));
  run_case("theta_damping_zero",
           with("Time stepping",
                "Theta rule = courant\n  set Theta damping = 0"));
  run_case("theta_rule_courant_newmark",
           with("Time stepping",
                "Theta rule = courant\n  set Scheme = newmark"));
  run_case("negative_time_step", with("Time stepping", "Time step = -1e-6"));
  run_case("zero_end_time", with("Time stepping", "End time = 0"));
  run_case("newmark_beta_zero", with("Time stepping", "Newmark beta = 0"));
  run_case("newmark_beta_below_half_gamma",
           with("Time stepping", "Newmark beta = 0.1"));
  run_case("free_flight_factor_zero",
           with("Time stepping", "Free-flight step factor = 0"));
  run_case("free_flight_factor_huge",
           with("Time stepping", "Free-flight step factor = 2000000000"));
  run_case("newmark_mass_redistribution",
           with("Time stepping", "Scheme = newmark") +
             "subsection Discretization\n  set Mass redistribution = true\n"
             "end\n");
  run_case("zero_modulus", with("Material", "Young's modulus = 0"));
  run_case("negative_density", with("Material", "Density = -7800"));
  run_case("negative_gap", with("Geometry", "Initial gap = -0.01"));
  // a load so large that the state overflows in the first steps: the
  // history's check names the time and the entries to look at (steps
  // so long that the state overflowed now meet the Courant limit first)
  run_case("state_overflows",
           with("Loads", "Gravity = 0, -1e307"),
           BLOCK_ON_PLANE_EXECUTABLE);
  // An impact velocity whose kinetic energy overflows, in the folder of
  // an earlier, finished run: refused before anything is written, so the
  // earlier run's files stay as they were.
  {
    const std::string rerun = "subsection Output\n"
                              "  set Output directory = bars_rerun\n"
                              "  set Plot = false\nend\n";
    std::ofstream("bars_rerun_finished.prm")
      << rerun
      << "subsection Material\n  set Young's modulus = 1\n  set Density = "
         "1\nend\nsubsection Time stepping\n  set Time step = 1e-3\n  set "
         "End time = 0.1\nend\n";
    const int finished =
      std::system(TWO_BARS_1D_EXECUTABLE " bars_rerun_finished.prm > "
                                         "bars_rerun_finished.log 2>&1");
    const auto contents = [](const std::string &file) {
      std::ifstream      in(file);
      std::ostringstream text;
      text << in.rdbuf();
      return text.str();
    };
    const std::string history = contents("bars_rerun/history.csv");
    const std::string summary = contents("bars_rerun/summary.json");
    impactfe_tests::check(finished == 0 && !history.empty() &&
                            !summary.empty() &&
                            std::filesystem::exists(
                              "bars_rerun/bar_1-00100.vtu"),
                          "two_bars_1d: the first run writes its files");
    run_case("kinetic_energy_overflows",
             rerun + "subsection Initial conditions\n"
                     "  set Impact velocity = 1e308\nend\n");
    impactfe_tests::check(
      contents("bars_rerun/history.csv") == history &&
        contents("bars_rerun/summary.json") == summary &&
        std::filesystem::exists("bars_rerun/bar_1-00100.vtu"),
      "two_bars_1d: the refused run leaves the earlier run's history, "
      "summary and VTU files as they were");
  }
  // deal.II keeps the last of two values silently: refused, with both
  // lines
  run_case("entry_set_twice",
           with("Time stepping", "Theta = 0.55\n  set Theta = 0.6"));
  run_case("misspelt_entry", with("Time stepping", "Tme step = 1e-6"));
  run_case("misspelt_subsection", with("Time steping", "Time step = 1e-6"));
  run_case("missing_file", "");
  // deal.II's messages for these do not name the file
  std::filesystem::create_directory("parameter_file_is_a_directory.prm");
  run_case("parameter_file_is_a_directory", "");
  // include statements: deal.II recursed on a file that includes itself
  // until the stack overflowed.
  run_case("include_itself",
           "include include_itself.prm\n" +
             with("Time stepping", "Theta = 0.55"));
  std::ofstream("include_b.prm") << "include include_cycle.prm\n";
  run_case("include_cycle",
           "include include_b.prm\n" + with("Time stepping", "Theta = 0.55"));
  run_case("include_missing",
           "include no_such_file.prm\n" +
             with("Time stepping", "Theta = 0.55"));
  // an entry set before an include that sets it again: the included value
  // would win silently (set after the include, it is an override)
  std::ofstream("sets_theta.prm")
    << "subsection Time stepping\n  set Theta = 0.55\nend\n";
  run_case("entry_set_before_an_include",
           with("Time stepping", "Theta = 0.6") + "include sets_theta.prm\n");
  // Boost's JSON and XML readers said "<unspecified file>"
  run_case("json_not_closed",
           "{\"Time stepping\": {\"Theta\": \"0.5\"\n",
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".json");
  run_case("xml_not_closed",
           "<?xml version=\"1.0\"?>\n<ParameterHandler><Time_20stepping>"
           "<Theta><value>0.5</val\n",
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".xml");
  // an entry set twice, in one object (a key twice) or in a subsection
  // given twice under its plain and its mangled name
  run_case("json_entry_set_twice",
           "{\"Material\": {\"Young's modulus\": \"1\", \"Density\": \"1\"},\n"
           " \"Time stepping\": {\"Time step\": \"1e-3\", \"End time\": "
           "\"1\"},\n"
           " \"Time_20stepping\": {\"End_20time\": {\"value\": \"2\"}}}\n",
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".json");
  {
    // but a subsection given twice with other entries is fine
    std::ofstream("json_subsection_twice.json")
      << "{\"Material\": {\"Young's modulus\": \"1\", \"Density\": "
         "\"1\"},\n \"Time stepping\": {\"Time step\": \"1e-3\"},\n "
         "\"Time_20stepping\": {\"End_20time\": {\"value\": \"0.01\"}},\n "
         "\"Output\": {\"Output directory\": \"json_run\", \"VTU "
         "output\": \"false\", \"Plot\": \"false\"}}\n";
    const int status =
      std::system(TWO_BARS_1D_EXECUTABLE " json_subsection_twice.json > "
                                         "json_subsection_twice.log 2>&1");
    impactfe_tests::check(status == 0 &&
                            std::filesystem::exists("json_run/summary.json"),
                          "a JSON file with a subsection given twice (other "
                          "entries) runs");
  }
  run_case("xml_entry_set_twice",
           "<?xml version=\"1.0\"?>\n<ParameterHandler><Time_20stepping>"
           "<Theta><value>0.6</value></Theta><Theta><value>0.7</value>"
           "</Theta></Time_20stepping></ParameterHandler>\n",
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".xml");
  run_case("parameter_file_extension",
           with("Time stepping", "Theta = 0.55"),
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".txt");

  // The 2D programs: meshes, obstacles, friction, contact boundaries.
  const std::string cylinder = CYLINDER_IMPACT_EXECUTABLE;
  const std::string plate    = OBLIQUE_PLATE_EXECUTABLE;
  const std::string bars_2d  = TWO_BARS_2D_EXECUTABLE;
  run_case("missing_mesh_file",
           with("Mesh", "Mesh file = no_such_mesh.msh"),
           cylinder);
  run_case("empty_contact_boundary",
           with("Mesh", "Contact boundary id = 7"),
           cylinder);
  run_case("negative_friction",
           with("Obstacle", "Friction coefficient = -0.1"),
           cylinder);
  run_case("friction_too_large_for_the_verification",
           with("Obstacle", "Friction coefficient = 1e14"),
           cylinder);
  run_case("negative_ball_radius",
           with("Obstacle", "Type = ball\n  set Radius = -1"),
           cylinder);
  run_case("bad_level_set",
           with("Obstacle", "Type = level set\n  set Level set = y+*2"),
           cylinder);
  check_only_the_message("bad_level_set");
  // finite at the nodes, NaN on the surface below them (y = 0)
  run_case("level_set_undefined_on_its_surface",
           with("Obstacle",
                "Type = level set\n  set Level set = y + 0*sqrt(y - 1)"),
           cylinder);
  // a modulus whose element matrices overflow: the message names it
  run_case("stiffness_overflows",
           with("Material", "Young's modulus = 1e305"),
           plate);
  run_case("odd_core_cells",
           with("Geometry", "Number of core cells = 5"),
           cylinder);
  run_case("upward_plate_velocity",
           with("Initial conditions", "Vertical velocity = 5"),
           plate);
  run_case("plate_below_obstacle",
           with("Obstacle", "Point on plane = 0, 0.001"),
           plate);
  run_case("offset_needs_node_to_segment",
           with("Geometry", "Interface mesh offset = 0.5"),
           bars_2d);
  // deal.II's string_to_double refused the subnormal number without
  // naming the entry; now it is read, and the normal is too short
  run_case("plane_normal_subnormal",
           with("Obstacle", "Normal = 0, 1e-320"),
           plate);
  run_case("plane_normal_not_a_number",
           with("Obstacle", "Normal = 0, 1e400"),
           plate);
  // a snapshot after the last step would never be written
  run_case("shape_snapshot_after_end",
           with("Output", "Shape snapshot times = 0.1, 7") +
             "subsection Time stepping\n  set End time = 0.5\nend\n",
           cylinder);
  run_case("plane_normal_with_three_coordinates",
           with("Obstacle", "Normal = 0, 1, 0"),
           plate);

  // Broken Gmsh files: the message names the section and the line, not
  // the next marker (deal.II's reader said "The string <$Nodes> is not
  // recognized", with its stack trace), and a quad with three nodes gets
  // deal.II's message without the trace.
  std::ofstream("short_node_line.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
       "2 1 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n";
  run_case("mesh_node_line_too_short",
           with("Mesh", "Mesh file = short_node_line.msh"),
           cylinder);
  std::ofstream("truncated.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
       "2 1 0 0\n";
  run_case("mesh_truncated_in_nodes",
           with("Mesh", "Mesh file = truncated.msh"),
           cylinder);
  std::ofstream("node_count.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
       "2 1 0 0\n3 1 1 0\n$EndNodes\n";
  run_case("mesh_node_count_wrong",
           with("Mesh", "Mesh file = node_count.msh"),
           cylinder);
  std::ofstream("quad_with_three_nodes.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
       "2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n$Elements\n1\n"
       "1 3 2 0 1 1 2 3\n$EndElements\n";
  run_case("mesh_quad_with_three_nodes",
           with("Mesh", "Mesh file = quad_with_three_nodes.msh"),
           cylinder);

  // Meshes of simplices (GridIn reads them): Q1 needs quadrilaterals and
  // hexahedra. The tetrahedron used to crash block_sliding_3d.
  std::ofstream("triangle.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n"
       "2 1 0 0\n3 0 1 0\n$EndNodes\n$Elements\n1\n1 2 2 1 1 1 2 3\n"
       "$EndElements\n";
  run_case("triangle_mesh", with("Mesh", "Mesh file = triangle.msh"), cylinder);
  std::ofstream("tetrahedron.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
       "2 0.1 0 0\n3 0 0.01 0\n4 0 0 0.1\n$EndNodes\n$Elements\n1\n"
       "1 4 2 1 1 1 2 3 4\n$EndElements\n";
  run_case("tetrahedral_mesh",
           with("Mesh", "Mesh file = tetrahedron.msh"),
           BLOCK_SLIDING_3D_EXECUTABLE);
  // Two quadrilaterals side by side, made wrong four ways: the second
  // names node 2 twice (a degenerate cell: the set-up crashed); node 2 is
  // defined twice (deal.II kept the second silently); the second has its
  // own nodes on the common edge (a cut body, taken silently); a
  // twisted quadrilateral (zero area here; in a larger mesh deal.II's
  // orientation of the cells fails, with a message about library bugs,
  // which is replaced).
  const std::string two_quads_nodes =
    "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n1 0 0 0\n2 1 0 "
    "0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2 1 0\n$EndNodes\n";
  std::ofstream("repeated_node.msh")
    << two_quads_nodes
    << "$Elements\n2\n1 3 2 1 1 1 2 5 4\n2 3 2 1 1 2 2 6 5\n$EndElements\n";
  run_case("mesh_cell_names_a_node_twice",
           with("Mesh", "Mesh file = repeated_node.msh"),
           cylinder);
  std::ofstream("node_defined_twice.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 "
       "0\n2 1 1 0\n4 0 1 0\n$EndNodes\n$Elements\n1\n1 3 2 1 1 1 2 2 "
       "4\n$EndElements\n";
  run_case("mesh_node_defined_twice",
           with("Mesh", "Mesh file = node_defined_twice.msh"),
           cylinder);
  std::ofstream("not_merged.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n1 0 0 0\n2 1 0 "
       "0\n3 1 1 0\n4 0 1 0\n5 1 0 0\n6 2 0 0\n7 2 1 0\n8 1 1 "
       "0\n$EndNodes\n$Elements\n2\n1 3 2 1 1 1 2 3 4\n2 3 2 1 1 5 6 7 "
       "8\n$EndElements\n";
  run_case("mesh_parts_not_merged",
           with("Mesh", "Mesh file = not_merged.msh"),
           cylinder);
  std::ofstream("twisted.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n2 1 0 "
       "0\n3 0 1 0\n4 1 1 0\n$EndNodes\n$Elements\n1\n1 3 2 1 1 1 2 3 "
       "4\n$EndElements\n";
  run_case("mesh_twisted_cell",
           with("Mesh", "Mesh file = twisted.msh"),
           cylinder);
  // A hexahedron with all its nodes in the plane y = 0: zero volume.
  std::ofstream("flat_hexahedron.msh")
    << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n8\n1 0 0 0\n"
       "2 0.1 0 0\n3 0.1 0 0.1\n4 0 0 0.1\n5 0 0 0\n6 0.1 0 0\n"
       "7 0.1 0 0.1\n8 0 0 0.1\n$EndNodes\n$Elements\n1\n"
       "1 5 2 1 1 1 2 3 4 5 6 7 8\n$EndElements\n";
  run_case("flat_hexahedral_mesh",
           with("Mesh", "Mesh file = flat_hexahedron.msh"),
           BLOCK_SLIDING_3D_EXECUTABLE);

  // Other formats and a directory: deal.II's messages said "an error
  // message printed above" (with a stack trace there), gave a page on
  // input/output errors, or complained about the Gmsh string "<>".
  std::ofstream("garbage.inp") << "garbage here\n1 2 3\n";
  run_case("mesh_abaqus_garbage",
           with("Mesh", "Mesh file = garbage.inp"),
           cylinder);
  check_only_the_message("mesh_abaqus_garbage");
  std::ofstream("garbage.ucd") << "garbage here\n1 2 3\n";
  run_case("mesh_ucd_garbage",
           with("Mesh", "Mesh file = garbage.ucd"),
           cylinder);
  std::filesystem::create_directory("mesh_directory.msh");
  run_case("mesh_file_is_a_directory",
           with("Mesh", "Mesh file = mesh_directory.msh"),
           cylinder);

  // Gmsh's format 4: deal.II's reader trusts the counts of the entity
  // blocks, and a file with a format-2 body under a 4.1 header made it
  // write nodes past its array (a crash) or read until memory ran out.
  std::ofstream("format_2_body.msh")
    << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n4\n1 0 0 0\n"
       "2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n$Elements\n1\n"
       "1 3 2 0 1 1 2 3 4\n$EndElements\n";
  run_case("mesh_gmsh4_header_format_2_body",
           with("Mesh", "Mesh file = format_2_body.msh"),
           cylinder);
  std::ofstream("gmsh4_block_count.msh")
    << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n"
       "2 1 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n"
       "0.5 0.5 0\n$EndNodes\n";
  run_case("mesh_gmsh4_node_block_too_long",
           with("Mesh", "Mesh file = gmsh4_block_count.msh"),
           cylinder);
  // An entity block names its entity by dimension and tag (4.1) or tag
  // and dimension (4.0): a 4.0 file with 4.1's order gave deal.II the
  // dimension 7 (a crash); an undeclared entity or elements of another
  // dimension would give wrong boundary ids.
  const std::string entities_of_square =
    "$Entities\n0 1 1 0\n1 0 0 0 1 0 0 1 1 0\n2 0 0 0 1 1 0 0 0\n"
    "$EndEntities\n";
  // the surface has the tag 7: its node block "2 7" is in 4.1's order
  std::ofstream("gmsh40_in_41_order.msh")
    << "$MeshFormat\n4 0 8\n$EndMeshFormat\n$Entities\n0 1 1 0\n"
       "1 0 0 0 1 0 0 1 1 0\n7 0 0 0 1 1 0 0 0\n$EndEntities\n"
       "$Nodes\n1 4\n2 7 0 4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n"
       "$EndNodes\n";
  run_case("mesh_gmsh40_block_in_41_order",
           with("Mesh", "Mesh file = gmsh40_in_41_order.msh"),
           cylinder);
  std::ofstream("gmsh4_undeclared_entity.msh")
    << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    << entities_of_square
    << "$Nodes\n1 4 1 4\n2 3 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n"
       "0 1 0\n$EndNodes\n";
  run_case("mesh_gmsh4_undeclared_entity",
           with("Mesh", "Mesh file = gmsh4_undeclared_entity.msh"),
           cylinder);
  std::ofstream("gmsh4_element_dimension.msh")
    << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    << entities_of_square
    << "$Nodes\n1 4 1 4\n2 2 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n"
       "0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n1 1 3 1\n1 1 2 3 4\n"
       "$EndElements\n";
  run_case("mesh_gmsh4_element_dimension",
           with("Mesh", "Mesh file = gmsh4_element_dimension.msh"),
           cylinder);
  // a partitioned file's blocks belong to entities that deal.II skips
  std::ofstream("gmsh4_partitioned.msh")
    << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"
    << entities_of_square << "$PartitionedEntities\n2\n0\n";
  run_case("mesh_gmsh4_partitioned",
           with("Mesh", "Mesh file = gmsh4_partitioned.msh"),
           cylinder);
  std::ofstream("gmsh4_binary.msh") << "$MeshFormat\n4.1 1 8\n";
  run_case("mesh_gmsh_binary",
           with("Mesh", "Mesh file = gmsh4_binary.msh"),
           cylinder);

  // 25 contacts are within 'Largest Lemke fallback' = 100 as candidates,
  // and one facet LCP of theirs (250 unknowns) within its 300 unknowns,
  // but not the exact cone's two: the run stops at once instead of
  // pivoting on a problem too large for the limit.
  std::filesystem::remove("results/lcp_failure_step_1.dat");
  run_case("block_3d_fallback_lcp_too_large",
           with("Contact solver",
                "Method = active set\n  set Active set iterations = 1\n"
                "  set Active set front iterations = 0\n"
                "  set Largest Lemke fallback = 100"),
           BLOCK_SLIDING_3D_EXECUTABLE);
  // The step that was not solved is written for replay, although the
  // active set method never formed W: its 25 contacts with the scene's mu,
  // and W symmetric, as a Delassus operator is.
  {
    const impactfe::lcp::ProblemFile file =
      impactfe::lcp::read_problem_file("results/lcp_failure_step_1.dat");
    const impactfe::lcp::ContactProblem &problem   = file.contact;
    double                               asymmetry = 0., largest = 0.;
    for (std::size_t i = 0; i < problem.W.n_rows(); ++i)
      for (std::size_t j = 0; j < problem.W.n_rows(); ++j)
        {
          asymmetry =
            std::max(asymmetry, std::abs(problem.W(i, j) - problem.W(j, i)));
          largest = std::max(largest, std::abs(problem.W(i, j)));
        }
    dealii::deallog << "written: " << problem.n_contacts << " contacts, "
                    << problem.n_directions << " directions, mu "
                    << problem.mu[0] << "\n";
    impactfe_tests::check(
      file.type == impactfe::lcp::ProblemType::friction_contact &&
        problem.n_contacts == 25 && problem.n_directions == 3 &&
        problem.W.n_rows() == 75 && largest > 0. &&
        asymmetry <= 1e-12 * largest,
      "block_3d_fallback_lcp_too_large: the unsolved problem written");
  }

  // A mesh that cannot be built stops before deal.II tries: 2^31 cells
  // overflow its indices; 1.6e7 hexahedra need 560 GB.
  run_case("cells_beyond_32_bit_indices",
           with("Geometry", "Number of cells per bar = 2000000000"));
  run_case("mesh_larger_than_memory",
           with("Geometry",
                "Number of cells along x = 400\n  set Number of cells up = "
                "100\n  set Number of cells along z = 400"),
           BLOCK_SLIDING_3D_EXECUTABLE,
           "this machine has");

  // The 3D plate: the friction cone and the contact boundary.
  const std::string plate_3d = OBLIQUE_PLATE_3D_EXECUTABLE;
  run_case("odd_number_of_facets",
           with("Contact solver", "Number of facets = 5"),
           plate_3d);
  run_case("too_many_facets",
           with("Contact solver", "Number of facets = 258"),
           plate_3d);
  run_case("two_facets_in_3d",
           with("Contact solver", "Number of facets = 2"),
           plate_3d);
  run_case("unknown_friction_cone",
           with("Contact solver", "Friction cone = round"),
           plate_3d);
  run_case("zero_exact_cone_tolerance",
           with("Contact solver", "Exact cone tolerance = 0"),
           plate_3d);
  run_case("plate_3d_missing_contact_boundary",
           with("Mesh", "Contact boundary id = 7"),
           plate_3d);

  // block_on_plane: its geometry, loads, second body and final phase.
  const std::string block = BLOCK_ON_PLANE_EXECUTABLE;
  run_case("block_negative_height", with("Geometry", "Height = -0.05"), block);
  run_case("block_negative_gap",
           with("Geometry", "Initial gap = -1e-3"),
           block);
  run_case("block_gravity_with_one_component",
           with("Loads", "Gravity = -9.81"),
           block);
  run_case("block_body_2_wider",
           with("Body 2", "Enabled = true\n  set Width = 0.2"),
           block);
  run_case("block_body_2_negative_gap",
           with("Body 2", "Enabled = true\n  set Gap above body 1 = -0.01"),
           block);
  run_case("block_body_2_zero_density",
           with("Material of body 2", "Density = 0"),
           block);
  // Young's modulus, the density, the time step and the end time have no
  // default (they were 1 Pa, 1 kg/m^3, 1 ms and 1 s: a file without them
  // ran, silently wrong); a second body's material must be set when the
  // body is in the scene
  const std::string time_stepping =
    "subsection Time stepping\n  set Time step = 1e-3\n"
    "  set End time = 1\nend\n";
  run_case("missing_youngs_modulus",
           with("Material", "Density = 7800") + time_stepping,
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".prm",
           false);
  run_case("missing_material",
           with("Time stepping", "Theta = 0.55") + time_stepping,
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".prm",
           false);
  run_case("missing_time_step",
           with("Time stepping", "End time = 2e-4") +
             "subsection Material\n  set Young's modulus = 1\n"
             "  set Density = 1\nend\n",
           TWO_BARS_1D_EXECUTABLE,
           "",
           ".prm",
           false);
  run_case("block_body_2_material_not_set",
           with("Body 2", "Enabled = true"),
           block);
  run_case("block_unknown_contact_method",
           with("Contact solver", "Method = newton"),
           block);
  run_case("block_active_set_without_fallback",
           with("Contact solver",
                "Method = active set\n  set Active set iterations = 1\n"
                "  set Active set front iterations = 0\n"
                "  set Largest Lemke fallback = 0"),
           block);
  run_case("block_final_phase_after_end",
           with("Verification", "Start of the final phase = 2"),
           block);
  run_case("block_zero_normal",
           with("Obstacle",
                "Type = ball\n  set Normal = 0, 0\n  set Center "
                "= 0, -1"),
           block);

  // hertz_impact: the graded ball's data.
  const std::string hertz = HERTZ_IMPACT_EXECUTABLE;
  run_case("hertz_zero_pole_cell_factor",
           with("Geometry", "Pole cell factor = 0"),
           hertz);
  run_case("hertz_fine_zone_over_the_sphere",
           with("Geometry", "Pole cell factor = 0.05"),
           hertz);
  run_case("hertz_inverted_graded_cell",
           with("Geometry",
                "Number of refinements = 3\n  set Pole cell factor = 0.2"),
           hertz);

  // hertz_on_block: a block narrower than the ball, a shrinking grading.
  const std::string hertz_on_block = HERTZ_ON_BLOCK_EXECUTABLE;
  run_case("hertz_on_block_narrow_block",
           with("Geometry", "Block half width = 0.005"),
           hertz_on_block);
  run_case("hertz_on_block_growth_below_one",
           with("Geometry", "Block growth factor = 0.8"),
           hertz_on_block);
  run_case("hertz_on_block_centre_cell_over_the_block",
           with("Geometry", "Block centre cell size = 0.05"),
           hertz_on_block);
  run_case("hertz_negative_peak_force_bound",
           with("Verification", "Maximum peak force error = -0.5"),
           hertz_on_block);
  // every verification bound: -1 is "no check", another negative value
  // is refused (it used to switch the check off without a word)
  run_case("negative_penetration_bound",
           with("Verification", "Maximum penetration = -0.5"));
  run_case("negative_gap_drift_bound",
           with("Verification", "Maximum gap drift = -2"),
           block);
  // a dump of step 0 or of a step after the end would write nothing
  run_case("dump_lcp_of_step_zero",
           with("Contact solver", "Dump LCP of step = 0"));
  run_case("dump_lcp_of_step_after_the_end",
           with("Contact solver", "Dump LCP of step = 2000000000"));

  // taylor_bar: the finite-strain program's own entries.
  const std::string taylor = TAYLOR_BAR_EXECUTABLE;
  run_case("taylor_theta_below_half", with("Time", "Theta = 0.3"), taylor);
  // a density of 1e-20 kg/m^3: a Courant number near 1e10, whose step
  // matrix kept no digits (on two ranks its factorisation failed, on one
  // the run ended with an impulse balance error of 196 and exit code 0)
  run_case("courant_number_above_1e6",
           with("Material", "Density = 1e-20"),
           cylinder);
  // taylor_bar used to accept these and ignore them without a word: it
  // writes no mesh files, and its J2 material has no viscosity
  run_case("taylor_write_meshes",
           with("Output", "Write meshes = true"),
           taylor);
  run_case("taylor_viscosity", with("Material", "Viscosity = 1e9"), taylor);
  // A run that stops at a step (an element inverted at 2000 m/s) in the
  // folder of an earlier, finished run: the earlier run's summary and final
  // cells are removed at the start, so that the folder holds one run's
  // files (its own history up to the failing step), not a mix of two.
  {
    const std::string rerun = "subsection Output\n"
                              "  set Output directory = taylor_rerun\n"
                              "  set VTU output = false\nend\n"
                              "subsection Time\n  set End time = 2e-6\nend\n";
    std::ofstream("taylor_rerun_finished.prm") << rerun;
    const int finished =
      std::system((std::string(TAYLOR_BAR_EXECUTABLE) +
                   " taylor_rerun_finished.prm > taylor_rerun_finished.log "
                   "2>&1")
                    .c_str());
    impactfe_tests::check(
      finished == 0 && std::filesystem::exists("taylor_rerun/summary.json") &&
        std::filesystem::exists("taylor_rerun/cells_final.csv"),
      "taylor_bar: the first run finishes and writes its "
      "summary and final cells");
    run_case("taylor_stops_at_a_step",
             rerun + "subsection Initial conditions\n"
                     "  set Impact velocity = 2000\nend\n",
             taylor);
    impactfe_tests::check(
      !std::filesystem::exists("taylor_rerun/summary.json") &&
        !std::filesystem::exists("taylor_rerun/cells_final.csv") &&
        std::filesystem::exists("taylor_rerun/history.csv"),
      "taylor_bar: after the stopped run the folder holds its history and "
      "no summary or final cells of the run before");
  }
  run_case("taylor_negative_time_step",
           with("Time", "Time step = -1e-7"),
           taylor);
  // no step would end within the run (it made 0 steps and exited 0)
  run_case("taylor_time_step_longer_than_end_time",
           with("Time", "Time step = 1e-3"),
           taylor);
  run_case("taylor_zero_yield_stress",
           with("Plasticity", "Yield stress = 0"),
           taylor);
  // shapes.csv is written by the 2D programs only
  run_case("taylor_shape_snapshot_times",
           with("Output", "Shape snapshot times = 1e-5"),
           taylor);
  run_case("taylor_negative_hardening",
           with("Plasticity", "Hardening modulus = -1e6"),
           taylor);
  run_case("taylor_negative_friction",
           with("Contact", "Friction coefficient = -0.1"),
           taylor);
  run_case("taylor_rebound_check_with_poisson",
           with("Verification", "Elastic rebound check = true"),
           taylor);
  run_case("taylor_newton_not_converged",
           with("Discretisation", "Maximum Newton iterations = 1"),
           taylor);
  // 3000 m/s and h = 1e-6 s: the first Newton iterate turns the front
  // cells inside out; the message names the step
  run_case("taylor_inverted_element",
           with("Initial conditions", "Impact velocity = 3000") +
             "subsection Time\n  set Time step = 1e-6\nend\n",
           taylor);
  run_case("taylor_3d_with_friction",
           with("Geometry", "Model = 3d") +
             "subsection Contact\n  set Friction coefficient = 0.2\nend\n",
           taylor);
  run_case("taylor_3d_radial_cells_not_a_power_of_two",
           with("Geometry", "Model = 3d") +
             "subsection Geometry\n  set Radial cells = 3\nend\n",
           taylor);
  // two_bars_3d: non-matching interface meshes need node-to-face.
  run_case("two_bars_3d_nonmatching_node_to_node",
           with("Geometry", "Number of cells across bar 2 = 3"),
           TWO_BARS_3D_EXECUTABLE);
  // contact_mpi on two ranks: every rank meets the error, rank 0
  // prints it, all exit with 1 (no rank is left waiting).
  const std::string mpi = MPIEXEC_TWO_RANKS " " BLOCK_SLIDING_MPI_EXECUTABLE;
  run_case("mpi_missing_density",
           with("Material", "Young's modulus = 1e9"),
           mpi,
           "",
           ".prm",
           false);
  // data that overflow at set-up: refused on every rank, before any output
  run_case("mpi_kinetic_energy_overflows",
           with("Initial conditions", "Sliding speed = 1e308"),
           mpi);
  run_case("mpi_stiffness_overflows",
           with("Material", "Young's modulus = 1e306"),
           mpi);
  run_case("mpi_more_ranks_than_cells",
           with("Geometry",
                "Number of cells along x = 1\n  set Number of cells along z "
                "= 1"),
           mpi);
  run_case("mpi_newmark_mass_redistribution",
           with("Time stepping", "Scheme = newmark") +
             "subsection Discretization\n  set Mass redistribution = true\n"
             "end\n",
           mpi);
  run_case("mpi_empty_contact_boundary",
           with("Mesh", "Contact boundary id = 7"),
           mpi);
  run_case("mpi_2d_oblique_direction",
           "set Dimension = 2\n" +
             with("Obstacle", "Point on plane = 0, 0\n  set Normal = 0, 1") +
             "subsection Initial conditions\n  set Sliding direction = "
             "0.6\nend\n",
           mpi);
  // rank 0 cannot write its files: the others must not wait for it
  run_case("mpi_unwritable_output_directory",
           "subsection Output\n  set Output directory = "
           "/proc/impactfe_cannot_write_here\n  set VTU output = false\n"
           "end\n",
           mpi);
  // taylor_bar on two ranks: a cell inverted by too long a step is found
  // by the rank that owns it; every rank stops, rank 0 gives its message
  run_case("taylor_bar_inverted_cell_on_two_ranks",
           with("Time", "Time step = 4e-6\n  set End time = 20e-6"),
           MPIEXEC_TWO_RANKS " " TAYLOR_BAR_EXECUTABLE);
  // a serial program started on two ranks: one message, not two runs
  // writing the same files
  run_case("serial_program_on_two_ranks",
           with("Time stepping", "End time = 0.1"),
           MPIEXEC_TWO_RANKS " " CYLINDER_IMPACT_EXECUTABLE);
  // Scene = impact throws the body of a mesh file with a velocity vector
  run_case("mpi_impact_velocity_of_two_components_in_3d",
           "set Scene = impact\n" +
             with("Initial conditions", "Initial velocity = 0, -1"),
           mpi);
  run_case("mpi_impact_without_mesh_file",
           "set Scene = impact\n" +
             with("Initial conditions", "Initial velocity = 0, -1, 0"),
           mpi);
  run_case("mpi_thickness_in_3d", with("Geometry", "Thickness = 0.5"), mpi);
  // read and checked even when the scene does not use it
  run_case("mpi_unused_second_material_out_of_range",
           with("Material of the second body", "Poisson's ratio = 0.7"),
           mpi);
  // Scene = two bodies: the bars of parameter_files/two_bars_2d_mpi.prm
  const std::string bars = std::string("set Dimension = 2\nset Scene = two "
                                       "bodies\n") +
                           with("Mesh",
                                "Mesh file = " PARAMETER_FILES_DIR
                                "/two_bars_2d_bar_1.msh\n  set Contact "
                                "boundary id = 1") +
                           "subsection Initial conditions\n  set Initial "
                           "velocity = 1, 0\nend\n";
  const std::string second_bar =
    "subsection Mesh of the second body\n  set Mesh file = " PARAMETER_FILES_DIR
    "/two_bars_2d_bar_2.msh\nend\n";
  run_case("mpi_two_bodies_without_second_mesh",
           bars + "subsection Second body\n  set Contact normal = -1, 0\nend\n",
           mpi);
  run_case("mpi_two_bodies_normal_of_three_components_in_2d",
           bars + second_bar +
             "subsection Second body\n  set Contact normal = -1, 0, 0\nend\n",
           mpi);
  // bar 2 with 3 cells across against bar 1's 4: no partner for the nodes
  // inside bar 1's end
  run_case(
    "mpi_two_bodies_nonmatching_interface",
    bars +
      "subsection Mesh of the second body\n  set Mesh file = " TESTS_PARAMETERS_DIR
      "/bar_2d_20x3.msh\nend\nsubsection Second body\n  set Contact "
      "normal = -1, 0\nend\n",
    mpi);
  run_case("mpi_two_bodies_node_to_face_in_2d",
           bars + second_bar +
             "subsection Second body\n  set Contact discretization = "
             "node-to-face\nend\n",
           mpi);
  // the second bar touches the obstacle on a boundary it does not have
  run_case("mpi_two_bodies_obstacle_contact_on_missing_boundary",
           bars + second_bar +
             "subsection Second body\n  set Contact normal = -1, 0\nend\n"
             "subsection Obstacle contact\n  set Boundary id of the second "
             "body = 7\nend\n"
             "subsection Obstacle\n  set Point on plane = 0, -1\n  set "
             "Normal = 0, 1\nend\n",
           mpi);
  // Scene = bodies: a pair that names a body the scene does not have, and
  // one body only
  const std::string three_bars =
    "set Dimension = 2\nset Scene = bodies\nsubsection Bodies\n  set Mesh "
    "files = " PARAMETER_FILES_DIR
    "/two_bars_2d_bar_1.msh, " PARAMETER_FILES_DIR
    "/two_bars_2d_bar_2.msh, " PARAMETER_FILES_DIR "/three_bars_2d_bar_3.msh\n";
  run_case("mpi_bodies_pair_with_a_fourth_body",
           three_bars + "  set Contact pairs = 1:1 against 4:0\nend\n",
           mpi);
  // per-body materials: a list of the wrong length, a value out of range
  run_case("mpi_bodies_densities_of_two_bodies",
           three_bars +
             "  set Contact pairs = 1:1 against 2:0\n  set Densities = 1, "
             "2\nend\n",
           mpi);
  run_case("mpi_bodies_poissons_ratio_out_of_range",
           three_bars +
             "  set Contact pairs = 1:1 against 2:0\n  set Poisson's "
             "ratios = 0, 0.5, 0\nend\n",
           mpi);
  run_case("mpi_bodies_velocity_not_a_number",
           three_bars + "  set Contact pairs = 1:1 against 2:0\n  set Initial "
                        "velocities = 1, 0; 0, x; 0, 0\nend\n",
           mpi);
  // nan passed as a number, and was reported as an overflow of the
  // kinetic energy ("largest initial velocity 1 m/s" on one rank)
  run_case("mpi_bodies_velocity_nan",
           three_bars + "  set Contact pairs = 1:1 against 2:0\n  set Initial "
                        "velocities = 1, 0; 0, nan; 0, 0\nend\n",
           mpi);
  // a pair or an obstacle contact named twice made its candidates twice
  // (with two coefficients, neither one's answer)
  run_case("mpi_bodies_pair_twice",
           three_bars + "  set Contact pairs = 1:1 against 2:0, 1:1 against "
                        "2:0 with friction 0.2\nend\n",
           mpi);
  run_case("mpi_bodies_obstacle_contact_twice",
           three_bars + "  set Contact pairs = 1:1 against 2:0\n  set "
                        "Obstacle contacts = 1:2, 1:2\nend\n",
           mpi);
  // gravity that overflows the state (the cylinder thrown at the plane):
  // with MUMPS the error met on rank 0 alone hung both ranks; AMG-CG took
  // the infinite right-hand side as converged with x = 0 and ran on,
  // without gravity, to exit code 0
  for (const std::string solver : {"direct", "amg cg"})
    run_case("mpi_gravity_overflow_" + solver.substr(0, solver.find(' ')),
             "include " PARAMETER_FILES_DIR "/cylinder_impact_mpi.prm\n" +
               with("Loads", "Gravity = 1e200") +
               "subsection Parallel solver\n  set Solver = " + solver +
               "\nend\nsubsection Time stepping\n  set End time = "
               "0.2\nend\n",
             mpi,
             "",
             ".prm",
             false);
  // a contact search that finds nothing, and one without a distance
  run_case("mpi_bodies_search_finds_nothing",
           three_bars +
             "  set Contact pairs = all:1 against all:1\n  set Contact "
             "search distance = 1e-9\nend\n",
           mpi);
  run_case("mpi_bodies_search_without_distance",
           three_bars + "  set Contact pairs = all:1 against 2:0\nend\n",
           mpi);
  // a pair of the wrong sides: block 2's lower side against block 1's
  // lower side, which it starts 0.02 m inside
  run_case("mpi_bodies_overlap",
           "set Dimension = 2\nset Scene = bodies\nsubsection Bodies\n  set "
           "Mesh files = " PARAMETER_FILES_DIR
           "/block_tower_1.msh, " PARAMETER_FILES_DIR
           "/block_tower_2.msh\n  set Contact pairs = 2:2 against 1:2\nend\n",
           mpi);
  // a search between two copies of one block: a node inside the other
  run_case("mpi_bodies_search_overlap",
           "set Dimension = 2\nset Scene = bodies\nsubsection Bodies\n  set "
           "Mesh files = " PARAMETER_FILES_DIR
           "/block_tower_1.msh, " PARAMETER_FILES_DIR
           "/block_tower_1.msh\n  set Contact pairs = all:2 against all:3\n  "
           "set Contact search distance = 0.05\nend\n",
           mpi);
  // searches during the run: not without a distance, not for one body
  run_case("mpi_bodies_search_interval_without_distance",
           three_bars +
             "  set Contact pairs = 1:1 against 2:0\n  set Contact search "
             "interval = 1\nend\n",
           mpi);
  run_case("mpi_search_interval_one_body",
           "set Dimension = 2\nsubsection Bodies\n  set Contact search "
           "interval = 5\nend\n",
           mpi);
  run_case("mpi_bodies_negative_pair_friction",
           three_bars +
             "  set Contact pairs = 1:1 against 2:0 with friction -0.1\nend\n",
           mpi);
  run_case("mpi_bodies_one_mesh",
           "set Dimension = 2\nset Scene = bodies\nsubsection Bodies\n  set "
           "Mesh files = " PARAMETER_FILES_DIR
           "/two_bars_2d_bar_1.msh\n  set Contact pairs = 1:1 against "
           "2:0\nend\n",
           mpi);
  run_case("mpi_second_body_without_two_bodies",
           with("Second body", "Contact normal = -1, 0, 0"),
           mpi);
  // the plate 1e-300 m thick: its momenta underflowed, and contact_mpi
  // printed an impulse balance of -nan (0/0) and exited with 0
  run_case("mpi_mass_underflows",
           "include " PARAMETER_FILES_DIR "/oblique_plate_mpi.prm\n" +
             with("Geometry", "Thickness = 1e-300") +
             "subsection Time stepping\n  set End time = 1e-4\nend\n",
           mpi,
           "",
           ".prm",
           false);
  run_case("mass_underflows",
           with("Geometry", "Thickness = 1e-300"),
           OBLIQUE_PLATE_EXECUTABLE);
  // A cell whose nodes are not in order around it (a 'bow tie': 2 3 5 6
  // instead of 2 3 6 5, node 6 moved so that the area is not zero) has a
  // positive area and passed: the serial programs ran on it, and
  // contact_mpi stopped in one rank's Cholesky factorisation ("not
  // positive definite") after 10 s and MPI_Abort.
  {
    std::ofstream("bow_tie.msh")
      << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n6\n"
         "1 0 0 0\n2 1 0 0\n3 2 0 0\n4 0 1 0\n5 1 1 0\n6 2.6 1.4 0\n"
         "$EndNodes\n$Elements\n4\n1 1 2 1 1 1 2\n2 1 2 1 1 2 3\n"
         "3 3 2 0 1 1 2 5 4\n4 3 2 0 1 2 3 5 6\n$EndElements\n";
    const std::string mesh = with("Mesh",
                                  "Mesh file = bow_tie.msh\n  set Contact "
                                  "boundary id = 1");
    run_case("mesh_bow_tie", mesh, cylinder);
    run_case("mpi_mesh_bow_tie",
             "set Dimension = 2\nset Scene = impact\n" + mesh +
               "subsection Initial conditions\n  set Initial velocity = 0, "
               "-1\nend\nsubsection Obstacle\n  set Point on plane = 0, "
               "-1\n  set Normal = 0, 1\nend\n",
             mpi);
  }
  run_case("mpi_write_meshes", with("Output", "Write meshes = true"), mpi);
  run_case("mpi_bad_solver_tolerance",
           with("Parallel solver", "Tolerance = 2"),
           mpi);
  return impactfe_tests::n_failed_checks == 0 ? 0 : 1;
}
