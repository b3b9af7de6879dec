// libFuzzer harness for io::parseSpatialAnalyzerPoints (SpatialAnalyzer ASCII point exports,
// docs/formats.md "Instrument exports"): any input parses or throws pkm::IoError; points read are
// finite, at least one, on increasing lines.
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/spatial_analyzer.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  pkm::fuzz::accepts([&] {
    const auto points = pkm::io::parseSpatialAnalyzerPoints({"fuzz.txt", text});
    pkm::fuzz::check(!points.empty(), "at least one point");
    std::size_t line = 0;
    for (const auto& p : points) {
      pkm::fuzz::check(p.position.allFinite(), "finite coordinates");
      pkm::fuzz::check(p.line > line, "points on increasing lines");
      line = p.line;
    }
  });
  return 0;
}
