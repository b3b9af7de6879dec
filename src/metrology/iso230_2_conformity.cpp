// ISO 230-2:2014 test conditions (iso230_2_conformity.hpp).
#include "pkm/metrology/iso230_2_conformity.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

struct RunCounts {
  int up = 0, down = 0;
};

/// "N runs" findings for one direction: fewer than the standard cycle's, and counts that differ
/// between targets.
void checkRuns(const std::map<double, RunCounts>& targets,
               int RunCounts::*count,
               const char* sign,
               bool check_count,
               std::vector<std::string>& out) {
  int lo = targets.begin()->second.*count, hi = lo;
  for (const auto& [target, c] : targets) {
    lo = std::min(lo, c.*count);
    hi = std::max(hi, c.*count);
  }
  double first_short = 0.0;
  int first_count = 0;
  for (const auto& [target, c] : targets)
    if (c.*count < hi) {
      first_short = target;
      first_count = c.*count;
      break;
    }
  if (hi == 0) return;
  if (lo != hi)
    out.push_back(
        fmt::format("run counts in the {} direction differ between targets ({} to {}; "
                    "target {:g} has {}): a run is incomplete",
                    sign,
                    lo,
                    hi,
                    first_short,
                    first_count));
  if (check_count && hi < kIso230_2Runs)
    out.push_back(
        fmt::format("{} runs in the {} direction: the standard test cycle approaches "
                    "every target {} times from each direction",
                    hi,
                    sign,
                    kIso230_2Runs));
}

}  // namespace

std::vector<std::string> iso230_2Nonconformities(std::span<const PositioningSample> samples,
                                                 double millimetres_per_unit) {
  PKM_CHECK(!samples.empty(), "ISO 230-2: no samples");
  PKM_CHECK(std::isfinite(millimetres_per_unit) && millimetres_per_unit > 0.0,
            "ISO 230-2: the unit scale must be > 0, got {}",
            millimetres_per_unit);
  std::map<double, RunCounts> targets;
  for (const PositioningSample& s : samples) {
    RunCounts& c = targets[s.target];
    (s.direction > 0 ? c.up : c.down) += 1;
  }
  const double travel_mm =
      (targets.rbegin()->first - targets.begin()->first) * millimetres_per_unit;
  const bool long_axis = travel_mm > kIso230_2LongAxis;
  std::vector<std::string> out;
  const bool up =
      std::any_of(targets.begin(), targets.end(), [](const auto& t) { return t.second.up > 0; });
  const bool down =
      std::any_of(targets.begin(), targets.end(), [](const auto& t) { return t.second.down > 0; });
  if (!up || !down)
    out.push_back(
        fmt::format("only {} approaches: the standard test cycle approaches every "
                    "target from both directions",
                    up ? "+" : "-"));
  checkRuns(targets, &RunCounts::up, "+", !long_axis, out);
  checkRuns(targets, &RunCounts::down, "-", !long_axis, out);
  const int n = static_cast<int>(targets.size());
  if (!long_axis) {
    const int needed =
        std::max(kIso230_2MinTargets,
                 static_cast<int>(std::ceil(kIso230_2TargetsPerMetre * travel_mm / 1000.0 - 1e-9)));
    if (n < needed)
      out.push_back(
          fmt::format("{} targets over {:g} mm of travel: ISO 230-2 asks for at least "
                      "{:g} per metre and {} in all ({} here)",
                      n,
                      travel_mm,
                      kIso230_2TargetsPerMetre,
                      kIso230_2MinTargets,
                      needed));
  } else if (travel_mm / std::max(n - 1, 1) > kIso230_2LongAxisSpacing) {
    out.push_back(
        fmt::format("targets {:g} mm apart on average over {:g} mm: on an axis over "
                    "{:g} mm ISO 230-2 spaces them about {:g} mm apart",
                    travel_mm / std::max(n - 1, 1),
                    travel_mm,
                    kIso230_2LongAxis,
                    kIso230_2LongAxisSpacing));
  }
  return out;
}

std::vector<std::string> implausibleDeviations(std::span<const PositioningSample> samples,
                                               std::string_view unit) {
  PKM_CHECK(!samples.empty(), "ISO 230-2: no samples");
  double lo = samples.front().target, hi = lo, worst = 0.0;
  for (const PositioningSample& s : samples) {
    lo = std::min(lo, s.target);
    hi = std::max(hi, s.target);
    worst = std::max(worst, std::fabs(s.measured - s.target));
  }
  const double travel = hi - lo;
  if (!(travel > 0.0) || worst <= kPlausibleDeviationFraction * travel) return {};
  return {
      fmt::format("deviations up to {:g} {} ({:.3g} % of the {:g} {} travel) are not "
                  "plausible for a machine axis: are the values in another unit than read "
                  "(µm read as mm), or does the measured column hold deviations? Check the "
                  "header's units, or give --unit / --error-unit / --columns",
                  worst,
                  unit,
                  100.0 * worst / travel,
                  travel,
                  unit)};
}

}  // namespace pkm::metrology
