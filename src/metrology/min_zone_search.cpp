// Branch and bound over the minimum-zone centre (min_zone_circle.hpp, searchMinimumZone).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/metrology/min_zone_circle.hpp"

namespace pkm::metrology {
namespace {

/// Squared distances' range of the candidate points from c.
struct Range2 {
  double lo2 = std::numeric_limits<double>::infinity();
  double hi2 = 0.0;
  [[nodiscard]] double width() const { return std::sqrt(hi2) - std::sqrt(lo2); }
};

Range2 rangeAbout(std::span<const Point2> points,
                  const std::vector<std::uint32_t>& candidates,
                  const Point2& c) {
  Range2 r;
  for (const std::uint32_t k : candidates) {
    const double d2 = (points[k] - c).squaredNorm();
    r.lo2 = std::min(r.lo2, d2);
    r.hi2 = std::max(r.hi2, d2);
  }
  return r;
}

/// The mean of the points, and ρ = the largest distance from it.
std::pair<Point2, double> meanAndReach(std::span<const Point2> points) {
  Point2 o = Point2::Zero();
  for (const Point2& p : points) o += p;
  o /= static_cast<double>(points.size());
  double rho2 = 0.0;
  for (const Point2& p : points) rho2 = std::max(rho2, (p - o).squaredNorm());
  return {o, std::sqrt(rho2)};
}

/// A lower bound of the point set's width over every direction: the smallest width over
/// `directions` directions spaced π/directions apart, less 2ρ|u − u_s| ≤ 4ρ·sin(π/(4·directions))
/// (each projection moves by at most ρ|u − u_s| when the direction turns from u_s to u).
double widthLowerBound(std::span<const Point2> points,
                       const Point2& o,
                       double rho,
                       int directions) {
  double smallest = std::numeric_limits<double>::infinity();
  for (int s = 0; s < directions; ++s) {
    const double a = std::numbers::pi * s / directions;
    const Point2 u(std::cos(a), std::sin(a));
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Point2& p : points) {
      const double t = (p - o).dot(u);
      lo = std::min(lo, t);
      hi = std::max(hi, t);
    }
    smallest = std::min(smallest, hi - lo);
  }
  return smallest - 4.0 * rho * std::sin(std::numbers::pi / (4.0 * directions));
}

/// The candidates that can still be the farthest or the nearest point somewhere in one of the
/// squares of half-side r about `centres` (ranges[i] about centres[i]): f_k(b) within 2√2·r of
/// the largest or of the smallest distance (f_k moves by at most √2·r in the square, the extreme
/// too).
std::vector<std::uint32_t> keepCandidates(std::span<const Point2> points,
                                          const std::vector<std::uint32_t>& candidates,
                                          const std::vector<Point2>& centres,
                                          const std::vector<Range2>& ranges,
                                          double r) {
  const double reach = 2.0 * std::numbers::sqrt2 * r;
  std::vector<std::uint32_t> kept;
  for (const std::uint32_t k : candidates) {
    for (std::size_t i = 0; i < centres.size(); ++i) {
      const double d2 = (points[k] - centres[i]).squaredNorm();
      const double far = std::sqrt(ranges[i].hi2) - reach;
      const double near = std::sqrt(ranges[i].lo2) + reach;
      if (far <= 0.0 || d2 >= far * far || d2 <= near * near) {
        kept.push_back(k);
        break;
      }
    }
  }
  return kept;
}

/// The search's working set S of point indices and its use: w_S(c) <= w(c) for any subset S (its
/// largest distance is no larger, its smallest no smaller), so S's widths bound w from below and
/// prune as well as all points do, at a fraction of the cost. When a square's w_S falls below the
/// best width, all points are evaluated there once, the point set's farthest and nearest points
/// join S (so that w_S = w at that centre) and the best width improves if w did.
class WorkingSet {
 public:
  WorkingSet(std::span<const Point2> points, const Point2& center) : points_(points) {
    constexpr std::size_t kAllBelow = 4096;  ///< smaller sets are searched whole
    constexpr std::size_t kSample = 2048;    ///< evenly strided sample of larger sets
    constexpr double kBand = 0.1;            ///< the zone's outer and inner tenth about center
    const std::size_t n = points.size();
    if (n <= kAllBelow) {
      for (std::size_t k = 0; k < n; ++k) add(k);
      return;
    }
    Range2 all;
    for (const Point2& p : points) {
      const double d2 = (p - center).squaredNorm();
      all.lo2 = std::min(all.lo2, d2);
      all.hi2 = std::max(all.hi2, d2);
    }
    const double lo = std::sqrt(all.lo2), hi = std::sqrt(all.hi2);
    const double outer = hi - kBand * (hi - lo), inner = lo + kBand * (hi - lo);
    const std::size_t stride = n / kSample;
    for (std::size_t k = 0; k < n; ++k) {
      const double d2 = (points[k] - center).squaredNorm();
      if (k % stride == 0 || d2 >= outer * outer || d2 <= inner * inner) add(k);
    }
  }
  [[nodiscard]] const std::vector<std::uint32_t>& indices() const { return indices_; }
  /// All points about c: their width; the farthest and nearest join S and `list`.
  double evaluateAll(const Point2& c, std::vector<std::uint32_t>& list) {
    std::size_t far = 0, near = 0;
    Range2 r;
    for (std::size_t k = 0; k < points_.size(); ++k) {
      const double d2 = (points_[k] - c).squaredNorm();
      if (d2 > r.hi2) r.hi2 = d2, far = k;
      if (d2 < r.lo2) r.lo2 = d2, near = k;
    }
    for (const std::size_t k : {far, near})
      if (add(k)) list.push_back(static_cast<std::uint32_t>(k));
    ++full_evaluations_;
    return r.width();
  }
  [[nodiscard]] std::size_t fullEvaluations() const { return full_evaluations_; }
  /// S holds every point (w_S = w).
  [[nodiscard]] bool complete() const { return indices_.size() == points_.size(); }

