#include "pkm/metrology/iso230_2.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <tuple>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Mean and sample standard deviation (divisor n - 1, ISO 230-2:2014) of deviations.
struct DirectionStats {
  double mean = kNaN;
  double s = kNaN;
  int runs = 0;
};

DirectionStats directionStats(std::span<const PositioningSample> group) {
  DirectionStats out;
  if (group.empty()) return out;
  double sum = 0.0;
  for (const PositioningSample& sample : group) sum += sample.measured - sample.target;
  const auto n = static_cast<double>(group.size());
  out.mean = sum / n;
  double squares = 0.0;
  for (const PositioningSample& sample : group) {
    const double d = sample.measured - sample.target - out.mean;
    squares += d * d;
  }
  out.s = std::sqrt(squares / (n - 1.0));
  out.runs = static_cast<int>(group.size());
  return out;
}

/// Range max - min of a set of values given as (low, high) per entry.
template <class Low, class High>
double range(const std::vector<TargetStatistics>& targets, Low low, High high) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const TargetStatistics& t : targets) {
    lo = std::min(lo, low(t));
    hi = std::max(hi, high(t));
  }
  return hi - lo;
}

/// Rejects non-finite samples, directions other than ±1 and runs below 1.
void checkIso230_2Samples(std::span<const PositioningSample> samples) {
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const PositioningSample& s = samples[i];
    PKM_CHECK(std::isfinite(s.target) && std::isfinite(s.measured),
              "ISO 230-2: sample {} (target {}, run {}) is not finite",
              i + 1,
              s.target,
              s.run);
    PKM_CHECK(s.direction == 1 || s.direction == -1,
              "ISO 230-2: sample {}: direction must be +1 or -1, got {}",
              i + 1,
              s.direction);
    PKM_CHECK(s.run >= 1, "ISO 230-2: sample {}: run must be >= 1, got {}", i + 1, s.run);
  }
}

/// The samples sorted by target, then '+' before '-', then run; rejects duplicates.
std::vector<PositioningSample> sortIso230_2Samples(std::span<const PositioningSample> samples) {
  std::vector<PositioningSample> sorted(samples.begin(), samples.end());
  const auto key = [](const PositioningSample& s) {
    return std::make_tuple(s.target, -s.direction, s.run);
  };
  std::sort(
      sorted.begin(), sorted.end(), [&](const PositioningSample& a, const PositioningSample& b) {
        return key(a) < key(b);
      });
  for (std::size_t i = 1; i < sorted.size(); ++i) {
    PKM_CHECK(key(sorted[i - 1]) != key(sorted[i]),
              "ISO 230-2: duplicate sample at target {}, direction {}, run {}",
              sorted[i].target,
              sorted[i].direction > 0 ? '+' : '-',
              sorted[i].run);
  }
  return sorted;
}

/// The statistics of one target (ISO 230-2:2014) from its samples, sorted '+' first, with
/// coverage factor k; rejects a direction with a single run.
TargetStatistics iso230_2Target(std::span<const PositioningSample> group, double k) {
  std::size_t split = 0;  // '+' samples first (sorted by -direction)
  while (split < group.size() && group[split].direction > 0) ++split;
  const DirectionStats up = directionStats(group.subspan(0, split));
  const DirectionStats down = directionStats(group.subspan(split, group.size() - split));
  for (const DirectionStats* d : {&up, &down}) {
    PKM_CHECK(d->runs != 1,
              "ISO 230-2: target {} has only 1 run in the {} direction (needs 2)",
              group[0].target,
              d == &up ? '+' : '-');
  }
  TargetStatistics t;
  t.target = group[0].target;
  t.mean_up = up.mean;
  t.mean_down = down.mean;
  t.s_up = up.s;
  t.s_down = down.s;
  t.runs_up = up.runs;
  t.runs_down = down.runs;
  t.reversal = up.mean - down.mean;         // B_i = x̄i↑ - x̄i↓
  t.repeatability_up = 2.0 * k * up.s;      // R_i↑ = 4 s_i↑ for k = 2
  t.repeatability_down = 2.0 * k * down.s;  // R_i↓ = 4 s_i↓
  t.mean = 0.5 * (up.mean + down.mean);     // x̄i
  t.repeatability = std::max(
      {k * up.s + k * down.s + std::abs(t.reversal), t.repeatability_up, t.repeatability_down});
  if (up.runs == 0 || down.runs == 0) t.repeatability = kNaN;  // std::max drops NaN silently
  return t;
}

