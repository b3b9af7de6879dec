// Kinematics along a path of rows (kinematics_path.hpp).
#include "pkm/workflow/kinematics_path.hpp"

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/exechon_drm.hpp"
#include "pkm/kinematics/exechon_ik.hpp"

namespace pkm::workflow {

namespace kin = pkm::kinematics;

namespace {
/// The prediction repeats the last step only when it was at most this long: × the characteristic
/// length, and in rad.
constexpr double kMaxPredictedTranslation = 0.05;
constexpr double kMaxPredictedRotation = 0.05;
}  // namespace

HexapodFkAngles::HexapodFkAngles(const io::HexapodMachine& machine,
                                 const std::optional<kin::PoseRpy>& seed,
                                 bool from_seed)
    : machine_(machine),
      first_(seed.value_or(machine.model.home).rpy),
      near_(first_),
      from_seed_(from_seed) {}

Eigen::Vector3d HexapodFkAngles::next(const FkStep& step) {
  if (!step.summary.ok()) {
    if (!from_seed_) near_ = machine_.model.home.rpy;  // the path starts again from home
    return Eigen::Vector3d::Zero();
  }
  const Eigen::Vector3d rpy = geometry::rpyFromRotation(step.world_R_platform, near_);
  if (!from_seed_) near_ = rpy;
  return rpy;
}

HexapodFkPath::HexapodFkPath(const io::HexapodMachine& machine,
                             const std::optional<kin::PoseRpy>& seed,
                             bool from_seed,
                             bool angles)
    : machine_(machine),
      data_(machine.model),
      first_seed_(seed.value_or(machine.model.home)),
      from_seed_(from_seed),
      seed_{first_seed_.position, geometry::rotationFromRpy(first_seed_.rpy)},
      max_predicted_translation_(kMaxPredictedTranslation * machine.model.characteristicLength()) {
  if (angles) angles_.emplace(machine, seed, from_seed);
}

FkStep HexapodFkPath::solve(const kin::StrutVector& readings) {
  // The servo loop's seed: the last pose moved on by the last step (a path sampled at a steady
  // rate changes little from step to step), unless that step was long. The rotation moves on by
  // the last step's rotation, R·(R_prevᵀ·R), without any angle conversion.
  Pose start = seed_;
  if (has_previous_) {
    const Eigen::Vector3d dp = seed_.p - previous_.p;
    const Eigen::Matrix3d step = previous_.R.transpose() * seed_.R;
    // trace = 1 + 2 cos(angle): the last rotation was at most kMaxPredictedRotation
    static const double kMinTrace = 1.0 + 2.0 * std::cos(kMaxPredictedRotation);
    if (dp.norm() <= max_predicted_translation_ && step.trace() >= kMinTrace) {
      start.p += dp;
      // One Newton–Schulz step, R ← R·(3I − RᵀR)/2, keeps the product orthonormal to rounding
      // (repeated products of rounded rotations drift from SO(3) geometrically).
      const Eigen::Matrix3d predicted = seed_.R * step;
      Eigen::Matrix3d correction = (predicted.transpose() * predicted).eval();
      correction *= -0.5;
      correction.diagonal().array() += 1.5;
      start.R.noalias() = predicted * correction;
    }
  }
  FkStep step;
  step.summary = kin::forwardKinematics(
      machine_.model, data_, readings, start.p, start.R, nullptr, machine_.fk);
  step.pose.position = data_.world_p_tcp;
  step.world_R_platform = data_.world_R_platform;
  if (angles_) step.pose.rpy = angles_->next(step);
  if (from_seed_) return step;
  if (step.summary.ok()) {
    previous_ = seed_;
    has_previous_ = solved_;  // the seed was a solution too: the last step is known
    seed_ = {data_.world_p_tcp, data_.world_R_platform};
    solved_ = true;
  } else {
    solved_ = false;
    seed_ = {machine_.model.home.position, geometry::rotationFromRpy(machine_.model.home.rpy)};
    has_previous_ = false;  // home again after a failure
  }
  return step;
}

ExechonFkPath::ExechonFkPath(const io::ExechonMachine& machine)
    : machine_(machine), data_(machine.model), seed_(machine.model.home) {}

FkStep ExechonFkPath::solve(const kin::ExechonJoints& joints,
                            const std::optional<std::array<double, 2>>& x2y2) {
  PKM_CHECK(!x2y2 || machine_.hybrid, "x2,y2 need a machine with a \"hybrid\" section");
  FkStep step;
  step.summary = kin::toolForwardKinematics(machine_.model, data_, joints, seed_, machine_.fk);
  if (!step.summary.ok()) {
    seed_ = machine_.model.home;
    return step;
  }
  seed_ = kin::configurationOf(data_);
  step.tool_point = data_.world_p_tool;
  step.tool_direction = data_.world_u_tool;
  if (x2y2) {  // tool in the work frame: the nominal chain of the hybrid machine
    kin::HybridCommand command;
    command.x2 = (*x2y2)[0];
    command.y2 = (*x2y2)[1];
    command.pkm = step.tool_point;
    step.tool_point = kin::hybridNominalToolPosition(*machine_.hybrid, command);
  }
  return step;
}

ExechonPosePath::ExechonPosePath(const io::ExechonMachine& machine)
    : machine_(machine), data_(machine.model), previous_(machine.model.home) {}

ExechonPoseStep ExechonPosePath::solve(const kin::ExechonToolPose& tool,
                                       const std::optional<std::array<double, 2>>& x2y2) {
  PKM_CHECK(!x2y2 || machine_.hybrid, "x2,y2 need a machine with a \"hybrid\" section");
  ExechonPoseStep step;
  kin::ExechonToolPose target = tool;
  if (machine_.hybrid) {
    step.command =
        x2y2 ? kin::hybridCommandForTool(*machine_.hybrid, tool.position, (*x2y2)[0], (*x2y2)[1])
             : kin::hybridCommandCentred(*machine_.hybrid, tool.position);
    target.position = step.command.pkm;
  }
  step.check = kin::checkToolPose(machine_.model, data_, target, previous_);
  step.solved = step.check.solver_status == "ok";
  step.status = step.check.status();
  if (!step.solved) return step;
  previous_ = kin::configurationOf(data_);
  if (!reference_) reference_ = data_.world_R_tool;
  step.joints = kin::jointsOf(data_);
  step.drm = kin::dependentRotation(data_.world_R_tool, *reference_);
  if (step.status == "ok" && machine_.hybrid &&
      !kin::hybridWithinLimits(*machine_.hybrid, step.command))
    step.status = "axis_limit";
  return step;
}

ExechonWristStep solveWristPoint(const kin::ExechonModel& model,
                                 kin::ExechonData& data,
                                 const Eigen::Vector3d& S) {
  ExechonWristStep step;
  step.ik = kin::tripodInverseKinematics(model, data, S);
  if (step.ik != kin::ExechonIkStatus::kOk) return step;
  step.readings = data.readings;
  step.e = data.e;
  step.status = "ok";
  const kin::ExechonCheckResult check = kin::checkConfiguration(model, data);
  for (const auto& v : check.violations)
    if (v.item.rfind("wrist", 0) != 0) {
      step.status = kin::toString(v.kind);
      break;
    }
  return step;
}

}  // namespace pkm::workflow
