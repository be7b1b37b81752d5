// FCLib HDF5 files: see include/impactfe/lcp/fclib_io.h and doc/lcp.md.
#include <impactfe/lcp/fclib_io.h>
#include <impactfe/lcp/lu.h>

#include <hdf5.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <numeric>
#include <stdexcept>

namespace impactfe
{
  namespace lcp
  {
    namespace
    {
      /// An HDF5 identifier closed by the matching H5?close on destruction.
      class Handle
      {
      public:
        Handle(const hid_t id_, herr_t (*close_)(hid_t))
          : id(id_)
          , close(close_)
        {}
        Handle(const Handle &) = delete;
        Handle &
        operator=(const Handle &) = delete;
        ~Handle()
        {
          if (id >= 0)
            close(id);
        }
        operator hid_t() const
        {
          return id;
        }
        bool
        valid() const
        {
          return id >= 0;
        }

      private:
        hid_t id;
        herr_t (*close)(hid_t);
      };

      /// HDF5 prints its error stack on every failed call unless told not
      /// to; our messages say what went wrong instead.
      void
      silence_hdf5()
      {
        H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
      }

      std::string
      number(const double x)
      {
        char text[32];
        std::snprintf(text, sizeof(text), "%g", x);
        return text;
      }

      /// A sparse matrix as triplets (duplicates allowed: they are summed).
      struct Triplets
      {
        int                 m = 0, n = 0;
        std::vector<int>    row, col;
        std::vector<double> value;
      };

      /// An open HDF5 file and the error messages that name it.
      class OpenFile
      {
      public:
        OpenFile(const std::string &filename_,
                 const hid_t        id,
                 const char        *what_failed)
          : filename(filename_)
          , file(id, H5Fclose)
        {
          if (!file.valid())
            fail(what_failed);
        }

        [[noreturn]] void
        fail(const std::string &what) const
        {
          throw std::runtime_error(filename + ": " + what);
        }

      protected:
        std::string  filename;
        const Handle file;
      };

      class Reader : public OpenFile
      {
      public:
        explicit Reader(const std::string &filename)
          : OpenFile(filename,
                     H5Fopen(filename.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT),
                     "cannot be opened as an HDF5 file")
        {}

        /// True if every component of the absolute @p path exists.
        bool
        exists(const std::string &path) const
        {
          std::size_t pos = 0;
          while ((pos = path.find('/', pos + 1)) != std::string::npos)
            if (H5Lexists(file, path.substr(0, pos).c_str(), H5P_DEFAULT) <= 0)
              return false;
          return H5Lexists(file, path.c_str(), H5P_DEFAULT) > 0;
        }

