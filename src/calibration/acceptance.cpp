#include "pkm/calibration/acceptance.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pkm::calibration {

std::vector<ParameterChange> implausibleChanges(const std::vector<ParameterValues>& parameters,
                                                double characteristic_length,
                                                std::string_view length_unit,
                                                double fraction,
                                                double angle_limit) {
  std::vector<ParameterChange> out;
  for (const ParameterValues& p : parameters) {
    const double limit = p.is_length ? fraction * characteristic_length : angle_limit;
    const double change = std::fabs(p.calibrated - p.nominal);
    if (change <= limit) continue;  // false for NaN: a NaN change is kept
    out.push_back({p, limit, p.is_length ? std::string(length_unit) : std::string("rad")});
  }
  const auto ratio = [](const ParameterChange& c) {
    const double r = std::fabs(c.change()) / c.limit;
    return std::isnan(r) ? std::numeric_limits<double>::infinity() : r;
  };
  std::stable_sort(out.begin(), out.end(), [&](const ParameterChange& a, const ParameterChange& b) {
    return ratio(a) > ratio(b);
  });
  return out;
}

std::string describe(const ParameterChange& c) {
  return fmt::format("{}: {:.6g} → {:.6g} {} (moved {:.4g}; plausible ≤ {:.4g})",
                     c.values.name,
                     c.values.nominal,
                     c.values.calibrated,
                     c.unit,
                     c.change(),
                     c.limit);
}

}  // namespace pkm::calibration
