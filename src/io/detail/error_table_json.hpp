/// @file
/// @brief Internal: the JSON form of 1-D error tables (six columns dx, dy, dz in the length unit
/// and ex_urad, ey_urad, ez_urad in microradians), shared by the geometric-errors and scenario
/// readers.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "io/detail/json_doc.hpp"
#include "pkm/geometry/error_table.hpp"

namespace pkm::io::detail {

namespace geo = pkm::geometry;

inline constexpr double kUrad = 1e-6;
/// The six error columns in ErrorMotion order.
inline constexpr std::array<const char*, 6> kErrorColumns = {
    "dx", "dy", "dz", "ex_urad", "ey_urad", "ez_urad"};
/// The factor from file to model units of column c.
inline double columnScale(std::size_t c) { return c < 3 ? 1.0 : kUrad; }

/// A non-empty array of finite numbers.
inline std::vector<double> numbers(const JsonDoc& doc, const json& v, const std::string& ptr) {
  if (!v.is_array() || v.empty()) doc.fail(ptr, "expected a non-empty array of numbers");
  std::vector<double> out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i)
    out.push_back(doc.number(v[i], fmt::format("{}/{}", ptr, i)));
  return out;
}

/// "out_of_range": "clamp" (default) or "error".
inline geo::OutOfRange policy(const JsonDoc& doc, const json& obj, const std::string& ptr) {
  const std::string p = doc.string(obj, ptr, "out_of_range", "clamp");
  if (p == "clamp") return geo::OutOfRange::kClamp;
  if (p == "error") return geo::OutOfRange::kThrow;
  doc.fail(ptr + "/out_of_range", "must be \"clamp\" or \"error\"");
}

/// Six value columns of length n into an n×6 matrix in model units (an absent column is zero).
inline Eigen::MatrixXd readColumns(const JsonDoc& doc,
                                   const json& obj,
                                   const std::string& ptr,
                                   std::size_t n) {
  Eigen::MatrixXd values = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), 6);
  for (std::size_t c = 0; c < kErrorColumns.size(); ++c) {
    if (!obj.contains(kErrorColumns[c])) continue;
    const std::string cp = ptr + "/" + kErrorColumns[c];
    const std::vector<double> col = numbers(doc, obj[kErrorColumns[c]], cp);
    if (col.size() != n) doc.fail(cp, fmt::format("expected {} values, found {}", n, col.size()));
    for (std::size_t i = 0; i < n; ++i)
      values(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) = col[i] * columnScale(c);
  }
  return values;
}

/// {"positions": [...], the six columns, "out_of_range"} as an ErrorTable1d.
inline geo::ErrorTable1d readErrorTable(const JsonDoc& doc,
                                        const json& obj,
                                        const std::string& ptr) {
  doc.onlyKeys(
      obj, ptr, {"positions", "dx", "dy", "dz", "ex_urad", "ey_urad", "ez_urad", "out_of_range"});
  std::vector<double> positions =
      numbers(doc, doc.required(obj, ptr, "positions"), ptr + "/positions");
  const Eigen::MatrixXd values = readColumns(doc, obj, ptr, positions.size());
  try {
    return geo::ErrorTable1d(std::move(positions), values, policy(doc, obj, ptr));
  } catch (const InvalidArgument& e) {
    doc.fail(ptr + "/positions", e.what());
  }
}

}  // namespace pkm::io::detail
