#include "pkm/simulation/hexapod_virtual_machine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/simulation/compliance.hpp"
#include "pkm/simulation/noise.hpp"

namespace pkm::simulation {

namespace kin = pkm::kinematics;

namespace {

/// Fixed-point iterations of the U-joint shifts (each changes them by about offset/strut length
/// times the last change, so two or three suffice) and the change at which they stop, mm.
constexpr int kMaxShiftIterations = 8;
constexpr double kShiftTolerance = 1e-12;

}  // namespace

kin::HexapodModel HexapodAssemblyErrors::apply(const kin::HexapodModel& nominal) const {
  kin::HexapodModel m = nominal;
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    m.struts[i].world_p_base += base_joint[i];
    m.struts[i].platform_p_joint += platform_joint[i];
    m.struts[i].length_offset += length_offset[static_cast<Eigen::Index>(i)];
  }
  return m;
}

void StrutActuation::validate() const {
  PKM_CHECK(std::isfinite(encoder_resolution) && encoder_resolution >= 0.0,
            "encoder resolution {} must be finite and >= 0",
            encoder_resolution);
  PKM_CHECK(backlash.allFinite() && (backlash.array() >= 0.0).all(),
            "backlash must be finite and >= 0");
  PKM_CHECK(std::isfinite(repeatability_sigma) && repeatability_sigma >= 0.0,
            "repeatability sigma {} must be finite and >= 0",
            repeatability_sigma);
}

HexapodVirtualMachine::HexapodVirtualMachine(kin::HexapodModel nominal,
                                             const HexapodAssemblyErrors& errors,
                                             StrutActuation actuation)
    : nominal_(std::move(nominal)),
      true_(errors.apply(nominal_)),
      controller_(nominal_),
      actuation_(std::move(actuation)),
      controller_data_(controller_),
      true_data_(true_),
      shifted_(true_) {
  nominal_.validate();
  true_.validate();
  actuation_.validate();
  PKM_CHECK(nominal_.unit == LengthUnit::kMillimetre,
            "machine '{}': simulated measurements need a machine in mm",
            nominal_.name);
  reset(0);
}

void HexapodVirtualMachine::setControllerModel(kin::HexapodModel model) {
  model.validate();
  PKM_CHECK(model.unit == LengthUnit::kMillimetre,
            "controller model '{}': simulated measurements need a machine in mm",
            model.name);
  controller_ = std::move(model);
  controller_data_ = kin::HexapodData(controller_);
}

void HexapodVirtualMachine::setUnmodelledGeometry(const HexapodUnmodelledGeometry& geometry) {
  geometry.validate();
  geometry_ = geometry;
  shifted_ = true_;
}

kin::FkSummary HexapodVirtualMachine::trueForward(const kin::StrutVector& actual,
                                                  const kin::PoseRpy& seed) {
  kin::FkSummary fk = kin::forwardKinematics(true_, true_data_, actual, seed);
  if (!fk.ok() || !geometry_.hasJointOffsets()) return fk;
  double change = std::numeric_limits<double>::infinity();
  for (int k = 0; k < kMaxShiftIterations && change > kShiftTolerance; ++k) {
    change = 0.0;
    for (std::size_t i = 0; i < kin::kStruts; ++i) {
      const Eigen::Vector3d& u = true_data_.unit_leg[i];
      const Eigen::Vector3d b = true_.struts[i].world_p_base + geometry_.base_joint[i].shift(u);
      const Eigen::Vector3d p =
          true_.struts[i].platform_p_joint +
          geometry_.platform_joint[i].shift(true_data_.world_R_platform.transpose() * u);
      change = std::max({change,
                         (b - shifted_.struts[i].world_p_base).norm(),
                         (p - shifted_.struts[i].platform_p_joint).norm()});
      shifted_.struts[i].world_p_base = b;
      shifted_.struts[i].platform_p_joint = p;
    }
    const kin::PoseRpy last = true_data_.pose;  // a copy: FK writes data.pose
    fk = kin::forwardKinematics(shifted_, true_data_, actual, last);
    if (!fk.ok()) return fk;
  }
  return fk;
}

