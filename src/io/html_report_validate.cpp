// Validation of report-data documents, schema pkm.report/1 (docs/report.md).
#include <fmt/format.h>

#include <set>
#include <string>

#include "detail/json_doc.hpp"
#include "detail/report_data.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::io {
namespace detail {
namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw InvalidArgument(fmt::format("report data: {}: {}", path.empty() ? "(root)" : path, what));
}

std::string member(const std::string& path, const char* key) {
  return path.empty() ? std::string(key) : fmt::format("{}.{}", path, key);
}

std::string element(const std::string& path, std::size_t i) {
  return fmt::format("{}[{}]", path, i);
}

void requireObject(const json& v, const std::string& path) {
  if (!v.is_object()) fail(path, "expected an object");
}

const json& required(const json& obj, const std::string& path, const char* key) {
  const auto it = obj.find(key);
  if (it == obj.end()) fail(path, fmt::format("missing key '{}'", key));
  return *it;
}

void requireString(const json& v, const std::string& path) {
  if (!v.is_string()) fail(path, "expected a string");
}

/// A required string member.
void stringKey(const json& obj, const std::string& path, const char* key) {
  requireString(required(obj, path, key), member(path, key));
}

/// An optional string member.
void optionalStringKey(const json& obj, const std::string& path, const char* key) {
  if (obj.contains(key)) requireString(obj[key], member(path, key));
}

/// An optional array member (absent means empty); returns a pointer to it or nullptr.
const json* optionalArray(const json& obj, const std::string& path, const char* key) {
  const auto it = obj.find(key);
  if (it == obj.end()) return nullptr;
  if (!it->is_array()) fail(member(path, key), "expected an array");
  return &*it;
}

void stringArray(const json& v, const std::string& path) {
  if (!v.is_array()) fail(path, "expected an array of strings");
  for (std::size_t i = 0; i < v.size(); ++i) requireString(v[i], element(path, i));
}

/// An array of finite numbers; returns its length.
std::size_t numberArray(const json& v, const std::string& path) {
  if (!v.is_array()) fail(path, "expected an array of numbers");
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!v[i].is_number()) fail(element(path, i), "expected a number");
  return v.size();
}

