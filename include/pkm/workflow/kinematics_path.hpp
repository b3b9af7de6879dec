/// @file
/// @brief The row-by-row jobs of `pkm hexapod fk` and `pkm exechon ik/fk/check` (docs/formats.md):
/// kinematics along a path of rows, where each row depends on the ones before as on a machine's
/// controller (FK seeded by the previous solution, IK by continuity, the dependent rotational
/// motion measured from the first pose). A front end reads the rows and prints the steps; these
/// classes hold the rules. Angles are in rad, lengths in the machine unit.
#pragma once

#include <array>
#include <optional>
#include <string_view>

#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::workflow {

/// One forward solve along a path.
struct FkStep {
  kinematics::FkSummary summary;  ///< status and iterations
  /// Hexapod: the solution (valid when summary.ok()); its angles only when the path computes
  /// them (HexapodFkPath's `angles`), else HexapodFkAngles gives them from world_R_platform.
  kinematics::PoseRpy pose;
  Eigen::Matrix3d world_R_platform = Eigen::Matrix3d::Identity();  ///< hexapod: the rotation
  /// Hexapod: pose.rpy holds geometry::rpyFromRotation(world_R_platform), the angles before
  /// HexapodFkAngles picks the equivalent triple nearest the path's (set by
  /// HexapodFkAngles::convert, so that another thread can take that share of the work).
  bool rpy_converted = false;
  /// Exechon: the tool point (world frame, or the work frame of a hybrid machine given x2, y2)
  /// and the unit tool direction (valid when summary.ok()).
  Eigen::Vector3d tool_point = Eigen::Vector3d::Zero();
  Eigen::Vector3d tool_direction = Eigen::Vector3d::Zero();
};

/// Hexapod FK along a path of strut readings as a servo loop solves it
/// (kinematics::forwardKinematics with the machine's FkOptions): each solve starts from the
/// previous solutions (the last one, moved on by the last step: a linear prediction), the first
/// from `seed` (default home), and the one after a failure from home. With `from_seed`, every row
/// is solved on its own from the seed, as for poses that do not form a path.
/// The roll-pitch-yaw angles of a HexapodFkPath's solutions, in the order solved, each chosen
/// nearest to the previous solution's (the first to the seed's; after a failure to home's, from
/// where the path starts again): the same angles whichever thread converts them.
class HexapodFkAngles {
 public:
  /// As the path's constructor arguments. `machine` must outlive this.
  HexapodFkAngles(const io::HexapodMachine& machine,
                  const std::optional<kinematics::PoseRpy>& seed,
                  bool from_seed);
  /// The angles of the next step (rad; zero for a failed step, which only moves the reference).
  Eigen::Vector3d next(const FkStep& step);
  /// Converts a solved step's rotation to angles ahead of next() (FkStep::rpy_converted): the
  /// costly part of next(), which does not depend on the order; any thread may call it.
  static void convert(FkStep& step);

 private:
  const io::HexapodMachine& machine_;
  Eigen::Vector3d first_;  ///< the seed's angles
  Eigen::Vector3d near_;   ///< the reference of the next step
  bool from_seed_ = false;
};

class HexapodFkPath {
 public:
  /// `machine` must outlive the path. With `angles` false the steps' pose.rpy is not computed
  /// (a HexapodFkAngles made with the same arguments gives them, e.g. on another thread).
  explicit HexapodFkPath(const io::HexapodMachine& machine,
                         const std::optional<kinematics::PoseRpy>& seed = std::nullopt,
                         bool from_seed = false,
                         bool angles = true);
  /// Solves the next row.
  FkStep solve(const kinematics::StrutVector& readings);
  /// As above, into `step` (every field the hexapod sets is written; the others are left).
  void solve(const kinematics::StrutVector& readings, FkStep& step);

 private:
  /// A pose as the solver takes it: TCP position, platform rotation (world frame).
  struct Pose {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
  };
  const io::HexapodMachine& machine_;
  kinematics::HexapodFkSolver solver_;  ///< the machine's model and FkOptions
  kinematics::HexapodData data_;
  kinematics::PoseRpy first_seed_;
  bool from_seed_ = false;
  Pose seed_;  ///< the next solve's seed (the last solution, or the first seed)
  std::optional<HexapodFkAngles> angles_;  ///< when the path computes the angles
  bool solved_ = false;                    ///< seed_ is the last row's solution
  bool has_previous_ = false;              ///< the last step is known (two solutions in a row)
  Eigen::Vector3d last_translation_ = Eigen::Vector3d::Zero();  ///< of the last step
  Eigen::Vector3d last_rotation_ = Eigen::Vector3d::Zero();  ///< of the last step: rotation vector
  int since_orthonormalised_ = 0;            ///< predictions since the last orthonormalisation
  double max_predicted_translation2_ = 0.0;  ///< longest last step the prediction repeats, squared
};