        template <typename T>
        std::vector<T>
        read_array(const std::string &path) const
        {
          if (!exists(path))
            fail("the dataset " + path + " is missing");
          const Handle set(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
          if (!set.valid())
            fail(path + " is not a dataset");
          const Handle      type(H5Dget_type(set), H5Tclose);
          const H5T_class_t type_class = H5Tget_class(type);
          if (type_class != H5T_INTEGER && type_class != H5T_FLOAT)
            fail("the dataset " + path + " does not hold numbers");
          if (std::is_integral<T>::value && type_class != H5T_INTEGER)
            fail("the dataset " + path + " should hold integers");
          const Handle   space(H5Dget_space(set), H5Sclose);
          const hssize_t n = H5Sget_simple_extent_npoints(space);
          if (n < 0)
            fail("cannot read the size of " + path);
          std::vector<T> values(static_cast<std::size_t>(n));
          const hid_t    memory_type =
            std::is_integral<T>::value ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE;
          if (n > 0 && H5Dread(set,
                               memory_type,
                               H5S_ALL,
                               H5S_ALL,
                               H5P_DEFAULT,
                               values.data()) < 0)
            fail("cannot read the dataset " + path);
          if constexpr (!std::is_integral<T>::value)
            for (std::size_t k = 0; k < values.size(); ++k)
              if (!std::isfinite(values[k]))
                fail(path + "[" + std::to_string(k) +
                     "] is not a finite number");
          return values;
        }

        int
        read_int(const std::string &path) const
        {
          const std::vector<int> v = read_array<int>(path);
          if (v.size() != 1)
            fail(path + " should hold one integer, it holds " +
                 std::to_string(v.size()));
          return v[0];
        }

        /// A string dataset (fixed or variable length); "" if absent.
        std::string
        read_string(const std::string &path) const
        {
          if (!exists(path))
            return "";
          const Handle set(H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose);
          const Handle type(H5Dget_type(set), H5Tclose);
          if (!set.valid() || H5Tget_class(type) != H5T_STRING)
            fail(path + " is not a string");
          if (H5Tis_variable_str(type) > 0)
            {
              const Handle space(H5Dget_space(set), H5Sclose);
              if (H5Sget_simple_extent_npoints(space) != 1)
                fail(path + " should hold one string");
              char        *text = nullptr;
              const Handle memory_type(H5Tcopy(H5T_C_S1), H5Tclose);
              H5Tset_size(memory_type, H5T_VARIABLE);
              if (H5Dread(
                    set, memory_type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &text) < 0)
                fail("cannot read the string " + path);
              const std::string result = text != nullptr ? text : "";
              H5Dvlen_reclaim(memory_type, space, H5P_DEFAULT, &text);
              return result;
            }
          const std::size_t size = H5Tget_size(type);
          std::string       buffer(size + 1, '\0');
          if (H5Dread(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, &buffer[0]) < 0)
            fail("cannot read the string " + path);
          return buffer.substr(0, std::strlen(buffer.c_str()));
        }

        /// The matrix of group @p path in any of the three forms.
        Triplets
        read_matrix(const std::string &path) const
        {
          Triplets A;
          A.m             = read_int(path + "/m");
          A.n             = read_int(path + "/n");
          const int  nz   = read_int(path + "/nz");
          const auto p    = read_array<int>(path + "/p");
          const auto idx  = read_array<int>(path + "/i");
          const auto x    = read_array<double>(path + "/x");
          const auto name = [&](const char *what) { return path + "/" + what; };
          if (A.m < 0 || A.n < 0)
            fail(path + " has a negative size " + std::to_string(A.m) + " x " +
                 std::to_string(A.n));
          if (nz >= 0) // triplets: i row, p column (CSparse)
            {
              if (p.size() < std::size_t(nz) || idx.size() < std::size_t(nz) ||
                  x.size() < std::size_t(nz))
                fail(path + " has nz = " + std::to_string(nz) +
                     " triplets but p, i or x is shorter");
              for (int k = 0; k < nz; ++k)
                {
                  if (idx[k] < 0 || idx[k] >= A.m || p[k] < 0 || p[k] >= A.n)
                    fail(name("i") + "/" + name("p") + " entry " +
                         std::to_string(k) + ": (" + std::to_string(idx[k]) +
                         ", " + std::to_string(p[k]) + ") is outside the " +
                         std::to_string(A.m) + " x " + std::to_string(A.n) +
                         " matrix");
                  A.row.push_back(idx[k]);
                  A.col.push_back(p[k]);
                  A.value.push_back(x[k]);
                }
              return A;
            }
          if (nz != -1 && nz != -2)
            fail(name("nz") + " = " + std::to_string(nz) +
                 " (>= 0 for triplets, -1 for compressed columns, -2 for "
                 "compressed rows)");
          const bool by_columns = nz == -1;
          const int  outer      = by_columns ? A.n : A.m;
          const int  inner      = by_columns ? A.m : A.n;
          if (p.size() < std::size_t(outer) + 1)
            fail(name("p") + " has " + std::to_string(p.size()) + " entries, " +
                 std::to_string(outer + 1) + " expected");
          if (p[0] != 0)
            fail(name("p") + "[0] = " + std::to_string(p[0]) + ", not 0");
          for (int j = 0; j < outer; ++j)
            if (p[j + 1] < p[j])
              fail(name("p") + " decreases at " + std::to_string(j + 1));
          const int nnz = p[outer];
          if (idx.size() < std::size_t(nnz) || x.size() < std::size_t(nnz))
            fail(path + " has " + std::to_string(nnz) +
                 " entries by its pointers but i or x is shorter");
          for (int j = 0; j < outer; ++j)
            for (int k = p[j]; k < p[j + 1]; ++k)
              {
                if (idx[k] < 0 || idx[k] >= inner)
                  fail(name("i") + "[" + std::to_string(k) +
                       "] = " + std::to_string(idx[k]) + " is outside 0.." +
                       std::to_string(inner - 1));
                A.row.push_back(by_columns ? idx[k] : j);
                A.col.push_back(by_columns ? j : idx[k]);
                A.value.push_back(x[k]);
              }
          return A;
        }

        /// r, u, v of a solution group (each empty if absent).
        FclibSolution
        read_solution(const std::string &path) const
        {
          FclibSolution s;
          if (exists(path + "/r"))
            s.r = read_array<double>(path + "/r");
          if (exists(path + "/u"))
            s.u = read_array<double>(path + "/u");
          if (exists(path + "/v"))
            s.v = read_array<double>(path + "/v");
          return s;
        }
      };