/// Ids become HTML element ids and anchors: letters, digits, '-', '_', '.', ':'.
void slug(const json& obj, const std::string& path) {
  stringKey(obj, path, "id");
  const std::string& id = obj["id"].get_ref<const std::string&>();
  const bool ok = !id.empty() && id.find_first_not_of(
                                     "abcdefghijklmnopqrstuvwxyz"
                                     "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                     "0123456789-_.:") == std::string::npos;
  if (!ok)
    fail(member(path, "id"),
         fmt::format("'{}' is not a slug (letters, digits, '-', '_', '.', ':')", id));
}

void table(const json& t, const std::string& path) {
  requireObject(t, path);
  stringKey(t, path, "title");
  const json& columns = required(t, path, "columns");
  stringArray(columns, member(path, "columns"));
  const json& rows = required(t, path, "rows");
  if (!rows.is_array()) fail(member(path, "rows"), "expected an array of rows");
  for (std::size_t r = 0; r < rows.size(); ++r) {
    const std::string rp = element(member(path, "rows"), r);
    if (!rows[r].is_array()) fail(rp, "expected an array of cells");
    if (rows[r].size() != columns.size())
      fail(rp, fmt::format("has {} cells for {} columns", rows[r].size(), columns.size()));
    for (std::size_t c = 0; c < rows[r].size(); ++c) {
      const json& cell = rows[r][c];
      if (!cell.is_string() && !cell.is_number() && !cell.is_null())
        fail(element(rp, c), "a cell must be a string, a number or null");
    }
  }
}

void series(const json& s, const std::string& path, const std::string& kind, const json* cats) {
  requireObject(s, path);
  stringKey(s, path, "label");
  const std::size_t ny = numberArray(required(s, path, "y"), member(path, "y"));
  if (kind == "bar") {
    const json* own = s.contains("categories") ? &s["categories"] : cats;
    if (own == nullptr) fail(path, "a bar series needs 'categories' (here or in its plot)");
    stringArray(*own, member(path, "categories"));
    if (own->size() != ny)
      fail(path, fmt::format("{} categories but {} y values", own->size(), ny));
    return;
  }
  const json& x = required(s, path, "x");
  const std::size_t nx = numberArray(x, member(path, "x"));
  if (nx != ny) fail(path, fmt::format("x has {} values but y has {}", nx, ny));
  if (kind == "line")
    for (std::size_t i = 1; i < nx; ++i)
      if (x[i].get<double>() < x[i - 1].get<double>())
        fail(element(member(path, "x"), i), "x of a line plot must be ascending");
  if (s.contains("lower") || s.contains("upper")) {
    if (kind != "line") fail(path, "'lower' and 'upper' (a band) belong to line plots only");
    for (const char* key : {"lower", "upper"}) {
      const std::size_t n = numberArray(required(s, path, key), member(path, key));
      if (n != ny) fail(path, fmt::format("{} has {} values but y has {}", key, n, ny));
    }
  }
  if (s.contains("value")) {
    const std::size_t nv = numberArray(s["value"], member(path, "value"));
    if (kind != "scatter") fail(member(path, "value"), "'value' colours only scatter plots");
    if (nv != nx) fail(path, fmt::format("value has {} entries but x has {}", nv, nx));
  }
}

void plot(const json& p, const std::string& path, std::set<std::string>& ids) {
  requireObject(p, path);
  slug(p, path);
  if (!ids.insert(p["id"].get<std::string>()).second)
    fail(member(path, "id"), fmt::format("duplicate plot id '{}'", p["id"].get<std::string>()));
  stringKey(p, path, "title");
  stringKey(p, path, "kind");
  const std::string kind = p["kind"].get<std::string>();
  if (kind != "line" && kind != "scatter" && kind != "polar" && kind != "bar")
    fail(member(path, "kind"), fmt::format("unknown kind '{}' (line, scatter, polar, bar)", kind));
  optionalStringKey(p, path, "x_label");
  optionalStringKey(p, path, "y_label");
  const json* cats = p.contains("categories") ? &p["categories"] : nullptr;
  if (cats != nullptr) {
    if (kind != "bar") fail(member(path, "categories"), "only bar plots have categories");
    stringArray(*cats, member(path, "categories"));
  }
  const json& ss = required(p, path, "series");
  if (!ss.is_array() || ss.empty()) fail(member(path, "series"), "expected a non-empty array");
  for (std::size_t i = 0; i < ss.size(); ++i)
    series(ss[i], element(member(path, "series"), i), kind, cats);
}

void section(const json& s,
             const std::string& path,
             std::set<std::string>& section_ids,
             std::set<std::string>& plot_ids) {
  requireObject(s, path);
  slug(s, path);
  if (!section_ids.insert(s["id"].get<std::string>()).second)
    fail(member(path, "id"), fmt::format("duplicate section id '{}'", s["id"].get<std::string>()));
  stringKey(s, path, "title");
  if (const json* ps = optionalArray(s, path, "paragraphs"))
    stringArray(*ps, member(path, "paragraphs"));
  if (const json* ts = optionalArray(s, path, "tables"))
    for (std::size_t i = 0; i < ts->size(); ++i)
      table((*ts)[i], element(member(path, "tables"), i));
  if (const json* ps = optionalArray(s, path, "plots"))
    for (std::size_t i = 0; i < ps->size(); ++i)
      plot((*ps)[i], element(member(path, "plots"), i), plot_ids);
}

}  // namespace

json parseReportData(std::string_view json_text, const std::string& source) {
  const json doc = parseJson(std::string(json_text), source);
  requireObject(doc, "");
  const json& schema = required(doc, "", "schema");
  if (!schema.is_string() || schema.get<std::string>() != kReportSchema)
    fail("schema", fmt::format("expected \"{}\"", kReportSchema));
  stringKey(doc, "", "title");
  optionalStringKey(doc, "", "subtitle");
  optionalStringKey(doc, "", "generated");
  if (const json* notes = optionalArray(doc, "", "notes")) stringArray(*notes, "notes");
  table(required(doc, "", "summary"), "summary");
  const json& sections = required(doc, "", "sections");
  if (!sections.is_array()) fail("sections", "expected an array");
  std::set<std::string> section_ids;
  std::set<std::string> plot_ids;
  for (std::size_t i = 0; i < sections.size(); ++i)
    section(sections[i], element("sections", i), section_ids, plot_ids);
  return doc;
}

}  // namespace detail

void validateReportData(std::string_view json_text, const std::string& source) {
  (void)detail::parseReportData(json_text, source);
}

}  // namespace pkm::io
