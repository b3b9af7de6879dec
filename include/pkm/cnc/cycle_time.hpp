/// @file
/// @brief Cycle-time model of `pkm gcode run` (docs/gcode.md "Cycle time"): along the
/// interpolated path, the speed of each sub-segment is the programmed feed (rapids at a rapid
/// rate) reduced so that no joint exceeds its velocity limit; the path acceleration of each
/// sub-segment is the largest one that keeps every joint within its acceleration limit; the speed
/// at each point between sub-segments is bounded so that the change of joint velocity across the
/// point stays within the acceleration limit; a forward/backward pass (look-ahead over the whole
/// program) then gives a trapezoidal speed profile per sub-segment, starting and ending at rest.
#pragma once

#include <limits>
#include <vector>

#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::cnc {

/// The controller's limits on a rapid besides its rate (LinuxCNC: a G0 runs at [TRAJ]
/// MAX_LINEAR_VELOCITY, lowered so that no axis exceeds its [AXIS_L] MAX_VELOCITY along the move,
/// and a rotary-only G0 at most at [TRAJ] MAX_ANGULAR_VELOCITY; LinuxCNC 2.9 "INI
/// Configuration", [TRAJ] and [AXIS_<letter>] sections). +infinity: no limit.
struct RapidAxisLimits {
  /// Largest speed of each axis X, Y, Z (mm/s), A, B, C (deg/s); > 0.
  Axes axis_velocity{kNoLimit, kNoLimit, kNoLimit, kNoLimit, kNoLimit, kNoLimit};
  double angular_rate = kNoLimit;  ///< rotary-only G0 path speed, deg/min; > 0
  static constexpr double kNoLimit = std::numeric_limits<double>::infinity();
  /// Whether any limit is finite.
  [[nodiscard]] bool any() const;
  /// Throws pkm::InvalidArgument when a limit is not > 0 (NaN included).
  void validate() const;
};

/// The path speed cap of a rapid from `a` to `b` (mm/s along XYZ, deg/s for a rotary-only
/// move, as segmentLength): the largest v with v·|b_i − a_i|/L <= axis_velocity_i for every axis
/// (L the segment's length), and for a rotary-only move v <= angular_rate/60. +inf without a
/// finite limit or for a segment of length 0.
[[nodiscard]] double rapidSpeedCap(const Axes& a, const Axes& b, const RapidAxisLimits& limits);

/// Joint and rapid limits (the same for all six struts).
struct MotionLimits {
  double max_joint_velocity = 100.0;       ///< model length unit per second; > 0
  double max_joint_acceleration = 1000.0;  ///< model length unit per second²; > 0
  double rapid_rate = 10000.0;             ///< G0 path speed, mm/min (or deg/min); > 0
  RapidAxisLimits rapid_axes;              ///< axis limits that lower a G0 (none by default)
  /// Throws pkm::InvalidArgument naming the field when one is not > 0 and finite.
  void validate() const;
};

/// Per-joint rate limits, for machines whose joints differ in unit or limit (an Exechon's legs in
/// the length unit and its wrist axes in degrees). Joint j of a joint vector (StrutVector: up to
/// six joints) may move at most max_velocity(j) per second and accelerate at most
/// max_acceleration(j) per second²; +infinity leaves a joint unlimited (also for unused slots).
struct JointRateLimits {
  kinematics::StrutVector max_velocity = kinematics::StrutVector::Constant(100.0);
  kinematics::StrutVector max_acceleration = kinematics::StrutVector::Constant(1000.0);
  double rapid_rate = 10000.0;  ///< G0 path speed, mm/min (or deg/min); > 0
  RapidAxisLimits rapid_axes;   ///< axis limits that lower a G0 (none by default)

  /// The same limits for all six joints (a hexapod's struts).
  [[nodiscard]] static JointRateLimits uniform(const MotionLimits& limits);
  /// Throws pkm::InvalidArgument when a limit is not > 0 (NaN included) or the rapid rate is not
  /// finite and > 0.
  void validate() const;
};

/// Path length of the sub-segment from `a` to `b`: the XYZ length in mm, or for a rotary-only
/// step the A/B/C length in degrees (LinuxCNC's feed rule for rotary-only moves); 0 if none moves.
[[nodiscard]] double segmentLength(const Axes& a, const Axes& b);

/// The programmed path speed of a point's sub-segment: feed/60 (mm/s), or rapid_rate/60 for a
/// rapid (or a move without a feed). The cycle time lowers a rapid further by rapidSpeedCap.
[[nodiscard]] double programmedSpeed(const PathPoint& p, const MotionLimits& limits);

/// Time of a sub-segment of length `ds` entered at speed `v0`, left at `v1`, cruising at most at
/// `vmax` with acceleration `a` (a trapezoid or triangle; v0, v1 <= vmax and reachable, as the
/// look-ahead guarantees). a = +inf gives ds / vmax.
[[nodiscard]] double trapezoidTime(double ds, double v0, double v1, double vmax, double a);

/// A stop of `seconds` at path point `point` (a G4 block or a cycle's dwell): the machine arrives
/// at rest, waits and leaves from rest.
struct PathDwell {
  std::size_t point = 0;
  double seconds = 0.0;
};

/// The path points where the program's dwells happen: a dwell after k motions is at the last
/// point of motion k − 1 (points[i].move), or at point 0 before any motion. `points` must be in
/// motion order (as PathInterpolator writes them).
[[nodiscard]] std::vector<PathDwell> dwellsOnPath(const std::vector<PathPoint>& points,
                                                  const std::vector<DwellEvent>& dwells);

/// Result of estimateCycleTime.
struct CycleTime {
  std::vector<double> t;  ///< arrival time at each point (s); t[0] = 0
  double total = 0.0;     ///< t.back() plus a dwell at the last point
  double dwell = 0.0;     ///< the dwells' share of total (s)
};

/// Times the path points[0..n) with strut readings q (model length unit). points[0] is the start
/// (the speed is 0 there, at the end and at each dwell). Throws pkm::InvalidArgument when sizes
/// differ, the limits are invalid or a dwell is negative or beyond the last point.
[[nodiscard]] CycleTime estimateCycleTime(const std::vector<PathPoint>& points,
                                          const std::vector<kinematics::StrutVector>& q,
                                          const MotionLimits& limits,
                                          const std::vector<PathDwell>& dwells = {});

/// As above with per-joint limits: joint j's rate is measured against its own limits (each
/// joint's |dq_j/ds| divided by its limit), so joints of different units share one path speed.
[[nodiscard]] CycleTime estimateCycleTime(const std::vector<PathPoint>& points,
                                          const std::vector<kinematics::StrutVector>& q,
                                          const JointRateLimits& limits,
                                          const std::vector<PathDwell>& dwells = {});

}  // namespace pkm::cnc
