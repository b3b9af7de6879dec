// libFuzzer harness for io::TextTable (the CSV table reader of `pkm analyze` and the calibration
// and join readers): any input parses or throws pkm::IoError. A table that parses gives the same
// header, metadata and fields when written back as CSV and parsed again, and its numeric
// accessors agree with io::parseFiniteDouble.
#include <cmath>
#include <cstring>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/text_table.hpp"

namespace {

using pkm::io::TextTable;

/// `t` as CSV text that parses back to the same table ("\n" first: a header that starts with a
/// byte-order mark keeps it).
std::string writeBack(const TextTable& t) {
  std::string out = "\n";
  for (const auto& [key, value] : t.metadata()) out += "# " + key + ": " + value + "\n";
  for (std::size_t c = 0; c < t.header().size(); ++c) out += (c ? "," : "") + t.header()[c];
  out += "\n";
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t c = 0; c < t.header().size(); ++c) {
      if (c) out += ",";
      out += t.text(r, c);
    }
    out += "\n";
  }
  return out;
}

bool sameTable(const TextTable& a, const TextTable& b) {
  if (a.header() != b.header() || a.metadata() != b.metadata() || a.rows() != b.rows())
    return false;
  for (std::size_t r = 0; r < a.rows(); ++r)
    for (std::size_t c = 0; c < a.header().size(); ++c)
      if (a.text(r, c) != b.text(r, c)) return false;
  return true;
}

void exercise(const TextTable& t) {
  pkm::fuzz::check(!t.header().empty(), "a parsed table has a header");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    for (std::size_t c = 0; c < t.header().size(); ++c) {
      double expected = 0.0;
      const bool finite = pkm::io::parseFiniteDouble(t.text(r, c), expected);
      double got = 0.0;
      const bool ok = pkm::fuzz::accepts([&] { got = t.number(r, c); });
      pkm::fuzz::check(ok == finite, "number() accepts what parseFiniteDouble accepts");
      pkm::fuzz::check(!ok || std::memcmp(&got, &expected, sizeof got) == 0,
                       "number() gives parseFiniteDouble's value");
      (void)pkm::fuzz::accepts([&] { (void)t.integer(r, c); });
      (void)pkm::fuzz::accepts([&] { (void)t.direction(r, c); });
    }
  }
  (void)t.meta("format");
  (void)t.findColumn({t.header().front(), "x"});
  (void)pkm::fuzz::accepts([&] { (void)t.column({"target_mm", "target"}); });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(pkm::fuzz::asText(data, size));
  (void)pkm::fuzz::accepts([&] { (void)TextTable::parseData(text, "fuzz.csv"); });
  pkm::fuzz::accepts([&] {
    const TextTable t = TextTable::parse(text, "fuzz.csv");
    exercise(t);
    const TextTable again = TextTable::parse(writeBack(t), "again.csv");
    pkm::fuzz::check(sameTable(t, again), "a table written back parses to the same table");
  });
  return 0;
}
