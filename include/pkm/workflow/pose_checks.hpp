/// @file
/// @brief Poses checked one by one for a front end that draws the machine (`POST /api/ik` of
/// `pkm serve`, docs/web.md): a hexapod's strut readings or an Exechon's legs and wrist, every
/// limit's margin, and the joint centres in the world frame to draw the mechanism with.
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::workflow {

/// A point or vector in the world frame, machine unit.
using WorldPoint = std::array<double, 3>;

/// One checked pose. Lengths in the machine unit, angles in degrees; a margin of +infinity is a
/// limit the machine disables.
struct PoseCheckRow {
  std::string status;          ///< "ok", or the word of the first violation / failed solve
  std::vector<double> joints;  ///< hexapod: strut readings; Exechon: legs A, B, C, wrist C, A
  std::vector<double> stroke_margin;  ///< per strut or leg
  /// Hexapod: per strut, the smaller of its base and platform joint's cone margin; Exechon:
  /// alpha, beta, wrist C, wrist A.
  std::vector<double> angle_margin;
  /// Hexapod: the smallest strut-axis distance minus the strut diameter (NaN: not checked).
  double clearance = std::numeric_limits<double>::quiet_NaN();
  std::array<int, 2> closest_pair{-1, -1};  ///< hexapod: the struts of `clearance`
  double condition_number = std::numeric_limits<double>::quiet_NaN();
  double condition_margin = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> violations;  ///< "KIND ITEM value V limit L"
  /// Drawing (empty when the solve failed): each strut's or leg's fixed end and moving end, the
  /// tool point and the tool's unit direction; Exechon: also the wrist point.
  std::vector<WorldPoint> base_points, moving_points;
  WorldPoint tool_point{}, tool_direction{};
  std::vector<WorldPoint> wrist_points;
  /// A hybrid machine (an Exechon on X2/Y2, MXT700S parallelism paper): the X2 carriage and Y2
  /// table positions the pose's split gives (machine unit); empty otherwise. The drawing's points
  /// are in the PKM's frame P, which X2 carries.
  std::vector<double> carriage;
};

/// Poses to check.
struct PoseCheckRequest {
  std::string machine = "default";  ///< machine file, LinuxCNC .hal or built-in name
  std::string ini;                  ///< the LinuxCNC INI of a .hal machine ("": found from it)
  /// Hexapod: x, y, z, a, b, c (machine unit, degrees); Exechon: tool point x, y, z and tool
  /// direction i, j, k (any length > 0).
  std::vector<std::array<double, 6>> poses;
  /// Throws pkm::InvalidArgument for no poses or more than kMaxPoseChecks, or a non-finite value.
  void validate() const;
};

/// The most poses one request may check.
inline constexpr std::size_t kMaxPoseChecks = 100'000;

/// What checkPoses found.
struct PoseCheckResult {
  std::string machine;                   ///< the machine's name
  std::string machine_type;              ///< "hexapod" or "exechon"
  std::string units;                     ///< "mm" or "inch"
  std::vector<std::string> joint_names;  ///< "strut 0".. or "leg A".., "wrist C", "wrist A"
  std::vector<PoseCheckRow> rows;        ///< one per pose, in order
};

/// The machine's home as a pose checkPoses takes: a hexapod's home pose (x, y, z, a, b, c), an
/// Exechon's tool point and direction at its home configuration. Throws pkm::IoError for an
/// unreadable machine.
[[nodiscard]] std::array<double, 6> homePose(const std::string& machine,
                                             const std::string& ini = "");

/// One hexapod pose (x, y, z in the model's unit, a, b, c in degrees) solved and checked on an
/// already loaded model, as checkPoses does for each of its poses; `data` is `model`'s work space
/// (kinematics::HexapodData(model)). For a caller that checks pose after pose of one machine (the
/// live view, 20 times a second) without reading its files each time.
[[nodiscard]] PoseCheckRow checkHexapodPose(const kinematics::HexapodModel& model,
                                            kinematics::HexapodData& data,
                                            const std::array<double, 6>& pose);

/// Solves and checks every pose: hexapod IK (kinematics::checkPose), Exechon tool IK by continuity
/// from the previous pose (workflow::ExechonPosePath). Throws as validate() and pkm::IoError for an
/// unreadable machine.
[[nodiscard]] PoseCheckResult checkPoses(const PoseCheckRequest& request);

}  // namespace pkm::workflow
