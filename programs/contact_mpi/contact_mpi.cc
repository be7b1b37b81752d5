/* ---------------------------------------------------------------------
 *
 * contact_mpi: contact dynamics on a distributed mesh (p4est, Trilinos
 * matrices and vectors; the solves with M~ substructured, by MUMPS or by
 * CG with ML's AMG; the contact problem replicated on every rank and
 * solved by the active set method). Three scenes: the elastic block of
 * block_sliding_3d (and its 2D section) sliding on a rigid plane under
 * gravity with Coulomb friction; a body read from a mesh file thrown at a
 * rigid obstacle; and that body thrown at a second one. Called
 * block_sliding_mpi until it ran more than the sliding block.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// The sliding block's parameter file is block_sliding_3d's: the same file
// runs with `block_sliding_3d` on one process and with `mpirun -np N
// contact_mpi` on N, and the two write the same columns of history.csv
// (time, forces, momentum, energies, active contacts), which must agree to
// the solves' tolerance (tests/parallel/). These entries are this
// program's own: the top-level `Dimension` (2: the block's section in the
// x-y plane, sliding along x; 3: the box), the subsection `Parallel
// solver`, `Scene = impact` with `Initial conditions/Initial velocity`:
// the body of `Mesh file` thrown at the obstacle, as cylinder_impact and
// oblique_plate do with the same file (cylinder_impact_mpi.prm,
// oblique_plate_mpi.prm; `Geometry/Thickness` in 2D), and `Scene = two
// bodies` with the subsections `Mesh of the second body` and `Second
// body`: the two bars of two_bars_2d and two_bars_3d
// (two_bars_2d_mpi.prm, two_bars_3d_mpi.prm). What the distributed step
// does and does not do yet is in doc/parallel.md.
#include <deal.II/base/mpi.h>
#include <deal.II/base/parameter_handler.h>

#include <impactfe/parallel/distributed_scene.h>
#include <impactfe/utilities/blas_threads.h>
#include <impactfe/utilities/mpi_errors.h>
#include <impactfe/utilities/program.h>

#include <iostream>
#include <string>



// @sect3{The main function}
// An error met here is normally met by every rank (the parameters, the
// set-up and the solves are collective), so rank 0 alone prints it and all
// exit with 1: no rank is left waiting
// (report_current_exception_on_rank_zero()).
int
main(int argc, char *argv[])
{
  // One core per rank: deal.II's threads are limited to one here, and so
  // is the BLAS (OpenBLAS starts a thread per core, whose idle workers
  // spin): otherwise one rank runs its dense products on two cores, and
  // two ranks' BLAS workers take cores from each other.
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  impactfe::set_blas_thread_limit(1);
  try
    {
      const std::string default_file = std::string(IMPACTFE_SOURCE_DIR) +
                                       "/parameter_files/block_sliding_mpi.prm";
      const impactfe::CommandLine command_line =
        impactfe::parse_command_line(argc, argv, "contact_mpi", default_file);
      if (impactfe::answer_informational_option(
            command_line,
            "contact_mpi",
            default_file,
            &impactfe::distributed::DistributedSceneParameters::
              declare_parameters))
        return 0;
      const std::string &file = command_line.parameter_file;
      impactfe::distributed::DistributedSceneParameters parameters;
      parameters.read(file);
      if (parameters.dimension == 2)
        impactfe::distributed::DistributedScene<2>(parameters, file).run();
      else
        impactfe::distributed::DistributedScene<3>(parameters, file).run();
    }
  catch (...)
    {
      return impactfe::report_current_exception_on_rank_zero(MPI_COMM_WORLD);
    }
  return 0;
}
