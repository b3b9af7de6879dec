// SpatialAnalyzer ASCII point exports (spatial_analyzer.hpp).
#include "pkm/io/spatial_analyzer.hpp"

#include <fmt/format.h>

#include <cctype>
#include <string_view>

#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"

namespace pkm::io {
namespace {

/// The fields of one line: comma-separated when it has a comma, else blank-separated.
std::vector<std::string_view> fieldsOf(std::string_view line) {
  std::vector<std::string_view> out;
  if (line.find(',') != std::string_view::npos) {
    std::size_t pos = 0;
    while (true) {
      const std::size_t comma = line.find(',', pos);
      out.push_back(trimBlanks(line.substr(pos, comma - pos)));
      if (comma == std::string_view::npos) break;
      pos = comma + 1;
    }
    return out;
  }
  return splitWords(line);
}

bool isAxisName(std::string_view field, char axis) {
  return field.size() == 1 && std::toupper(static_cast<unsigned char>(field[0])) == axis;
}

constexpr std::size_t kMaxFields = 6;  // collection, group, target, X, Y, Z

}  // namespace

std::vector<SpatialAnalyzerPoint> parseSpatialAnalyzerPoints(const NamedText& input) {
  std::vector<SpatialAnalyzerPoint> points;
  std::size_t width = 0, width_line = 0, line_no = 0, pos = 0;
  const std::string_view text(input.text);
  bool first = true;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) end = text.size();
    const std::string_view line = trimBlanks(text.substr(pos, end - pos));
    pos = end + 1;
    ++line_no;
    if (line.empty() || line.starts_with("//")) continue;
    auto fail = [&](const std::string& what) { throw IoError(locate(input.name, line_no, what)); };
    const std::vector<std::string_view> f = fieldsOf(line);
    const std::size_t n = f.size();
    if (first && n >= 3 && isAxisName(f[n - 3], 'X') && isAxisName(f[n - 2], 'Y') &&
        isAxisName(f[n - 1], 'Z')) {
      first = false;  // a header line
      continue;
    }
    first = false;
    if (n < 3 || n > kMaxFields)
      fail(
          fmt::format("{} fields: pkm reads SpatialAnalyzer's Cartesian point export, "
                      "[[Collection] Group] Target X Y Z (export without tolerances, "
                      "uncertainties, time stamps, offsets or comments)",
                      n));
    if (width == 0) {
      width = n;
      width_line = line_no;
    } else if (n != width) {
      fail(fmt::format("{} fields, but line {} has {}", n, width_line, width));
    }
    SpatialAnalyzerPoint p;
    const std::size_t names = n - 3;
    if (names == 3) p.collection = std::string(f[0]);
    if (names >= 2) p.group = std::string(f[names - 2]);
    if (names >= 1) p.target = std::string(f[names - 1]);
    for (int k = 0; k < 3; ++k) {
      const std::string_view field = f[names + static_cast<std::size_t>(k)];
      if (!parseFiniteDouble(field, p.position[k]))
        fail(fmt::format("{} '{}' is not a finite number", "XYZ"[k], field));
    }
    p.line = line_no;
    points.push_back(std::move(p));
  }
  if (points.empty()) throw IoError(fmt::format("{}: no points", input.name));
  return points;
}

}  // namespace pkm::io