void HexapodVirtualMachine::setStrutGrowth(double relative) {
  PKM_CHECK(std::isfinite(relative) && relative > -1.0,
            "strut growth {} must be finite and > -1",
            relative);
  growth_ = relative;
}

void HexapodVirtualMachine::setCompliance(std::optional<HexapodCompliance> compliance) {
  std::string why;
  PKM_CHECK(!compliance || compliance->isValid(&why), "hexapod compliance: {}", why);
  compliance_ = std::move(compliance);
  loads_.setZero();
}

std::vector<std::string> HexapodVirtualMachine::axisNames() const {
  return {"x", "y", "z", "a", "b", "c"};
}

geometry::RigidTransform HexapodVirtualMachine::nominalPose(const Eigen::VectorXd& command) const {
  checkCommand(command, 6);
  return kin::toRigidTransform({command.head<3>(), command.tail<3>()});
}

void HexapodVirtualMachine::reset(std::uint64_t noise_seed) {
  rng_ = RandomStream(noise_seed);
  approach_.fill(1);
  load_side_.fill(0);
  moved_ = false;
}

geometry::RigidTransform HexapodVirtualMachine::moveTo(const Eigen::VectorXd& command) {
  checkCommand(command, 6);
  kin::PoseRpy pose;
  pose.position = command.head<3>();
  pose.rpy = command.tail<3>();
  commanded_ = kin::inverseKinematics(controller_, controller_data_, pose);
  if (actuation_.encoder_resolution > 0.0) {
    const NoiseModel counts{
        0.0, 0.0, actuation_.encoder_resolution};  // rounding only, draws nothing
    for (Eigen::Index i = 0; i < kin::kStruts; ++i)
      commanded_[i] = counts.apply(commanded_[i], 0.0, rng_);
  }
  kin::StrutVector actual = commanded_;
  for (Eigen::Index i = 0; i < kin::kStruts; ++i) {
    const auto iu = static_cast<std::size_t>(i);
    if (moved_ && commanded_[i] != last_[i]) approach_[iu] = commanded_[i] > last_[i] ? 1 : -1;
    actual[i] +=
        -0.5 * actuation_.backlash[i] * approach_[iu] + rng_.normal(actuation_.repeatability_sigma);
  }
  for (Eigen::Index i = 0; i < kin::kStruts; ++i)
    actual[i] += geometry_.lead[static_cast<std::size_t>(i)].at(actual[i]);
  if (growth_ != 0.0)
    for (Eigen::Index i = 0; i < kin::kStruts; ++i)
      actual[i] += growth_ * (actual[i] + true_.struts[static_cast<std::size_t>(i)].length_offset);
  if (compliance_) {  // the struts' load at the commanded pose (controller_data_ holds its IK)
    loads_ = hexapodStrutLoads(controller_, controller_data_, *compliance_);
    for (Eigen::Index i = 0; i < kin::kStruts; ++i)
      actual[i] += legDeflection(loads_[i],
                                 compliance_->strut_stiffness_n_per_um,
                                 compliance_->joint_clearance_mm,
                                 load_side_[static_cast<std::size_t>(i)]);
  }
  const kin::PoseRpy seed = moved_ ? last_pose_ : pose;
  last_ = commanded_;
  moved_ = true;
  const kin::FkSummary fk = trueForward(actual, seed);
  PKM_CHECK(fk.ok(),
            "the true hexapod cannot reach the command ({}): forward kinematics {}",
            fmt::join(command, ", "),
            kin::toString(fk.status));
  last_pose_ = true_data_.pose;
  return geometry::makeTransform(true_data_.world_R_platform, true_data_.world_p_tcp);
}

}  // namespace pkm::simulation
