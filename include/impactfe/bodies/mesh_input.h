#ifndef impactfe_bodies_mesh_input_h
#define impactfe_bodies_mesh_input_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/types.h>

#include <deal.II/grid/tria.h>

#include <filesystem>
#include <string>
#include <vector>

namespace impactfe
{
  using namespace dealii;

  /**
   * The path of @p file_name, a file named in a parameter file, relative
   * to the directory of the parameter file that names it: @p parameter_file
   * or one of the files it includes (`include` statements, themselves
   * relative to the working directory, as ParameterHandler reads them),
   * whichever sets an entry to @p file_name last, as the entry's value or
   * an item of its comma-separated list. So a file that includes
   * parameter_files/cylinder_impact_mpi.prm from elsewhere still finds the
   * mesh that file names. An absolute name is returned as it is; a name
   * that no file sets is taken relative to @p parameter_file.
   */
  std::filesystem::path
  resolve_relative_to_setting_file(const std::string &file_name,
                                   const std::string &parameter_file);



  /**
   * Where a body's mesh comes from, and which boundary id carries its
   * contact candidates. One subsection per body (e.g. `Mesh`, or
   * `Mesh of bar 1`): an empty `Mesh file` means the program's built-in
   * geometry; otherwise deal.II's GridIn reads the file (Gmsh `.msh`, UCD
   * `.ucd`/`.inp`, Abaqus `.inp`, VTK `.vtk`), boundary ids included.
   */
  struct MeshParameters
  {
    std::string        file_name;
    std::string        format              = "auto";
    types::boundary_id contact_boundary_id = 0;

    static void
    declare_parameters(ParameterHandler  &prm,
                       const std::string &subsection,
                       const unsigned int default_contact_boundary_id);
    void
    parse_parameters(ParameterHandler &prm, const std::string &subsection);

    bool
    from_file() const
    {
      return !file_name.empty();
    }

    /**
     * Read the mesh file into @p triangulation (which must be empty). A
     * relative file name is taken relative to the directory of the
     * parameter file that sets it: @p parameter_file or a file it includes
     * (resolve_relative_to_setting_file()). Throws with the file name if it
     * does not exist or cannot be read.
     */
    template <int dim>
    void
    read(Triangulation<dim> &triangulation,
         const std::string  &parameter_file) const;
  };



  /**
   * One mesh of several bodies, for a program that holds them in one
   * (distributed) triangulation: the coarse cells of @p bodies side by
   * side, sharing no vertex even where they touch, with material id i on
   * the cells of body i and the boundary ids of each body's faces kept
   * (deal.II's GridGenerator::merge_triangulations() merges touching
   * vertices and drops the boundary ids). @p result must be empty; the
   * bodies must be coarse meshes without hanging nodes.
   */
  template <int dim>
  void
  merge_body_meshes(const std::vector<const Triangulation<dim> *> &bodies,
                    Triangulation<dim>                            &result);



  /**
   * Write the active cells of @p triangulation as a Gmsh file that
   * MeshParameters::read() reads back as the same coarse mesh: the
   * vertices, the cells with their material ids, and the boundary faces
   * with non-zero boundary ids (a refined mesh is written flat). Throws
   * with the file name if it cannot be written.
   */
  template <int dim>
  void
  write_mesh_file(const Triangulation<dim> &triangulation,
                  const std::string        &file_name);
} // namespace impactfe

#endif