 private:
  bool add(std::size_t k) {
    if (member_.size() < points_.size()) member_.resize(points_.size(), false);
    if (member_[k]) return false;
    member_[k] = true;
    indices_.push_back(static_cast<std::uint32_t>(k));
    return true;
  }
  std::span<const Point2> points_;
  std::vector<std::uint32_t> indices_;
  std::vector<bool> member_;
  std::size_t full_evaluations_ = 0;
};

}  // namespace

ZoneSearch searchMinimumZone(std::span<const Point2> points,
                             const Point2& center,
                             double width,
                             const ZoneSearchOptions& options) {
  PKM_CHECK(options.tolerance > 0.0 && std::isfinite(options.tolerance),
            "minimum-zone search: tolerance must be > 0");
  PKM_CHECK(options.directions >= 4, "minimum-zone search: directions must be >= 4");
  PKM_CHECK(points.size() < std::numeric_limits<std::uint32_t>::max(),
            "minimum-zone search: too many points");
  requirePoints(points, 3, "minimum-zone search");
  PKM_CHECK(std::isfinite(center.x()) && std::isfinite(center.y()) && std::isfinite(width),
            "minimum-zone search: non-finite start");
  constexpr std::size_t kMaxFullEvaluations = 512;  ///< evaluations of all points, then give up
  ZoneSearch out;
  out.best_center = center;
  out.best_width = width;
  const auto [o, rho] = meanAndReach(points);
  const double w_lower = widthLowerBound(points, o, rho, options.directions);
  if (!(w_lower > width)) return out;  // a nearly straight zone competes: no bounded region
  WorkingSet set(points, center);
  std::vector<std::uint32_t> candidates = set.indices();
  std::vector<Point2> level{o};
  double r = rho + rho * rho / (2.0 * (w_lower - width));  // half-side of this level's squares
  const double slack = 2.0 * std::numbers::sqrt2;
  while (!level.empty()) {
    if (out.boxes + level.size() > options.max_boxes) return out;  // budget: not proven
    out.boxes += level.size();
    std::vector<Range2> ranges(level.size());
    for (std::size_t i = 0; i < level.size(); ++i) {
      ranges[i] = rangeAbout(points, candidates, level[i]);
      if (ranges[i].width() >= out.best_width) continue;
      if (!set.complete()) {
        if (set.fullEvaluations() == kMaxFullEvaluations) return out;
        (void)set.evaluateAll(level[i], candidates);
        ranges[i] = rangeAbout(points, candidates, level[i]);  // now w itself there
      }
      if (ranges[i].width() < out.best_width) {
        out.best_width = ranges[i].width();
        out.best_center = level[i];
      }
    }
    std::vector<Point2> kept;
    std::vector<Range2> kept_ranges;
    for (std::size_t i = 0; i < level.size(); ++i) {
      if (ranges[i].width() - slack * r <= out.best_width - options.tolerance) {
        kept.push_back(level[i]);
        kept_ranges.push_back(ranges[i]);
      }
    }
    if (kept.empty()) break;
    candidates = keepCandidates(points, candidates, kept, kept_ranges, r);
    const double h = 0.5 * r;
    level.clear();
    for (const Point2& b : kept)
      for (const Point2& d : {Point2(-h, -h), Point2(h, -h), Point2(-h, h), Point2(h, h)})
        level.push_back(b + d);
    r = h;
  }
  out.proven = true;
  out.lower_bound = out.best_width - options.tolerance;
  return out;
}

}  // namespace pkm::metrology
