#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>

#include <impactfe/utilities/blas_threads.h>
#include <impactfe/utilities/program.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <new>
#include <set>
#include <sstream>

namespace impactfe
{
  std::string
  format_number(const double value)
  {
    std::ostringstream s;
    s << value;
    return s.str();
  }



  std::string
  format_input(const double value)
  {
    std::ostringstream s;
    for (int digits = 6; digits <= 17; ++digits)
      {
        s.str("");
        s.precision(digits);
        s << value;
        if (!std::isfinite(value) ||
            std::strtod(s.str().c_str(), nullptr) == value)
          break;
      }
    return s.str();
  }



  void
  append_csv_number(std::string &line, const double value, const char separator)
  {
    char       text[40];
    const auto end = std::to_chars(text,
                                   text + sizeof(text) - 1,
                                   value,
                                   std::chars_format::general,
                                   10)
                       .ptr;
    *end = separator;
    line.append(text, end + 1);
  }



  double
  parse_list_number(const std::string &text,
                    const std::string &subsection,
                    const std::string &entry)
  {
    const auto   begin = text.find_first_not_of(" \t");
    const auto   last  = text.find_last_not_of(" \t");
    const auto   item  = begin == std::string::npos ?
                           std::string() :
                           text.substr(begin, last - begin + 1);
    char        *end   = nullptr;
    const double value = item.empty() ? 0. : std::strtod(item.c_str(), &end);
    AssertThrow(!item.empty() && *end == '\0' && std::isfinite(value),
                dealii::ExcMessage(subsection + ": '" + entry + "' has '" +
                                   text + "', which is not a finite number."));
    return value;
  }



  void
  require_positive(const double       value,
                   const std::string &subsection,
                   const std::string &entry)
  {
    AssertThrow(value > 0. && std::isfinite(value),
                dealii::ExcMessage(subsection + ": '" + entry +
                                   "' must be > 0, got " +
                                   format_number(value) + "."));
  }



  namespace
  {
    // ParameterHandler names an entry by its path, subsections and name
    // joined by '.', every character that is not an ASCII letter or digit
    // written as _ and two hex digits (a space is _20).
    std::string
    mangled_parameter_name(const std::string &name)
    {
      std::string mangled;
      for (const unsigned char c : name)
        if ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
            (c >= '0' && c <= '9'))
          mangled += static_cast<char>(c);
        else
          {
            static const char hex[] = "0123456789abcdef";
            mangled += '_';
            mangled += hex[c / 16];
            mangled += hex[c % 16];
          }
      return mangled;
    }



