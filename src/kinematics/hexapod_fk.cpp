#include "pkm/kinematics/hexapod_fk.hpp"

#include <fmt/format.h>

#include <cmath>

#include "kinematics/detail/hexapod_legs.hpp"
#include "kinematics/detail/newton.hpp"
#include "kinematics/detail/solve6.hpp"
#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::kinematics {

std::string_view toString(FkStatus status) {
  switch (status) {
    case FkStatus::kOk:
      return "ok";
    case FkStatus::kNoConvergence:
      return "no_convergence";
    case FkStatus::kSingular:
      return "singular";
    case FkStatus::kInvalidInput:
      return "invalid_input";
  }
  return "unknown";
}

bool FkOptions::isValid(std::string* why) const {
  auto fail = [why](const std::string& msg) {
    if (why != nullptr) *why = msg;
    return false;
  };
  if (!(tolerance > 0.0) || !std::isfinite(tolerance))
    return fail(fmt::format("tolerance must be finite and > 0 (got {})", tolerance));
  if (max_iterations < 1)
    return fail(fmt::format("max_iterations must be >= 1 (got {})", max_iterations));
  if (max_backtracks < 0)
    return fail(fmt::format("max_backtracks must be >= 0 (got {})", max_backtracks));
  if (!(singular_pivot_ratio > 0.0 && singular_pivot_ratio < 1.0))
    return fail(
        fmt::format("singular_pivot_ratio must be in (0, 1) (got {})", singular_pivot_ratio));
  return true;
}

FkSummary forwardKinematics(const HexapodModel& model,
                            HexapodData& data,
                            const StrutVector& readings,
                            const PoseRpy& seed,
                            const FkOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "invalid FkOptions: {}", why);
  FkSummary summary;
  if (!readings.allFinite() || !seed.position.allFinite() || !seed.rpy.allFinite()) {
    summary.status = FkStatus::kInvalidInput;
    summary.max_residual = INFINITY;
    return summary;
  }

  struct Pose {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
  };
  Pose x{seed.position, geometry::rotationFromRpy(seed.rpy)};
  const double inv_length = 1.0 / model.characteristicLength();
  auto evaluate = [&](const Pose& at, StrutVector& r) {
    detail::computeLegs(model, data, at.p, at.R);
    r = data.readings - readings;
    const double n2 = r.squaredNorm();
    return std::isfinite(n2) ? n2 : INFINITY;
  };
  auto solve = [&](StrutVector& delta) {
    // The angular columns × 1/L make the pivot test unit-free; δθ is scaled back after.
    Matrix6d J = computeStrutJacobian(model, data);
    J.rightCols<3>() *= inv_length;
    const double ratio = detail::solve6(J, delta);
    delta.tail<3>() *= inv_length;
    return ratio;
  };
  auto retract = [](const Pose& at, const StrutVector& delta, double step) {
    return Pose{at.p - step * delta.head<3>(), geometry::so3Exp(-step * delta.tail<3>()) * at.R};
  };
  summary = detail::dampedNewton<kStruts>(options, x, evaluate, solve, retract);
  data.pose.position = x.p;
  data.pose.rpy = geometry::rpyFromRotation(x.R, seed.rpy);
  return summary;
}

}  // namespace pkm::kinematics
