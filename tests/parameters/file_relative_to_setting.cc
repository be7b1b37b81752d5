// A file named in a parameter file (a mesh) is found relative to the
// directory of the file that sets it, also when that file is included
// from elsewhere: a user's override that includes
// parameter_files/cylinder_impact_mpi.prm from another directory used to
// look for cylinder_12x9.msh next to the override.

#include <impactfe/bodies/mesh_input.h>

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "../tests.h"

using namespace impactfe;
using namespace impactfe_tests;

namespace
{
  void
  write(const std::string &file, const std::string &text)
  {
    std::filesystem::create_directories(
      std::filesystem::path(file).parent_path());
    std::ofstream(file) << text;
  }

  void
  expect(const std::string &name,
         const std::string &file_name,
         const std::string &expected)
  {
    const std::string resolved =
      resolve_relative_to_setting_file(file_name, "a/top.prm").string();
    deallog << name << ": " << resolved << std::endl;
    check(resolved == expected, name, "expected " + expected);
  }
} // namespace

int
main()
{
  initlog();

  // set in an included file (include paths: relative to the working
  // directory, as ParameterHandler reads them)
  write("b/inc.prm",
        "subsection Mesh\n  set Mesh file = m.msh   # next to inc.prm\nend\n");
  write("a/top.prm", "include b/inc.prm\nset Dimension = 2\n");
  expect("set in the included file", "m.msh", "b/m.msh");
  expect("an absolute name", "/data/m.msh", "/data/m.msh");
  expect("a name that no file sets", "other.msh", "a/other.msh");

  // the top file sets it again after the include: its own directory
  write("a/top.prm",
        "include b/inc.prm\nsubsection Mesh\n  set Mesh file = m.msh\nend\n");
  expect("set again after the include", "m.msh", "a/m.msh");

  // a comment is not a setting; a list's item is
  write("a/top.prm",
        "include b/inc.prm\n# set Mesh file = m.msh\n"
        "subsection Bodies\n  set Mesh files = x.msh, m.msh\nend\n");
  expect("an item of a list", "m.msh", "a/m.msh");
  expect("the other item", "x.msh", "a/x.msh");
  write("a/top.prm", "include b/inc.prm\n# set Mesh file = m.msh\n");
  expect("a comment is not a setting", "m.msh", "b/m.msh");

  // two levels of includes, and a setting continued on the next line
  write("c/deep.prm", "subsection Mesh\n  set Mesh file = \\\n  d.msh\nend\n");
  write("b/inc.prm", "include c/deep.prm\n");
  write("a/top.prm", "include b/inc.prm\n");
  expect("two levels, a continued line", "d.msh", "c/d.msh");

  // A program run on an override elsewhere that includes a test's file
  // with a relative mesh name (tests/cylinder_impact/disc_4x3.msh).
  write("override/run.prm",
        "include " TESTS_PARAMETERS_DIR
        "/../cylinder_impact/mesh_from_file.prm\n"
        "subsection Output\n  set Output directory = override/results\n"
        "  set VTU output = false\n  set Plot = false\nend\n"
        "subsection Time stepping\n  set End time = 0.5\nend\n");
  const int status = std::system(CYLINDER_IMPACT_EXECUTABLE
                                 " override/run.prm > override/run.log 2>&1");
  check(WIFEXITED(status) && WEXITSTATUS(status) == 0,
        "cylinder_impact on an override that includes a file with a mesh",
        "exit status " + std::to_string(status) + ", see override/run.log");
  check(std::filesystem::exists("override/results/summary.json"),
        "it wrote its summary");
  return n_failed_checks == 0 ? 0 : 1;
}
