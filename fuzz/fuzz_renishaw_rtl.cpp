// libFuzzer harness for io::readRenishawRtl (Renishaw LaserXL .rtl linear-measurement files,
// docs/formats.md "Instrument exports"): any input reads or throws pkm::IoError; samples read
// have runs >= 1 and directions ±1, and no (target, direction, run) twice.
#include <set>
#include <string>
#include <tuple>

#include "fuzz_support.hpp"
#include "pkm/io/renishaw_rtl.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = pkm::fuzz::asText(data, size);
  (void)pkm::io::isRenishawRtl(text);
  pkm::fuzz::accepts([&] {
    std::set<std::tuple<double, int, int>> seen;
    for (const auto& s : pkm::io::readRenishawRtl({"fuzz.rtl", std::string(text)})) {
      pkm::fuzz::check(s.run >= 1, "run >= 1");
      pkm::fuzz::check(s.direction == 1 || s.direction == -1, "direction ±1");
      pkm::fuzz::check(seen.insert({s.target, s.direction, s.run}).second,
                       "no (target, direction, run) twice");
    }
  });
  return 0;
}
