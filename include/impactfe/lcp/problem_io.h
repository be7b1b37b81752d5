// Reading and writing LCPs and frictional contact problems in the text
// formats of Siconos numerics' test collections (see doc/lcp.md):
//
//  LinearComplementarityProblem:  n, NumericsMatrix M, q (n values)
//  FrictionContactProblem:        d, n_c, NumericsMatrix W, q (d n_c values),
//                                 mu (n_c values)
//  NumericsMatrix:                storage size0 size1, then
//    storage 0 (dense):           size0 size1, size0*size1 values COLUMN-major
//    storage 1 (sparse block):    nbblocks, blocknumber0, blocknumber1,
//                                 cumulative block row sizes, cumulative block
//                                 column sizes, filled1, filled2, index1_data,
//                                 index2_data, then per block its number and
//                                 its values column-major
//    storage 2 (CSparse):         [origin 1|2|3], [CSparse Version line], then
//                                 "m-by-n, nzmax: X nnz: Y, 1-norm: Z" and per
//                                 column "col j : locations a to b" and
//                                 "i : value" lines (compressed column; rows
//                                 for origin 3), or "triplet: m-by-n, nzmax: X
//                                 nnz: Y" and "i j : value" lines
// Text after the data (Siconos files often end with a comment) is ignored;
// numbers are refused (a wrong size, or a global problem M, H, q, b, mu
// taken for a local one), but for the one flag, 0 or 1, that Siconos'
// older writers put after a friction-contact problem.
#ifndef impactfe_lcp_problem_io_h
#define impactfe_lcp_problem_io_h

#include <impactfe/lcp/contact_problem.h>
#include <impactfe/lcp/dense_matrix.h>

#include <iosfwd>
#include <string>
#include <vector>

namespace impactfe
{
  namespace lcp
  {
    /// w = M z + q.
    struct LCPProblem
    {
      DenseMatrix         M;
      std::vector<double> q;
    };

    enum class ProblemType
    {
      lcp,
      friction_contact
    };

    /// A problem read from a file: exactly one of lcp / contact is filled.
    struct ProblemFile
    {
      ProblemType    type = ProblemType::lcp;
      LCPProblem     lcp;
      ContactProblem contact;
    };

    /**
     * Read either kind of file; the type is detected from the first four
     * numbers: "n s n n" with s in {0,1,2} is an LCP, "d n_c s d*n_c" with
     * d in {1,2,3} a friction-contact problem (LCP preferred if both fit).
     * d = 1 (a frictionless contact problem) is our extension: Siconos has
     * d = 2, 3 only. A friction-contact file has no separate gap term:
     * free_velocity = q and gap_term = 0.
     * Throws std::runtime_error("<name>: <what is wrong>") on malformed input.
     */
    ProblemFile
    read_problem(std::istream &in, const std::string &name);

    /// read_problem() on a file; an unreadable file is a std::runtime_error.
    /// An HDF5 file is read as an FCLib problem (read_fclib_file()).
    ProblemFile
    read_problem_file(const std::string &filename);

    /// How a matrix is written: NumericsMatrix storage 0, or storage 2 as
    /// compressed columns or triplets (zeros are not written).
    enum class MatrixStorage
    {
      dense,
      compressed_column,
      triplet
    };

    /// Write an LCP (full precision).
    void
    write_lcp(std::ostream              &out,
              const DenseMatrix         &M,
              const std::vector<double> &q,
              MatrixStorage              storage = MatrixStorage::dense);

    /**
     * Write a contact problem as a Siconos FrictionContactProblem (dense W).
     * Siconos has no gap term: it is folded into q, q = free_velocity +
     * gap_term on the normal rows. Solving the file therefore gives the same
     * LCP, and the same impulses, as the problem itself.
     */
    void
    write_friction_contact(std::ostream         &out,
                           const ContactProblem &problem,
                           MatrixStorage storage = MatrixStorage::dense);

    /// Write to a file (std::runtime_error if it cannot be written).
    void
    write_lcp_file(const std::string         &filename,
                   const DenseMatrix         &M,
                   const std::vector<double> &q,
                   MatrixStorage              storage = MatrixStorage::dense);

    /// Write to a file (std::runtime_error if it cannot be written).
    void
    write_friction_contact_file(const std::string    &filename,
                                const ContactProblem &problem,
                                MatrixStorage storage = MatrixStorage::dense);
  } // namespace lcp
} // namespace impactfe

#endif