    // The template of --print-parameters with the entries that have no
    // default (@p required, ParameterHandler's paths) commented out: their
    // placeholders would otherwise pass for values, and a run of the
    // unedited template would simulate E = 1 Pa, h = 1e-3 s, ...
    std::string
    template_with_required_entries_open(const std::string           &text,
                                        const std::set<std::string> &required)
    {
      std::istringstream       in(text);
      std::ostringstream       out;
      std::vector<std::string> path;
      std::string              line;
      while (std::getline(in, line))
        {
          const auto        first = line.find_first_not_of(' ');
          const std::string body =
            first == std::string::npos ? std::string() : line.substr(first);
          if (body.rfind("subsection ", 0) == 0)
            path.push_back(mangled_parameter_name(body.substr(11)));
          else if (body == "end" && !path.empty())
            path.pop_back();
          else if (body.rfind("set ", 0) == 0 &&
                   body.find('=') != std::string::npos)
            {
              const std::string before = body.substr(0, body.find('='));
              std::string       name   = before.substr(4);
              name.erase(name.find_last_not_of(' ') + 1);
              std::string full;
              for (const std::string &s : path)
                full += s + '.';
              if (required.count(full + mangled_parameter_name(name)) > 0)
                line = line.substr(0, first) + "# " + before +
                       "= (no default: set it)";
            }
          out << line << '\n';
        }
      return out.str();
    }
  } // namespace



  void
  require_entries_set(const dealii::ParameterHandler &prm,
                      const std::string              &subsection,
                      const std::vector<std::string> &entries)
  {
    // @p subsection is a top-level one: call this outside any subsection.
    const std::set<std::string> not_set = prm.get_entries_wrongly_not_set();
    std::vector<std::string>    missing;
    for (const std::string &entry : entries)
      if (not_set.count(mangled_parameter_name(subsection) + '.' +
                        mangled_parameter_name(entry)) > 0)
        missing.push_back("'" + entry + "'");
    std::string list;
    for (unsigned int i = 0; i < missing.size(); ++i)
      list += (i == 0                  ? "" :
               i + 1 == missing.size() ? " and " :
                                         ", ") +
              missing[i];
    AssertThrow(missing.empty(),
                dealii::ExcMessage(
                  "Subsection '" + subsection +
                  "': the parameter file does "
                  "not set " +
                  list + ". " +
                  (missing.size() == 1 ? "This entry has" :
                                         "These entries have") +
                  " no default: add 'set <entry> = <value>' to the "
                  "subsection (see the entry's help text for its unit)."));
  }



  void
  require_representable_mass(const double mass, const std::string &what)
  {
    AssertThrow(mass >= 1e-100 && mass <= 1e100,
                dealii::ExcMessage(
                  "Initial conditions: the mass of " + what +
                  " ('Density' times the volume, or the area times "
                  "'Thickness' in 2D) is " +
                  format_number(mass) +
                  " kg, outside [1e-100, 1e100] kg, where momenta and "
                  "energies would leave double precision: the run is not "
                  "started."));
  }



  void
  require_non_negative(const double       value,
                       const std::string &subsection,
                       const std::string &entry)
  {
    AssertThrow(value >= 0. && std::isfinite(value),
                dealii::ExcMessage(subsection + ": '" + entry +
                                   "' must be >= 0, got " +
                                   format_number(value) + "."));
  }



  std::string
  exception_text(const std::exception &error)
  {
    std::ostringstream text;
    if (const auto *deal_error =
          dynamic_cast<const dealii::ExceptionBase *>(&error))
      deal_error->print_info(text);
    else
      text << error.what();
    const std::string raw   = text.str();
    const auto        begin = raw.find_first_not_of(" \t\r\n");
    return begin == std::string::npos ?
             std::string() :
             raw.substr(begin, raw.find_last_not_of(" \t\r\n") - begin + 1);
  }



  namespace
  {
    // Without the white space at both ends, as deal.II's Utilities::trim().
    std::string
    trim(const std::string &text)
    {
      const auto begin = text.find_first_not_of(" \t\r\n\v\f");
      return begin == std::string::npos ?
               std::string() :
               text.substr(begin,
                           text.find_last_not_of(" \t\r\n\v\f") - begin + 1);
    }
  } // namespace



  std::vector<std::pair<unsigned int, std::string>>
  parameter_file_statements(const std::filesystem::path &file)
  {
    // As ParameterHandler::parse_input() and scan_line(): each line is
    // trimmed, a trailing backslash joins it to the next one, and then the
    // joined statement loses its comment, has its tabs made blanks and is
    // trimmed again (so a comment ending in a backslash swallows the next
    // line, as in deal.II).
    std::vector<std::pair<unsigned int, std::string>> statements;
    std::ifstream                                     in(file);
    std::string                                       raw, joined;
    unsigned int line_number = 0, first_line = 0;
    bool         continued = false;
    const auto   finish    = [&]() {
      std::string statement = joined.substr(0, joined.find('#'));
      std::replace(statement.begin(), statement.end(), '\t', ' ');
      statement = trim(statement);
      if (!statement.empty())
        statements.emplace_back(first_line, statement);
      joined.clear();
    };
    while (std::getline(in, raw))
      {
        ++line_number;
        if (!continued)
          first_line = line_number;
        std::string line = trim(raw);
        continued        = !line.empty() && line.back() == '\\';
        if (continued)
          line.pop_back();
        joined += line;
        if (!continued)
          finish();
      }
    if (continued) // deal.II reads a last line that ends in a backslash
      finish();
    return statements;
  }



  std::string
  included_file(const std::string &statement)
  {
    if ((statement.rfind("include", 0) != 0 &&
         statement.rfind("INCLUDE", 0) != 0) ||
        statement.size() <= 7 ||
        !std::isspace(static_cast<unsigned char>(statement[7])))
      return "";
    const auto begin = statement.find_first_not_of(" \t", 7);
    return begin == std::string::npos ? "" : statement.substr(begin);
  }



  namespace
  {
    using EntryPath = std::vector<std::string>; // subsections, then name

    std::string
    describe_entry(const EntryPath &entry)
    {
      std::string subsection;
      for (std::size_t i = 0; i + 1 < entry.size(); ++i)
        subsection += (subsection.empty() ? "" : "/") + entry[i];
      return "'" + entry.back() + "'" +
             (subsection.empty() ? std::string(" (top level)") :
                                   " in subsection '" + subsection + "'");
    }

    // Follows the include statements of @p file depth first (@p chain holds
    // the files that include it, outermost first) and returns the entries
    // that the file and its included files set, relative to where the file
    // is read. deal.II keeps the last `set` of an entry without a word, so
    // two in one file are refused (a value edited in one place and left in
    // another is lost), and so is an entry set before an include that sets
    // it again (the included value would win). An entry set after the
    // include is an override, and allowed.
    std::set<EntryPath>
    check_include_statements(const std::filesystem::path        &file,
                             std::vector<std::filesystem::path> &chain)
    {
      chain.push_back(file);
      const auto starts_with_keyword = [](const std::string &statement,
                                          const std::string &lower,
                                          const std::string &upper) {
        return (statement.rfind(lower + " ", 0) == 0 ||
                statement.rfind(upper + " ", 0) == 0);
      };
      std::vector<std::string>          path;     // the open subsections
      std::map<EntryPath, unsigned int> set_here; // and the line
      std::set<EntryPath>               entries;
      for (const auto &[line, statement] : parameter_file_statements(file))
        {
          const std::string at = "The parameter file '" + file.string() +
                                 "', line " + std::to_string(line);
          if (starts_with_keyword(statement, "subsection", "SUBSECTION"))
            path.push_back(trim(statement.substr(10)));
          else if ((statement == "end" || statement == "END") && !path.empty())
            path.pop_back();
          else if (starts_with_keyword(statement, "set", "SET") &&
                   statement.find('=') != std::string::npos)
            {
              EntryPath entry = path;
              entry.push_back(
                trim(statement.substr(3, statement.find('=') - 3)));
              const auto [first, is_new] = set_here.emplace(entry, line);
              AssertThrow(is_new,
                          dealii::ExcMessage(
                            at + ": " + describe_entry(entry) +
                            " is set a second time (first at line " +
                            std::to_string(first->second) +
                            "); only the last value would count. Keep one "
                            "of the two."));
              entries.insert(entry);
            }
          const std::string name = included_file(statement);
          if (name.empty())
            continue;
          const std::string where = at + ", includes '" + name + "'";
          // deal.II opens it as a stream: any file but a directory (a
          // pipe or /dev/null too)
          std::error_code unreadable;
          AssertThrow(std::filesystem::exists(name, unreadable),
                      dealii::ExcMessage(
                        where + ", which does not exist (include statements "
                                "are relative to the directory the program "
                                "runs in)."));
          AssertThrow(!std::filesystem::is_directory(name, unreadable),
                      dealii::ExcMessage(where + ", which is a directory."));
          for (const auto &including : chain)
            if (std::filesystem::equivalent(including, name, unreadable))
              {
                std::string cycle;
                for (const auto &link : chain)
                  cycle += "'" + link.string() + "' -> ";
                AssertThrow(false,
                            dealii::ExcMessage(where + ": an include cycle (" +
                                               cycle + "'" + name + "')."));
              }
          AssertThrow(chain.size() < 64,
                      dealii::ExcMessage(where + ": more than 64 nested "
                                                 "include statements."));
          // the included file is read inside the open subsections
          for (const EntryPath &included :
               check_include_statements(name, chain))
            {
              EntryPath entry = path;
              entry.insert(entry.end(), included.begin(), included.end());
              const auto earlier = set_here.find(entry);
              AssertThrow(earlier == set_here.end(),
                          dealii::ExcMessage(
                            where + ", which sets " + describe_entry(entry) +
                            " again after line " +
                            std::to_string(earlier->second) +
                            " set it: the included value would count. Set "
                            "it after the include statement to override "
                            "the included file."));
              entries.insert(entry);
            }
        }
      chain.pop_back();
      return entries;
    }



    // The same for JSON and XML (deal.II's formats, read as Boost property
    // trees): an entry is a node with a "value" child, or a leaf; its key
    // may be mangled ("Time_20step") or not, and a subsection may appear
    // twice, so entries are compared by their demangled paths.
    void
    check_tree_entries_set_once(const std::string &file, const bool json)
    {
      boost::property_tree::ptree tree;
      if (json)
        boost::property_tree::read_json(file, tree);
      else
        boost::property_tree::read_xml(file, tree);
      const auto demangle = [](const std::string &key) {
        std::string name;
        for (std::size_t i = 0; i < key.size(); ++i)
          if (key[i] == '_' && i + 2 < key.size() &&
              std::isxdigit(static_cast<unsigned char>(key[i + 1])) &&
              std::isxdigit(static_cast<unsigned char>(key[i + 2])))
            {
              name +=
                static_cast<char>(std::stoi(key.substr(i + 1, 2), nullptr, 16));
              i += 2;
            }
          else
            name += key[i];
        return name;
      };
      std::set<EntryPath> seen;
      const std::function<void(const boost::property_tree::ptree &,
                               const EntryPath &)>
        walk =
          [&](const boost::property_tree::ptree &node, const EntryPath &path) {
            for (const auto &[key, child] : node)
              {
                if (key.rfind("<xml", 0) == 0)
                  continue;
                EntryPath entry = path;
                entry.push_back(demangle(key));
                if (child.empty() || child.count("value") > 0)
                  {
                    AssertThrow(seen.insert(entry).second,
                                dealii::ExcMessage(
                                  "The parameter file '" + file +
                                  "': " + describe_entry(entry) +
                                  " is set twice; only the last value would "
                                  "count. Keep one of the two."));
                  }
                else
                  walk(child, entry);
              }
          };
      // deal.II's XML has one root element, ParameterHandler
      if (json)
        walk(tree, {});
      else
        for (const auto &[key, root] : tree)
          if (key.rfind("<xml", 0) != 0)
            walk(root, {});
    }
  } // namespace



  void
  read_parameter_file(dealii::ParameterHandler &prm, const std::string &file)
  {
    AssertThrow(std::filesystem::exists(file),
                dealii::ExcMessage("The parameter file '" + file +
                                   "' does not exist."));
    AssertThrow(!std::filesystem::is_directory(file),
                dealii::ExcMessage("The parameter file '" + file +
                                   "' is a directory."));
    const std::string extension = std::filesystem::path(file).extension();
    AssertThrow(extension == ".prm" || extension == ".json" ||
                  extension == ".xml",
                dealii::ExcMessage(
                  "The parameter file '" + file +
                  "' must end in .prm, .json or .xml (the extension tells "
                  "deal.II its format), got '" +
                  extension + "'."));
    if (extension == ".prm")
      {
        std::vector<std::filesystem::path> chain;
        check_include_statements(file, chain);
        prm.parse_input(file);
        return;
      }
    // deal.II reads JSON and XML through Boost's property tree, whose
    // messages say "<unspecified file>(line)": put the file's name there.
    try
      {
        prm.parse_input(file);
        check_tree_entries_set_once(file, extension == ".json");
      }
    catch (const std::exception &error)
      {
        // Boost's syntax errors, with "<unspecified file>(2)" as "line 2",
        // on one line; deal.II's own messages (an undeclared entry, a value
        // that does not match its pattern) already say what is wrong.
        std::string       raw = exception_text(error);
        const std::string unnamed("<unspecified file>(");
        if (raw.find(unnamed) == std::string::npos)
          throw;
        for (auto at = raw.find(unnamed); at != std::string::npos;
             at      = raw.find(unnamed))
          {
                 const auto close = raw.find(')', at);
                 const auto end =
              close == std::string::npos ? raw.size() : close + 1;
                 raw.replace(at,
                        end - at,
                        "line " + raw.substr(at + unnamed.size(),
                                             end - 1 - at - unnamed.size()));
          }
        std::istringstream words(raw);
        std::string        text;
        for (std::string word; words >> word;)
          text += (text.empty() ? "" : " ") + word;
        AssertThrow(false,
                    dealii::ExcMessage(
                      "The parameter file '" + file + "' is not valid " +
                      (extension == ".json" ? "JSON" : "XML") + ": " + text));
      }
  }



  double
  get_verification_bound(dealii::ParameterHandler &prm,
                         const std::string        &entry)
  {
    const double bound = prm.get_double(entry);
    AssertThrow(bound == -1. || (bound >= 0. && std::isfinite(bound)),
                dealii::ExcMessage("Verification: '" + entry +
                                   "' must be >= 0 or -1 (no check), got " +
                                   format_number(bound) + "."));
    return bound;
  }



  void
  require_friction_coefficient(const double       value,
                               const std::string &subsection,
                               const std::string &entry)
  {
    require_non_negative(value, subsection, entry);
    AssertThrow(value <= 1e6,
                dealii::ExcMessage(
                  subsection + ": '" + entry + "' must be at most 1e6, got " +
                  format_number(value) +
                  " (the contact problem's friction rows would keep fewer "
                  "digits than its verification needs)."));
  }



  void
  require_mesh_fits_in_memory(const double       n_cells,
                              const unsigned int dim,
                              const std::string &subsection,
                              const std::string &entries,
                              const double       bytes_per_cell_of_program)
  {
    // Half the peak resident memory per cell measured with /usr/bin/time
    // on two_bars_1d, two_bars_2d and block_sliding_3d (1, 9.4 and 72 kB).
    const double      bytes_per_cell = bytes_per_cell_of_program > 0. ?
                                         bytes_per_cell_of_program :
                                       dim == 1 ? 500. :
                                       dim == 2 ? 4.5e3 :
                                                  3.5e4;
    const std::string mesh = subsection + ": the mesh of " + entries + " has " +
                             format_figure(n_cells) + " cells in " +
                             std::to_string(dim) + "D";
    // deal.II is built with 32-bit cell and DoF indices.
    AssertThrow(n_cells < 2147483648.,
                dealii::ExcMessage(mesh + ", more than deal.II's 32-bit "
                                          "indices count (2^31)."));
    const double pages     = double(sysconf(_SC_PHYS_PAGES));
    const double page_size = double(sysconf(_SC_PAGESIZE));
    const double memory    = pages * page_size;
    const double needed    = n_cells * bytes_per_cell;
    AssertThrow(pages <= 0. || page_size <= 0. || needed <= memory,
                dealii::ExcMessage(mesh + ", which need at least " +
                                   format_figure(needed / 1e9) + " GB (" +
                                   format_figure(bytes_per_cell / 1e3) +
                                   " kB per cell); this machine has " +
                                   format_figure(memory / 1e9) +
                                   " GB of memory."));
  }



  std::string
  format_figure(const double value, const double round_off)
  {
    std::ostringstream text;
    if (std::abs(value) < round_off)
      text << "< " << round_off;
    else
      text << std::setprecision(3) << value;
    return text.str();
  }



  LaunchedProcesses
  launched_processes()
  {
    // a launcher's variable, if it holds a number
    const auto read = [](const char *name, unsigned int &value) {
      const char *text = std::getenv(name);
      if (text == nullptr || *text == '\0')
        return false;
      char               *end    = nullptr;
      const unsigned long number = std::strtoul(text, &end, 10);
      if (*end != '\0')
        return false;
      value = static_cast<unsigned int>(number);
      return true;
    };
    LaunchedProcesses processes;
    for (const auto &[size_name, rank_name] :
         {std::pair{"OMPI_COMM_WORLD_SIZE", "OMPI_COMM_WORLD_RANK"},
          std::pair{"PMI_SIZE", "PMI_RANK"}})
      if (read(size_name, processes.size))
        {
          read(rank_name, processes.rank);
          break;
        }
    return processes;
  }



  void
  require_one_process(const std::string &program,
                      const std::string &alternative)
  {
    const LaunchedProcesses processes = launched_processes();
    if (processes.size <= 1)
      return;
    // exit 0: mpirun stops all processes at the first non-zero exit, which
    // could stop rank 0 before it has printed; it still returns rank 0's 1
    if (processes.rank != 0)
      std::exit(0);
    AssertThrow(false,
                dealii::ExcMessage(
                  program +
                  " runs on one process, but an MPI launcher "
                  "started it on " +
                  std::to_string(processes.size) +
                  ": each process would make the same run and write the "
                  "same files. Run it without mpirun; " +
                  alternative));
  }



  std::string
  command_line_usage(const std::string &program,
                     const std::string &default_file)
  {
    // The programs that run on several ranks initialise MPI before this.
    const std::string on_ranks =
      dealii::Utilities::MPI::job_supports_mpi() ?
        "       mpirun -np N " + program +
          " [parameter file]   (a distributed run on N ranks)\n" :
        std::string();
    return "Usage: " + program + " [parameter file]\n" + on_ranks + "       " +
           program + " --print-parameters\n" + "       " + program +
           " --help (or -h)\n" +
           "Runs the parameter file (default: " + default_file +
           ").\n"
           "Its 'include' statements are relative to the current directory; "
           "mesh and\n"
           "data file names to the directory of the file that sets them.\n"
           "--print-parameters writes every entry with its default and help "
           "text\n"
           "(units, ranges) in the parameter-file format, a template to "
           "edit; the entries\n"
           "without a default are commented out there: set them.\n"
           "The output files are described in README.md, 'Output files'.\n";
  }



  CommandLine
  parse_command_line(const int          argc,
                     char              *argv[],
                     const std::string &program,
                     const std::string &default_file)
  {
    CommandLine command_line;
    command_line.parameter_file = default_file;
    for (int i = 1; i < argc; ++i)
      {
        const std::string argument = argv[i];
        if (argument == "--help" || argument == "-h")
          command_line.action = CommandLine::Action::help;
        else if (argument == "--print-parameters")
          command_line.action = CommandLine::Action::print_parameters;
        else
          {
            // A name that starts with '-' is an option misspelt more often
            // than a file; "./-x.prm" reaches such a file.
            AssertThrow(argument.empty() || argument[0] != '-',
                        dealii::ExcMessage(
                          "unknown option '" + argument + "'.\n" +
                          command_line_usage(program, default_file)));
            AssertThrow(i == 1 && argc == 2,
                        dealii::ExcMessage(
                          "one parameter file at most, got " +
                          std::to_string(argc - 1) + " arguments.\n" +
                          command_line_usage(program, default_file)));
            command_line.parameter_file = argument;
          }
      }
    AssertThrow(argc <= 2,
                dealii::ExcMessage("one argument at most, got " +
                                   std::to_string(argc - 1) + ".\n" +
                                   command_line_usage(program, default_file)));
    return command_line;
  }



  bool
  answer_informational_option(
    const CommandLine                                     &command_line,
    const std::string                                     &program,
    const std::string                                     &default_file,
    const std::function<void(dealii::ParameterHandler &)> &declare_parameters)
  {
    if (command_line.action == CommandLine::Action::run)
      return false;
    // The serial programs do not initialise MPI.
    const bool rank_zero =
      !dealii::Utilities::MPI::job_supports_mpi() ||
      dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD) == 0;
    if (command_line.action == CommandLine::Action::help)
      {
        if (rank_zero)
          std::cout << command_line_usage(program, default_file);
        return true;
      }
    dealii::ParameterHandler prm;
    declare_parameters(prm);
    std::ostringstream text;
    prm.print_parameters(text, dealii::ParameterHandler::PRM);
    if (rank_zero)
      std::cout << template_with_required_entries_open(
        text.str(), prm.get_entries_wrongly_not_set());
    return true;
  }



  int
  report_exception(const std::exception &exc)
  {
    std::cerr << std::endl
              << "----------------------------------------------------"
              << std::endl
              << "Exception on processing: " << std::endl;
    if (const auto *deal_exc =
          dynamic_cast<const dealii::ExceptionBase *>(&exc))
      deal_exc->print_info(std::cerr);
    else if (dynamic_cast<const std::bad_alloc *>(&exc) != nullptr)
      std::cerr << "    Out of memory: the problem is too large for this "
                   "machine (check the numbers of cells, the refinement and "
                   "'Number of facets')."
                << std::endl;
    else
      std::cerr << exc.what() << std::endl;
    std::cerr << "Aborting!" << std::endl
              << "----------------------------------------------------"
              << std::endl;
    return 1;
  }



  namespace
  {
    double
    process_cpu_seconds()
    {
      timespec now;
      clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
      return now.tv_sec + 1e-9 * now.tv_nsec;
    }
  } // namespace

  void
  set_thread_limit(const unsigned int n_threads)
  {
    dealii::MultithreadInfo::set_thread_limit(
      n_threads == 0 ? dealii::numbers::invalid_unsigned_int : n_threads);
    set_blas_thread_limit(n_threads);
  }



  double
  thread_cpu_seconds()
  {
    timespec now;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
    return now.tv_sec + 1e-9 * now.tv_nsec;
  }

  double
  wall_seconds()
  {
    timespec now;
    clock_gettime(CLOCK_MONOTONIC, &now);
    return now.tv_sec + 1e-9 * now.tv_nsec;
  }

  Stopwatch::Stopwatch(const Clock clock)
    : clock(clock)
  {}

  double
  Stopwatch::now() const
  {
    return clock == Clock::wall ? wall_seconds() : process_cpu_seconds();
  }

  void
  Stopwatch::start()
  {
    started_at = now();
  }

  void
  Stopwatch::stop()
  {
    if (started_at >= 0.)
      accumulated += now() - started_at;
    started_at = -1.;
  }

  double
  Stopwatch::seconds() const
  {
    return accumulated;
  }



  int
  report_unknown_exception()
  {
    std::cerr << std::endl
              << "----------------------------------------------------"
              << std::endl
              << "Unknown exception!" << std::endl
              << "Aborting!" << std::endl
              << "----------------------------------------------------"
              << std::endl;
    return 1;
  }



  int
  report_current_exception()
  {
    try
      {
        throw;
      }
    catch (const std::exception &exc)
      {
        return report_exception(exc);
      }
    catch (...)
      {
        return report_unknown_exception();
      }
  }
} // namespace impactfe
