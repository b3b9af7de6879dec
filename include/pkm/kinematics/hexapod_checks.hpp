/// @file
/// @brief Per-pose limit checks of a hexapod: strut stroke, joint cone angles, leg-to-leg
/// interference and singularity proximity, each with the strut or limit named and its margin.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::kinematics {

/// Which limit a check is about.
enum class LimitKind {
  kStroke,        ///< strut reading outside [min_reading, max_reading]
  kJointAngle,    ///< base or platform joint deflection beyond its cone half-angle
  kInterference,  ///< two struts closer than the strut diameter
  kSingular,      ///< scaled Jacobian condition number above HexapodModel::max_condition
  kDegenerate,    ///< a strut of zero length (joint centres coincide)
};

/// "stroke", "joint_angle", "interference", "singular", "degenerate" (the CLI status words).
[[nodiscard]] std::string_view toString(LimitKind kind);

/// One violated limit.
struct LimitViolation {
  LimitKind kind = LimitKind::kStroke;
  std::string item;     ///< what is violated, e.g. "strut 3", "platform joint 2", "struts 1-4"
  double value = 0.0;   ///< reading (length), angle (rad), distance (length) or condition number
  double limit = 0.0;   ///< the limit it is compared with, same unit
  double margin = 0.0;  ///< signed distance to the limit (< 0 when violated), same unit
};

/// Results of checkPose. Margins are >= 0 when a limit holds; +infinity when the limit is disabled.
struct HexapodCheckResult {
  StrutVector readings = StrutVector::Zero();        ///< model length unit
  StrutVector stroke_margin = StrutVector::Zero();   ///< min(reading − min, max − reading)
  StrutVector base_angle = StrutVector::Zero();      ///< joint deflection from its cone axis, rad
  StrutVector platform_angle = StrutVector::Zero();  ///< rad
  StrutVector base_angle_margin = StrutVector::Zero();      ///< max_angle − angle, rad
  StrutVector platform_angle_margin = StrutVector::Zero();  ///< rad
  double min_leg_distance = 0.0;   ///< smallest strut-axis distance over checked pairs, length unit
  int closest_pair[2] = {-1, -1};  ///< the struts of min_leg_distance (-1 when no pair is checked)
  double interference_margin = 0.0;  ///< min_leg_distance − strut_diameter
  int unchecked_pairs = 0;  ///< pairs sharing a joint (ends closer than a diameter): not checked
  double condition_number = 0.0;           ///< scaledConditionNumber at the pose
  double condition_margin = 0.0;           ///< max_condition − condition_number
  std::vector<LimitViolation> violations;  ///< in the order stroke, angle, interference, singular

  [[nodiscard]] bool ok() const { return violations.empty(); }
  /// "ok" or the status word of the first violation.
  [[nodiscard]] std::string_view status() const;
};

/// Runs inverse kinematics for `pose` and every limit check. Leaves data at `pose` with J_q_x
/// filled.
[[nodiscard]] HexapodCheckResult checkPose(const HexapodModel& model,
                                           HexapodData& data,
                                           const PoseRpy& pose);

}  // namespace pkm::kinematics
