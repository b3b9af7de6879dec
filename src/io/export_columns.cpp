// Columns of instrument exports recognised by name (export_columns.hpp).
#include "pkm/io/export_columns.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cassert>
#include <cctype>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace {

/// Lower case (ASCII), "µm" as "um", runs of spaces and '_' as one space, trimmed.
std::string normalise(std::string_view text) {
  std::string out;
  for (std::size_t k = 0; k < text.size(); ++k) {
    const unsigned char c = static_cast<unsigned char>(text[k]);
    if (c == 0xC2 && k + 1 < text.size() && static_cast<unsigned char>(text[k + 1]) == 0xB5) {
      out += 'u';  // U+00B5 MICRO SIGN
      ++k;
    } else if (c == 0xCE && k + 1 < text.size() &&
               static_cast<unsigned char>(text[k + 1]) == 0xBC) {
      out += 'u';  // U+03BC GREEK SMALL LETTER MU
      ++k;
    } else if (c == ' ' || c == '_' || c == '\t') {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += static_cast<char>(std::tolower(c));
    }
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

/// The unit a `_suffix` states, when the suffix is a length unit.
bool isUnitSuffix(std::string_view suffix) { return millimetresPer(suffix).has_value(); }

}  // namespace

HeaderField splitHeaderField(std::string_view field) {
  std::string text = normalise(field);
  for (const auto& [open, close] : {std::pair{'(', ')'}, std::pair{'[', ']'}}) {
    const std::size_t a = text.rfind(open);
    if (a == std::string::npos || text.empty() || text.back() != close) continue;
    std::string unit = normalise(text.substr(a + 1, text.size() - a - 2));
    std::string name = normalise(text.substr(0, a));
    return {std::move(name), std::move(unit)};
  }
  const std::size_t space = text.rfind(' ');
  if (space != std::string::npos && isUnitSuffix(text.substr(space + 1)))
    return {text.substr(0, space), text.substr(space + 1)};
  return {std::move(text), ""};
}

std::optional<double> millimetresPer(std::string_view unit) {
  const std::string u = normalise(unit);
  if (u == "mm") return 1.0;
  if (u == "um" || u == "micron" || u == "microns") return 1e-3;
  if (u == "nm") return 1e-6;
  if (u == "m") return 1000.0;
  if (u == "in" || u == "inch" || u == "inches") return 25.4;
  return std::nullopt;
}

ColumnAssignments parseColumnAssignments(std::string_view text) {
  ColumnAssignments out;
  std::size_t start = 0;
  while (start <= text.size()) {
    std::size_t comma = text.find(',', start);
    if (comma == std::string_view::npos) comma = text.size();
    const std::string_view item = text.substr(start, comma - start);
    const std::size_t eq = item.find('=');
    std::string role = eq == std::string_view::npos ? "" : normalise(item.substr(0, eq));
    std::string name = eq == std::string_view::npos ? "" : std::string(item.substr(eq + 1));
    while (!name.empty() && name.front() == ' ') name.erase(0, 1);
    while (!name.empty() && name.back() == ' ') name.pop_back();
    if (role.empty() || name.empty())
      throw InvalidArgument(
          fmt::format("--columns: '{}' is not ROLE=COLUMN (e.g. target=Target (mm))", item));
    out.emplace_back(std::move(role), std::move(name));
    start = comma + 1;
  }
  return out;
}

ExportColumns::ExportColumns(const TextTable& table,
                             const std::vector<ColumnRole>& roles,
                             const ColumnAssignments& assigned)
    : table_(&table) {
  const std::vector<std::string>& header = table.header();
  std::vector<HeaderField> fields;
  for (const std::string& h : header) fields.push_back(splitHeaderField(h));
  const std::string found = fmt::format("'{}'", fmt::join(header, "', '"));
  for (const ColumnRole& r : roles) {
    Assigned a{std::string(r.role), {}, std::nullopt};
    for (const std::string_view n : r.names) a.names.emplace_back(n);
    roles_.push_back(std::move(a));
  }
  for (const auto& assignment : assigned) {
    const std::string& role = assignment.first;
    const std::string& name = assignment.second;
    const auto it = std::find_if(
        roles_.begin(), roles_.end(), [&](const Assigned& a) { return a.role == role; });
    if (it == roles_.end()) {
      std::vector<std::string> known;
      for (const Assigned& a : roles_) known.push_back(a.role);
      table.failHeader(fmt::format(
          "--columns: unknown quantity '{}' (this input takes {})", role, fmt::join(known, ", ")));
    }
    const std::string wanted = normalise(name);
    for (std::size_t c = 0; c < header.size() && !it->column; ++c)
      if (normalise(header[c]) == wanted || fields[c].name == wanted) it->column = c;
    if (!it->column)
      table.failHeader(
          fmt::format("--columns: no column '{}' for '{}'; found {}", name, role, found));
  }
  for (Assigned& a : roles_) {
    for (std::size_t c = 0; c < fields.size() && !a.column; ++c)
      if (std::find(a.names.begin(), a.names.end(), fields[c].name) != a.names.end()) a.column = c;
  }
}

void ExportColumns::require(
    std::initializer_list<std::initializer_list<std::string_view>> alternatives) const {
  std::vector<std::string> missing;
  for (const auto& group : alternatives) {
    bool met = false;
    std::vector<std::string> described;
    for (const std::string_view role : group) {
      met = met || find(role).has_value();
      const auto it = std::find_if(
          roles_.begin(), roles_.end(), [&](const Assigned& a) { return a.role == role; });
      assert(it != roles_.end());
      described.push_back(fmt::format("{} ('{}')", role, fmt::join(it->names, "', '")));
    }
    if (!met) missing.push_back(fmt::format("{}", fmt::join(described, " or ")));
  }
  if (missing.empty()) return;
  table_->failHeader(fmt::format(
      "missing {}: {}; found '{}' (names are case-insensitive and may carry a unit, e.g. "
      "'Target (mm)'; --columns ROLE=COLUMN assigns one)",
      missing.size() == 1 ? "column" : "columns",
      fmt::join(missing, "; "),
      fmt::join(table_->header(), "', '")));
}

std::optional<std::size_t> ExportColumns::find(std::string_view role) const {
  for (const Assigned& a : roles_)
    if (a.role == role) return a.column;
  return std::nullopt;
}

std::size_t ExportColumns::at(std::string_view role) const {
  const std::optional<std::size_t> c = find(role);
  assert(c.has_value());
  return *c;
}

std::string ExportColumns::unit(std::string_view role) const {
  const std::optional<std::size_t> c = find(role);
  return c ? splitHeaderField(table_->header()[*c]).unit : std::string();
}

double columnScale(const TextTable& table,
                   const ExportColumns& columns,
                   std::string_view role,
                   std::string_view fallback,
                   std::string_view option,
                   bool required) {
  const std::string stated = columns.unit(role);
  const std::string column = table.header()[columns.at(role)];
  if (!stated.empty()) {
    const std::optional<double> s = millimetresPer(stated);
    if (!s)
      table.failHeader(fmt::format(
          "column '{}': '{}' is not a length unit (mm, um, nm, m, in)", column, stated));
    const std::optional<double> f = millimetresPer(fallback);
    if (!fallback.empty() && f != s)
      table.failHeader(
          fmt::format("column '{}' states {} but {} says {}", column, stated, option, fallback));
    return *s;
  }
  if (fallback.empty()) {
    if (required)
      table.failHeader(fmt::format(
          "column '{}' does not state its unit: give {} um (or mm, in)", column, option));
    return 1.0;
  }
  const std::optional<double> f = millimetresPer(fallback);
  if (!f)
    throw InvalidArgument(
        fmt::format("{}: '{}' is not a length unit (mm, um, nm, m, in)", option, fallback));
  return *f;
}

}  // namespace pkm::io
