#include "pkm/cnc/path_interpolation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// Sweeps closer to zero than this (radians) count as a full circle (end equals start).
constexpr double kFullCircleEps = 1e-12;

/// ceil(x) as a count, at least 1; saturated far below the largest size_t (a count that large is
/// refused by the point limit anyway), so that no conversion overflows.
std::size_t saturatedCount(double x) {
  constexpr double kCap = 1e18;
  if (!(x < kCap)) return static_cast<std::size_t>(kCap);
  return std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(x)));
}

std::size_t stepsFor(double length, double max_step) {
  if (!std::isfinite(max_step) || length <= 0.0) return 1;
  return saturatedCount(length / max_step);
}

}  // namespace

std::size_t arcSteps(double radius, double sweep, double tolerance) {
  const double a = std::abs(sweep);
  if (a == 0.0) return 1;
  // Capped at half a turn per step so that every chord keeps the arc's direction.
  const double dmax =
      radius <= 0.0
          ? std::numbers::pi
          : std::min(std::numbers::pi, 2.0 * std::acos(std::max(-1.0, 1.0 - tolerance / radius)));
  return saturatedCount(a / dmax);
}

double arcSweep(double a0, double a1, int turns) {
  double d = a1 - a0;
  if (turns > 0) {
    while (d <= kFullCircleEps) d += kTwoPi;
    while (d > kTwoPi + kFullCircleEps) d -= kTwoPi;
    return d + kTwoPi * static_cast<double>(turns - 1);
  }
  while (d >= -kFullCircleEps) d -= kTwoPi;
  while (d < -kTwoPi - kFullCircleEps) d += kTwoPi;
  return d - kTwoPi * static_cast<double>(-turns - 1);
}

PathInterpolator::PathInterpolator(const InterpolationOptions& options, const Axes& start)
    : options_(options), pos_(start) {
  PKM_CHECK(options.tolerance > 0.0, "interpolation tolerance must be > 0");
  PKM_CHECK(options.max_step > 0.0, "interpolation max_step must be > 0");
  PKM_CHECK(options.max_angle_step > 0.0, "interpolation max_angle_step must be > 0");
}

PathTooLong::PathTooLong(std::size_t needed_points, std::size_t limit_points)
    : InvalidArgument(fmt::format("the path would need at least {} interpolated points, more than "
                                  "the limit of {}",
                                  needed_points,
                                  limit_points)),
      needed(needed_points),
      limit(limit_points) {}

void PathInterpolator::append(const Move& move, std::uint32_t index, std::vector<PathPoint>& out) {
  const auto room = [&](std::size_t n) {
    if (n > options_.max_points || out.size() > options_.max_points - n)
      throw PathTooLong(out.size() + n, options_.max_points);  // n is at most 1e18
  };
  const Axes s = pos_;
  const Axes& e = move.end;
  PathPoint p;
  p.line = move.line;
  p.move = index;
  p.kind = move.kind;
  p.feed = move.feed;
  double rot = 0.0;
  for (std::size_t k = 3; k < 6; ++k) rot = std::max(rot, std::abs(e[k] - s[k]));
  const std::size_t n_rot = stepsFor(rot, options_.max_angle_step);
  if (move.kind != MoveKind::kArc) {
    const double len = std::hypot(e[0] - s[0], e[1] - s[1], e[2] - s[2]);
    // A move that goes nowhere (e.g. `G1 F150`) may add no point: no zero-length segment in a
    // joint path, none in the joint rates or the time model. The path's first point is kept.
    if (options_.skip_still_moves && len == 0.0 && rot == 0.0 && !out.empty()) return;
    const std::size_t n = std::max(stepsFor(len, options_.max_step), n_rot);
    room(n);
    for (std::size_t i = 1; i <= n; ++i) {
      const double u = static_cast<double>(i) / static_cast<double>(n);
      for (std::size_t k = 0; k < 6; ++k) p.pos[k] = i == n ? e[k] : s[k] + u * (e[k] - s[k]);
      out.push_back(p);
    }
  } else {
    const auto [i1, i2, in] = planeAxes(move.plane);
    const double c1 = move.centre[i1], c2 = move.centre[i2];
    const double r0 = std::hypot(s[i1] - c1, s[i2] - c2);
    const double r1 = std::hypot(e[i1] - c1, e[i2] - c2);
    const double a0 = std::atan2(s[i2] - c2, s[i1] - c1);
    const double sweep = arcSweep(a0, std::atan2(e[i2] - c2, e[i1] - c1), move.turns);
    const double planar = std::abs(sweep) * std::max(r0, r1);
    const double helix = std::hypot(planar, e[in] - s[in]);
    const std::size_t n = std::max({arcSteps(std::max(r0, r1), sweep, options_.tolerance),
                                    stepsFor(helix, options_.max_step),
                                    n_rot});
    room(n);
    for (std::size_t i = 1; i <= n; ++i) {
      if (i == n) {
        p.pos = e;
      } else {
        const double u = static_cast<double>(i) / static_cast<double>(n);
        const double r = r0 + u * (r1 - r0);
        const double a = a0 + u * sweep;
        p.pos[i1] = c1 + r * std::cos(a);
        p.pos[i2] = c2 + r * std::sin(a);
        p.pos[in] = s[in] + u * (e[in] - s[in]);
        for (std::size_t k = 3; k < 6; ++k) p.pos[k] = s[k] + u * (e[k] - s[k]);
      }
      out.push_back(p);
    }
  }
  pos_ = e;
}

}  // namespace pkm::cnc
