// Reading and writing frictional contact problems in the HDF5 layout of the
// Friction Contact Library (FCLib), the exchange format of the Siconos and
// LMGC90 communities (see doc/lcp.md, "FCLib HDF5 files"):
//
//   /fclib_local/W/{m,n,nz,nzmax,p,i,x}   Delassus matrix W (m = d n_c)
//   /fclib_local/vectors/{q,mu}           u = W r + q, friction coefficients
//   /fclib_local/spacedim                 d = 2 or 3
//   /fclib_global/{M,H}/...               M v = H r + f, u = H^T v + w
//   /fclib_global/vectors/{f,w,mu}
//   /fclib_global/spacedim
//   /fclib_{local,global}/info/{title,description,math_info}   (optional)
//   /solution/{r,u,v}, /guesses/number_of_guesses, /guesses/<k>/{r,u,v}
//
// A matrix is compressed by columns (nz = -1: p has n + 1 column pointers,
// i row indices), by rows (nz = -2: p has m + 1 row pointers, i column
// indices) or a list of nz >= 0 triplets (i row and p column indices, as
// CSparse and the Siconos files have them); x holds the values.
//
// The code uses the HDF5 C library directly (the one deal.II is built with);
// it shares nothing with FCLib's own implementation.
#ifndef impactfe_lcp_fclib_io_h
#define impactfe_lcp_fclib_io_h

#include <impactfe/lcp/contact_problem.h>

#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// The optional text of a problem (/fclib_*/info).
    struct FclibInfo
    {
      std::string title;
      std::string description;
      std::string math_info;
    };

    /// A solution or guess: local impulses r, local velocities u = W r + q,
    /// and for global problems the velocities v (empty when absent).
    struct FclibSolution
    {
      std::vector<double> r;
      std::vector<double> u;
      std::vector<double> v;
    };

    /// A problem read from an FCLib file.
    struct FclibProblem
    {
      /// The local problem: W, free_velocity = q, gap_term = 0, mu. A global
      /// problem is condensed, W = H^T M^{-1} H, q = H^T M^{-1} f + w.
      ContactProblem contact;
      /// True if the file held /fclib_global.
      bool from_global = false;
      /// Size of M for a global problem (0 otherwise).
      unsigned int n_global_dofs = 0;
      FclibInfo    info;
      /// /solution, if the file has one (r, u may be empty otherwise).
      FclibSolution              solution;
      std::vector<FclibSolution> guesses;
    };

    /// True if @p filename starts with the HDF5 signature.
    bool
    is_hdf5_file(const std::string &filename);

    /**
     * Read an FCLib file. Throws std::runtime_error("<file>: <what>") if the
     * file is not HDF5, has neither /fclib_local nor /fclib_global, lacks a
     * dataset, has inconsistent sizes or indices, holds a mixed problem (V, R
     * or G, which impactfe does not solve), or if M of a global problem is
     * not symmetric positive definite.
     */
    FclibProblem
    read_fclib_file(const std::string &filename);

    /// How W is written to an FCLib file.
    enum class FclibStorage
    {
      compressed_column,
      compressed_row,
      triplet
    };

    /**
     * Write @p problem as /fclib_local (zeros of W are not stored), with the
     * gap term folded into q as in the text format, and /solution if
     * @p solution is given (its r, u, v as far as not empty). Overwrites the
     * file. Throws std::runtime_error if it cannot be written.
     */
    void
    write_fclib_local_file(
      const std::string    &filename,
      const ContactProblem &problem,
      const FclibInfo      &info     = FclibInfo(),
      const FclibSolution  *solution = nullptr,
      FclibStorage          storage  = FclibStorage::compressed_column);

    /**
     * FCLib's solution of a local problem for the impulses @p P: r = P and
     * the relative velocity u = W P + q (with the gap term on the normal
     * components).
     */
    FclibSolution
    local_solution(const ContactProblem &problem, const std::vector<double> &P);

    /** |P - r| / |r| (Euclidean norms), for comparing with a file's r. */
    double
    relative_difference(const std::vector<double> &P,
                        const std::vector<double> &r);
  } // namespace lcp
} // namespace impactfe

#endif
