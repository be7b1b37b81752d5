#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/grid_out.h>
#include <deal.II/grid/tria_description.h>

#include <impactfe/bodies/mesh_input.h>
#include <impactfe/utilities/program.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace impactfe
{
  namespace
  {
    std::string
    trimmed(const std::string &text)
    {
      const auto first = text.find_first_not_of(" \t\r");
      if (first == std::string::npos)
        return "";
      return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
    }

    // The words of a file, with the number of the line each is on.
    class WordReader
    {
    public:
      WordReader(std::istream &input, unsigned int &line_number)
        : input(input)
        , line_number(line_number)
      {}

      // The words left on the current line or, if none, those of the next
      // line that has any; none at the end of the file.
      std::vector<std::string>
      next_line()
      {
        std::vector<std::string> line_words;
        std::string              word;
        while (words >> word)
          line_words.push_back(word);
        if (!line_words.empty())
          return line_words;
        std::string line;
        while (line_words.empty() && std::getline(input, line))
          {
            ++line_number;
            words.clear();
            words.str(line);
            while (words >> word)
              line_words.push_back(word);
          }
        return line_words;
      }

      // The next word, or an empty string at the end of the file.
      std::string
      next()
      {
        std::string word;
        while (!(words >> word))
          {
            std::string line;
            if (!std::getline(input, line))
              return "";
            ++line_number;
            words.clear();
            words.str(line);
          }
        return word;
      }

      // Read @p line_words again before the rest of the file.
      void
      push_back(const std::vector<std::string> &line_words)
      {
        std::string line;
        for (const std::string &w : line_words)
          line += w + " ";
        words.clear();
        words.str(line);
      }

    private:
      std::istream      &input;
      unsigned int      &line_number;
      std::istringstream words;
    };

    // The nodes of Gmsh's linear elements (and the point), by type number;
    // 0 for the types deal.II does not read.
    unsigned int
    gmsh_nodes_per_element(const long type)
    {
      switch (type)
        {
          case 1: // line
            return 2;
          case 2: // triangle
          case 4: // tetrahedron
            return type == 2 ? 3 : 4;
          case 3: // quadrilateral
            return 4;
          case 5: // hexahedron
            return 8;
          case 6: // prism
            return 6;
          case 7: // pyramid
            return 5;
          case 15: // point
            return 1;
          default:
            return 0;
        }
    }

    // The dimension of the elements of a type that
    // gmsh_nodes_per_element() knows.
    long
    gmsh_element_dimension(const long type)
    {
      return type == 15 ? 0 : type == 1 ? 1 : type <= 3 ? 2 : 3;
    }

    // The $Nodes and $Elements sections of an ASCII Gmsh file of format 4.0
    // or 4.1 (entity blocks, each with its own count), read from
    // @p input just after the $MeshFormat line. deal.II's reader trusts
    // the counts: with a wrong one it writes nodes past the end of its
    // array (a crash later) or reads until memory runs out, so a count
    // that does not match the section is refused here.
    void
    check_gmsh4_sections(std::istream                &input,
                         const std::filesystem::path &path,
                         unsigned int                &line_number,
                         const double                 version)
    {
      WordReader reader(input, line_number);
      const auto where = [&]() {
        return "Mesh: '" + path.string() + "' (Gmsh format " +
               (version == 4. ? std::string("4.0") : std::string("4.1")) +
               "), line " + std::to_string(line_number) + ": ";
      };
      // The next word as an integer >= 0 that the section calls @p what.
      const auto count = [&](const char *what) {
        const std::string word = reader.next();
        char             *end  = nullptr;
        const long        value =
          word.empty() ? -1 : std::strtol(word.c_str(), &end, 10);
        AssertThrow(!word.empty() && *end == '\0' && value >= 0,
                    dealii::ExcMessage(
                      where() + "expected " + std::string(what) +
                      " (an integer >= 0), got " +
                      (word.empty() ? std::string("the end of the file") :
                                      "'" + word + "'") +
                      "."));
        return value;
      };
      const auto number = [&](const char *what) {
        const std::string word = reader.next();
        char             *end  = nullptr;
        if (!word.empty())
          std::strtod(word.c_str(), &end);
        AssertThrow(!word.empty() && *end == '\0',
                    dealii::ExcMessage(where() + "expected " +
                                       std::string(what) + " (a number), got " +
                                       (word.empty() ?
                                          std::string("the end of the file") :
                                          "'" + word + "'") +
                                       "."));
      };
      const auto expect_end = [&](const std::string &end_marker,
                                  const std::string &announced) {
        const std::string word = reader.next();
        AssertThrow(word == end_marker,
                    dealii::ExcMessage(where() + "expected " + end_marker +
                                       " after the " + announced + ", got " +
                                       (word.empty() ?
                                          std::string("the end of the file") :
                                          "'" + word + "'") +
                                       "."));
      };
      const bool four_one = version == 4.1;
      // A section's first line: the number of entity blocks, of items and
      // (4.1) the smallest and largest tag. A single number there is the
      // count of format 2, under a $MeshFormat line that says 4.
      const auto section_header = [&](const std::string &section,
                                      const char        *items) {
        const std::vector<std::string> words = reader.next_line();
        std::string                    header;
        for (const std::string &w : words)
          header += (header.empty() ? "" : " ") + w;
        const std::size_t expected = four_one ? 4 : 2;
        AssertThrow(words.size() != 1,
                    dealii::ExcMessage(
                      where() + "the " + section + " section starts with '" +
                      header +
                      "', a single count as in Gmsh's format 2, but the "
                      "$MeshFormat line says format 4 (entity blocks); if "
                      "the file is in format 2, that line should read "
                      "'2.2 0 8'."));
        AssertThrow(words.size() == expected,
                    dealii::ExcMessage(where() + "the " + section +
                                       " section must start with " +
                                       std::to_string(expected) +
                                       " numbers, got '" + header + "'."));
        reader.push_back(words);
        const long n_blocks = count("the number of entity blocks");
        const long n_items  = count(items);
        if (four_one)
          {
            count("the smallest tag");
            count("the largest tag");
          }
        return std::make_pair(n_blocks, n_items);
      };
      // A block may not hold more items than the section has left, and
      // the blocks together must hold them all.
      const auto check_block_size = [&](const std::string &section,
                                        const std::string &items,
                                        const long         in_block,
                                        const long         n_left) {
        AssertThrow(in_block <= n_left,
                    dealii::ExcMessage(where() + "the blocks of " + section +
                                       " hold more " + items +
                                       " than the section announces."));
      };
      const auto check_total = [&](const std::string &section,
                                   const std::string &items,
                                   const long         n_items,
                                   const long         n_blocks,
                                   const long         n_read) {
        AssertThrow(n_read == n_items,
                    dealii::ExcMessage(where() + section + " announces " +
                                       std::to_string(n_items) + " " + items +
                                       " and its " + std::to_string(n_blocks) +
                                       " blocks hold " +
                                       std::to_string(n_read) + "."));
        expect_end("$End" + section.substr(1),
                   std::to_string(n_items) + " " + items);
      };

      // An entity block's header: the entity's dimension and tag (4.1) or
      // tag and dimension (4.0). deal.II indexes an array by the dimension
      // (a crash beyond 3), and an entity that $Entities does not declare
      // has no physical tags to give.
      std::array<std::set<long>, 4> declared;
      bool                          entities_read = false;
      const auto entity_block = [&](const std::string &section) {
        const long first  = count("an entity block's dimension or tag");
        const long second = count("an entity block's dimension or tag");
        const long dim    = four_one ? first : second,
                   tag    = four_one ? second : first;
        AssertThrow(dim <= 3,
                    dealii::ExcMessage(
                      where() + "an entity block of " + section +
                      " has the dimension " + std::to_string(dim) +
                      " (0 to 3). A block starts with " +
                      (four_one ? "the dimension, then the entity tag" :
                                  "the entity tag, then the dimension") +
                      " in format " + (four_one ? "4.1" : "4.0") + "."));
        AssertThrow(!entities_read || declared[dim].count(tag) == 1,
                    dealii::ExcMessage(
                      where() + "an entity block of " + section +
                      " belongs to the entity of dimension " +
                      std::to_string(dim) + " and tag " + std::to_string(tag) +
                      ", which $Entities does not declare."));
        return dim;
      };

      std::string word;
      while (!(word = reader.next()).empty())
        {
          AssertThrow(word != "$PartitionedEntities",
                      dealii::ExcMessage(
                        where() +
                        "a partitioned mesh ($PartitionedEntities): "
                        "deal.II reads the entities of an unpartitioned one "
                        "only, and would lose the boundary ids. Save the "
                        "mesh without partitions (in Gmsh: unpartition it, "
                        "gmsh.model.mesh.unpartition(), before saving)."));
          if (word == "$Entities")
            {
              // Points, curves, surfaces, volumes: a tag, a point (4.1) or
              // a bounding box, physical tags, and (but for points) the
              // tags of the bounding entities.
              long n_entities[4];
              for (long &n : n_entities)
                n = count("the number of entities of a dimension");
              for (unsigned int entity_dim = 0; entity_dim < 4; ++entity_dim)
                for (long entity = 0; entity < n_entities[entity_dim]; ++entity)
                  {
                    declared[entity_dim].insert(count("an entity tag"));
                    const unsigned int n_coordinates =
                      (four_one && entity_dim == 0) ? 3 : 6;
                    for (unsigned int i = 0; i < n_coordinates; ++i)
                      number("an entity's coordinate");
                    for (long n = count("the number of physical tags"); n > 0;
                         --n)
                      number("a physical tag");
                    if (entity_dim > 0)
                      for (long n = count("the number of bounding entities");
                           n > 0;
                           --n)
                        number("a bounding entity tag");
                  }
              expect_end("$EndEntities", "entities");
              entities_read = true;
            }
          else if (word == "$Nodes")
            {
              std::set<long> node_tags;
              const auto [n_blocks, n_nodes] =
                section_header("$Nodes", "the number of nodes");
              long n_read = 0;
              for (long block = 0; block < n_blocks; ++block)
                {
                  entity_block("$Nodes");
                  AssertThrow(count("the 'parametric' flag") == 0,
                              dealii::ExcMessage(
                                where() +
                                "a node block with parametric coordinates; "
                                "save the mesh without them "
                                "(Mesh.SaveParametric = 0)."));
                  const long in_block = count("the number of nodes of a block");
                  check_block_size("$Nodes",
                                   "nodes",
                                   in_block,
                                   n_nodes - n_read);
                  // deal.II keeps the last node of a tag silently
                  const auto node_tag = [&]() {
                    const long tag = count("a node tag");
                    AssertThrow(node_tags.insert(tag).second,
                                dealii::ExcMessage(
                                  where() + "node " + std::to_string(tag) +
                                  " is defined a second time."));
                  };
                  if (four_one)
                    for (long node = 0; node < in_block; ++node)
                      node_tag();
                  for (long node = 0; node < in_block; ++node)
                    {
                      if (!four_one)
                        node_tag();
                      for (unsigned int d = 0; d < 3; ++d)
                        number("a node coordinate");
                    }
                  n_read += in_block;
                }
              check_total("$Nodes", "nodes", n_nodes, n_blocks, n_read);
            }
          else if (word == "$Elements")
            {
              const auto [n_blocks, n_elements] =
                section_header("$Elements", "the number of elements");
              long n_read = 0;
              for (long block = 0; block < n_blocks; ++block)
                {
                  const long         dim  = entity_block("$Elements");
                  const long         type = count("an element type");
                  const unsigned int n_element_nodes =
                    gmsh_nodes_per_element(type);
                  AssertThrow(n_element_nodes > 0,
                              dealii::ExcMessage(
                                where() + "element type " +
                                std::to_string(type) +
                                " is not a linear one (impactfe reads Q1 "
                                "meshes: quadrilaterals, hexahedra, and lines "
                                "or points for boundary ids)."));
                  // the dimension decides whose physical tags the elements
                  // get: a mismatch would give wrong boundary ids
                  const long type_dim = gmsh_element_dimension(type);
                  AssertThrow(
                    type_dim == dim,
                    dealii::ExcMessage(
                      where() + "an element block of dimension " +
                      std::to_string(dim) + " holds elements of type " +
                      std::to_string(type) + ", which have dimension " +
                      std::to_string(type_dim) + "."));
                  const long in_block =
                    count("the number of elements of a block");
                  check_block_size("$Elements",
                                   "elements",
                                   in_block,
                                   n_elements - n_read);
                  for (long element = 0; element < in_block; ++element)
                    for (unsigned int i = 0; i <= n_element_nodes; ++i)
                      count("an element tag or node tag");
                  n_read += in_block;
                }
              check_total(
                "$Elements", "elements", n_elements, n_blocks, n_read);
            }
        }
    }

    // The structure of an ASCII Gmsh file of format 1 or 2: each $Nodes
    // ($NOD) and $Elements ($ELM) section has a count and then that many
    // lines before its end marker, and a node line has an id and three
    // coordinates. deal.II's reader stops on a broken section with a
    // message about the next marker ("The string <$Nodes> is not
    // recognized"); this says which section and line is wrong instead.
    // Files of format 4 go to check_gmsh4_sections().
    void
    check_gmsh_sections(const std::filesystem::path &path)
    {
      std::ifstream input(path);
      std::string   line;
      unsigned int  line_number = 0;
      const auto    where       = [&]() {
        return "Mesh: '" + path.string() + "', line " +
               std::to_string(line_number) + ": ";
      };
      while (std::getline(input, line))
        {
          ++line_number;
          const std::string marker = trimmed(line);
          if (marker == "$MeshFormat")
            {
              std::getline(input, line);
              ++line_number;
              std::istringstream format(line);
              double             version   = 0.;
              int                file_type = 0;
              format >> version >> file_type;
              AssertThrow(!format || file_type == 0,
                          dealii::ExcMessage(
                            where() + "'" + trimmed(line) +
                            "': a binary Gmsh file; deal.II reads ASCII "
                            "ones (save with Mesh.Binary = 0)."));
              if (format && (version == 4. || version == 4.1))
                {
                  check_gmsh4_sections(input, path, line_number, version);
                  return;
                }
              if (!format || version >= 3.)
                return;
              continue;
            }
          const bool nodes = marker == "$Nodes" || marker == "$NOD";
          if (!nodes && marker != "$Elements" && marker != "$ELM")
            continue;
          const std::string end_marker = marker == "$Nodes" ? "$EndNodes" :
                                         marker == "$NOD"   ? "$ENDNOD" :
                                         marker == "$Elements" ?
                                                            "$EndElements" :
                                                            "$ENDELM";
          std::getline(input, line);
          ++line_number;
          std::istringstream count_line(line);
          long               count = -1;
          count_line >> count;
          AssertThrow(count_line && count >= 0,
                      dealii::ExcMessage(where() + "the number of " +
                                         (nodes ? "nodes" : "elements") +
                                         " after " + marker +
                                         " must be an integer >= 0, got '" +
                                         trimmed(line) + "'."));
          long             n_lines = 0;
          bool             ended   = false;
          std::set<double> node_ids;
          while (std::getline(input, line))
            {
              ++line_number;
              const std::string text = trimmed(line);
              if (text == end_marker)
                {
                  ended = true;
                  break;
                }
              AssertThrow(text.empty() || text[0] != '$',
                          dealii::ExcMessage(where() + "found " + text +
                                             " inside the " + marker +
                                             " section, which has no " +
                                             end_marker + "."));
              ++n_lines;
              if (nodes)
                {
                  std::istringstream fields(text);
                  double             id = 0., x = 0., y = 0., z = 0.;
                  fields >> id >> x >> y >> z;
                  AssertThrow(!fields.fail(),
                              dealii::ExcMessage(where() +
                                                 "a node needs an id and three "
                                                 "coordinates, got '" +
                                                 text + "'."));
                  // deal.II keeps the last node of an id silently
                  AssertThrow(node_ids.insert(id).second,
                              dealii::ExcMessage(where() + "node " +
                                                 format_number(id) +
                                                 " is defined a second time."));
                }
            }
          AssertThrow(ended,
                      dealii::ExcMessage(
                        "Mesh: '" + path.string() + "': the " + marker +
                        " section announces " + std::to_string(count) + " " +
                        (nodes ? "nodes" : "elements") +
                        " and the file ends "
                        "after " +
                        std::to_string(n_lines) + " of them, with no " +
                        end_marker + "."));
          AssertThrow(n_lines == count,
                      dealii::ExcMessage(
                        where() + "the " + marker + " section announces " +
                        std::to_string(count) + " " +
                        (nodes ? "nodes" : "elements") + " but has " +
                        std::to_string(n_lines) + " lines."));
        }
    }

    // Two mistakes that GridIn takes silently: a cell that names one node
    // twice (a degenerate cell: its DoFs do not fit the element, and a
    // product with the mass matrix crashed), and two nodes at one place
    // (a mesh made of parts that were not merged, e.g. without Gmsh's
    // Coherence: the body is cut along their common edges, and nothing
    // holds the two sides together).
    template <int dim>
    void
    check_cell_vertices(const Triangulation<dim>    &triangulation,
                        const std::filesystem::path &path)
    {
      const auto position = [](const Point<dim> &x) {
        std::ostringstream out;
        out << "(" << x << ")";
        return out.str();
      };
      double            smallest_cell = std::numeric_limits<double>::infinity();
      std::vector<bool> used(triangulation.n_vertices(), false);
      for (const auto &cell : triangulation.active_cell_iterators())
        {
          for (const unsigned int i : cell->vertex_indices())
            {
              used[cell->vertex_index(i)] = true;
              for (unsigned int j = 0; j < i; ++j)
                AssertThrow(cell->vertex_index(i) != cell->vertex_index(j),
                            ExcMessage(
                              "Mesh: cell " +
                              std::to_string(cell->active_cell_index()) +
                              " of '" + path.string() + "' names the node at " +
                              position(cell->vertex(i)) +
                              " twice: a degenerate cell, which a Q1 "
                              "element cannot have."));
            }
          AssertThrow(cell->minimum_vertex_distance() > 0.,
                      ExcMessage("Mesh: cell " +
                                 std::to_string(cell->active_cell_index()) +
                                 " of '" + path.string() +
                                 "' has two nodes at one place: a "
                                 "degenerate cell, which a Q1 element "
                                 "cannot have."));
          // The Q1 map's Jacobian at each corner, from the edges along the
          // reference axes (vertex k's neighbour along axis d is k ^ 2^d):
          // a negative one is a folded cell (a 'bow tie', or a corner
          // turned inwards), whose map is not one-to-one although its
          // measure may be positive.
          for (const unsigned int k : cell->vertex_indices())
            {
              Tensor<2, dim> edges;
              double         lengths = 1.;
              for (unsigned int d = 0; d < dim; ++d)
                {
                  const unsigned int   other = k ^ (1u << d);
                  const Tensor<1, dim> edge = cell->vertex(std::max(k, other)) -
                                              cell->vertex(std::min(k, other));
                  for (unsigned int e = 0; e < dim; ++e)
                    edges[e][d] = edge[e];
                  lengths *= edge.norm();
                }
              AssertThrow(determinant(edges) > -1e-10 * lengths,
                          ExcMessage(
                            "Mesh: cell " +
                            std::to_string(cell->active_cell_index()) +
                            " of '" + path.string() +
                            "' is folded at its "
                            "node at " +
                            position(cell->vertex(k)) +
                            ": its nodes are not in order around it (a "
                            "'bow tie'), or a corner points inwards. Its Q1 "
                            "map is not one-to-one there; check the node "
                            "order of the element."));
            }
          smallest_cell =
            std::min(smallest_cell, cell->minimum_vertex_distance());
        }
      // Nodes in boxes of half the shortest cell edge: a node's twin is in
      // its box or a neighbouring one (linear in the number of nodes; a
      // sweep along x met whole planes of nodes of equal x).
      const auto  &vertices  = triangulation.get_vertices();
      const double tolerance = 1e-8 * smallest_cell;
      const double box_size  = 0.5 * smallest_cell;
      // (box numbers as doubles: no overflow for a tiny box far out)
      std::map<std::array<double, dim>, std::vector<unsigned int>> boxes;
      const auto box_of = [&](const Point<dim> &x) {
        std::array<double, dim> box;
        for (unsigned int d = 0; d < dim; ++d)
          box[d] = std::floor(x[d] / box_size);
        return box;
      };
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (used[v])
          boxes[box_of(vertices[v])].push_back(v);
      for (unsigned int v = 0; v < vertices.size(); ++v)
        if (used[v])
          {
            const std::array<double, dim> box = box_of(vertices[v]);
            for (unsigned int n = 0; n < Utilities::pow(3u, dim); ++n)
              {
                std::array<double, dim> neighbour = box;
                for (unsigned int d = 0, k = n; d < dim; ++d, k /= 3)
                  neighbour[d] += double(k % 3) - 1.;
                const auto found = boxes.find(neighbour);
                if (found != boxes.end())
                  for (const unsigned int w : found->second)
                    AssertThrow(
                      w == v || vertices[v].distance(vertices[w]) > tolerance,
                      ExcMessage(
                        "Mesh: '" + path.string() + "' has two nodes at " +
                        position(vertices[v]) +
                        ": the mesh is cut there, by a slit or by parts "
                        "that were not merged (in Gmsh: Coherence). A body "
                        "cannot have a slit of zero width: nothing would "
                        "keep its two sides from passing through each "
                        "other."));
              }
          }
    }

    // Reads @p file as ParameterHandler does (parameter_file_statements(),
    // `include` relative to the working directory) and records in
    // @p setting_file the last file, in reading order, with a `set ... =
    // value` whose value, or one of its comma-separated items, is @p value.
    // read_parameter_file() has refused include cycles before this runs;
    // the depth limit guards callers that did not read the file with it.
    void
    find_setting_file(const std::filesystem::path &file,
                      const std::string           &value,
                      std::filesystem::path       &setting_file,
                      const unsigned int           depth = 0)
    {
      if (depth > 64)
        return;
      for (const auto &statement : parameter_file_statements(file))
        {
          const std::string &text     = statement.second;
          const std::string  included = included_file(text);
          if (!included.empty())
            find_setting_file(included, value, setting_file, depth + 1);
          else if (text.rfind("set", 0) == 0 && text.size() > 3 &&
                   std::isspace(static_cast<unsigned char>(text[3])))
            {
              const auto equals = text.find('=');
              if (equals == std::string::npos)
                continue;
              const std::string assigned = text.substr(equals + 1);
              for (std::size_t begin = 0, end = 0; end != std::string::npos;
                   begin = end + 1)
                {
                  end = assigned.find(',', begin);
                  if (trimmed(assigned.substr(begin, end - begin)) == value)
                    {
                      setting_file = file;
                      break;
                    }
                }
            }
        }
    }
  } // namespace



  std::filesystem::path
  resolve_relative_to_setting_file(const std::string &file_name,
                                   const std::string &parameter_file)
  {
    const std::filesystem::path path(file_name);
    if (path.is_absolute() || parameter_file.empty())
      return path;
    std::filesystem::path setting_file = parameter_file;
    find_setting_file(parameter_file, trimmed(file_name), setting_file);
    return setting_file.parent_path() / path;
  }



  void
  MeshParameters::declare_parameters(
    ParameterHandler  &prm,
    const std::string &subsection,
    const unsigned int default_contact_boundary_id)
  {
    prm.enter_subsection(subsection);
    prm.declare_entry("Mesh file",
                      "",
                      Patterns::Anything(),
                      "Mesh file of this body (Gmsh .msh, UCD .ucd, Abaqus "
                      ".inp, VTK .vtk), relative to the directory of the "
                      "parameter file that sets it (an included file's "
                      "own). Empty: the program's built-in geometry, "
                      "where the scene has one (a scene without one needs "
                      "a file). Coordinates in [m].");
    prm.declare_entry("Mesh file format",
                      "auto",
                      Patterns::Selection("auto|msh|ucd|abaqus|vtk"),
                      "Format of the mesh file: auto, msh, ucd, abaqus or "
                      "vtk; auto: from its extension (.msh, .ucd, .inp = "
                      "Abaqus, .vtk).");
    prm.declare_entry("Contact boundary id",
                      std::to_string(default_contact_boundary_id),
                      Patterns::Integer(0, 254),
                      "Boundary id of the faces whose nodes are contact "
                      "candidates [-]. For a mesh file: the id the file gives "
                      "those faces (Gmsh: the physical tag).");
    prm.leave_subsection();
  }



  void
  MeshParameters::parse_parameters(ParameterHandler  &prm,
                                   const std::string &subsection)
  {
    prm.enter_subsection(subsection);
    file_name           = prm.get("Mesh file");
    format              = prm.get("Mesh file format");
    contact_boundary_id = prm.get_integer("Contact boundary id");
    prm.leave_subsection();
  }



  template <int dim>
  void
  MeshParameters::read(Triangulation<dim> &triangulation,
                       const std::string  &parameter_file) const
  {
    const std::filesystem::path path =
      resolve_relative_to_setting_file(file_name, parameter_file);
    AssertThrow(std::filesystem::exists(path),
                ExcMessage("Mesh: the mesh file '" + path.string() +
                           "' does not exist."));

    std::string chosen = format;
    if (chosen == "auto")
      {
        const std::string extension = path.extension().string();
        chosen                      = extension == ".msh" ? "msh" :
                                      extension == ".ucd" ? "ucd" :
                                      extension == ".inp" ? "abaqus" :
                                      extension == ".vtk" ? "vtk" :
                                                            "";
        AssertThrow(!chosen.empty(),
                    ExcMessage("Mesh: cannot tell the format of '" +
                               path.string() +
                               "' from its extension; set 'Mesh file "
                               "format'."));
      }
    const typename GridIn<dim>::Format grid_format =
      chosen == "msh" ? GridIn<dim>::msh :
      chosen == "ucd" ? GridIn<dim>::ucd :
      chosen == "vtk" ? GridIn<dim>::vtk :
                        GridIn<dim>::abaqus;

    GridIn<dim> grid_in(triangulation);
    // A directory opens as a stream and reads as an empty file.
    AssertThrow(!std::filesystem::is_directory(path),
                ExcMessage("Mesh: '" + path.string() + "' is a directory."));
    std::ifstream input(path);
    AssertThrow(input,
                ExcMessage("Mesh: cannot open '" + path.string() + "'."));
    if (chosen == "msh")
      check_gmsh_sections(path);
    // deal.II's ABAQUS reader converts to UCD and, when that fails, prints
    // the inner exception (with its stack trace) to std::cerr before it
    // throws a message that points "above": keep that text and say what
    // it says in one line.
    std::ostringstream printed;
    std::string        reason;
    try
      {
        const CerrCapture capture(printed);
        grid_in.read(input, grid_format);
      }
    catch (const std::exception &error)
      {
        reason = exception_text(error);
      }
    if (!reason.empty())
      {
        const std::string inner = printed.str();
        const auto        info  = inner.find("Additional information:");
        if (info != std::string::npos)
          {
            const auto begin = inner.find_first_not_of(" \n", info + 23);
            reason =
              "not a mesh deal.II's ABAQUS reader can read (its "
              "conversion to UCD said: " +
              trimmed(inner.substr(begin, inner.find('\n', begin) - begin)) +
              ")";
          }
        // deal.II's orientation of the cells (a twisted cell cannot be
        // oriented) fails with ExcInternalError, a page about library bugs
        if (reason.find("indicates that some condition which the author") !=
            std::string::npos)
          reason = "deal.II stopped with an internal error while it built "
                   "the mesh. The usual cause is a cell it cannot orient: a "
                   "twisted cell (its nodes not in cyclic order around it, "
                   "a 'bow tie'). Check the node order of the elements.";
        // ExcIO's text is a page of possible causes, most about writing
        if (reason.rfind("An input/output error has occurred", 0) == 0)
          reason = "the file does not follow the " + chosen +
                   " format, or ends too early (deal.II's reader stopped "
                   "with an input/output error).";
        AssertThrow(false,
                    ExcMessage("Mesh: cannot read '" + path.string() + "' as " +
                               chosen + ": " + reason));
      }
    std::cerr << printed.str();
    AssertThrow(triangulation.n_active_cells() > 0,
                ExcMessage("Mesh: the mesh file '" + path.string() +
                           "' has no cells."));
    // Cells of zero or negative measure (all nodes in a plane, or wrongly
    // ordered) would give a singular or indefinite mass matrix.
    for (const auto &cell : triangulation.active_cell_iterators())
      AssertThrow(
        !cell->reference_cell().is_hyper_cube() || cell->measure() > 0.,
        ExcMessage("Mesh: cell " + std::to_string(cell->active_cell_index()) +
                   " of '" + path.string() + "' has zero or negative " +
                   (dim == 3 ? "volume." : "area.")));
    // Q1 elements need quadrilaterals (hexahedra in 3D); GridIn also reads
    // triangles, tetrahedra, wedges and pyramids, on which FE_Q fails.
    AssertThrow(triangulation.all_reference_cells_are_hyper_cube(),
                ExcMessage("Mesh: the mesh file '" + path.string() +
                           "' has cells that are not " +
                           (dim == 3 ?
                              std::string("hexahedra (tetrahedra, wedges or "
                                          "pyramids); impactfe's Q1 "
                                          "elements need hexahedra.") :
                              std::string("quadrilaterals (triangles); "
                                          "impactfe's Q1 elements need "
                                          "quadrilaterals."))));
    check_cell_vertices(triangulation, path);
  }



  // Each body's vertices are appended with an offset; the boundary ids are
  // set afterwards on the faces found by their vertex numbers, which
  // create_triangulation() keeps.
  template <int dim>
  void
  merge_body_meshes(const std::vector<const Triangulation<dim> *> &bodies,
                    Triangulation<dim>                            &result)
  {
    std::vector<Point<dim>>                                 vertices;
    std::vector<CellData<dim>>                              cells;
    std::map<std::vector<unsigned int>, types::boundary_id> face_ids;
    for (unsigned int b = 0; b < bodies.size(); ++b)
      {
        const Triangulation<dim> &body = *bodies[b];
        AssertThrow(body.n_levels() == 1,
                    ExcMessage("merge_body_meshes: body " + std::to_string(b) +
                               "'s mesh is refined; give its coarse mesh."));
        const unsigned int offset = vertices.size();
        vertices.insert(vertices.end(),
                        body.get_vertices().begin(),
                        body.get_vertices().end());
        for (const auto &cell : body.active_cell_iterators())
          {
            CellData<dim> data(cell->n_vertices());
            for (const unsigned int v : cell->vertex_indices())
              data.vertices[v] = cell->vertex_index(v) + offset;
            data.material_id = b;
            cells.push_back(data);
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() && face->boundary_id() != 0)
                {
                  std::vector<unsigned int> key;
                  for (const unsigned int v : face->vertex_indices())
                    key.push_back(face->vertex_index(v) + offset);
                  std::sort(key.begin(), key.end());
                  face_ids[key] = face->boundary_id();
                }
          }
      }
    Triangulation<dim> merged;
    merged.create_triangulation(vertices, cells, SubCellData());
    for (const auto &cell : merged.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            std::vector<unsigned int> key;
            for (const unsigned int v : face->vertex_indices())
              key.push_back(face->vertex_index(v));
            std::sort(key.begin(), key.end());
            const auto found = face_ids.find(key);
            if (found != face_ids.end())
              face->set_boundary_id(found->second);
          }
    result.copy_triangulation(merged);
  }



  template <int dim>
  void
  write_mesh_file(const Triangulation<dim> &triangulation,
                  const std::string        &file_name)
  {
    std::ofstream out(file_name);
    AssertThrow(out,
                ExcMessage("Output: cannot write the mesh file '" + file_name +
                           "'."));
    // every digit: the positions of the serial run, not 6 digits of them
    out.precision(17);
    GridOut grid_out;
    grid_out.set_flags(GridOutFlags::Msh(/*write_faces=*/true,
                                         /*write_lines=*/false));
    grid_out.write_msh(triangulation, out);
    AssertThrow(out,
                ExcMessage("Output: writing the mesh file '" + file_name +
                           "' failed."));
  }



  template void
  write_mesh_file<1>(const Triangulation<1> &, const std::string &);
  template void
  write_mesh_file<2>(const Triangulation<2> &, const std::string &);
  template void
  write_mesh_file<3>(const Triangulation<3> &, const std::string &);
  template void
  merge_body_meshes<2>(const std::vector<const Triangulation<2> *> &,
                       Triangulation<2> &);
  template void
  merge_body_meshes<3>(const std::vector<const Triangulation<3> *> &,
                       Triangulation<3> &);
  template void
  MeshParameters::read<1>(Triangulation<1> &, const std::string &) const;
  template void
  MeshParameters::read<2>(Triangulation<2> &, const std::string &) const;
  template void
  MeshParameters::read<3>(Triangulation<3> &, const std::string &) const;
} // namespace impactfe
