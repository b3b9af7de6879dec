#include "pkm/metrology/circular_test.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/metrology/min_zone_circle.hpp"

namespace pkm::metrology {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kMaxGapInMedianSpacings = 5.0;

struct Polar {
  double theta;
  double r;
};

std::vector<Polar> polarSorted(std::span<const Point2> points, const Point2& c) {
  std::vector<Polar> p;
  p.reserve(points.size());
  for (const Point2& q : points) {
    const Point2 v = q - c;
    double t = std::atan2(v.y(), v.x());
    if (t < 0.0) t += kTwoPi;
    p.push_back({t, v.norm()});
  }
  std::sort(p.begin(), p.end(), [](const Polar& a, const Polar& b) { return a.theta < b.theta; });
  return p;
}

/// max |r_b(θ_a) − r_a| over the samples of `a`, r_b interpolated linearly in θ (periodic; gaps
/// wider than kMaxGapInMedianSpacings median spacings are not bridged).
void oneWay(const std::vector<Polar>& a, const std::vector<Polar>& b, double* best, double* at) {
  const std::size_t n = b.size();
  std::vector<double> gaps(n);
  for (std::size_t i = 0; i + 1 < n; ++i) gaps[i] = b[i + 1].theta - b[i].theta;
  gaps[n - 1] = b[0].theta + kTwoPi - b[n - 1].theta;
  std::vector<double> sorted = gaps;
  std::nth_element(
      sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2), sorted.end());
  const double max_gap = kMaxGapInMedianSpacings * std::max(sorted[n / 2], 1e-12);
  for (const Polar& q : a) {
    const auto it = std::upper_bound(
        b.begin(), b.end(), q.theta, [](double t, const Polar& p) { return t < p.theta; });
    Polar lo;
    Polar hi;
    if (it == b.begin() || it == b.end()) {
      lo = b[n - 1];
      hi = b[0];
      hi.theta += kTwoPi;
      if (it == b.begin()) lo.theta -= kTwoPi;
    } else {
      lo = *(it - 1);
      hi = *it;
    }
    const double gap = hi.theta - lo.theta;
    if (gap > max_gap) continue;
    const double w = gap > 0.0 ? (q.theta - lo.theta) / gap : 0.0;
    const double r = lo.r + w * (hi.r - lo.r);
    const double diff = std::abs(q.r - r);
    if (diff > *best) {
      *best = diff;
      *at = q.theta;
    }
  }
}

Point2 centreOf(std::span<const Point2> points, const CircularTestOptions& options) {
  switch (options.centre) {
    case CircularCentre::kLeastSquares:
      return fitCircle(points).circle.center;
    case CircularCentre::kMinimumZone:
      return fitMinimumZoneCircle(points).center;
    case CircularCentre::kNominal:
      break;
  }
  return *options.nominal_center;
}

CircularRun evaluateRun(std::span<const Point2> points, const CircularTestOptions& options) {
  CircularRun run;
  run.center = centreOf(points, options);
  const std::vector<double> r = radialDistances(points, run.center);
  const auto [lo, hi] = std::minmax_element(r.begin(), r.end());
  run.circular_deviation = *hi - *lo;
  double sum = 0.0;
  for (double x : r) sum += x;
  run.radius = sum / static_cast<double>(r.size());
  if (options.nominal_radius) {
    const Point2 c =
        options.nominal_center ? *options.nominal_center : fitCircle(points).circle.center;
    const std::vector<double> rf = radialDistances(points, c);
    const auto [flo, fhi] = std::minmax_element(rf.begin(), rf.end());
    double s = 0.0;
    for (double x : rf) s += x - *options.nominal_radius;
    run.radial_deviation_max = *fhi - *options.nominal_radius;
    run.radial_deviation_min = *flo - *options.nominal_radius;
    run.mean_radial_deviation = s / static_cast<double>(rf.size());
  }
  return run;
}

}  // namespace

std::pair<double, double> circularHysteresis(std::span<const Point2> a,
                                             std::span<const Point2> b,
                                             const Point2& center) {
  requirePoints(a, 2, "circular hysteresis (first run)");
  requirePoints(b, 2, "circular hysteresis (second run)");
  const std::vector<Polar> pa = polarSorted(a, center);
  const std::vector<Polar> pb = polarSorted(b, center);
  double best = 0.0;
  double at = 0.0;
  oneWay(pa, pb, &best, &at);
  oneWay(pb, pa, &best, &at);
  return {best, at};
}

CircularTestResult evaluateCircularTest(std::span<const Point2> cw,
                                        std::span<const Point2> ccw,
                                        const CircularTestOptions& options) {
  requirePoints(cw, 4, "circular test (CW run)");
  requirePoints(ccw, 4, "circular test (CCW run)");
  PKM_CHECK(options.centre != CircularCentre::kNominal || options.nominal_center.has_value(),
            "circular test: the nominal centre is required for centre = nominal");
  if (options.nominal_radius)
    PKM_CHECK(*options.nominal_radius > 0.0 && std::isfinite(*options.nominal_radius),
              "circular test: the nominal radius must be > 0");
  CircularTestResult res;
  res.centre = options.centre;
  res.cw = evaluateRun(cw, options);
  res.ccw = evaluateRun(ccw, options);
  std::vector<Point2> both(cw.begin(), cw.end());
  both.insert(both.end(), ccw.begin(), ccw.end());
  res.common_center = centreOf(both, options);
  res.bidirectional_deviation = roundnessAbout(both, res.common_center);
  const auto [h, theta] = circularHysteresis(cw, ccw, res.common_center);
  res.hysteresis = h;
  res.hysteresis_angle = theta;
  return res;
}

}  // namespace pkm::metrology
