#include "pkm/simulation/cartesian_machine.hpp"

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/compliance.hpp"

namespace pkm::simulation {

void CartesianErrors::validate() const {
  const char* names[] = {"X", "Y", "Z"};
  for (std::size_t k = 0; k < 3; ++k)
    PKM_CHECK(!axes[k] || axes[k]->components() == 6,
              "the {} error table has {} columns, expected 6",
              names[k],
              axes[k] ? axes[k]->components() : 0);
  PKM_CHECK(
      std::isfinite(squareness.xy) && std::isfinite(squareness.xz) && std::isfinite(squareness.yz),
      "a squareness error is not finite");
}

void CartesianLayout::validate() const {
  std::string sorted = order;
  std::sort(sorted.begin(), sorted.end());
  PKM_CHECK(sorted == "XYZ", "axis order '{}' is not a permutation of XYZ", order);
  PKM_CHECK(tool_offset.allFinite(), "tool offset is not finite");
}

void CartesianActuation::validate() const {
  PKM_CHECK(backlash.allFinite() && (backlash.array() >= 0.0).all(),
            "backlash must be finite and >= 0");
  PKM_CHECK(repeatability_sigma.allFinite() && (repeatability_sigma.array() >= 0.0).all(),
            "repeatability sigma must be finite and >= 0");
}

CartesianMachine::CartesianMachine(CartesianLayout layout,
                                   CartesianErrors errors,
                                   CartesianActuation actuation)
    : layout_(std::move(layout)), errors_(std::move(errors)), actuation_(std::move(actuation)) {
  layout_.validate();
  errors_.validate();
  actuation_.validate();
}

void CartesianMachine::reset(std::uint64_t noise_seed) {
  rng_ = RandomStream(noise_seed);
  approach_.setOnes();
  offset_.setZero();
  moved_ = false;
}

std::vector<std::string> CartesianMachine::axisNames() const { return {"x", "y", "z"}; }

geometry::RigidTransform CartesianMachine::nominalPose(const Eigen::VectorXd& command) const {
  checkCommand(command, 3);
  return geometry::translationTransform(command + layout_.tool_offset);
}

Eigen::Vector3d CartesianMachine::axisDirection(int k) const {
  PKM_CHECK(k >= 0 && k < 3, "axis index {} is not 0, 1 or 2", k);
  const CartesianSquareness& s = errors_.squareness;
  if (k == 0) return Eigen::Vector3d::UnitX();
  if (k == 1) return {-std::sin(s.xy), std::cos(s.xy), 0.0};
  // The unit vector with d_Z·x̂ = −sin(xz) and d_Z·d_Y = −sin(yz), on the +z side.
  const double a = -std::sin(s.xz);
  const double b = (a * std::sin(s.xy) - std::sin(s.yz)) / std::cos(s.xy);
  return {a, b, std::sqrt(1.0 - a * a - b * b)};
}

geometry::RigidTransform CartesianMachine::moveTo(const Eigen::VectorXd& command) {
  checkCommand(command, 3);
  // Reversal and repeatability: an axis that moves gets a new offset from its command.
  for (Eigen::Index k = 0; k < 3; ++k) {
    if (moved_ && command[k] == last_[k]) continue;
    if (moved_) approach_[k] = command[k] > last_[k] ? 1 : -1;
    offset_[k] = -0.5 * actuation_.backlash[k] * approach_[k] +
                 rng_.normal(actuation_.repeatability_sigma[k]);
  }
  last_ = command;
  moved_ = true;
  geometry::RigidTransform pose = geometry::RigidTransform::Identity();
  for (const char axis : layout_.order) {
    const int k = axis - 'X';
    const auto ku = static_cast<std::size_t>(k);
    const double q = command[k];
    pose = pose * geometry::translationTransform((q + offset_[k]) * axisDirection(k));
    if (errors_.axes[ku])
      pose = pose * geometry::errorMotionHtm(errors_.axes[ku]->evaluateMotion(q));
  }
  pose = pose * geometry::translationTransform(layout_.tool_offset);
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  // the nominal carriage position so far
  for (const char axis : layout_.order) {
    const int k = axis - 'X';
    const AxisSag& s = sag_[static_cast<std::size_t>(k)];
    pivot[k] = command[k];
    if (s.kind == AxisSag::Kind::kNone) continue;
    const Eigen::Vector3d e = s.sense * Eigen::Vector3d::Unit(k);
    pose = sagCarryingTool(pose, axisDeflection(s, command[k]), e, pivot);
  }
  return pose;
}

void CartesianMachine::setSag(const std::array<AxisSag, 3>& sag) {
  for (const AxisSag& s : sag) {
    std::string why;
    PKM_CHECK(s.isValid(&why), "Cartesian axis sag: {}", why);
  }
  sag_ = sag;
}

}  // namespace pkm::simulation