      /**
       * W = H^T M^{-1} H and q = H^T M^{-1} f + w. M is split into its
       * decoupled diagonal blocks (one per rigid body, or one per deformable
       * body), each factorised by dense Cholesky; only the columns of H
       * that touch a block take part in its product.
       */
      void
      condense_global(const Reader              &reader,
                      const Triplets            &M,
                      const Triplets            &H,
                      const std::vector<double> &f,
                      const std::vector<double> &w,
                      DenseMatrix               &W,
                      std::vector<double>       &q)
      {
        const int n = M.m, m = H.n;
        // connected components of M's graph (union-find)
        std::vector<int> parent(n);
        std::iota(parent.begin(), parent.end(), 0);
        const auto find = [&](int a) {
          while (parent[a] != a)
            a = parent[a] = parent[parent[a]];
          return a;
        };
        for (std::size_t k = 0; k < M.row.size(); ++k)
          if (M.value[k] != 0.)
            parent[find(M.row[k])] = find(M.col[k]);
        std::vector<std::vector<int>> blocks(n);
        for (int a = 0; a < n; ++a)
          blocks[find(a)].push_back(a);
        std::vector<int> block_of(n), position(n);
        for (int b = 0; b < n; ++b)
          for (std::size_t r = 0; r < blocks[b].size(); ++r)
            {
              block_of[blocks[b][r]] = b;
              position[blocks[b][r]] = int(r);
            }
        // entries of M and H sorted by block
        std::vector<std::vector<std::size_t>> M_entries(n), H_entries(n);
        for (std::size_t k = 0; k < M.row.size(); ++k)
          M_entries[block_of[M.row[k]]].push_back(k);
        for (std::size_t k = 0; k < H.row.size(); ++k)
          H_entries[block_of[H.row[k]]].push_back(k);

        // A symmetric M is often stored by one triangle (LMGC90's files):
        // then the other is its mirror image.
        std::size_t n_lower = 0, n_upper = 0;
        for (std::size_t k = 0; k < M.row.size(); ++k)
          if (M.value[k] != 0.)
            {
              n_lower += M.row[k] > M.col[k];
              n_upper += M.row[k] < M.col[k];
            }
        const bool one_triangle = (n_lower == 0) != (n_upper == 0);

        W.reinit(m, m);
        q.assign(w.begin(), w.end());
        double max_M = 0.;
        for (const double v : M.value)
          max_M = std::max(max_M, std::abs(v));
        CholeskyFactorization cholesky;
        std::vector<int>      column_position(m, -1);
        for (int b = 0; b < n; ++b)
          {
            const std::vector<int> &rows = blocks[b];
            if (rows.empty())
              continue;
            const std::size_t size = rows.size();
            if (size > 8000)
              reader.fail("M has a coupled block of " + std::to_string(size) +
                          " rows; condensing it densely would need " +
                          std::to_string(size * size * 8 / 1000000) + " MB");
            DenseMatrix Mb(size, size);
            for (const std::size_t k : M_entries[b])
              {
                Mb(position[M.row[k]], position[M.col[k]]) += M.value[k];
                if (one_triangle && M.row[k] != M.col[k])
                  Mb(position[M.col[k]], position[M.row[k]]) += M.value[k];
              }
            for (std::size_t i = 0; i < size; ++i)
              for (std::size_t j = 0; j < i; ++j)
                if (std::abs(Mb(i, j) - Mb(j, i)) > 1e-12 * max_M)
                  reader.fail("M is not symmetric: M(" +
                              std::to_string(rows[i]) + ", " +
                              std::to_string(rows[j]) + ") != M(" +
                              std::to_string(rows[j]) + ", " +
                              std::to_string(rows[i]) + ")");
            if (!cholesky.factorize(Mb))
              reader.fail("M is not positive definite (its block of rows " +
                          std::to_string(rows.front()) + ".." +
                          std::to_string(rows.back()) + ")");
            std::vector<int> columns;
            for (const std::size_t k : H_entries[b])
              if (column_position[H.col[k]] < 0)
                {
                  column_position[H.col[k]] = int(columns.size());
                  columns.push_back(H.col[k]);
                }
            // X = M_b^{-1} [H_b, f_b]
            DenseMatrix Hb(size, columns.size()), X(size, columns.size() + 1);
            for (const std::size_t k : H_entries[b])
              Hb(position[H.row[k]], column_position[H.col[k]]) += H.value[k];
            for (std::size_t r = 0; r < size; ++r)
              {
                for (std::size_t c = 0; c < columns.size(); ++c)
                  X(r, c) = Hb(r, c);
                X(r, columns.size()) = f[rows[r]];
              }
            cholesky.solve(X);
            for (std::size_t a = 0; a < columns.size(); ++a)
              {
                for (std::size_t c = 0; c <= columns.size(); ++c)
                  {
                    double s = 0.;
                    for (std::size_t r = 0; r < size; ++r)
                      s += Hb(r, a) * X(r, c);
                    if (c < columns.size())
                      W(columns[a], columns[c]) += s;
                    else
                      q[columns[a]] += s;
                  }
              }
            for (const int c : columns)
              column_position[c] = -1;
          }
      }


