// libFuzzer harness for the positioning and straightness readers (io/positioning_files.hpp:
// instrument exports, canonical tables, simulator files and Renishaw .rtl files by content): any
// input reads or throws pkm::IoError / pkm::InvalidArgument. An input may carry a second file
// after a line "%%next", and `--columns`-style assignments on a first line "%%columns SPEC".
// Samples that are read have runs >= 1 and directions ±1.
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "pkm/io/positioning_files.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  std::string_view text = pkm::fuzz::asText(data, size);
  pkm::io::PositioningColumns how;
  if (text.starts_with("%%columns ")) {
    const std::size_t eol = std::min(text.find('\n'), text.size());
    const std::string_view spec = text.substr(10, eol - 10);
    if (!pkm::fuzz::accepts([&] { how.columns = pkm::io::parseColumnAssignments(spec); }))
      how.columns.clear();
    text.remove_prefix(std::min(eol + 1, text.size()));
    how.unit = "um";
    how.error_unit = "um";
  }
  const pkm::fuzz::Split parts = pkm::fuzz::splitAt(text, "%%next");
  std::vector<pkm::io::NamedText> inputs{{"a.csv", parts.first}};
  if (parts.found) inputs.push_back({"b.csv", parts.second});
  pkm::fuzz::accepts([&] {
    std::vector<std::string> unstated;
    for (const auto& s : pkm::io::readPositioningSamples(inputs, how, &unstated)) {
      pkm::fuzz::check(s.run >= 1, "run >= 1");
      pkm::fuzz::check(s.direction == 1 || s.direction == -1, "direction ±1");
    }
  });
  pkm::fuzz::accepts([&] {
    const pkm::io::Profile p = pkm::io::readStraightnessPoints(inputs);
    pkm::fuzz::check(p.position.size() == p.value.size(), "one value per position");
    const pkm::io::Profile m = pkm::io::perTargetMean(p);
    pkm::fuzz::check(m.position.size() == m.value.size(), "one mean per position");
  });
  pkm::fuzz::accepts([&] { (void)pkm::io::readStraightness(inputs); });
  pkm::fuzz::accepts([&] {
    std::vector<pkm::io::TextTable> tables;
    for (const auto& in : inputs) tables.push_back(pkm::io::TextTable::parse(in.text, in.name));
    (void)pkm::io::meanProfile(tables, true);
  });
  return 0;
}
