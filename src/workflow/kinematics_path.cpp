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
/// Predicted rotations between two orthonormalisations.
constexpr int kOrthonormaliseEvery = 64;
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
  const Eigen::Vector3d rpy = geometry::nearestRpy(
      step.rpy_converted ? step.pose.rpy : geometry::rpyFromRotation(step.world_R_platform), near_);
  if (!from_seed_) near_ = rpy;
  return rpy;
}

void HexapodFkAngles::convert(FkStep& step) {
  if (!step.summary.ok()) return;
  step.pose.rpy = geometry::rpyFromRotation(step.world_R_platform);
  step.rpy_converted = true;
}

HexapodFkPath::HexapodFkPath(const io::HexapodMachine& machine,
                             const std::optional<kin::PoseRpy>& seed,
                             bool from_seed,
                             bool angles)
    : machine_(machine),
      solver_(machine.model, machine.fk),
      data_(machine.model),
      first_seed_(seed.value_or(machine.model.home)),
      from_seed_(from_seed),
      seed_{first_seed_.position, geometry::rotationFromRpy(first_seed_.rpy)},
      max_predicted_translation2_(
          std::pow(kMaxPredictedTranslation * machine.model.characteristicLength(), 2)) {
  if (angles) angles_.emplace(machine, seed, from_seed);
}

FkStep HexapodFkPath::solve(const kin::StrutVector& readings) {
  FkStep step;
  solve(readings, step);
  return step;
}

void HexapodFkPath::solve(const kin::StrutVector& readings, FkStep& step) {
  // The servo loop's seed: the last pose moved on by the last step (a path sampled at a steady
  // rate changes little from step to step), unless that step was long. The rotation moves on by
  // exp([ω]×), ω the last step's rotation vector.
  Pose start = seed_;
  if (has_previous_ && last_translation_.squaredNorm() <= max_predicted_translation2_ &&
      last_rotation_.squaredNorm() <= kMaxPredictedRotation * kMaxPredictedRotation) {
    start.p += last_translation_;
    start.R.noalias() = geometry::so3Exp(last_rotation_) * seed_.R;
    // A product of rounded rotations is orthonormal to rounding only; the solution inherits the
    // seed's rounding, so now and then one Newton–Schulz step, R ← R·(3I − RᵀR)/2, takes it back
    // (the errors of the products add up; they do not grow geometrically).
    if (++since_orthonormalised_ == kOrthonormaliseEvery) {
      since_orthonormalised_ = 0;
      Eigen::Matrix3d correction = (start.R.transpose() * start.R).eval();
      correction *= -0.5;
      correction.diagonal().array() += 1.5;
      start.R = (start.R * correction).eval();
    }
  }
  step.summary = solver_.solve(data_, readings, start.p, start.R);
  step.rpy_converted = false;
  step.pose.position = data_.world_p_tcp;
  step.world_R_platform = data_.world_R_platform;
  if (angles_) step.pose.rpy = angles_->next(step);
  if (from_seed_) return;
  if (step.summary.ok()) {
    if (solved_) {
      // The step from the last solution: its translation, and the rotation vector of
      // M = R·R_lastᵀ = exp([ω]×) from M's antisymmetric part, (M − Mᵀ)/2 = sin|ω|/|ω|·[ω]×
      // (first order in |ω|: ample for a prediction; a long step is not repeated anyway).
      const Eigen::Matrix3d& R = data_.world_R_platform;
      const Eigen::Matrix3d& L = seed_.R;
      last_translation_ = data_.world_p_tcp - seed_.p;
      last_rotation_ = 0.5 * Eigen::Vector3d(R.row(2).dot(L.row(1)) - R.row(1).dot(L.row(2)),
                                             R.row(0).dot(L.row(2)) - R.row(2).dot(L.row(0)),
                                             R.row(1).dot(L.row(0)) - R.row(0).dot(L.row(1)));
    }
    has_previous_ = solved_;  // the seed was a solution too: the last step is known
    seed_ = {data_.world_p_tcp, data_.world_R_platform};
    solved_ = true;
  } else {
    solved_ = false;
    seed_ = {machine_.model.home.position, geometry::rotationFromRpy(machine_.model.home.rpy)};
    has_previous_ = false;  // home again after a failure
  }
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
