/// @file
/// @brief Limit checks of a hexapod along an interpolated G-code path (`pkm gcode run`): at every
/// point the pose checks of kinematics/hexapod_checks.hpp (strut stroke, base/platform joint
/// angles, leg-to-leg interference, singularity proximity, degenerate struts), and along the path
/// the joint velocity at the programmed feed and the joint acceleration at the programmed feed
/// inside each motion. Each check keeps its worst point and its first violation with the
/// program line, the position and the margin (positive while the limit holds).
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/cnc/cycle_time.hpp"
#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::cnc {

/// The checks, in report order.
enum class PathCheck {
  kReach,
  kStroke,
  kJointAngle,
  kInterference,
  kSingular,
  kDegenerate,
  kJointVelocity,
  kJointAcceleration
};
inline constexpr std::size_t kPathChecks = 8;

/// "reach", "stroke", "joint_angle", "interference", "singular", "degenerate", "joint_velocity",
/// "joint_acceleration".
[[nodiscard]] std::string_view toString(PathCheck check);

/// Where and how much: one evaluation of a check.
struct CheckEvent {
  std::size_t line = 0;  ///< program line
  Axes pos{};            ///< machine position, mm and degrees
  std::string item;      ///< e.g. "strut 3", "platform joint 2", "struts 1-4"
  double value = 0.0;    ///< reading, angle (rad), distance, condition number, rate
  double limit = 0.0;    ///< the limit, same unit
  double margin = std::numeric_limits<double>::infinity();  ///< limit − value side, < 0 violated
};

/// Summary of one check over the path.
struct CheckStat {
  bool enabled = false;        ///< false when the machine disables the limit (margin +inf)
  std::size_t violations = 0;  ///< points (or sub-segments) where it is violated
  CheckEvent worst;            ///< smallest margin
  CheckEvent first;            ///< first violation (valid when violations > 0)
  /// What `worst` was chosen by: the margin, or for per-joint rates the margin relative to the
  /// joint's own limit (joints of different units compare fairly).
  double worst_rank = std::numeric_limits<double>::infinity();
  /// How many violations to keep in `events` (0: none; a front end listing every violation sets
  /// it, bounding the memory a long program can take).
  std::size_t keep = 0;
  std::vector<CheckEvent> events;  ///< the first `keep` violations, in path order
};

/// All checks of one path.
struct PathCheckReport {
  std::array<CheckStat, kPathChecks> stats{};
  std::size_t points = 0;  ///< points checked
  [[nodiscard]] const CheckStat& operator[](PathCheck c) const {
    return stats[static_cast<std::size_t>(c)];
  }
  /// True when no check is violated.
  [[nodiscard]] bool ok() const;
};

/// Records one evaluation of a check at `p`: counts a violation (margin < 0 or NaN), keeps the
/// first violation (and the first stat.keep in stat.events), and keeps the evaluation as the worst
/// when `rank` (default: the margin) is the smallest so far. A margin of +infinity means the limit
/// is disabled and records nothing.
void recordCheck(CheckStat& stat,
                 const PathPoint& p,
                 std::string item,
                 double value,
                 double limit,
                 double margin,
                 double rank = std::numeric_limits<double>::quiet_NaN());

/// The joint velocity and acceleration checks (as checkPath describes them) with per-joint
/// limits: joint j is named joint_name(j) and measured against its own limits; the worst point is
/// the one nearest its limit relative to the limit. Writes report's kJointVelocity and
/// kJointAcceleration stats. Throws pkm::InvalidArgument on size mismatch or invalid limits.
void checkJointRates(const std::vector<PathPoint>& points,
                     const std::vector<kinematics::StrutVector>& q,
                     const JointRateLimits& limits,
                     const std::function<std::string(int)>& joint_name,
                     PathCheckReport& report);

/// Runs every check along points[0..n) with readings q (model length unit, as
/// HexapodJointConverter gives them). Joint velocity of sub-segment k: max_j |Δq_j|/Δs · v_prog,
/// v_prog the programmed speed (programmedSpeed). Joint acceleration at a point between two
/// sub-segments of the same motion: max_j |Δ(dq_j/ds)| / mean(Δs) · v_prog² (the centripetal
/// joint acceleration at the programmed feed; corners between motions are left to the
/// cycle-time model, which slows down for them). Rapids have no programmed feed (a controller
/// runs G0 as fast as the joints allow) and are left out of both. Degenerate: the shortest
/// distance between a strut's joint centres, limit 0. Reach: enabled and never violated (the
/// hexapod's inverse kinematics is closed-form and always defined). Throws pkm::InvalidArgument on
/// size mismatch.
/// `keep_violations`: violations each check keeps in its CheckStat::events (0: none).
[[nodiscard]] PathCheckReport checkPath(const kinematics::HexapodModel& model,
                                        const std::vector<PathPoint>& points,
                                        const std::vector<kinematics::StrutVector>& q,
                                        const MotionLimits& limits,
                                        std::size_t keep_violations = 0);

}  // namespace pkm::cnc
