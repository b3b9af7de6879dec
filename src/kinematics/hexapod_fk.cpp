#include "pkm/kinematics/hexapod_fk.hpp"

#include <fmt/format.h>

#include <cmath>

#include "kinematics/detail/hexapod_legs.hpp"
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

namespace {

/// Below this fraction of the tolerance no polishing step is taken after convergence.
constexpr double kPolishFraction = 1e-3;

/// Residual r = readings(p, R) − target; fills data's leg quantities. Returns |r|² (infinite if
/// NaN).
double evaluate(const HexapodModel& model,
                HexapodData& data,
                const Eigen::Vector3d& p,
                const Eigen::Matrix3d& R,
                const StrutVector& target,
                StrutVector& r) {
  detail::computeLegs(model, data, p, R);
  r = data.readings - target;
  const double n2 = r.squaredNorm();
  return std::isfinite(n2) ? n2 : INFINITY;
}

}  // namespace

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

  Eigen::Vector3d p = seed.position;
  Eigen::Matrix3d R = geometry::rotationFromRpy(seed.rpy);
  StrutVector r;
  double norm2 = evaluate(model, data, p, R, readings, r);
  const double inv_length = 1.0 / model.characteristicLength();

  summary.status = FkStatus::kNoConvergence;
  bool polishing = false;
  for (int iter = 0;; ++iter) {
    summary.max_residual = r.cwiseAbs().maxCoeff();
    if (!std::isfinite(norm2)) {
      summary.status = FkStatus::kNoConvergence;
      break;
    }
    if (summary.max_residual <= options.tolerance) {
      summary.status = FkStatus::kOk;
      // Strut residuals at the tolerance can still mean a pose error of a few tolerances (the
      // Jacobian's inverse amplifies them). One more Newton step, quadratically convergent, makes
      // the pose accurate to far below the tolerance; it is skipped once the residual is already
      // tiny.
      if (polishing || summary.max_residual <= kPolishFraction * options.tolerance ||
          iter == options.max_iterations)
        break;
      polishing = true;
    }
    if (iter == options.max_iterations) break;

    // Newton step on the scaled Jacobian (angular columns × 1/L) so the pivot test is unit-free.
    computeStrutJacobian(model, data);
    Matrix6d J = data.J_q_x;
    J.rightCols<3>() *= inv_length;
    StrutVector delta = r;
    if (!(detail::solve6(J, delta) > options.singular_pivot_ratio)) {
      summary.status = FkStatus::kSingular;
      break;
    }
    delta.tail<3>() *= inv_length;
    if (!delta.allFinite()) {
      summary.status = FkStatus::kSingular;
      break;
    }

    // Backtracking: accept the first step length that reduces |r|.
    double alpha = 1.0;
    bool accepted = false;
    Eigen::Vector3d p_try;
    Eigen::Matrix3d R_try;
    StrutVector r_try;
    for (int k = 0; k <= options.max_backtracks; ++k) {
      p_try = p - alpha * delta.head<3>();
      R_try = geometry::so3Exp(-alpha * delta.tail<3>()) * R;
      const double n2 = evaluate(model, data, p_try, R_try, readings, r_try);
      if (n2 < norm2 || (!polishing && r_try.cwiseAbs().maxCoeff() <= options.tolerance)) {
        accepted = true;
        norm2 = n2;
        break;
      }
      alpha *= 0.5;
      ++summary.backtracks;
    }
    ++summary.iterations;
    if (!accepted) {
      evaluate(model, data, p, R, readings, r);  // restore data to the best iterate
      summary.max_residual = r.cwiseAbs().maxCoeff();
      if (!polishing) summary.status = FkStatus::kNoConvergence;
      break;
    }
    p = p_try;
    R = R_try;
    r = r_try;
    if (polishing) {
      summary.max_residual = r.cwiseAbs().maxCoeff();
      break;
    }
  }
  data.pose.position = p;
  data.pose.rpy = geometry::rpyFromRotation(R, seed.rpy);
  return summary;
}

}  // namespace pkm::kinematics
