#include <deal.II/base/exceptions.h>

#include <deal.II/grid/grid_in.h>

#include <impactfe/bodies/mesh_input.h>

#include <filesystem>
#include <fstream>

namespace impactfe
{
  void
  MeshParameters::declare_parameters(
    ParameterHandler  &prm,
    const std::string &subsection,
    const unsigned int default_contact_boundary_id)
  {
    prm.enter_subsection(subsection);
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::Anything(),
                      "Mesh file of this body (Gmsh .msh, UCD .ucd, Abaqus "
                      ".inp, VTK .vtk), relative to the parameter file's "
                      "directory. Empty: the program's built-in geometry. "
                      "Coordinates in [m].");
    prm.declare_entry("Mesh file format",
                      "auto",
                      Patterns::Selection("auto|msh|ucd|abaqus|vtk"),
                      "Format of the mesh file; auto: from its extension "
                      "(.msh, .ucd, .inp = Abaqus, .vtk).");
    prm.declare_entry("Contact boundary id",
                      std::to_string(default_contact_boundary_id),
                      Patterns::Integer(0, 254),
                      "Boundary id of the faces whose nodes are contact "
                      "candidates [-]. For a mesh file: the id the file gives "
                      "those faces (Gmsh: the physical tag).");
    prm.leave_subsection();
  }



  void
  MeshParameters::parse_parameters(ParameterHandler  &prm,
                                   const std::string &subsection)
  {
    prm.enter_subsection(subsection);
    file_name           = prm.get("Mesh file");
    format              = prm.get("Mesh file format");
    contact_boundary_id = prm.get_integer("Contact boundary id");
    prm.leave_subsection();
  }



  template <int dim>
  void
  MeshParameters::read(Triangulation<dim> &triangulation,
                       const std::string  &parameter_file) const
  {
    std::filesystem::path path(file_name);
    if (path.is_relative())
      path = std::filesystem::path(parameter_file).parent_path() / path;
    AssertThrow(std::filesystem::exists(path),
                ExcMessage("Mesh: the mesh file '" + path.string() +
                           "' does not exist."));

    std::string chosen = format;
    if (chosen == "auto")
      {
        const std::string extension = path.extension().string();
        chosen                      = extension == ".msh" ? "msh" :
                                      extension == ".ucd" ? "ucd" :
                                      extension == ".inp" ? "abaqus" :
                                      extension == ".vtk" ? "vtk" :
                                                            "";
        AssertThrow(!chosen.empty(),
                    ExcMessage("Mesh: cannot tell the format of '" +
                               path.string() +
                               "' from its extension; set 'Mesh file "
                               "format'."));
      }
    const typename GridIn<dim>::Format grid_format =
      chosen == "msh" ? GridIn<dim>::msh :
      chosen == "ucd" ? GridIn<dim>::ucd :
      chosen == "vtk" ? GridIn<dim>::vtk :
                        GridIn<dim>::abaqus;

    GridIn<dim>   grid_in(triangulation);
    std::ifstream input(path);
    AssertThrow(input,
                ExcMessage("Mesh: cannot open '" + path.string() + "'."));
    try
      {
        grid_in.read(input, grid_format);
      }
    catch (const std::exception &error)
      {
        AssertThrow(false,
                    ExcMessage("Mesh: cannot read '" + path.string() + "' as " +
                               chosen + ": " + error.what()));
      }
    AssertThrow(triangulation.n_active_cells() > 0,
                ExcMessage("Mesh: the mesh file '" + path.string() +
                           "' has no cells."));
    // Cells of zero or negative measure (all nodes in a plane, or wrongly
    // ordered) would give a singular or indefinite mass matrix.
    for (const auto &cell : triangulation.active_cell_iterators())
      AssertThrow(
        !cell->reference_cell().is_hyper_cube() || cell->measure() > 0.,
        ExcMessage("Mesh: cell " + std::to_string(cell->active_cell_index()) +
                   " of '" + path.string() + "' has zero or negative " +
                   (dim == 3 ? "volume." : "area.")));
    // Q1 elements need quadrilaterals (hexahedra in 3D); GridIn also reads
    // triangles, tetrahedra, wedges and pyramids, on which FE_Q fails.
    AssertThrow(triangulation.all_reference_cells_are_hyper_cube(),
                ExcMessage("Mesh: the mesh file '" + path.string() +
                           "' has cells that are not " +
                           (dim == 3 ?
                              std::string("hexahedra (tetrahedra, wedges or "
                                          "pyramids); impactfe's Q1 "
                                          "elements need hexahedra.") :
                              std::string("quadrilaterals (triangles); "
                                          "impactfe's Q1 elements need "
                                          "quadrilaterals."))));
  }



  template void
  MeshParameters::read<1>(Triangulation<1> &, const std::string &) const;
  template void
  MeshParameters::read<2>(Triangulation<2> &, const std::string &) const;
  template void
  MeshParameters::read<3>(Triangulation<3> &, const std::string &) const;
} // namespace impactfe
