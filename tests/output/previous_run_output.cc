// remove_previous_run_output(): a rerun into the same output directory
// removes the earlier run's summary.json, plot, VTU collection, shapes and
// the VTU files of its bodies (five digits or more) (a longer earlier run left
// its last VTU files beside the new ones, and its plot stayed if the rerun
// failed), and touches nothing else: LCP dumps, other programs' files, the
// user's own, names that only look alike. A distributed program's
// .pvtu records (four digits or more) and their pieces (a rank's digits)
// go as well.

#include <impactfe/output/output.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../tests.h"

using namespace impactfe;
using namespace impactfe_tests;

int
main()
{
  initlog();

  const std::string directory = "previous_run";
  std::filesystem::remove_all(directory);
  std::filesystem::create_directory(directory);
  const std::vector<std::string> files = {"summary.json",
                                          "history.png",
                                          "solution.pvd",
                                          "shapes.csv",
                                          "history.csv",
                                          "lcp_step_3.dat",
                                          "bar_1-00000.vtu",
                                          "bar_1-00120.vtu",
                                          "bar_2-00120.vtu",
                                          "bar_1-123456.vtu",
                                          "bar_1-120.vtu",
                                          "bar_1-0012a.vtu",
                                          "bar_10-00120.vtu",
                                          "block-00001.vtu",
                                          "notes.txt"};
  for (const std::string &file : files)
    std::ofstream(directory + "/" + file) << "earlier run\n";
  // a directory with a body's VTU name is not a file: left alone
  std::filesystem::create_directory(directory + "/bar_2-00000.vtu");

  // a distributed program's records of "solution"
  for (const std::string &file : {"solution_0003.pvtu",
                                  "solution_0003.1.vtu",
                                  "solution_12345.0000.vtu",
                                  "solution_0003.15.vtu",
                                  "solution_003.pvtu",
                                  "solution_003.1.vtu",
                                  "solution_0003..vtu",
                                  "solution_0003.1a.vtu",
                                  "solution_0003.pvd",
                                  "solution_0003.0001.vtu.bak",
                                  "solutions_0003.pvtu"})
    std::ofstream(directory + "/" + file) << "earlier run\n";

  remove_previous_run_output(directory, {"bar_1", "bar_2"}, {"solution"});

  std::vector<std::string> left;
  for (const auto &entry : std::filesystem::directory_iterator(directory))
    left.push_back(entry.path().filename().string());
  std::sort(left.begin(), left.end());
  dealii::deallog << "left:";
  for (const std::string &file : left)
    dealii::deallog << " " << file;
  dealii::deallog << std::endl;

  const std::vector<std::string> expected = {"bar_1-0012a.vtu",
                                             "bar_1-120.vtu",
                                             "bar_10-00120.vtu",
                                             "bar_2-00000.vtu",
                                             "block-00001.vtu",
                                             "history.csv",
                                             "lcp_step_3.dat",
                                             "notes.txt",
                                             "solution_0003..vtu",
                                             "solution_0003.0001.vtu.bak",
                                             "solution_0003.1a.vtu",
                                             "solution_0003.pvd",
                                             "solution_003.1.vtu",
                                             "solution_003.pvtu",
                                             "solutions_0003.pvtu"};
  check(left == expected,
        "the earlier run's summary, plot, collection and body VTU files "
        "removed, nothing else");

  // an empty directory and one that does not exist: nothing to do
  remove_previous_run_output(directory + "/bar_2-00000.vtu", {"bar_2"});
  remove_previous_run_output("no_such_directory", {"bar_1"});
  check(!std::filesystem::exists("no_such_directory"),
        "a missing directory is not created");
}
