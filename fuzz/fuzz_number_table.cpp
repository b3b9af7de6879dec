// libFuzzer harness for io::NumberTable (the bulk reader of `pkm analyze circle`): any input parses
// or throws pkm::IoError. A comma-separated table that parses has the header, metadata, rows and
// line numbers io::TextTable finds in it, and every value is parseFiniteDouble's, bit for bit; a
// blank-separated one gives each line's words through parseFiniteDouble. Every column is read.
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_support.hpp"
#include "pkm/core/text.hpp"
#include "pkm/io/csv.hpp"
#include "pkm/io/number_table.hpp"
#include "pkm/io/text_table.hpp"

namespace {

using pkm::io::NumberTable;

bool sameDouble(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Line `n` (1-based) of `text`, without its line end.
std::string_view lineOf(std::string_view text, std::size_t n) {
  for (std::size_t i = 1; i < n; ++i) text.remove_prefix(text.find('\n') + 1);
  return text.substr(0, text.find('\n'));
}

void compareWithTextTable(std::string_view text, const NumberTable& t) {
  const pkm::io::TextTable ref = pkm::io::TextTable::parse(std::string(text), "fuzz.csv");
  pkm::fuzz::check(ref.header() == t.header(), "the header TextTable finds");
  pkm::fuzz::check(ref.metadata() == t.metadata(), "the metadata TextTable finds");
  pkm::fuzz::check(ref.rows() == t.rows(), "the rows TextTable finds");
  for (std::size_t r = 0; r < t.rows(); ++r) {
    pkm::fuzz::check(ref.line(r) == t.line(r), "the lines TextTable finds");
    for (std::size_t k = 0; k < t.width(); ++k) {
      double v = 0.0;
      pkm::fuzz::check(pkm::io::parseFiniteDouble(ref.text(r, t.headerIndex(k)), v),
                       "a value read is a finite number");
      pkm::fuzz::check(sameDouble(v, t.row(r)[k]), "the value parseFiniteDouble reads");
    }
  }
}

void compareWithWords(std::string_view text, const NumberTable& t) {
  for (std::size_t r = 0; r < t.rows(); ++r) {
    const std::vector<std::string_view> words = pkm::splitWords(lineOf(text, t.line(r)));
    pkm::fuzz::check(words.size() == t.header().size(), "a row has a word per column");
    for (std::size_t k = 0; k < t.width(); ++k) {
      double v = 0.0;
      pkm::fuzz::check(pkm::io::parseFiniteDouble(words[t.headerIndex(k)], v),
                       "a value read is a finite number");
      pkm::fuzz::check(sameDouble(v, t.row(r)[k]), "the value parseFiniteDouble reads");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = pkm::fuzz::asText(data, size);
  std::vector<std::string> header;
  (void)pkm::fuzz::accepts(
      [&] { header = NumberTable::parse(text, "fuzz.csv", {}, false).header(); });
  if (header.empty()) return 0;
  std::vector<pkm::io::ColumnNames> all;
  for (const std::string& name : header) all.push_back({name});
  pkm::fuzz::accepts([&] {
    const NumberTable t = NumberTable::parse(text, "fuzz.csv", all, false);
    if (t.commaSeparated())
      compareWithTextTable(text, t);
    else
      compareWithWords(text, t);
  });
  return 0;
}
