#include "pkm/compensation/axis_table.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

#include "pkm/core/error.hpp"

namespace pkm::compensation {
namespace {

/// Relative tolerance of the equidistance test (of the span).
constexpr double kEvenTolerance = 1e-9;

void checkColumn(std::span<const double> v, const char* what) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    PKM_CHECK(std::isfinite(v[i]), "{} row {} is not finite", what, i);
  }
}

void checkIncreasing(std::span<const double> v, const char* what) {
  for (std::size_t i = 1; i < v.size(); ++i) {
    PKM_CHECK(v[i] > v[i - 1],
              "{} must be strictly increasing: row {} ({}) after row {} ({})",
              what,
              i,
              v[i],
              i - 1,
              v[i - 1]);
  }
}

std::vector<double> resampleColumn(std::span<const double> x,
                                   std::span<const double> y,
                                   std::span<const double> at) {
  std::vector<double> out;
  out.reserve(at.size());
  for (double a : at) out.push_back(interpolateHeld(x, y, a));
  return out;
}

std::vector<double> evenPositions(double first, double last, std::size_t points) {
  std::vector<double> p(points);
  const double step = (last - first) / static_cast<double>(points - 1);
  for (std::size_t i = 0; i < points; ++i) p[i] = first + step * static_cast<double>(i);
  p.back() = last;  // exact end despite rounding
  return p;
}

}  // namespace

double interpolateHeld(std::span<const double> x, std::span<const double> y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), at) - x.begin());
  const std::size_t lo = hi - 1;
  const double t = (at - x[lo]) / (x[hi] - x[lo]);
  return y[lo] + t * (y[hi] - y[lo]);
}

void AxisErrorTable::validate() const {
  PKM_CHECK(nominal.size() >= 2, "axis table '{}' needs at least 2 rows, has {}", axis, size());
  PKM_CHECK(error_up.size() == nominal.size() && error_down.size() == nominal.size(),
            "axis table '{}': column sizes differ ({}, {}, {})",
            axis,
            nominal.size(),
            error_up.size(),
            error_down.size());
  checkColumn(nominal, "nominal");
  checkColumn(error_up, "error_up");
  checkColumn(error_down, "error_down");
  checkIncreasing(nominal, "nominal");
}

double AxisErrorTable::errorAt(double position, int direction) const {
  PKM_CHECK(std::isfinite(position), "errorAt: position is not finite");
  PKM_CHECK(direction == 1 || direction == -1, "errorAt: direction must be +1 or -1");
  return interpolateHeld(nominal, direction > 0 ? error_up : error_down, position);
}

double AxisErrorTable::maxAbsError() const {
  double m = 0.0;
  for (std::size_t i = 0; i < size(); ++i) {
    m = std::max({m, std::abs(error_up[i]), std::abs(error_down[i])});
  }
  return m;
}

AxisErrorTable tableFromIso230_2(const metrology::Iso230_2Result& result, std::string axis) {
  AxisErrorTable t;
  t.axis = std::move(axis);
  for (const metrology::TargetStatistics& s : result.targets) {
    const bool up = std::isfinite(s.mean_up), down = std::isfinite(s.mean_down);
    PKM_CHECK(up || down, "ISO 230-2 target {} has no finite mean deviation", s.target);
    t.nominal.push_back(s.target);
    t.error_up.push_back(up ? s.mean_up : s.mean_down);
    t.error_down.push_back(down ? s.mean_down : s.mean_up);
  }
  t.validate();
  return t;
}

void CrossAxisTable::validate() const {
  PKM_CHECK(!input_axis.empty() && !output_axis.empty(), "cross-axis table needs axis names");
  PKM_CHECK(
      position.size() >= 2, "cross-axis table needs at least 2 rows, has {}", position.size());
  PKM_CHECK(error.size() == position.size(),
            "cross-axis table: {} positions but {} errors",
            position.size(),
            error.size());
  checkColumn(position, "position");
  checkColumn(error, "error");
  checkIncreasing(position, "position");
}

CrossAxisTable crossTableFromPoints(std::string input_axis,
                                    std::string output_axis,
                                    std::span<const double> positions,
                                    std::span<const double> deviations) {
  PKM_CHECK(positions.size() == deviations.size(),
            "{} positions but {} deviations",
            positions.size(),
            deviations.size());
  std::map<double, std::pair<double, int>> sums;
  for (std::size_t i = 0; i < positions.size(); ++i) {
    PKM_CHECK(
        std::isfinite(positions[i]) && std::isfinite(deviations[i]), "point {} is not finite", i);
    auto& [sum, n] = sums[positions[i]];
    sum += deviations[i];
    ++n;
  }
  CrossAxisTable t{std::move(input_axis), std::move(output_axis), {}, {}};
  for (const auto& [p, s] : sums) {
    t.position.push_back(p);
    t.error.push_back(s.first / s.second);
  }
  t.validate();
  return t;
}

