// summary.json's writer, JsonObject: the text it makes (numbers to ten
// digits, escaped strings, non-finite numbers as null, nested objects), and
// a key written twice is refused: two_bars_1d once wrote courant_number
// twice, which JSON readers resolve differently (Python keeps the last
// value).

#include <impactfe/output/output.h>

#include <cmath>
#include <fstream>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "../tests.h"

using namespace impactfe;
using namespace impactfe_tests;

int
main()
{
  initlog();

  JsonObject nested;
  nested.add("pivots", 12.).add("status", std::string("solved"));
  JsonObject summary;
  summary.add("program", std::string("a \"quoted\" name\\"))
    .add("theta", 0.55)
    .add("energy_ratio", 1. / 3.)
    .add("missing", std::numeric_limits<double>::quiet_NaN())
    .add("lcp", nested);
  // the file as written, line by line
  summary.write("summary.json");
  std::ifstream written("summary.json");
  for (std::string line; std::getline(written, line);)
    deallog << line << std::endl;

  for (const auto &[what, add] :
       std::vector<std::pair<std::string, std::function<void(JsonObject &)>>>{
         {"number", [](JsonObject &o) { o.add("theta", 0.5); }},
         {"string", [](JsonObject &o) { o.add("theta", std::string("x")); }},
         {"object", [](JsonObject &o) { o.add("theta", JsonObject()); }}})
    {
      bool refused = false;
      try
        {
          add(summary);
        }
      catch (const std::logic_error &e)
        {
          refused = true;
          deallog << "second 'theta' (" << what << "): " << e.what()
                  << std::endl;
        }
      check(refused, "a second key 'theta' (" + what + ") is refused");
    }
  // the refused keys left the object as it was
  check(summary.str().find("0.5\n") == std::string::npos &&
          summary.str().find("\"x\"") == std::string::npos,
        "the object is unchanged after the refusals");
  // the same key in a nested object is another key
  JsonObject outer;
  outer.add("pivots", 1.).add("lcp", nested);
  check(outer.str().find("\"pivots\": 12") != std::string::npos,
        "a nested object may repeat an outer key");
  return n_failed_checks == 0 ? 0 : 1;
}
