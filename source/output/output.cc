#include <deal.II/base/exceptions.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/mapping_q_eulerian.h>

#include <deal.II/numerics/data_out.h>

#include <impactfe/output/output.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace impactfe
{
  void
  OutputParameters::declare_parameters(ParameterHandler  &prm,
                                       const std::string &default_directory)
  {
    prm.enter_subsection("Output");
    prm.declare_entry("Output directory",
                      default_directory,
                      Patterns::Anything(),
                      "Directory for history.csv, summary.json, the VTU/PVD "
                      "files and the plots. Created if missing. A relative "
                      "path is taken from the directory the program runs "
                      "in (not from the parameter file's, as mesh files "
                      "are); the run's last lines name it.");
    prm.declare_entry("VTU output",
                      "true",
                      Patterns::Bool(),
                      "Write VTU files (deformed mesh, velocity, contact "
                      "force, gap, active set) and a solution.pvd record.");
    prm.declare_entry("Output interval",
                      "1",
                      Patterns::Integer(1),
                      "Write VTU files every this many time steps [steps]. "
                      "history.csv always has every step.");
    prm.declare_entry("Write meshes",
                      "false",
                      Patterns::Bool(),
                      "Serial contact programs (contact_mpi and taylor_bar "
                      "refuse it): write each body's mesh as <body "
                      "name>.msh (Gmsh, with its boundary ids) at the "
                      "set-up, so that "
                      "contact_mpi can run the same scene on several MPI "
                      "ranks ('Mesh file', Scene = impact or two "
                      "bodies).");
    prm.declare_entry("Plot",
                      "true",
                      Patterns::Bool(),
                      "Draw the PNG plots at the end of the run (needs "
                      "python3 with matplotlib).");
    prm.declare_entry(
      "Print performance data",
      "true",
      Patterns::Bool(),
      "Print CPU times and LCP pivot counts on the screen (they "
      "are always in summary.json). Tests set this to false so "
      "that the screen output is reproducible.");
    prm.declare_entry("Shape snapshot times",
                      "",
                      Patterns::Anything(),
                      "Comma-separated times at which the deformed mesh of "
                      "each body is written to shapes.csv for figures (2D) "
                      "[s]. Empty: none.");
    prm.leave_subsection();
  }



  void
  OutputParameters::parse_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    directory         = prm.get("Output directory");
    vtu_output        = prm.get_bool("VTU output");
    output_interval   = prm.get_integer("Output interval");
    plot              = prm.get_bool("Plot");
    write_meshes      = prm.get_bool("Write meshes");
    print_performance = prm.get_bool("Print performance data");
    shape_times =
      parse_time_list(prm.get("Shape snapshot times"), "Shape snapshot times");
    prm.leave_subsection();
    AssertThrow(!directory.empty(),
                ExcMessage("Output: 'Output directory' must not be empty."));
  }



  void
  OutputParameters::check_shape_times(const bool         writes_shapes,
                                      const unsigned int n_steps,
                                      const double       time_step) const
  {
    if (shape_times.empty())
      return;
    AssertThrow(writes_shapes,
                ExcMessage("Output: 'Shape snapshot times' is for the 2D "
                           "programs (shapes.csv holds edges of plane "
                           "meshes); this run writes no shapes, so leave "
                           "it empty."));
    // ShapeWriter::write_if_due() takes a time within half a step.
    const double last_time = n_steps * time_step;
    AssertThrow(shape_times.back() <= last_time + 0.5 * time_step,
                ExcMessage("Output: 'Shape snapshot times' has " +
                           format_number(shape_times.back()) +
                           " s, after the run's last step at " +
                           format_number(last_time) +
                           " s ('End time'): that shape would never be "
                           "written."));
  }



  void
  OutputParameters::refuse_mesh_output(const std::string &why) const
  {
    AssertThrow(!write_meshes,
                ExcMessage("Output: 'Write meshes' = true, but this program "
                           "writes no mesh files: " +
                           why + "."));
  }



  void
  create_output_directory(const std::string &directory)
  {
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    AssertThrow(!error && std::filesystem::is_directory(directory),
                ExcMessage("Output: cannot create the output directory '" +
                           directory + "': " + error.message()));
  }



  void
  remove_previous_run_output(const std::string              &directory,
                             const std::vector<std::string> &body_names,
                             const std::vector<std::string> &parallel_records)
  {
    std::error_code not_removed; // then writing it fails with a message
    for (const char *name : {"summary.json",
                             "history.png",
                             "solution.pvd",
                             "shapes.csv",
                             "cells_final.csv"})
      std::filesystem::remove(directory + "/" + name, not_removed);
    const auto digits = [](const std::string &text,
                           const std::size_t  at_least) {
      return text.size() >= at_least &&
             std::all_of(text.begin(), text.end(), [](const char c) {
               return c >= '0' && c <= '9';
             });
    };
    // the part of @p file between @p prefix and ".vtu", if it has both
    const auto between = [](const std::string &file,
                            const std::string &prefix,
                            std::string       &middle) {
      if (file.size() < prefix.size() + 4 || file.rfind(prefix, 0) != 0 ||
          file.compare(file.size() - 4, 4, ".vtu") != 0)
        return false;
      middle = file.substr(prefix.size(), file.size() - prefix.size() - 4);
      return true;
    };
    // "<body>-" and five or more digits (setw(5)) and ".vtu"
    const auto is_body_vtu = [&](const std::string &file) {
      std::string number;
      for (const std::string &body : body_names)
        if (between(file, body + "-", number) && digits(number, 5))
          return true;
      return false;
    };
    // "<record>_" and four or more digits, then ".pvtu", or "." and the
    // rank's digits (as many as the number of ranks needs) and ".vtu"
    // (DataOut::write_vtu_with_pvtu_record())
    const auto is_parallel_record = [&](const std::string &file) {
      for (const std::string &record : parallel_records)
        {
          const std::string prefix = record + "_";
          if (file.rfind(prefix, 0) != 0)
            continue;
          const std::string rest = file.substr(prefix.size());
          const auto        dot  = rest.find('.');
          if (dot == std::string::npos || !digits(rest.substr(0, dot), 4))
            continue;
          const std::string tail = rest.substr(dot + 1);
          std::string       rank;
          if (tail == "pvtu" || (between(tail, "", rank) && digits(rank, 1)))
            return true;
        }
      return false;
    };
    std::vector<std::filesystem::path> stale;
    for (const auto &entry :
         std::filesystem::directory_iterator(directory, not_removed))
      if (entry.is_regular_file(not_removed) &&
          (is_body_vtu(entry.path().filename().string()) ||
           is_parallel_record(entry.path().filename().string())))
        stale.push_back(entry.path());
    for (const auto &file : stale)
      std::filesystem::remove(file, not_removed);
  }



  HistoryWriter::HistoryWriter(const std::string              &file_name,
                               const std::vector<std::string> &columns)
    : file_name(file_name)
    , out(file_name)
    , column_names(columns)
  {
    AssertThrow(out, ExcMessage("Output: cannot write " + file_name));
    for (unsigned int i = 0; i < columns.size(); ++i)
      out << columns[i] << (i + 1 == columns.size() ? "\n" : ",");
    out << std::setprecision(10);
  }



  void
  HistoryWriter::add_row(const std::vector<double> &values)
  {
    AssertThrow(values.size() == column_names.size(), ExcInternalError());
    line.clear();
    for (unsigned int i = 0; i < values.size(); ++i)
      {
        AssertThrow(std::isfinite(values[i]),
                    ExcMessage(
                      "Output: the value of column '" + column_names[i] +
                      "' is not finite" +
                      (column_names[0] == "time" && i > 0 ?
                         " at time " + format_number(values[0]) + " s" :
                         std::string()) +
                      " (the state overflowed or diverged: check "
                      "'Time step', 'End time' and the data); the "
                      "run is stopped before it writes it."));
        append_csv_number(line, values[i], i + 1 == values.size() ? '\n' : ',');
      }
    out.write(line.data(), line.size());
    AssertThrow(out,
                ExcMessage("Output: writing " + file_name +
                           " failed (disk full or an I/O error)."));
  }



  void
  HistoryWriter::close()
  {
    out.close();
    AssertThrow(!out.fail(),
                ExcMessage("Output: writing " + file_name +
                           " failed (disk full or an I/O error)."));
  }



  const std::vector<std::string> &
  HistoryWriter::columns() const
  {
    return column_names;
  }



  // A key written twice makes a file that JSON readers take differently
  // (Python keeps the last value, others the first): a programming error.
  void
  JsonObject::check_new_key(const std::string &key) const
  {
    for (const auto &entry : entries)
      if (entry.first == key)
        throw std::logic_error("summary.json: the key '" + key +
                               "' is written twice.");
  }

  JsonObject &
  JsonObject::add(const std::string &key, const double value)
  {
    check_new_key(key);
    std::ostringstream s;
    if (std::isfinite(value))
      s << std::setprecision(10) << value;
    else
      s << "null";
    entries.emplace_back(key, s.str());
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const std::string &value)
  {
    check_new_key(key);
    std::string escaped = "\"";
    for (const char c : value)
      {
        if (c == '"' || c == '\\')
          escaped += '\\';
        escaped += c;
      }
    entries.emplace_back(key, escaped + "\"");
    return *this;
  }

  JsonObject &
  JsonObject::add(const std::string &key, const JsonObject &value)
  {
    check_new_key(key);
    entries.emplace_back(key, "\x01" + std::to_string(entries.size()));
    nested.push_back(value);
    return *this;
  }

  std::string
  JsonObject::str(const unsigned int indent) const
  {
    const std::string pad(indent + 2, ' ');
    std::string       s            = "{\n";
    unsigned int      nested_index = 0;
    for (unsigned int i = 0; i < entries.size(); ++i)
      {
        s += pad + "\"" + entries[i].first + "\": ";
        if (!entries[i].second.empty() && entries[i].second[0] == '\x01')
          s += nested[nested_index++].str(indent + 2);
        else
          s += entries[i].second;
        s += (i + 1 == entries.size() ? "\n" : ",\n");
      }
    return s + std::string(indent, ' ') + "}";
  }

  void
  JsonObject::write(const std::string &file_name) const
  {
    std::ofstream out(file_name);
    AssertThrow(out, ExcMessage("Output: cannot write " + file_name));
    out << str() << "\n";
    out.close();
    AssertThrow(!out.fail(),
                ExcMessage("Output: writing " + file_name +
                           " failed (disk full or an I/O error)."));
  }



  template <int dim>
  SolutionWriter<dim>::SolutionWriter(const std::string &directory)
    : directory(directory)
  {}



  template <int dim>
  void
  SolutionWriter<dim>::write(const MultibodySystem<dim> &system,
                             const unsigned int          step)
  {
    const auto         &bodies   = system.bodies();
    const auto         &state    = system.state();
    const ContactSet   &contacts = system.contacts();
    std::vector<double> gaps;
    contacts.gaps(state.displacement, gaps);

    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const ElasticBody<dim> &body = *bodies[b];

        // Nodal scalars (gap, active flag) on a scalar Q1 space of the
        // same mesh; nodes that are no candidate get gap = -1 and active 0.
        DoFHandler<dim> scalar_dofs(body.dof_handler().get_triangulation());
        const FE_Q<dim> scalar_fe(1);
        scalar_dofs.distribute_dofs(scalar_fe);
        Vector<double> gap(scalar_dofs.n_dofs()), active(scalar_dofs.n_dofs());
        gap = -1.;
        std::vector<types::global_dof_index> vertex_to_scalar(
          body.dof_handler().get_triangulation().n_vertices(),
          numbers::invalid_dof_index);
        for (const auto &cell : scalar_dofs.active_cell_iterators())
          for (const unsigned int v : cell->vertex_indices())
            vertex_to_scalar[cell->vertex_index(v)] =
              cell->vertex_dof_index(v, 0);
        for (unsigned int c = 0; c < contacts.n_candidates(); ++c)
          {
            const ContactCandidate &cand   = contacts.candidate(c);
            unsigned int            vertex = numbers::invalid_unsigned_int;
            if (cand.body_a == b)
              vertex = cand.vertex_a;
            else if (cand.body_b == b)
              vertex = cand.vertices_b[std::distance(
                cand.weights_b.begin(),
                std::max_element(cand.weights_b.begin(),
                                 cand.weights_b.begin() + cand.n_vertices_b))];
            if (vertex == numbers::invalid_unsigned_int)
              continue;
            gap(vertex_to_scalar[vertex])    = gaps[c];
            active(vertex_to_scalar[vertex]) = system.active_set()[c] ? 1. : 0.;
          }

        const Vector<double> &u = state.displacement.block(b);
        MappingQEulerian<dim> deformed(1, body.dof_handler(), u);
        DataOut<dim>          data_out;
        data_out.attach_dof_handler(body.dof_handler());
        const std::vector<
          DataComponentInterpretation::DataComponentInterpretation>
          vector_field(
            dim, DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(u,
                                 std::vector<std::string>(dim, "displacement"),
                                 DataOut<dim>::type_dof_data,
                                 vector_field);
        data_out.add_data_vector(state.velocity.block(b),
                                 std::vector<std::string>(dim, "velocity"),
                                 DataOut<dim>::type_dof_data,
                                 vector_field);
        data_out.add_data_vector(system.nodal_contact_force().block(b),
                                 std::vector<std::string>(dim, "contact_force"),
                                 DataOut<dim>::type_dof_data,
                                 vector_field);
        data_out.add_data_vector(scalar_dofs, gap, "gap");
        data_out.add_data_vector(scalar_dofs, active, "active_contact");
        data_out.build_patches(deformed, 1);

        DataOutBase::VtkFlags flags(state.time, step);
        data_out.set_flags(flags);
        std::ostringstream name;
        name << body.name() << "-" << std::setw(5) << std::setfill('0') << step
             << ".vtu";
        std::ofstream out(directory + "/" + name.str());
        AssertThrow(out, ExcMessage("Output: cannot write " + name.str()));
        data_out.write_vtu(out);
        records.emplace_back(state.time, b, name.str());
      }

    // The record is written whole to a new file that then replaces the old
    // one, so solution.pvd is always a valid collection.
    const std::string pvd_name = directory + "/solution.pvd";
    std::ofstream     pvd(pvd_name + ".new");
    AssertThrow(pvd, ExcMessage("Output: cannot write " + pvd_name + ".new"));
    pvd << "<?xml version=\"1.0\"?>\n"
        << "<VTKFile type=\"Collection\" version=\"0.1\" "
           "byte_order=\"LittleEndian\">\n  <Collection>\n";
    pvd << std::setprecision(12);
    for (const auto &[time, part, file] : records)
      pvd << "    <DataSet timestep=\"" << time << "\" group=\"\" part=\""
          << part << "\" file=\"" << file << "\"/>\n";
    pvd << "  </Collection>\n</VTKFile>\n";
    pvd.close();
    AssertThrow(pvd, ExcMessage("Output: cannot write " + pvd_name + ".new"));
    std::error_code error;
    std::filesystem::rename(pvd_name + ".new", pvd_name, error);
    AssertThrow(!error,
                ExcMessage("Output: cannot write " + pvd_name + " (" +
                           error.message() + ")"));
  }



  template <int dim>
  ShapeWriter<dim>::ShapeWriter(const std::string         &file_name,
                                const std::vector<double> &times)
    : out(file_name)
    , times(times)
  {
    AssertThrow(out, ExcMessage("Output: cannot write " + file_name));
    AssertThrow(std::is_sorted(times.begin(), times.end()),
                ExcMessage("Output: the snapshot times must be increasing."));
    out << "time,body,x0,y0,x1,y1\n" << std::setprecision(10);
  }



  template <int dim>
  void
  ShapeWriter<dim>::write_if_due(const MultibodySystem<dim> &system,
                                 const double                time_step)
  {
    if (dim != 2)
      return;
    const double t   = system.state().time;
    bool         due = false;
    while (next < times.size() && t >= times[next] - 0.5 * time_step)
      {
        due = true;
        ++next;
      }
    if (!due)
      return;
    for (unsigned int b = 0; b < system.bodies().size(); ++b)
      {
        const ElasticBody<dim> &body     = *system.bodies()[b];
        const Vector<double>   &u        = system.state().displacement.block(b);
        const auto              deformed = [&](const unsigned int vertex) {
          Point<dim> x =
            body.dof_handler().get_triangulation().get_vertices()[vertex];
          for (unsigned int d = 0; d < dim; ++d)
            x[d] += body.nodal_value(u, vertex, d);
          return x;
        };
        // Each edge once: boundary faces, and interior faces seen from the
        // cell with the smaller index.
        for (const auto &cell : body.dof_handler().active_cell_iterators())
          for (const unsigned int f : cell->face_indices())
            if (cell->face(f)->at_boundary() ||
                cell->active_cell_index() <
                  cell->neighbor(f)->active_cell_index())
              {
                const Point<dim> x0 = deformed(cell->face(f)->vertex_index(0));
                const Point<dim> x1 = deformed(cell->face(f)->vertex_index(1));
                out << t << "," << b << "," << x0[0] << "," << x0[1] << ","
                    << x1[0] << "," << x1[1] << "\n";
              }
      }
    out.flush();
  }



  std::vector<double>
  parse_time_list(const std::string &text, const std::string &entry_name)
  {
    std::vector<double> times;
    for (const std::string &item : Utilities::split_string_list(text))
      {
        double value = 0.;
        try
          {
            value = Utilities::string_to_double(item);
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage("'" + entry_name + "': '" + item +
                                   "' is not a number."));
          }
        AssertThrow(value >= 0. && std::isfinite(value),
                    ExcMessage("'" + entry_name +
                               "': times must be >= 0, got " + item + "."));
        times.push_back(value);
      }
    std::sort(times.begin(), times.end());
    return times;
  }



  std::string
  plot_history(const std::string              &history,
               const std::string              &png,
               const std::vector<std::string> &columns,
               const std::string              &title,
               std::string                    &why_not)
  {
    const std::string script =
      std::string(IMPACTFE_SOURCE_DIR) + "/tools/plot_history.py";
    if (!std::filesystem::exists(script))
      {
        why_not = "the plot script " + script + " is missing";
        return "";
      }
    if (std::system(
          "/usr/bin/python3 -c 'import matplotlib' > /dev/null 2>&1") != 0)
      {
        why_not = "python3-matplotlib is not installed (apt-get install "
                  "python3-matplotlib)";
        return "";
      }
    std::string command = "/usr/bin/python3 '" + script + "' '" + history +
                          "' '" + png + "' --title '" + title + "'";
    for (const auto &c : columns)
      command += " '" + c + "'";
    if (std::system((command + " > /dev/null 2>&1").c_str()) != 0)
      {
        why_not = "the plot script failed (run: " + command + ")";
        return "";
      }
    return png;
  }



  void
  report_output_files(std::ostream                   &out,
                      const OutputParameters         &output,
                      const std::string              &files,
                      const std::vector<std::string> &columns,
                      const std::string              &title)
  {
    out << "Results in " << output.directory << "/: " << files << std::endl;
    if (!output.plot)
      return;
    std::string       why_not;
    const std::string png = plot_history(output.directory + "/history.csv",
                                         output.directory + "/history.png",
                                         columns,
                                         title,
                                         why_not);
    out << (png.empty() ? "No plot: " + why_not : "Plot: " + png) << std::endl;
  }



  template class ShapeWriter<1>;
  template class ShapeWriter<2>;
  template class ShapeWriter<3>;
  template class SolutionWriter<1>;
  template class SolutionWriter<2>;
  template class SolutionWriter<3>;
} // namespace impactfe
