// libFuzzer harness for io::CsvReader (the streaming numeric CSV reader) and
// io::parseFiniteDouble: any input reads or throws pkm::IoError; every number read is finite;
// parseFiniteDouble agrees with std::from_chars on the documented syntax (surrounding blanks, an
// optional leading '+', finite values only).
#include <charconv>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_support.hpp"
#include "pkm/io/csv.hpp"

namespace {

/// parseFiniteDouble as documented, on std::from_chars.
bool referenceParse(std::string_view s, double& value) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  if (!s.empty() && s.front() == '+') {
    s.remove_prefix(1);
    if (!s.empty() && s.front() == '-') return false;
  }
  if (s.empty()) return false;
  const auto [ptr, ec] = std::from_chars(s.data(), s.data() + s.size(), value);
  return ec == std::errc() && ptr == s.data() + s.size() && std::isfinite(value);
}

void checkNumber(std::string_view field) {
  double got = 0.0, expected = 0.0;
  const bool ok = pkm::io::parseFiniteDouble(field, got);
  const bool ref = referenceParse(field, expected);
  pkm::fuzz::check(ok == ref, "parseFiniteDouble accepts what from_chars accepts");
  pkm::fuzz::check(!ok || std::memcmp(&got, &expected, sizeof got) == 0,
                   "parseFiniteDouble gives from_chars' value");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = pkm::fuzz::asText(data, size);
  // Every comma-separated field of every line, as a number.
  for (std::size_t pos = 0; pos <= text.size();) {
    const std::size_t end = std::min(text.find_first_of(",\n", pos), text.size());
    checkNumber(text.substr(pos, end - pos));
    pos = end + 1;
  }
  (void)pkm::io::splitWords(text);
  (void)pkm::io::trimBlanks(text);
  // Two required columns and an optional one, as the dial-gauge and kinematics readers ask.
  pkm::fuzz::accepts([&] {
    pkm::io::CsvReader reader(pkm::io::NamedText{"fuzz.csv", std::string(text)}, {"x", "y"});
    const bool has_z = reader.addOptionalColumn("z");
    std::vector<double> values(has_z ? 3 : 2);
    std::size_t rows = 0;
    while (reader.next(values)) {
      for (const double v : values) pkm::fuzz::check(std::isfinite(v), "CsvReader values finite");
      pkm::fuzz::check(++rows <= text.size(), "at most one row per byte");
    }
  });
  return 0;
}
