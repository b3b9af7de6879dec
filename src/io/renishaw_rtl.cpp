// Renishaw LaserXL .rtl text files (renishaw_rtl.hpp).
#include "pkm/io/renishaw_rtl.hpp"

#include <fmt/format.h>

#include <cctype>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"

namespace pkm::io {
namespace {

constexpr double kMillimetresPerMicrometre = 1e-3;

/// The lines of `text` (without line ends), 1-based numbering by index + 1.
std::vector<std::string_view> rtlLines(std::string_view text) {
  std::vector<std::string_view> lines;
  std::size_t pos = 0;
  while (pos <= text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    lines.push_back(trimBlanks(text.substr(pos, end - pos)));
    pos = end + 1;
  }
  return lines;
}

bool isSection(std::string_view line) { return line.size() > 2 && line.ends_with("::"); }

/// The whitespace-separated numbers of `text`; throws naming `where` for a field that is not one.
std::vector<double> numbers(std::string_view text, const std::string& where) {
  std::vector<double> out;
  std::size_t pos = 0;
  while (pos < text.size()) {
    while (pos < text.size() && (text[pos] == ' ' || text[pos] == '\t')) ++pos;
    if (pos >= text.size()) break;
    std::size_t end = pos;
    while (end < text.size() && text[end] != ' ' && text[end] != '\t') ++end;
    double v = 0.0;
    if (!parseFiniteDouble(text.substr(pos, end - pos), v))
      throw IoError(
          fmt::format("{}: '{}' is not a finite number", where, text.substr(pos, end - pos)));
    out.push_back(v);
    pos = end;
  }
  return out;
}

/// "Key : value" → value when the line's key (spaces ignored, case-insensitive) is `key`.
std::optional<std::string_view> keyValue(std::string_view line, std::string_view key) {
  const std::size_t colon = line.find(':');
  if (colon == std::string_view::npos) return std::nullopt;
  std::string k;
  for (const char c : line.substr(0, colon))
    if (c != ' ' && c != '\t') k += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  std::string want;
  for (const char c : key)
    if (c != ' ') want += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (k != want) return std::nullopt;
  return trimBlanks(line.substr(colon + 1));
}

/// Whether `v` is an integer within int's range (converting any other double to int is undefined
/// behaviour).
bool isIndex(double v) { return v == std::floor(v) && std::abs(v) <= 1e9; }

struct Reading {
  int run = 0;
  int target = 0;  ///< 1-based index into the targets
  double deviation_um = 0.0;
  std::size_t line = 0;
};

/// The targets (mm) listed after "Targets :" up to the "Flags" line or the next section.
std::vector<double> readTargets(const std::vector<std::string_view>& lines,
                                const std::string& name) {
  for (std::size_t k = 0; k < lines.size(); ++k) {
    const auto first = keyValue(lines[k], "Targets");
    if (!first) continue;
    std::vector<double> targets = numbers(*first, locate(name, k + 1, "Targets"));
    for (std::size_t j = k + 1; j < lines.size(); ++j) {
      if (isSection(lines[j]) || lines[j].find(':') != std::string_view::npos) break;
      for (const double v : numbers(lines[j], locate(name, j + 1, "Targets"))) targets.push_back(v);
    }
    // Two indices at one position would give two readings of one (target, direction, run).
    std::set<double> seen;
    for (const double t : targets)
      if (!seen.insert(t).second)
        throw IoError(locate(name, k + 1, fmt::format("Targets: {} is listed twice", t)));
    return targets;
  }
  throw IoError(locate(name, 0, "an .rtl file without 'Targets :' (TARGET DATA::)"));
}

/// The rows after "Run Target Data:" up to the next section or blank line.
std::vector<Reading> readDeviations(const std::vector<std::string_view>& lines,
                                    const std::string& name) {
  std::size_t k = 0;
  while (k < lines.size() && !keyValue(lines[k], "Run Target Data")) ++k;
  if (k == lines.size())
    throw IoError(locate(name, 0, "an .rtl file without 'Run Target Data:' (DEVIATIONS::)"));
  std::vector<Reading> out;
  for (++k; k < lines.size() && !lines[k].empty() && !isSection(lines[k]); ++k) {
    const std::string where = locate(name, k + 1, "deviation row");
    const std::vector<double> v = numbers(lines[k], where);
    if (v.size() != 3 || !isIndex(v[0]) || !isIndex(v[1]))
      throw IoError(where + ": expected 'run target-index deviation'");
    out.push_back({static_cast<int>(v[0]), static_cast<int>(v[1]), v[2], k + 1});
  }
  if (out.empty()) throw IoError(locate(name, k + 1, "an .rtl file without deviation rows"));
  return out;
}

/// +1 or −1 per Renishaw run: the order in which it visits the targets.
std::map<int, int> runDirections(const std::vector<Reading>& rows, const std::string& name) {
  std::map<int, std::vector<const Reading*>> by_run;
  for (const Reading& r : rows) by_run[r.run].push_back(&r);
  std::map<int, int> direction;
  for (const auto& [run, visits] : by_run) {
    int d = 0;
    for (std::size_t k = 1; k < visits.size(); ++k) {
      const int step = visits[k]->target > visits[k - 1]->target ? 1 : -1;
      if (d != 0 && step != d)
        throw IoError(locate(
            name, visits[k]->line, fmt::format("run {} visits its targets in both orders", run)));
      d = step;
    }
    direction[run] = d != 0 ? d : (run % 2 == 1 ? 1 : -1);
  }
  return direction;
}

}  // namespace

bool isRenishawRtl(std::string_view text) {
  for (const std::string_view line : rtlLines(text)) {
    if (line.empty()) continue;
    return isSection(line) && text.find("DEVIATIONS::") != std::string_view::npos;
  }
  return false;
}

std::vector<metrology::PositioningSample> readRenishawRtl(const NamedText& input) {
  const std::vector<std::string_view> lines = rtlLines(input.text);
  const std::vector<double> targets = readTargets(lines, input.name);
  for (std::size_t k = 0; k < lines.size(); ++k)
    if (const auto count = keyValue(lines[k], "Target-count")) {
      const std::vector<double> n = numbers(*count, locate(input.name, k + 1, "Target-count"));
      if (n.size() != 1 || n[0] != static_cast<double>(targets.size()))
        throw IoError(locate(
            input.name,
            k + 1,
            fmt::format("Target-count {} but {} targets are listed", *count, targets.size())));
    }
  const std::vector<Reading> rows = readDeviations(lines, input.name);
  const std::map<int, int> direction = runDirections(rows, input.name);
  std::map<int, int> iso_run;  // Renishaw run -> run number within its direction
  std::map<int, int> count_per_direction;
  for (const auto& [run, d] : direction) iso_run[run] = ++count_per_direction[d];
  std::set<std::pair<int, int>> seen;
  std::vector<metrology::PositioningSample> out;
  for (const Reading& r : rows) {
    if (r.target < 1 || r.target > static_cast<int>(targets.size()))
      throw IoError(
          locate(input.name,
                 r.line,
                 fmt::format("target index {} is outside 1…{}", r.target, targets.size())));
    if (!seen.insert({r.run, r.target}).second)
      throw IoError(
          locate(input.name, r.line, fmt::format("run {} reads target {} twice", r.run, r.target)));
    const double target = targets[static_cast<std::size_t>(r.target - 1)];
    out.push_back({target,
                   direction.at(r.run),
                   iso_run.at(r.run),
                   target + r.deviation_um * kMillimetresPerMicrometre});
  }
  return out;
}

}  // namespace pkm::io
