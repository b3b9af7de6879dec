/// @file
/// @brief Interpolation of G-code motions (cnc::Move, machine coordinates) into points for
/// joint-space conversion (docs/gcode.md "gcode run"): arcs and helices to a chordal tolerance
/// (sagitta rule), lines and rotary moves to a maximum step, A/B/C linear in the path parameter.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "pkm/cnc/move.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {

/// The default InterpolationOptions::max_points.
inline constexpr std::size_t kDefaultMaxPathPoints = 10'000'000;

/// Thrown by PathInterpolator::append when a path would exceed InterpolationOptions::max_points;
/// the caller names the program and line.
class PathTooLong : public InvalidArgument {
 public:
  PathTooLong(std::size_t needed, std::size_t limit);
  std::size_t needed;  ///< the points the path would have with this motion (at least)
  std::size_t limit;   ///< InterpolationOptions::max_points
};

/// A position in machine coordinates: X, Y, Z (mm), A, B, C (degrees).
using Axes = std::array<double, 6>;

/// One interpolated point: the end of a sub-segment of a motion.
struct PathPoint {
  std::size_t line = 0;    ///< source line of the motion
  std::uint32_t move = 0;  ///< index of the motion in the program (0-based)
  MoveKind kind = MoveKind::kRapid;
  Axes pos{};  ///< position, mm and degrees
  /// Feed of the motion in mm/min (NaN for rapids), as cnc::Move::feed.
  double feed = std::numeric_limits<double>::quiet_NaN();
};

/// How finely motions are cut.
struct InterpolationOptions {
  /// Chordal tolerance of arcs (mm): the sagitta r·(1 − cos(Δθ/2)) of every arc chord is at most
  /// this. Must be > 0.
  double tolerance = 0.01;
  /// Longest XYZ chord of a sub-segment (mm), lines and arcs alike; +inf for no limit. > 0.
  double max_step = std::numeric_limits<double>::infinity();
  /// Largest change of any of A/B/C over one sub-segment (degrees); +inf for no limit. > 0.
  double max_angle_step = std::numeric_limits<double>::infinity();
  /// A line that goes nowhere (`G1 F150`) adds no point (true: joint paths, no zero-length
  /// segment) or one point where the machine is (false: the program rewriting of
  /// compensateProgram, which writes words for every motion line).
  bool skip_still_moves = false;
  /// The most points a path may have (> 0): a program that would need more (a helix of a
  /// hundred million turns, a 0.1 µm step over metres) is refused before its points are made,
  /// so that memory stays bounded. The default is far above any machining program (a 100,000-
  /// line program needs a few hundred thousand): 10 million points, about 1.5 GB of joint path.
  std::size_t max_points = kDefaultMaxPathPoints;
};

/// Number of equal angular steps so that the sagitta of each chord of an arc of radius `radius`
/// (mm) sweeping `sweep` radians (any sign) is at most `tolerance`: Δθ_max = 2·acos(1 − tol/r)
/// (chord geometry: sagitta s = r·(1 − cos(Δθ/2))), n = ceil(|sweep| / Δθ_max), at least 1.
[[nodiscard]] std::size_t arcSteps(double radius, double sweep, double tolerance);

/// The signed sweep (radians) of an arc from start angle `a0` to end angle `a1` (radians, in the
/// plane's (first, second) axes) with LinuxCNC's signed `turns` (G3 > 0, G2 < 0): for G3 the
/// counter-clockwise angle in (0, 2π] plus 2π·(turns − 1), mirrored for G2.
[[nodiscard]] double arcSweep(double a0, double a1, int turns);

/// Cuts motions into points. Keeps the current position between calls (start: all zero, the
/// interpreter's start-up machine position).
class PathInterpolator {
 public:
  /// Throws pkm::InvalidArgument when an option is not > 0 or not a number.
  explicit PathInterpolator(const InterpolationOptions& options, const Axes& start = {});

  /// Appends the points of `move` (its end included, its start, the previous end, not) to `out`,
  /// tagged with `index` and the move's line; with options.skip_still_moves a line that goes
  /// nowhere adds none (unless `out` is empty: the path's first point). Throws PathTooLong, before
  /// adding any, when out.size() plus the move's points would exceed options.max_points. Lines: n =
  /// ceil(max(|ΔXYZ|/max_step, max|ΔABC|/max_angle_step)) equal steps. Arcs (LinuxCNC G17/G18/G19
  /// planes, the plane axes (X,Y), (Z,X), (Y,Z)): the angle is split into n equal steps, n the
  /// largest of arcSteps, the helix length / max_step and the rotary change / max_angle_step; the
  /// radius goes linearly from the start radius to the end radius (LinuxCNC's spiral for slightly
  /// unequal radii), the normal axis and A/B/C linearly in the angle.
  void append(const Move& move, std::uint32_t index, std::vector<PathPoint>& out);

  /// The current position (the end of the last motion).
  [[nodiscard]] const Axes& position() const { return pos_; }

 private:
  InterpolationOptions options_;
  Axes pos_{};
};

}  // namespace pkm::cnc