/// Exechon tool FK along a path of joint readings (kinematics::toolForwardKinematics), seeded as
/// HexapodFkPath. With x2, y2 (a hybrid machine) the tool point is carried into the work frame by
/// the nominal chain (kinematics::hybridNominalToolPosition).
class ExechonFkPath {
 public:
  /// `machine` must outlive the path.
  explicit ExechonFkPath(const io::ExechonMachine& machine);
  /// Solves the next row. Throws pkm::InvalidArgument for x2, y2 on a machine without a hybrid
  /// section.
  FkStep solve(const kinematics::ExechonJoints& joints,
               const std::optional<std::array<double, 2>>& x2y2 = std::nullopt);

 private:
  const io::ExechonMachine& machine_;
  kinematics::ExechonData data_;
  kinematics::ExechonConfiguration seed_;
};

/// One tool pose of an Exechon path, solved and checked.
struct ExechonPoseStep {
  kinematics::ExechonCheckResult check;  ///< kinematics::checkToolPose
  /// The IK succeeded (check.solver_status is "ok"); joints and drm are valid only then.
  bool solved = false;
  /// check.status(), or "axis_limit" when every PKM limit holds but X2 or Y2 is outside its
  /// stroke.
  std::string_view status;
  kinematics::ExechonJoints joints;   ///< leg readings and wrist readings C, A
  double drm = 0.0;                   ///< φ_DRM from the path's first solved pose, rad
                                      ///< (Lee et al. 2019)
  kinematics::HybridCommand command;  ///< hybrid machine: x2, y2 and the PKM command
};

/// Exechon tool IK and checks along a path of tool poses (`exechon ik --poses`, `exechon check`):
/// IK by continuity from the previous solved pose (the first from home). On a hybrid machine the
/// tool position is in the work frame, and X2/Y2 take their share first: the given x2, y2
/// (kinematics::hybridCommandForTool) or the centred split (hybridCommandCentred).
class ExechonPosePath {
 public:
  /// `machine` must outlive the path.
  explicit ExechonPosePath(const io::ExechonMachine& machine);
  /// Solves and checks the next pose. Throws pkm::InvalidArgument for x2, y2 on a machine
  /// without a hybrid section.
  ExechonPoseStep solve(const kinematics::ExechonToolPose& tool,
                        const std::optional<std::array<double, 2>>& x2y2 = std::nullopt);
  /// The mechanism at the last solve (joint centres, wrist point; valid when it was solved).
  [[nodiscard]] const kinematics::ExechonData& data() const { return data_; }

 private:
  const io::ExechonMachine& machine_;
  kinematics::ExechonData data_;
  kinematics::ExechonConfiguration previous_;
  std::optional<Eigen::Matrix3d> reference_;  ///< tool frame of the first solved pose (frame H)
};

/// The tripod of an Exechon at one wrist point (`exechon ik --wrist`).
struct ExechonWristStep {
  kinematics::ExechonIkStatus ik = kinematics::ExechonIkStatus::kOk;
  kinematics::ExechonLegVector readings = kinematics::ExechonLegVector::Zero();  ///< legs A, B, C
  Eigen::Vector3d e = Eigen::Vector3d::Zero();  ///< (α, β in rad, h)
  /// "ok" or the status word of the first violation that is not about the wrist (a wrist point
  /// has no tool direction); empty when the IK failed.
  std::string_view status;
};

/// Tripod IK at wrist point S (Zoppi base frame, machine unit) in the machine's branch, then the
/// tripod's limits (kinematics::tripodInverseKinematics, checkConfiguration).
[[nodiscard]] ExechonWristStep solveWristPoint(const kinematics::ExechonModel& model,
                                               kinematics::ExechonData& data,
                                               const Eigen::Vector3d& S);

}  // namespace pkm::workflow
