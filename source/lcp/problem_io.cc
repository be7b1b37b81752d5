#include <impactfe/lcp/problem_io.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
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
              s << "expected an integer in [" << min << ", " << max << "] for " << what;
              error(s.str());
            }
          ++pos;
          return static_cast<long>(v);
        }

      private:
        static double
        parse(const std::string &t, bool &ok)
        {
          const char *b = t.c_str();
          char       *e = nullptr;
          errno         = 0;
          const double v = std::strtod(b, &e);
          // ERANGE on underflow (a subnormal or a value that rounds to 0,
          // e.g. far-field entries of an FE Delassus operator) is fine: the
          // value is the closest double. Overflow is not.
          const bool overflow = (errno == ERANGE && std::abs(v) > 1.);
          ok                  = (e != b && *e == '\0' && !overflow && std::isfinite(v));
          return v;
        }

        std::string               name;
        std::vector<std::string>  tokens;
        std::vector<unsigned int> lines;
        std::size_t               pos = 0;
      };

      constexpr long max_size = 1000000;

      DenseMatrix
      read_numerics_matrix(Tokens &t)
      {
        const long storage = t.integer("the matrix storage type", 0, 2);
        const long size0   = t.integer("the number of matrix rows", 0, max_size);
        const long size1   = t.integer("the number of matrix columns", 0, max_size);
        if (storage == 2)
          t.error("sparse (CSparse, storage type 2) matrices are not supported; use dense (0) or sparse block (1)");
        DenseMatrix M(size0, size1, 0.);
        if (storage == 0)
          {
            const long r = t.integer("the dense matrix row count", size0, size0);
            const long c = t.integer("the dense matrix column count", size1, size1);
            for (long j = 0; j < c; ++j) // column-major
              for (long i = 0; i < r; ++i)
                M(i, j) = t.number("a matrix entry");
            return M;
          }
        // sparse block storage
        const long nbblocks = t.integer("nbblocks", 0, max_size);
        if (nbblocks == 0)
          return M;
        const long          bn0 = t.integer("blocknumber0", 1, size0);
        const long          bn1 = t.integer("blocknumber1", 1, size1);
        std::vector<long>   rs(bn0), cs(bn1);
        for (long i = 0; i < bn0; ++i)
          rs[i] = t.integer("a cumulative block row size", i == 0 ? 1 : rs[i - 1] + 1, size0);
        for (long i = 0; i < bn1; ++i)
          cs[i] = t.integer("a cumulative block column size", i == 0 ? 1 : cs[i - 1] + 1, size1);
        if (rs.back() != size0 || cs.back() != size1)
          t.error("block sizes do not add up to the matrix size");
        const long        filled1 = t.integer("filled1", bn0 + 1, bn0 + 1);
        const long        filled2 = t.integer("filled2", nbblocks, nbblocks);
        std::vector<long> index1(filled1), index2(filled2);
        for (long i = 0; i < filled1; ++i)
          index1[i] = t.integer("index1_data", i == 0 ? 0 : index1[i - 1], filled2);
        if (index1[0] != 0 || index1.back() != filled2)
          t.error("index1_data must run from 0 to filled2");
        for (long i = 0; i < filled2; ++i)
          index2[i] = t.integer("index2_data", 0, bn1 - 1);
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

      void
      write_dense(std::ostream &out, const DenseMatrix &M)
      {
        out << 0 << '\n' << M.n_rows() << '\n' << M.n_cols() << '\n';
        out << M.n_rows() << '\t' << M.n_cols() << '\n';
        for (std::size_t j = 0; j < M.n_cols(); ++j)
          {
            for (std::size_t i = 0; i < M.n_rows(); ++i)
              out << M(i, j) << ' ';
            out << '\n';
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
      const double a0 = t.peek_number(0, ok[0]), a1 = t.peek_number(1, ok[1]), a2 = t.peek_number(2, ok[2]),
                   a3 = t.peek_number(3, ok[3]);
      if (!(ok[0] && ok[1] && ok[2] && ok[3]))
        t.error("not a Siconos LCP or friction-contact file: it must start with four integers");
      const bool is_lcp = (a1 == 0 || a1 == 1 || a1 == 2) && a2 == a0 && a3 == a0;
      const bool is_fc  = (a0 == 1 || a0 == 2 || a0 == 3) && (a2 == 0 || a2 == 1 || a2 == 2) && a3 == a0 * a1;

      ProblemFile file;
      if (is_lcp)
        {
          file.type    = ProblemType::lcp;
          const long n = t.integer("the LCP size", 0, max_size);
          file.lcp.M   = read_numerics_matrix(t);
          if (file.lcp.M.n_rows() != std::size_t(n) || file.lcp.M.n_cols() != std::size_t(n))
            t.error("the matrix is not n x n");
          file.lcp.q.resize(n);
          for (auto &v : file.lcp.q)
            v = t.number("an entry of q");
          return file;
        }
      if (is_fc)
        {
          file.type       = ProblemType::friction_contact;
          ContactProblem &p = file.contact;
          p.n_directions  = static_cast<unsigned int>(t.integer("the contact dimension", 1, 3));
          p.n_contacts    = static_cast<unsigned int>(t.integer("the number of contacts", 0, max_size));
          p.W             = read_numerics_matrix(t);
          const std::size_t m = std::size_t(p.n_contacts) * p.n_directions;
          if (p.W.n_rows() != m || p.W.n_cols() != m)
            t.error("the matrix is not (d n_c) x (d n_c)");
          p.free_velocity.resize(m);
          for (auto &v : p.free_velocity)
            v = t.number("an entry of q");
          p.mu.resize(p.n_contacts);
          for (auto &v : p.mu)
            {
              v = t.number("a friction coefficient");
              if (v < 0.)
                t.error("negative friction coefficient");
            }
          p.gap_term.assign(p.n_contacts, 0.);
          return file;
        }
      t.error("not a Siconos LCP (n, storage, n, n, ...) or friction-contact (d, n_c, storage, d n_c, ...) file");
    }



    ProblemFile
    read_problem_file(const std::string &filename)
    {
      std::ifstream in(filename);
      if (!in)
        throw std::runtime_error(filename + ": cannot open the file for reading");
      return read_problem(in, filename);
    }



    void
    write_lcp(std::ostream &out, const DenseMatrix &M, const std::vector<double> &q)
    {
      if (M.n_rows() != q.size() || M.n_cols() != q.size())
        throw std::invalid_argument("write_lcp: inconsistent sizes");
      const auto old = out.precision(17);
      out << q.size() << '\n';
      write_dense(out, M);
      for (const double v : q)
        out << v << ' ';
      out << '\n';
      out.precision(old);
    }



    void
    write_friction_contact(std::ostream &out, const ContactProblem &p)
    {
      check_contact_problem(p);
      const auto old = out.precision(17);
      out << p.n_directions << '\n' << p.n_contacts << '\n';
      write_dense(out, p.W);
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        for (unsigned int a = 0; a < p.n_directions; ++a)
          out << p.free_velocity[c * p.n_directions + a] + (a == 0 ? p.gap_term[c] : 0.) << ' ';
      out << '\n';
      for (unsigned int c = 0; c < p.n_contacts; ++c)
        out << (p.mu.empty() ? 0. : p.mu[c]) << ' ';
      out << '\n';
      out.precision(old);
    }



    void
    write_lcp_file(const std::string &filename, const DenseMatrix &M, const std::vector<double> &q)
    {
      std::ofstream out(filename);
      if (!out)
        throw std::runtime_error(filename + ": cannot open the file for writing");
      write_lcp(out, M, q);
      if (!out)
        throw std::runtime_error(filename + ": write error");
    }



    void
    write_friction_contact_file(const std::string &filename, const ContactProblem &problem)
    {
      std::ofstream out(filename);
      if (!out)
        throw std::runtime_error(filename + ": cannot open the file for writing");
      write_friction_contact(out, problem);
      if (!out)
        throw std::runtime_error(filename + ": write error");
    }
  } // namespace lcp
} // namespace impactfe