std::string_view toString(TableFormat format) {
  switch (format) {
    case TableFormat::kLinuxcnc0:
      return "linuxcnc0";
    case TableFormat::kLinuxcnc1:
      return "linuxcnc1";
    case TableFormat::kSiemensEec:
      return "siemens-eec";
    case TableFormat::kSiemensCec:
      return "siemens-cec";
    case TableFormat::kIsgCsv:
      return "isg";
  }
  return "?";
}

TableFormat parseTableFormat(std::string_view name) {
  for (TableFormat f : {TableFormat::kLinuxcnc0,
                        TableFormat::kLinuxcnc1,
                        TableFormat::kSiemensEec,
                        TableFormat::kSiemensCec,
                        TableFormat::kIsgCsv}) {
    if (toString(f) == name) return f;
  }
  throw InvalidArgument(fmt::format(
      "unknown table format '{}' (linuxcnc0, linuxcnc1, siemens-eec, siemens-cec, isg)", name));
}

FormatTraits traits(TableFormat format) {
  switch (format) {
    case TableFormat::kLinuxcnc0:
      return {StoredValue::kActualPosition, true, false, 256, 256};
    case TableFormat::kLinuxcnc1:
      return {StoredValue::kCorrection, true, false, 256, 256};
    case TableFormat::kSiemensEec:
    case TableFormat::kSiemensCec:
      return {StoredValue::kError, false, true, 200, 0};
    case TableFormat::kIsgCsv:
      return {StoredValue::kError, false, false, 1500, 0};
  }
  return {};
}

double storedValue(StoredValue stored, double nominal, double error) {
  switch (stored) {
    case StoredValue::kError:
      return error;
    case StoredValue::kCorrection:
      return -error;
    case StoredValue::kActualPosition:
      return nominal + error;
  }
  return error;
}

bool isEvenlySpaced(std::span<const double> positions) {
  if (positions.size() < 3) return true;
  const double span = positions.back() - positions.front();
  const double step = span / static_cast<double>(positions.size() - 1);
  for (std::size_t i = 1; i < positions.size(); ++i) {
    if (std::abs(positions[i] - positions[i - 1] - step) > kEvenTolerance * std::abs(span)) {
      return false;
    }
  }
  return true;
}

std::size_t pointsForTarget(std::span<const double> positions,
                            bool even_spacing,
                            std::size_t max_points) {
  PKM_CHECK(max_points >= 2, "max_points must be at least 2, got {}", max_points);
  PKM_CHECK(positions.size() >= 2, "a table needs at least 2 rows");
  const std::size_t n = positions.size();
  if (!even_spacing || isEvenlySpaced(positions)) return std::min(n, max_points);
  double gap = positions.back() - positions.front();
  for (std::size_t i = 1; i < n; ++i) gap = std::min(gap, positions[i] - positions[i - 1]);
  const double wanted = std::ceil((positions.back() - positions.front()) / gap) + 1.0;
  if (!(wanted < static_cast<double>(max_points))) return max_points;
  return std::max(n, static_cast<std::size_t>(wanted));
}

AxisErrorTable resampleEven(const AxisErrorTable& table, std::size_t points) {
  table.validate();
  PKM_CHECK(points >= 2, "resampling needs at least 2 points, got {}", points);
  AxisErrorTable out;
  out.axis = table.axis;
  out.nominal = evenPositions(table.nominal.front(), table.nominal.back(), points);
  out.error_up = resampleColumn(table.nominal, table.error_up, out.nominal);
  out.error_down = resampleColumn(table.nominal, table.error_down, out.nominal);
  return out;
}

CrossAxisTable resampleEven(const CrossAxisTable& table, std::size_t points) {
  table.validate();
  PKM_CHECK(points >= 2, "resampling needs at least 2 points, got {}", points);
  CrossAxisTable out{table.input_axis, table.output_axis, {}, {}};
  out.position = evenPositions(table.position.front(), table.position.back(), points);
  out.error = resampleColumn(table.position, table.error, out.position);
  return out;
}

namespace {

void checkLimit(const FormatTraits& target, std::size_t max_points) {
  PKM_CHECK(max_points >= 2, "max_points must be at least 2, got {}", max_points);
  PKM_CHECK(target.hard_max_points == 0 || max_points <= target.hard_max_points,
            "max_points {} exceeds the format's limit of {} rows",
            max_points,
            target.hard_max_points);
}

bool fits(std::span<const double> positions, const FormatTraits& target, std::size_t max_points) {
  return positions.size() <= max_points && (!target.even_spacing || isEvenlySpaced(positions));
}

}  // namespace

AxisErrorTable fitToTarget(const AxisErrorTable& table,
                           const FormatTraits& target,
                           std::size_t max_points) {
  checkLimit(target, max_points);
  table.validate();
  if (fits(table.nominal, target, max_points)) return table;
  return resampleEven(table, pointsForTarget(table.nominal, target.even_spacing, max_points));
}

CrossAxisTable fitToTarget(const CrossAxisTable& table,
                           const FormatTraits& target,
                           std::size_t max_points) {
  checkLimit(target, max_points);
  table.validate();
  if (fits(table.position, target, max_points)) return table;
  return resampleEven(table, pointsForTarget(table.position, target.even_spacing, max_points));
}

}  // namespace pkm::compensation
