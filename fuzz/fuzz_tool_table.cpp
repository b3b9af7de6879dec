// libFuzzer harness for cnc::ToolTable::parse (LinuxCNC .tbl tool tables, docs/gcode.md): any
// input parses or throws pkm::IoError, in mm and in inch; every offset and diameter read is
// finite and the tools are keyed by their own numbers.
#include <cmath>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/cnc/tool_table.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = pkm::fuzz::asText(data, size);
  for (const double mm_per_unit : {1.0, 25.4}) {
    pkm::fuzz::accepts([&] {
      const pkm::cnc::ToolTable t = pkm::cnc::ToolTable::parse(text, mm_per_unit, "fuzz.tbl");
      for (const auto& [number, tool] : t.tools) {
        pkm::fuzz::check(number == tool.number && number >= 0 && tool.pocket >= 0,
                         "tools keyed by number, numbers >= 0");
        for (const double v : tool.offset) pkm::fuzz::check(std::isfinite(v), "finite offsets");
        pkm::fuzz::check(std::isfinite(tool.diameter), "finite diameter");
        pkm::fuzz::check(t.find(number) == &tool, "find gives the tool");
      }
    });
  }
  return 0;
}
