#include <impactfe/lcp/fclib_io.h>
#include <impactfe/lcp/problem_io.h>

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace impactfe
{
  namespace lcp
  {
    namespace
    {
      /// Whitespace-separated tokens with their line numbers.
      class Tokens
      {
      public:
        Tokens(std::istream &in, const std::string &name_)
          : name(name_)
        {
          std::string  line;
          unsigned int line_no = 0;
          while (std::getline(in, line))
            {
              ++line_no;
              std::istringstream s(line);
              std::string        t;
              while (s >> t)
                {
                  tokens.push_back(t);
                  lines.push_back(line_no);
                }
            }
        }

        [[noreturn]] void
        error(const std::string &what) const
        {
          std::ostringstream s;
          s << name << ": " << what;
          if (pos < tokens.size())
            s << " (line " << lines[pos] << ", read '" << tokens[pos] << "')";
          else if (!tokens.empty())
            s << " (at the end of the file, line " << lines.back() << ")";
          throw std::runtime_error(s.str());
        }

        bool
        at_end() const
        {
          return pos >= tokens.size();
        }

        /// The number of tokens not yet read.
        std::size_t
        remaining() const
        {
          return tokens.size() - pos;
        }

        /// After the data: text (a comment, as Siconos files often end
        /// with) may follow, a number may not. A number there means the
        /// header announced fewer values than the file holds (a wrong n or
        /// n_c, or a global problem M, H, q, b, mu read as a local one: the
        /// reader would take H's header for q), and reading on would solve
        /// another problem than the file's. @p allowed_flag: one last "0"
        /// or "1" is accepted, the flag that Siconos' older writers put
        /// after a friction-contact problem (most files of its collection
        /// end with it).
        void
        expect_no_more_numbers(const std::string &header,
                               const std::string &hint,
                               const bool         allowed_flag)
        {
          std::size_t n = 0;
          for (bool ok = true; ok; ++n)
            peek_number(n, ok);
          --n;
          if (n == 0 || (allowed_flag && n == 1 &&
                         (peek_text() == "0" || peek_text() == "1")))
            return;
          error(std::to_string(n) + " more number(s) after the data that " +
                header + " announces; " + hint);
        }

        /// The next token as text ("" at the end), without consuming it.
        const std::string &
        peek_text(const std::size_t offset = 0) const
        {
          static const std::string none;
          return pos + offset < tokens.size() ? tokens[pos + offset] : none;
        }

        /// Line of the next token (0 at the end).
        unsigned int
        line() const
        {
          return pos < tokens.size() ? lines[pos] : 0;
        }

        /// Skip every remaining token of the current token's line.
        void
        skip_line()
        {
          const unsigned int l = line();
          while (pos < tokens.size() && lines[pos] == l)
            ++pos;
        }

        /// Consume the literal token @p word, or report what was expected.
        void
        expect(const std::string &word, const std::string &what)
        {
          if (at_end() || tokens[pos] != word)
            error("expected '" + word + "' " + what);
          ++pos;
        }

        /// An integer token followed by an optional trailing character
        /// (CSparse writes "3822," and "1334-by-1334,").
        long
        integer_with_suffix(const std::string &what,
                            const long         min,
                            const long         max,
                            const char         suffix)
        {
          if (!at_end() && !tokens[pos].empty() && tokens[pos].back() == suffix)
            {
              tokens[pos].pop_back();
              return integer(what, min, max);
            }
          return integer(what, min, max);
        }

        /// The current token split at "-by-" into (rows, columns), which
        /// must be (rows, columns).
        void
        dimensions(const std::string &what, const long rows, const long columns)
        {
          if (at_end())
            error("missing " + what);
          std::string t = tokens[pos];
          if (!t.empty() && t.back() == ',')
            t.pop_back();
          const std::size_t by  = t.find("-by-");
          bool              ok0 = false, ok1 = false;
          double            r = 0., c = 0.;
          if (by != std::string::npos)
            {
              r = parse(t.substr(0, by), ok0);
              c = parse(t.substr(by + 4), ok1);
            }
          if (!ok0 || !ok1 || r != std::floor(r) || c != std::floor(c) ||
              r < 0 || c < 0)
            error("expected 'rows-by-columns,' for " + what);
          if (r != rows || c != columns)
            error(what + " differs from the storage header (" +
                  std::to_string(rows) + " x " + std::to_string(columns) + ")");
          ++pos;
        }

        double
        peek_number(const std::size_t offset, bool &ok) const
        {
          ok = pos + offset < tokens.size();
          if (!ok)
            return 0.;
          return parse(tokens[pos + offset], ok);
        }

        double
        number(const std::string &what)
        {
          if (at_end())
            error("missing " + what);
          bool         ok = false;
          const double v  = parse(tokens[pos], ok);
          if (!ok)
            error("expected a number for " + what);
          ++pos;
          return v;
        }

        long
        integer(const std::string &what, const long min, const long max)
        {
          if (at_end())
            error("missing " + what);
          bool         ok = false;
          const double v  = parse(tokens[pos], ok);
          if (!ok || v != std::floor(v) || v < min || v > max)
            {
              std::ostringstream s;
              s << "expected an integer in [" << min << ", " << max << "] for "
                << what;
              error(s.str());
            }
          ++pos;
          return static_cast<long>(v);
        }

      private:
        static double
        parse(const std::string &t, bool &ok)
        {
          const char *b  = t.c_str();
          char       *e  = nullptr;
          errno          = 0;
          const double v = std::strtod(b, &e);
          // ERANGE on underflow (a subnormal or a value that rounds to 0,
          // e.g. far-field entries of an FE Delassus operator) is fine: the
          // value is the closest double. Overflow is not.
          const bool overflow = (errno == ERANGE && std::abs(v) > 1.);
          ok = (e != b && *e == '\0' && !overflow && std::isfinite(v));
          return v;
        }

        std::string               name;
        std::vector<std::string>  tokens;
        std::vector<unsigned int> lines;
        std::size_t               pos = 0;
      };

      constexpr long max_size = 1000000;

      /**
       * Storage type 2 (NumericsSparseMatrix): the text CSparse prints,
       * as Siconos writes it (NSM_write_in_file / CSparseMatrix_print_in_file):
       *
       *   [origin]              1 triplet, 2 compressed column, 3 compressed
       *                         row (newer files; older files lack it)
       *   [CSparse Version ...] one line, skipped
       *   m-by-n, nzmax: X nnz: Y, 1-norm: Z           (compressed)
       *       col j : locations a to b                 (per column j)
       *         i : value                              (b - a + 1 entries)
       *   triplet: m-by-n, nzmax: X nnz: Y             (triplet)
       *       i j : value                              (Y entries)
       *
       * In compressed row storage "col j" is row j and "i" a column. Triplet
       * entries with the same (i, j) are summed, as CSparse's compression
       * does. The values are written by Siconos with 6 significant digits
       * (%g): such a file holds that rounded matrix, nothing more.
       */
      void
      read_sparse(Tokens &t, const long size0, const long size1, DenseMatrix &M)
      {
        long origin = 0;
        // the optional origin stands alone on its line
        if (t.peek_text() == "1" || t.peek_text() == "2" ||
            t.peek_text() == "3")
          origin =
            t.integer("the sparse matrix origin (1 triplet, 2 CSC, 3 CSR)",
                      1,
                      3);
        if (t.peek_text() == "(null)")
          t.error("the sparse matrix was written as (null)");
        if (t.peek_text() == "CSparse" || t.peek_text() == "CXSparse")
          t.skip_line();
        const bool triplet = (t.peek_text() == "triplet:");
        if (triplet)
          t.expect("triplet:", "");
        if (origin == 1 && !triplet)
          t.error(
            "origin 1 (triplet) announced, but the header is not 'triplet: ...'");
        if (triplet && origin > 1)
          t.error("a triplet header, but origin " + std::to_string(origin) +
                  " (compressed) announced");
        const bool by_rows = (origin == 3);
        t.dimensions("the sparse matrix size", size0, size1);
        t.expect("nzmax:", "in the sparse matrix header");
        const long nzmax = t.integer("nzmax", 0, max_size * 100);
        t.expect("nnz:", "in the sparse matrix header");
        const long nnz = t.integer_with_suffix("nnz", 0, nzmax, ',');
        if (!triplet)
          {
            // ", 1-norm: Z" closes the header line
            t.expect("1-norm:", "in the sparse matrix header");
            t.number("the 1-norm");
          }

        auto entry = [&](const long i, const long j, const double v) {
          if (i < 0 || i >= size0 || j < 0 || j >= size1)
            t.error("entry (" + std::to_string(i) + ", " + std::to_string(j) +
                    ") outside the matrix");
          M(i, j) += v;
        };

        if (triplet)
          {
            for (long p = 0; p < nnz; ++p)
              {
                const long i = t.integer("a triplet row index", 0, size0 - 1);
                const long j =
                  t.integer("a triplet column index", 0, size1 - 1);
                t.expect(":", "after a triplet's indices");
                entry(i, j, t.number("a triplet value"));
              }
            return;
          }
        const long n_outer = by_rows ? size0 : size1;
        const long n_inner = by_rows ? size1 : size0;
        long       next    = 0; // the location the next column must start at
        for (long j = 0; j < n_outer; ++j)
          {
            t.expect("col",
                     by_rows ? "(row " + std::to_string(j) +
                                 " of a compressed-row matrix)" :
                               "(column " + std::to_string(j) + ")");
            t.integer("the column number", j, j);
            t.expect(":", "after the column number");
            t.expect("locations", "in a column header");
            t.integer("the first location of the column", next, next);
            t.expect("to", "in a column header");
            const long last =
              t.integer("the last location of the column", next - 1, nnz - 1);
            for (long p = next; p <= last; ++p)
              {
                const long i = t.integer("a row index", 0, n_inner - 1);
                t.expect(":", "after a row index");
                const double v = t.number("a matrix entry");
                if (by_rows)
                  entry(j, i, v);
                else
                  entry(i, j, v);
              }
            next = last + 1;
          }
        if (next != nnz)
          t.error("the columns hold " + std::to_string(next) +
                  " entries, the header says nnz = " + std::to_string(nnz));
      }

      DenseMatrix
      read_numerics_matrix(Tokens &t)
      {
        const long storage = t.integer("the matrix storage type", 0, 2);
        const long size0 = t.integer("the number of matrix rows", 0, max_size);
        const long size1 =
          t.integer("the number of matrix columns", 0, max_size);
        // The matrix is stored dense whatever the file's storage: check
        // that it can be before allocating it (a header of n = 20000 took
        // 3.2 GB before the reader found the entries missing).
        const double entries = double(size0) * double(size1);
        if (storage == 0 && double(t.remaining()) < entries + 2.)
          t.error("the header announces a dense " + std::to_string(size0) +
                  "-by-" + std::to_string(size1) + " matrix (" +
                  std::to_string(size0 * size1) +
                  " entries), but the file holds only " +
                  std::to_string(t.remaining()) + " more numbers and words");
        const double pages     = double(sysconf(_SC_PHYS_PAGES));
        const double page_size = double(sysconf(_SC_PAGESIZE));
        if (pages > 0. && page_size > 0. && 8. * entries > pages * page_size)
          {
            std::ostringstream need;
            need << std::setprecision(3) << 8. * entries / 1e9
                 << " GB stored dense, more than this machine's "
                 << pages * page_size / 1e9 << " GB of memory";
            t.error("the header announces a " + std::to_string(size0) + "-by-" +
                    std::to_string(size1) + " matrix: " + need.str());
          }
        // Whatever the storage, q (n or d n_c numbers) follows the matrix:
        // a sparse header of n = 40000 in a 70-byte file took 12.8 GB. (A
        // small matrix is read first: its own errors say more.)
        if (8. * entries > 1e8 && double(t.remaining()) < double(size0))
          t.error("the header announces a " + std::to_string(size0) + "-by-" +
                  std::to_string(size1) + " matrix, but the file holds only " +
                  std::to_string(t.remaining()) +
                  " more numbers and words, fewer than q alone needs");
        DenseMatrix M(size0, size1, 0.);
        if (storage == 2)
          {
            read_sparse(t, size0, size1, M);
            return M;
          }
        if (storage == 0)
          {
            const long r =
              t.integer("the dense matrix row count", size0, size0);
            const long c =
              t.integer("the dense matrix column count", size1, size1);
            for (long j = 0; j < c; ++j) // column-major
              for (long i = 0; i < r; ++i)
                M(i, j) = t.number("a matrix entry");
            return M;
          }
        // sparse block storage
        const long nbblocks = t.integer("nbblocks", 0, max_size);
        if (nbblocks == 0)
          return M;
        const long        bn0 = t.integer("blocknumber0", 1, size0);
        const long        bn1 = t.integer("blocknumber1", 1, size1);
        std::vector<long> rs(bn0), cs(bn1);
        for (long i = 0; i < bn0; ++i)
          rs[i] = t.integer("a cumulative block row size",
                            i == 0 ? 1 : rs[i - 1] + 1,
                            size0);
        for (long i = 0; i < bn1; ++i)
          cs[i] = t.integer("a cumulative block column size",
                            i == 0 ? 1 : cs[i - 1] + 1,
                            size1);
        if (rs.back() != size0 || cs.back() != size1)
          t.error("block sizes do not add up to the matrix size");
        const long        filled1 = t.integer("filled1", bn0 + 1, bn0 + 1);
        const long        filled2 = t.integer("filled2", nbblocks, nbblocks);
        std::vector<long> index1(filled1), index2(filled2);
        for (long i = 0; i < filled1; ++i)
          index1[i] =
            t.integer("index1_data", i == 0 ? 0 : index1[i - 1], filled2);
        if (index1[0] != 0 || index1.back() != filled2)
          t.error("index1_data must run from 0 to filled2");
        for (long i = 0; i < filled2; ++i)
          index2[i] = t.integer("index2_data", 0, bn1 - 1);
        // a block given twice would overwrite the first (triplets add up)
        for (long r = 0; r + 1 < filled1; ++r)
          {
            std::vector<long> columns(index2.begin() + index1[r],
                                      index2.begin() + index1[r + 1]);
            std::sort(columns.begin(), columns.end());
            const auto twice =
              std::adjacent_find(columns.begin(), columns.end());
            if (twice != columns.end())
              t.error("block row " + std::to_string(r) +
                      " lists block column " + std::to_string(*twice) +
                      " twice: each block must appear once");
          }
        for (long r = 0; r + 1 < filled1; ++r)
          for (long b = index1[r]; b < index1[r + 1]; ++b)
            {
              t.integer("the block number", b, b);
              const long c   = index2[b];
              const long r0  = (r == 0 ? 0 : rs[r - 1]);
              const long c0  = (c == 0 ? 0 : cs[c - 1]);
              const long nr  = rs[r] - r0;
              const long ncl = cs[c] - c0;
              for (long jj = 0; jj < ncl; ++jj)
                for (long ii = 0; ii < nr; ++ii)
                  M(r0 + ii, c0 + jj) = t.number("a block entry");
            }
        return M;
      }

      /// A NumericsMatrix in the requested storage, at full precision (17
      /// significant digits, unlike Siconos' %g for sparse matrices).
      void
      write_matrix(std::ostream       &out,
                   const DenseMatrix  &M,
                   const MatrixStorage storage)
      {
        if (storage == MatrixStorage::dense)
          {
            out << 0 << '\n' << M.n_rows() << '\n' << M.n_cols() << '\n';
            out << M.n_rows() << '\t' << M.n_cols() << '\n';
            for (std::size_t j = 0; j < M.n_cols(); ++j)
              {
                for (std::size_t i = 0; i < M.n_rows(); ++i)
                  out << M(i, j) << ' ';
                out << '\n';
              }
            return;
          }
        std::size_t nnz   = 0;
        double      norm1 = 0.;
        for (std::size_t j = 0; j < M.n_cols(); ++j)
          {
            double column_sum = 0.;
            for (std::size_t i = 0; i < M.n_rows(); ++i)
              if (M(i, j) != 0.)
                {
                  ++nnz;
                  column_sum += std::abs(M(i, j));
                }
            norm1 = std::max(norm1, column_sum);
          }
        const bool triplet = (storage == MatrixStorage::triplet);
        out << 2 << '\n'
            << M.n_rows() << '\n'
            << M.n_cols() << '\n'
            << (triplet ? 1 : 2) << '\n';
        out << "CSparse Version 3.1.9 text layout, written by impactfe\n";
        if (triplet)
          out << "triplet: " << M.n_rows() << "-by-" << M.n_cols()
              << ", nzmax: " << nnz << " nnz: " << nnz << '\n';
        else
          out << M.n_rows() << "-by-" << M.n_cols() << ", nzmax: " << nnz
              << " nnz: " << nnz << ", 1-norm: " << norm1 << '\n';
        std::size_t location = 0;
        for (std::size_t j = 0; j < M.n_cols(); ++j)
          {
            std::size_t count = 0;
            for (std::size_t i = 0; i < M.n_rows(); ++i)
              count += (M(i, j) != 0.);
            if (!triplet)
              out << "    col " << j << " : locations " << location << " to "
                  << static_cast<long>(location + count) - 1 << '\n';
            for (std::size_t i = 0; i < M.n_rows(); ++i)
              if (M(i, j) != 0.)
                {
                  if (triplet)
                    out << "    " << i << ' ' << j << " : " << M(i, j) << '\n';
                  else
                    out << "      " << i << " : " << M(i, j) << '\n';
                }
            location += count;
          }
      }
    } // namespace



    ProblemFile
    read_problem(std::istream &in, const std::string &name)
    {
      Tokens t(in, name);
      if (t.at_end())
        t.error("empty file");
      bool         ok[4];
      const double a0 = t.peek_number(0, ok[0]), a1 = t.peek_number(1, ok[1]),
                   a2 = t.peek_number(2, ok[2]), a3 = t.peek_number(3, ok[3]);
      if (!(ok[0] && ok[1] && ok[2] && ok[3]))
        t.error(
          "not a Siconos LCP or friction-contact file: it must start with four integers");
      const bool is_lcp =
        (a1 == 0 || a1 == 1 || a1 == 2) && a2 == a0 && a3 == a0;
      const bool is_fc = (a0 == 1 || a0 == 2 || a0 == 3) &&
                         (a2 == 0 || a2 == 1 || a2 == 2) && a3 == a0 * a1;

      ProblemFile file;
      if (is_lcp)
        {
          file.type    = ProblemType::lcp;
          const long n = t.integer("the LCP size", 0, max_size);
          file.lcp.M   = read_numerics_matrix(t);
          if (file.lcp.M.n_rows() != std::size_t(n) ||
              file.lcp.M.n_cols() != std::size_t(n))
            t.error("the matrix is not n x n");
          file.lcp.q.resize(n);
          for (auto &v : file.lcp.q)
            v = t.number("an entry of q");
          t.expect_no_more_numbers("the LCP size n = " + std::to_string(n),
                                   "is n right?",
                                   false);
          return file;
        }
      if (is_fc)
        {
          file.type         = ProblemType::friction_contact;
          ContactProblem &p = file.contact;
          p.n_directions =
            static_cast<unsigned int>(t.integer("the contact dimension", 1, 3));
          p.n_contacts = static_cast<unsigned int>(
            t.integer("the number of contacts", 0, max_size));
          p.W                 = read_numerics_matrix(t);
          const std::size_t m = std::size_t(p.n_contacts) * p.n_directions;
          if (p.W.n_rows() != m || p.W.n_cols() != m)
            t.error("the matrix is not (d n_c) x (d n_c)");
          p.free_velocity.resize(m);
          for (auto &v : p.free_velocity)
            v = t.number("an entry of q");
          p.mu.resize(p.n_contacts);
          for (std::size_t c = 0; c < p.mu.size(); ++c)
            {
              p.mu[c] = t.number("a friction coefficient");
              if (!(p.mu[c] >= 0.))
                {
                  std::ostringstream value;
                  value << p.mu[c];
                  t.error("the friction coefficient of contact " +
                          std::to_string(c) + " is " + value.str() +
                          ", not >= 0 (the position given is that of the "
                          "next number)");
                }
            }
          p.gap_term.assign(p.n_contacts, 0.);
          t.expect_no_more_numbers(
            "d = " + std::to_string(p.n_directions) +
              ", n_c = " + std::to_string(p.n_contacts),
            "is n_c right, or is it a global problem (M, H, q, b, mu), "
            "which is read from FCLib files only?",
            true);
          return file;
        }
      t.error(
        "not a Siconos LCP (n, storage, n, n, ...) or friction-contact (d, n_c, storage, d n_c, ...) file");
    }



    ProblemFile
    read_problem_file(const std::string &filename)
    {
      if (std::filesystem::is_directory(filename))
        throw std::runtime_error(filename + ": is a directory, not a file");
      if (is_hdf5_file(filename))
        {
          ProblemFile file;
          file.type    = ProblemType::friction_contact;
          file.contact = read_fclib_file(filename).contact;
          return file;
        }
      std::ifstream in(filename);
      if (!in)
        throw std::runtime_error(filename +
                                 ": cannot open the file for reading");
      return read_problem(in, filename);
    }



    void
    write_lcp(std::ostream              &out,
              const DenseMatrix         &M,
              const std::vector<double> &q,
              const MatrixStorage        storage)
    {
      if (M.n_rows() != q.size() || M.n_cols() != q.size())
        throw std::invalid_argument("write_lcp: inconsistent sizes");
      const auto old = out.precision(17);
      out << q.size() << '\n';
      write_matrix(out, M, storage);
      for (const double v : q)
        out << v << ' ';
      out << '\n';
      out.precision(old);
    }



    void
    write_friction_contact(std::ostream         &out,
                           const ContactProblem &p,
                           const MatrixStorage   storage)
    {
      check_contact_problem(p);
      const auto old = out.precision(17);
      out << p.n_directions << '\n' << p.n_contacts << '\n';
      write_matrix(out, p.W, storage);
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        for (unsigned int a = 0; a < p.n_directions; ++a)
          out << p.free_velocity[c * p.n_directions + a] +
                   (a == 0 ? p.gap_term[c] : 0.)
              << ' ';
      out << '\n';
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        out << (p.mu.empty() ? 0. : p.mu[c]) << ' ';
      out << '\n';
      out.precision(old);
    }



    void
    write_lcp_file(const std::string         &filename,
                   const DenseMatrix         &M,
                   const std::vector<double> &q,
                   const MatrixStorage        storage)
    {
      std::ofstream out(filename);
      if (!out)
        throw std::runtime_error(filename +
                                 ": cannot open the file for writing");
      write_lcp(out, M, q, storage);
      if (!out)
        throw std::runtime_error(filename + ": write error");
    }



    void
    write_friction_contact_file(const std::string    &filename,
                                const ContactProblem &problem,
                                const MatrixStorage   storage)
    {
      std::ofstream out(filename);
      if (!out)
        throw std::runtime_error(filename +
                                 ": cannot open the file for writing");
      write_friction_contact(out, problem, storage);
      if (!out)
        throw std::runtime_error(filename + ": write error");
    }
  } // namespace lcp
} // namespace impactfe