      /// The problem's datasets that impactfe cannot solve.
      void
      refuse_mixed(const Reader &reader, const std::string &root)
      {
        for (const char *part : {"V", "R", "G"})
          if (reader.exists(root + "/" + part))
            reader.fail(root + "/" + part +
                        " is present: mixed problems with equality "
                        "constraints are not supported");
        for (const char *part : {"s", "b"})
          if (reader.exists(root + "/vectors/" + part))
            reader.fail(root + "/vectors/" + part +
                        " is present: mixed problems with equality "
                        "constraints are not supported");
      }


      class Writer : public OpenFile
      {
      public:
        explicit Writer(const std::string &filename)
          : OpenFile(filename,
                     H5Fcreate(filename.c_str(),
                               H5F_ACC_TRUNC,
                               H5P_DEFAULT,
                               H5P_DEFAULT),
                     "cannot be created")
        {}

        void
        group(const std::string &path)
        {
          const Handle g(H5Gcreate2(file,
                                    path.c_str(),
                                    H5P_DEFAULT,
                                    H5P_DEFAULT,
                                    H5P_DEFAULT),
                         H5Gclose);
          if (!g.valid())
            fail("cannot create the group " + path);
        }

        template <typename T>
        void
        array(const std::string &path, const std::vector<T> &values)
        {
          const hsize_t size = values.size();
          const Handle  space(H5Screate_simple(1, &size, nullptr), H5Sclose);
          const bool    integral = std::is_integral<T>::value;
          const Handle  set(create_dataset(path,
                                          integral ? H5T_STD_I32LE :
                                                      H5T_IEEE_F64LE,
                                          space),
                           H5Dclose);
          if (!set.valid() ||
              (size > 0 &&
               H5Dwrite(set,
                        integral ? H5T_NATIVE_INT : H5T_NATIVE_DOUBLE,
                        H5S_ALL,
                        H5S_ALL,
                        H5P_DEFAULT,
                        values.data()) < 0))
            fail("cannot write the dataset " + path);
        }

