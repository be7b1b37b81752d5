/* ---------------------------------------------------------------------
 *
 * block_sliding_mpi: the elastic block of block_sliding_3d (and its 2D
 * section) sliding on a rigid plane under gravity with Coulomb friction,
 * or a body read from a mesh file thrown at a rigid obstacle, on a
 * distributed mesh: p4est, Trilinos matrices and vectors, CG with ML's
 * AMG for the solves with M~, and the contact problem replicated on every
 * rank and solved by the active set method.
 *
 * ---------------------------------------------------------------------
 */

// @sect3{Introduction}
//
// The scene and its parameter file are block_sliding_3d's: the same file
// runs with `block_sliding_3d` on one process and with `mpirun -np N
// block_sliding_mpi` on N, and the two write the same columns of
// history.csv (time, forces, momentum, energies, active contacts), which
// must agree to the solves' tolerance (tests/parallel/). These entries are
// this program's own: the top-level `Dimension` (2: the block's section in
// the x-y plane, sliding along x; 3: the box), the subsection `Parallel
// solver`, and `Scene = impact` with `Initial conditions/Initial velocity`:
// the body of `Mesh file` thrown at the obstacle, as cylinder_impact and
// oblique_plate do with the same file (cylinder_impact_mpi.prm,
// oblique_plate_mpi.prm; `Geometry/Thickness` in 2D). What the
// distributed step does and does not do yet is in doc/parallel.md.
#include <deal.II/base/mpi.h>

#include <impactfe/parallel/sliding_block_scene.h>
#include <impactfe/utilities/program.h>

#include <string>



// @sect3{The main function}
// Every error met here is met by every rank (the parameters, the set-up and
// the solves are collective), so rank 0 alone prints it and all exit with
// 1: no rank is left waiting.
int
main(int argc, char *argv[])
{
  dealii::Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  const bool                               root =
    dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
  try
    {
      AssertThrow(argc <= 2,
                  dealii::ExcMessage("Usage: block_sliding_mpi [parameter "
                                     "file]"));
      const std::string                             file = argc > 1 ?
                                                             std::string(argv[1]) :
                                                             std::string(IMPACTFE_SOURCE_DIR) +
                                   "/parameter_files/block_sliding_mpi.prm";
      impactfe::distributed::SlidingBlockParameters parameters;
      parameters.read(file);
      if (parameters.dimension == 2)
        impactfe::distributed::SlidingBlockScene<2>(parameters, file).run();
      else
        impactfe::distributed::SlidingBlockScene<3>(parameters, file).run();
    }
  catch (...)
    {
      return root ? impactfe::report_current_exception() : 1;
    }
  return 0;
}
