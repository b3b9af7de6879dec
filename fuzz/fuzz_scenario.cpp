// libFuzzer harness for io::parseScenarioJson (simulation scenarios, docs/formats.md "Scenario
// files"): any input parses or throws pkm::IoError / pkm::InvalidArgument. A scenario that parses
// can be written with a seed (io::scenarioJsonWithSeed), which parses again, and its truth file
// (io::truthJson) can be written.
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::io::Scenario s;
  // No base directory: a hybrid scenario's machine and errors are built-in names (or files
  // relative to the working directory).
  if (!pkm::fuzz::accepts([&] { s = pkm::io::parseScenarioJson(text, "fuzz.json"); })) return 0;
  std::string seeded;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { seeded = pkm::io::scenarioJsonWithSeed(s, 7); }),
                   "a scenario that parses is written with a seed");
  pkm::fuzz::check(pkm::fuzz::accepts([&] {
                     const pkm::io::Scenario back = pkm::io::parseScenarioJson(seeded, "seeded");
                     pkm::fuzz::check(back.seed == 7, "the seed written is read");
                   }),
                   "a scenario written with a seed parses");
  pkm::fuzz::check(pkm::fuzz::accepts([&] { (void)pkm::io::truthJson(s, 7); }),
                   "a scenario that parses has a truth file");
  return 0;
}