        void
        string(const std::string &path, const std::string &text)
        {
          const Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
          H5Tset_size(type, text.size() + 1);
          H5Tset_strpad(type, H5T_STR_NULLTERM);
          const Handle space(H5Screate(H5S_SCALAR), H5Sclose);
          const Handle set(create_dataset(path, type, space), H5Dclose);
          if (!set.valid() ||
              H5Dwrite(set, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, text.c_str()) <
                0)
            fail("cannot write the string " + path);
        }

        hid_t
        create_dataset(const std::string &path,
                       const hid_t        type,
                       const hid_t        space)
        {
          return H5Dcreate2(file,
                            path.c_str(),
                            type,
                            space,
                            H5P_DEFAULT,
                            H5P_DEFAULT,
                            H5P_DEFAULT);
        }

        void
        flush()
        {
          if (H5Fflush(file, H5F_SCOPE_GLOBAL) < 0)
            fail("cannot be written");
        }
      };
    } // namespace



    bool
    is_hdf5_file(const std::string &filename)
    {
      std::ifstream in(filename, std::ios::binary);
      char          signature[8] = {};
      in.read(signature, 8);
      return in.gcount() == 8 &&
             std::memcmp(signature, "\211HDF\r\n\032\n", 8) == 0;
    }



    FclibProblem
    read_fclib_file(const std::string &filename)
    {
      silence_hdf5();
      if (!std::ifstream(filename))
        throw std::runtime_error(filename +
                                 ": cannot open the file for reading");
      if (!is_hdf5_file(filename))
        throw std::runtime_error(filename + ": not an HDF5 file");
      const Reader reader(filename);

      FclibProblem problem;
      std::string  root;
      if (reader.exists("/fclib_local"))
        root = "/fclib_local";
      else if (reader.exists("/fclib_global"))
        {
          root                = "/fclib_global";
          problem.from_global = true;
        }
      else
        reader.fail("neither /fclib_local nor /fclib_global is present: not "
                    "an FCLib frictional contact problem");
      refuse_mixed(reader, root);

      const int d = reader.read_int(root + "/spacedim");
      if (d < 1 || d > 3)
        reader.fail(root + "/spacedim = " + std::to_string(d) +
                    " (2 or 3; 1 is impactfe's frictionless extension)");
      ContactProblem &p      = problem.contact;
      p.n_directions         = unsigned(d);
      std::vector<double> mu = reader.read_array<double>(root + "/vectors/mu");

      int m = 0;
      if (!problem.from_global)
        {
          const Triplets W = reader.read_matrix(root + "/W");
          if (W.m != W.n)
            reader.fail(root + "/W is " + std::to_string(W.m) + " x " +
                        std::to_string(W.n) + ", not square");
          m = W.m;
          // q before the dense W: a header's m = 60000 with a short q
          // would take 29 GB first
          p.free_velocity = reader.read_array<double>(root + "/vectors/q");
          if (p.free_velocity.size() != std::size_t(m))
            reader.fail(root + "/vectors/q has " +
                        std::to_string(p.free_velocity.size()) +
                        " entries, W has " + std::to_string(m) + " rows");
          p.W.reinit(m, m);
          for (std::size_t k = 0; k < W.row.size(); ++k)
            p.W(W.row[k], W.col[k]) += W.value[k];
        }
      else
        {
          const Triplets M = reader.read_matrix(root + "/M");
          const Triplets H = reader.read_matrix(root + "/H");
          if (M.m != M.n)
            reader.fail(root + "/M is " + std::to_string(M.m) + " x " +
                        std::to_string(M.n) + ", not square");
          if (H.m != M.m)
            reader.fail(root + "/H has " + std::to_string(H.m) +
                        " rows, M has " + std::to_string(M.m));
          const auto f = reader.read_array<double>(root + "/vectors/f");
          const auto w = reader.read_array<double>(root + "/vectors/w");
          if (f.size() != std::size_t(M.m))
            reader.fail(root + "/vectors/f has " + std::to_string(f.size()) +
                        " entries, M has " + std::to_string(M.m) + " rows");
          if (w.size() != std::size_t(H.n))
            reader.fail(root + "/vectors/w has " + std::to_string(w.size()) +
                        " entries, H has " + std::to_string(H.n) + " columns");
          m                     = H.n;
          problem.n_global_dofs = unsigned(M.m);
          condense_global(reader, M, H, f, w, p.W, p.free_velocity);
        }
      if (m % d != 0)
        reader.fail("the local problem has " + std::to_string(m) +
                    " rows, not a multiple of spacedim = " + std::to_string(d));
      p.n_contacts = unsigned(m / d);
      if (mu.size() != p.n_contacts)
        reader.fail(root + "/vectors/mu has " + std::to_string(mu.size()) +
                    " entries for " + std::to_string(p.n_contacts) +
                    " contacts");
      for (std::size_t c = 0; c < mu.size(); ++c)
        if (mu[c] < 0.)
          reader.fail(root + "/vectors/mu[" + std::to_string(c) +
                      "] = " + number(mu[c]) + " < 0");
      p.mu = std::move(mu);
      p.gap_term.assign(p.n_contacts, 0.);

      problem.info.title       = reader.read_string(root + "/info/title");
      problem.info.description = reader.read_string(root + "/info/description");
      problem.info.math_info   = reader.read_string(root + "/info/math_info");

      const auto check_solution = [&](const FclibSolution &s,
                                      const std::string   &path) {
        if ((!s.r.empty() && s.r.size() != std::size_t(m)) ||
            (!s.u.empty() && s.u.size() != std::size_t(m)) ||
            (!s.v.empty() && s.v.size() != problem.n_global_dofs))
          reader.fail(path + ": r, u or v does not match the problem's size");
      };
      if (reader.exists("/solution"))
        {
          problem.solution = reader.read_solution("/solution");
          check_solution(problem.solution, "/solution");
        }
      if (reader.exists("/guesses/number_of_guesses"))
        {
          const int n_guesses = reader.read_int("/guesses/number_of_guesses");
          for (int k = 1; k <= n_guesses; ++k)
            {
              const std::string path = "/guesses/" + std::to_string(k);
              // (a count of 2e9 with no groups ran on for ever)
              if (!reader.exists(path))
                reader.fail(
                  "/guesses/number_of_guesses = " + std::to_string(n_guesses) +
                  " but " + path + " is missing");
              problem.guesses.push_back(reader.read_solution(path));
              check_solution(problem.guesses.back(), path);
            }
        }
      return problem;
    }