/// The axis parameters (B, R, E, M, A and their one-direction forms) from result.targets (not
/// empty), with coverage factor k; rejects targets measured in other directions than the first.
void summariseIso230_2(Iso230_2Result& result, double k) {
  const TargetStatistics& first = result.targets.front();
  for (const TargetStatistics& t : result.targets) {
    PKM_CHECK((t.runs_up > 0) == (first.runs_up > 0) && (t.runs_down > 0) == (first.runs_down > 0),
              "ISO 230-2: target {} is measured in other directions than target {}",
              t.target,
              first.target);
  }
  const bool has_up = first.runs_up > 0;
  const bool has_down = first.runs_down > 0;
  result.bidirectional = has_up && has_down;
  const auto m = static_cast<double>(result.targets.size());

  double B = 0.0, B_sum = 0.0, R_up = 0.0, R_down = 0.0, R = 0.0;
  for (const TargetStatistics& t : result.targets) {
    B = std::max(B, std::abs(t.reversal));  // B = max |B_i|
    B_sum += t.reversal;
    R_up = std::max(R_up, t.repeatability_up);
    R_down = std::max(R_down, t.repeatability_down);
    R = std::max(R, t.repeatability);
  }
  using T = const TargetStatistics&;
  result.R_up = has_up ? R_up : kNaN;
  result.R_down = has_down ? R_down : kNaN;
  result.E_up =
      has_up ? range(
                   result.targets, [](T t) { return t.mean_up; }, [](T t) { return t.mean_up; })
             : kNaN;
  result.E_down =
      has_down
          ? range(
                result.targets, [](T t) { return t.mean_down; }, [](T t) { return t.mean_down; })
          : kNaN;
  result.A_up = has_up ? range(
                             result.targets,
                             [k](T t) { return t.mean_up - k * t.s_up; },
                             [k](T t) { return t.mean_up + k * t.s_up; })
                       : kNaN;
  result.A_down = has_down ? range(
                                 result.targets,
                                 [k](T t) { return t.mean_down - k * t.s_down; },
                                 [k](T t) { return t.mean_down + k * t.s_down; })
                           : kNaN;
  if (result.bidirectional) {
    result.B = B;
    result.B_mean = B_sum / m;
    result.R = R;
    result.E = range(
        result.targets,
        [](T t) { return std::min(t.mean_up, t.mean_down); },
        [](T t) { return std::max(t.mean_up, t.mean_down); });
    result.M = range(
        result.targets, [](T t) { return t.mean; }, [](T t) { return t.mean; });
    result.A = range(
        result.targets,
        [k](T t) { return std::min(t.mean_up - k * t.s_up, t.mean_down - k * t.s_down); },
        [k](T t) { return std::max(t.mean_up + k * t.s_up, t.mean_down + k * t.s_down); });
  } else {
    result.B = result.B_mean = result.R = result.E = result.M = result.A = kNaN;
  }
}

}  // namespace

Iso230_2Result evaluateIso230_2(std::span<const PositioningSample> samples,
                                const Iso230_2Options& options) {
  const double k = options.coverage_factor;
  PKM_CHECK(std::isfinite(k) && k > 0.0, "ISO 230-2: coverage factor must be > 0, got {}", k);
  PKM_CHECK(!samples.empty(), "ISO 230-2: no samples");
  checkIso230_2Samples(samples);
  const std::vector<PositioningSample> sorted = sortIso230_2Samples(samples);

  Iso230_2Result result;
  const std::span<const PositioningSample> all(sorted);
  std::size_t begin = 0;
  while (begin < sorted.size()) {
    std::size_t end = begin;
    while (end < sorted.size() && sorted[end].target == sorted[begin].target) ++end;
    result.targets.push_back(iso230_2Target(all.subspan(begin, end - begin), k));
    begin = end;
  }
  summariseIso230_2(result, k);
  return result;
}

}  // namespace pkm::metrology
