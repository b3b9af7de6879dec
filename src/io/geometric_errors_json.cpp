#include <array>
#include <vector>

#include "io/detail/error_table_json.hpp"
#include "io/detail/json_doc.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/geometric_errors.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/number_format.hpp"

namespace pkm::io {

namespace kin = pkm::kinematics;
namespace geo = pkm::geometry;
using detail::json;
using detail::JsonDoc;

namespace {

using detail::columnScale;
using detail::kUrad;
using detail::numbers;
using detail::policy;
using detail::readColumns;
constexpr const auto& kColumns = detail::kErrorColumns;
/// The most nodes a PKM error grid may have (docs/formats.md, "Geometric errors"): 100³, far more
/// than a measured volumetric map; 48 MB of values.
constexpr std::size_t kMaxGridNodes = 1'000'000;

geo::ErrorGrid3d readGrid(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  doc.onlyKeys(
      obj, ptr, {"x", "y", "z", "dx", "dy", "dz", "ex_urad", "ey_urad", "ez_urad", "out_of_range"});
  std::array<std::vector<double>, 3> axes;
  const char* names[] = {"x", "y", "z"};
  std::size_t n = 1;
  for (std::size_t a = 0; a < 3; ++a) {
    axes[a] = numbers(doc, doc.required(obj, ptr, names[a]), ptr + "/" + names[a]);
    // The values are allocated for every node, given or not: a few thousand bytes of axes must
    // not ask for gigabytes.
    if (axes[a].size() > kMaxGridNodes / n)
      doc.fail(ptr + "/" + names[a],
               fmt::format("the grid has more than {} nodes (nx·ny·nz)", kMaxGridNodes));
    n *= axes[a].size();
  }
  const Eigen::MatrixXd values = readColumns(doc, obj, ptr, n);
  try {
    return geo::ErrorGrid3d(std::move(axes), values, policy(doc, obj, ptr));
  } catch (const InvalidArgument& e) {
    doc.fail(ptr, e.what());
  }
}

void writeColumns(std::string& out, const Eigen::MatrixXd& values, const char* indent) {
  for (std::size_t c = 0; c < kColumns.size(); ++c) {
    out += fmt::format(",\n{}\"{}\": [", indent, kColumns[c]);
    for (Eigen::Index i = 0; i < values.rows(); ++i) {
      if (i > 0) out += ", ";
      appendNumber(out, values(i, static_cast<Eigen::Index>(c)) / columnScale(c));
    }
    out += "]";
  }
}

void writeArray(std::string& out, const std::vector<double>& v) {
  out += "[";
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (i > 0) out += ", ";
    appendNumber(out, v[i]);
  }
  out += "]";
}

const char* policyName(geo::OutOfRange p) {
  return p == geo::OutOfRange::kClamp ? "clamp" : "error";
}

}  // namespace

kin::GeometricErrors parseGeometricErrorsJson(const std::string& text, const std::string& source) {
  const json root = detail::parseJson(text, source);
  const JsonDoc doc(text, source);
  if (!root.is_object()) doc.fail("", "expected an object");
  if (doc.string(root, "", "type", "") != "hybrid_geometric_errors")
    doc.fail("/type", "expected \"type\": \"hybrid_geometric_errors\"");
  doc.onlyKeys(
      root, "", {"schema", "type", "description", "units", "squareness_urad", "x2", "y2", "pkm"});
  kin::GeometricErrors e;
  e.unit = detail::readSchemaAndUnits(doc, root, "pkm.errors/1");
  if (root.contains("squareness_urad")) {
    const json& s = root["squareness_urad"];
    doc.onlyKeys(s, "/squareness_urad", {"szX2", "sxP", "syP", "szP"});
    e.squareness.sz_x2 = kUrad * doc.number(s, "/squareness_urad", "szX2", 0.0);
    e.squareness.sx_p = kUrad * doc.number(s, "/squareness_urad", "sxP", 0.0);
    e.squareness.sy_p = kUrad * doc.number(s, "/squareness_urad", "syP", 0.0);
    e.squareness.sz_p = kUrad * doc.number(s, "/squareness_urad", "szP", 0.0);
  }
  if (root.contains("x2")) e.x2 = detail::readErrorTable(doc, root["x2"], "/x2");
  if (root.contains("y2")) e.y2 = detail::readErrorTable(doc, root["y2"], "/y2");
  if (root.contains("pkm")) e.pkm = readGrid(doc, root["pkm"], "/pkm");
  try {
    e.validate();
  } catch (const InvalidArgument& ex) {
    doc.fail("", ex.what());
  }
  return e;
}

kin::GeometricErrors readGeometricErrorsJson(const std::string& path) {
  return parseGeometricErrorsJson(readTextFile(path), path);
}

std::string writeGeometricErrorsJson(const kin::GeometricErrors& e) {
  std::string out =
      "{\n  \"schema\": \"pkm.errors/1\",\n  \"type\": \"hybrid_geometric_errors\",\n";
  out += fmt::format("  \"units\": \"{}\",\n", toString(e.unit));
  out +=
      fmt::format("  \"squareness_urad\": {{\"szX2\": {}, \"sxP\": {}, \"syP\": {}, \"szP\": {}}}",
                  formatNumber(e.squareness.sz_x2 / kUrad),
                  formatNumber(e.squareness.sx_p / kUrad),
                  formatNumber(e.squareness.sy_p / kUrad),
                  formatNumber(e.squareness.sz_p / kUrad));
  for (const auto& [key, table] : {std::pair{"x2", &e.x2}, std::pair{"y2", &e.y2}}) {
    if (!*table) continue;
    out += fmt::format(",\n  \"{}\": {{\"out_of_range\": \"{}\",\n    \"positions\": ",
                       key,
                       policyName((*table)->outOfRange()));
    writeArray(out, (*table)->positions());
    writeColumns(out, (*table)->values(), "    ");
    out += "}";
  }
  if (e.pkm) {
    out += fmt::format(",\n  \"pkm\": {{\"out_of_range\": \"{}\"", policyName(e.pkm->outOfRange()));
    const char* names[] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
      out += fmt::format(",\n    \"{}\": ", names[a]);
      writeArray(out, e.pkm->axis(a));
    }
    writeColumns(out, e.pkm->values(), "    ");
    out += "}";
  }
  out += "\n}\n";
  return out;
}

}  // namespace pkm::io
