/// @file
/// @brief The documents of a calibration pose plan (`pkm plan-poses`, docs/calibration.md "Pose
/// planning"): the chosen poses as CSV, the G-code program that drives the machine through them,
/// the one-line summary and the JSON of the plan. The plan itself is calibration::PosePlan.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "pkm/calibration/identifiability.hpp"
#include "pkm/calibration/pose_planning.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::io {

/// One move of an Exechon plan's program: the tool point (world frame, machine unit) and the
/// wrist readings A, C (rad) of the configuration that reaches it.
struct ExechonPlanMove {
  Eigen::Vector3d tool_point = Eigen::Vector3d::Zero();
  double a = 0.0;  ///< wrist reading A, rad
  double c = 0.0;  ///< wrist reading C, rad
};

/// A pose plan, as reported.
struct PosePlanReport {
  std::string kind = "hexapod";  ///< "hexapod" (6-DOF poses) or "exechon" (tracker points)
  std::string machine;           ///< the machine's name
  LengthUnit unit = LengthUnit::kMillimetre;
  std::string index_label = "O1";  ///< the index as it was asked for ("O1".."O5", any case)
  calibration::ObservabilityIndex index = calibration::ObservabilityIndex::kO1;
  calibration::PosePlan plan;  ///< the planner's result (indices into the candidates)
  std::size_t candidates = 0;  ///< candidates the plan chose from
  int parameters = 0;          ///< parameters the plan identifies (Exechon: 26)
  double feed = 1000.0;        ///< G-code feed rate, machine unit per minute
  /// Hexapod: the chosen poses (position in the machine unit, roll-pitch-yaw in rad), in order,
  /// and the home pose.
  std::vector<kinematics::PoseRpy> poses;
  kinematics::PoseRpy home;
  /// Exechon: the chosen tool poses (the input of `pkm exechon ik --poses`), in order, and the
  /// program's moves: home first, then one per chosen point.
  std::vector<kinematics::ExechonToolPose> points;
  std::vector<ExechonPlanMove> moves;
};

/// The chosen poses as CSV: hexapod `pose,x,y,z,a,b,c` (angles in degrees), Exechon
/// `pose,x,y,z,i,j,k`; numbers in round-trip form.
[[nodiscard]] std::string posePlanCsv(const PosePlanReport& report);

/// The summary line (no newline): the number chosen, the index value against a random choice,
/// the condition number, the rank and the exchanges.
[[nodiscard]] std::string posePlanSummary(const PosePlanReport& report);

/// The G-code program: home, then `N.. G1` to every chosen pose followed by `M0`, home, `M2`.
/// Hexapod moves are X Y Z A B C (roll-pitch-yaw in degrees); Exechon moves are X Y Z A C with
/// the wrist readings (`gcode run --orientation axes`), rounded to 4 decimals without "-0.0000".
[[nodiscard]] std::string posePlanGcode(const PosePlanReport& report);

/// The plan as JSON (two-space indent, closing newline): kind, machine, index, its value, the
/// random baseline, all five indices, condition number, rank, exchanges, candidates and the
/// chosen poses (hexapod angles in degrees).
[[nodiscard]] std::string posePlanJson(const PosePlanReport& report);

}  // namespace pkm::io