    void
    write_fclib_local_file(const std::string    &filename,
                           const ContactProblem &problem,
                           const FclibInfo      &info,
                           const FclibSolution  *solution,
                           const FclibStorage    storage)
    {
      silence_hdf5();
      const std::size_t m =
        std::size_t(problem.n_directions) * problem.n_contacts;
      if (problem.W.n_rows() != m || problem.W.n_cols() != m ||
          problem.free_velocity.size() != m ||
          problem.gap_term.size() != problem.n_contacts ||
          problem.mu.size() != problem.n_contacts)
        throw std::invalid_argument(
          "write_fclib_local_file: inconsistent problem sizes");

      std::vector<int>    p, i;
      std::vector<double> x;
      int                 nz      = 0;
      const bool          by_rows = storage == FclibStorage::compressed_row;
      if (storage == FclibStorage::triplet)
        {
          for (std::size_t c = 0; c < m; ++c)
            for (std::size_t r = 0; r < m; ++r)
              if (problem.W(r, c) != 0.)
                {
                  i.push_back(int(r));
                  p.push_back(int(c));
                  x.push_back(problem.W(r, c));
                }
          nz = int(x.size());
        }
      else
        {
          p.push_back(0);
          for (std::size_t a = 0; a < m; ++a)
            {
              for (std::size_t b = 0; b < m; ++b)
                {
                  const double v = by_rows ? problem.W(a, b) : problem.W(b, a);
                  if (v != 0.)
                    {
                      i.push_back(int(b));
                      x.push_back(v);
                    }
                }
              p.push_back(int(x.size()));
            }
          nz = by_rows ? -2 : -1;
        }
      std::vector<double> q = problem.free_velocity;
      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        q[c * problem.n_directions] += problem.gap_term[c];

      Writer out(filename);
      out.group("/fclib_local");
      out.group("/fclib_local/W");
      out.array("/fclib_local/W/m", std::vector<int>{int(m)});
      out.array("/fclib_local/W/n", std::vector<int>{int(m)});
      out.array("/fclib_local/W/nz", std::vector<int>{nz});
      out.array("/fclib_local/W/nzmax", std::vector<int>{int(x.size())});
      out.array("/fclib_local/W/p", p);
      out.array("/fclib_local/W/i", i);
      out.array("/fclib_local/W/x", x);
      out.group("/fclib_local/vectors");
      out.array("/fclib_local/vectors/q", q);
      out.array("/fclib_local/vectors/mu", problem.mu);
      out.array("/fclib_local/spacedim",
                std::vector<int>{int(problem.n_directions)});
      if (!info.title.empty() || !info.description.empty() ||
          !info.math_info.empty())
        {
          out.group("/fclib_local/info");
          out.string("/fclib_local/info/title", info.title);
          out.string("/fclib_local/info/description", info.description);
          out.string("/fclib_local/info/math_info", info.math_info);
        }
      if (solution != nullptr)
        {
          out.group("/solution");
          if (!solution->r.empty())
            out.array("/solution/r", solution->r);
          if (!solution->u.empty())
            out.array("/solution/u", solution->u);
          if (!solution->v.empty())
            out.array("/solution/v", solution->v);
        }
      out.flush();
    }


    FclibSolution
    local_solution(const ContactProblem &problem, const std::vector<double> &P)
    {
      FclibSolution s;
      s.r = P;
      problem.W.vmult(s.u, P);
      for (std::size_t k = 0; k < s.u.size(); ++k)
        s.u[k] += problem.free_velocity[k];
      for (unsigned int c = 0; c < problem.n_contacts; ++c)
        s.u[c * problem.n_directions] += problem.gap_term[c];
      return s;
    }



    double
    relative_difference(const std::vector<double> &P,
                        const std::vector<double> &r)
    {
      double d2 = 0., r2 = 0.;
      for (std::size_t k = 0; k < P.size(); ++k)
        {
          d2 += (P[k] - r[k]) * (P[k] - r[k]);
          r2 += r[k] * r[k];
        }
      return std::sqrt(d2 / std::max(r2, 1e-300));
    }

  } // namespace lcp
} // namespace impactfe
