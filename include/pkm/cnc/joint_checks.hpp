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
  kStroke,
  kJointAngle,
  kInterference,
  kSingular,
  kDegenerate,
  kJointVelocity,
  kJointAcceleration
};
inline constexpr std::size_t kPathChecks = 7;

/// "stroke", "joint_angle", "interference", "singular", "degenerate", "joint_velocity",
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

/// Runs every check along points[0..n) with readings q (model length unit, as
/// HexapodJointConverter gives them). Joint velocity of sub-segment k: max_j |Δq_j|/Δs · v_prog,
/// v_prog the programmed speed (programmedSpeed). Joint acceleration at a point between two
/// sub-segments of the same motion: max_j |Δ(dq_j/ds)| / mean(Δs) · v_prog² (the centripetal
/// joint acceleration at the programmed feed; corners between motions are left to the
/// cycle-time model, which slows down for them). Rapids have no programmed feed (a controller
/// runs G0 as fast as the joints allow) and are left out of both. Degenerate: the shortest
/// distance between a strut's joint centres, limit 0. Throws pkm::InvalidArgument on size mismatch.
[[nodiscard]] PathCheckReport checkPath(const kinematics::HexapodModel& model,
                                        const std::vector<PathPoint>& points,
                                        const std::vector<kinematics::StrutVector>& q,
                                        const MotionLimits& limits);

}  // namespace pkm::cnc
