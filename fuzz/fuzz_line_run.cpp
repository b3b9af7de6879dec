// libFuzzer harness for io::parseLineRunCsv (the simulator's linear, straightness and angular
// measurement files, docs/formats.md "Measurement files"): any input parses or throws
// pkm::IoError; what parses has one run per reading, finite readings, runs >= 1, directions ±1
// and sub-steps >= 0.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/measurement_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::fuzz::accepts([&] {
    const pkm::io::LineRunFile f = pkm::io::parseLineRunCsv(text, "fuzz.csv");
    pkm::fuzz::check(f.runs.size() == f.readings.size(), "one run number per reading");
    pkm::fuzz::check(f.reading_unit == "mm" || f.reading_unit == "urad", "reading unit");
    for (std::size_t i = 0; i < f.readings.size(); ++i) {
      const auto& r = f.readings[i];
      pkm::fuzz::check(std::isfinite(r.target) && std::isfinite(r.reading), "finite readings");
      pkm::fuzz::check(r.direction == 1 || r.direction == -1, "direction ±1");
      pkm::fuzz::check(r.sub_step >= 0, "sub_step >= 0");
      pkm::fuzz::check(f.runs[i] >= 1, "run >= 1");
    }
  });
  return 0;
}
