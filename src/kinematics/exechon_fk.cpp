#include "pkm/kinematics/exechon_fk.hpp"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "kinematics/exechon_tripod_math.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_ik.hpp"

namespace pkm::kinematics {

namespace {

/// Below this fraction of the tolerance no polishing step is taken after convergence.
constexpr double kPolishFraction = 1e-3;

/// Residual r = lengths(e) − target; optionally the Jacobian. Returns |r|² (infinite if NaN).
double residual(const ExechonModel& model,
                const Eigen::Vector3d& e,
                const Eigen::Vector3d& target,
                Eigen::Vector3d& r,
                Eigen::Matrix3d* J) {
  r = detail::legLengths(
          model.tripod, detail::trigOf(e), model.tripod.deltaA, model.tripod.deltaC, J) -
      target;
  const double n2 = r.squaredNorm();
  return std::isfinite(n2) ? n2 : INFINITY;
}

/// Solves J·x = b by LU with partial pivoting; returns the smallest |pivot| / largest |pivot|.
double solve3(const Eigen::Matrix3d& J, Eigen::Vector3d& b) {
  const Eigen::PartialPivLU<Eigen::Matrix3d> lu(J);
  const Eigen::Vector3d pivots = lu.matrixLU().diagonal().cwiseAbs();
  const double ratio = pivots.maxCoeff() > 0.0 ? pivots.minCoeff() / pivots.maxCoeff() : 0.0;
  if (ratio > 0.0) b = lu.solve(b);
  return ratio;
}

}  // namespace

FkSummary tripodForwardKinematics(const ExechonModel& model,
                                  ExechonData& data,
                                  const ExechonLegVector& readings,
                                  const Eigen::Vector3d& seed_e,
                                  const FkOptions& options) {
  std::string why;
  PKM_CHECK(options.isValid(&why), "invalid FkOptions: {}", why);
  FkSummary summary;
  if (!readings.allFinite() || !seed_e.allFinite()) {
    summary.status = FkStatus::kInvalidInput;
    summary.max_residual = INFINITY;
    return summary;
  }
  Eigen::Vector3d target;
  for (int i = 0; i < kExechonLegs; ++i)
    target[i] = readings[i] + model.legs[static_cast<std::size_t>(i)].length_offset;
  const double length = model.characteristicLength();

  Eigen::Vector3d e = seed_e, r, e_try, r_try;
  Eigen::Matrix3d J, J_try;
  double norm2 = residual(model, e, target, r, &J);
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
      if (polishing || summary.max_residual <= kPolishFraction * options.tolerance ||
          iter == options.max_iterations)
        break;
      polishing = true;
    }
    if (iter == options.max_iterations) break;

    // Newton step with the angular columns in length units (× L) so that the pivot test is
    // unit-free.
    Eigen::Matrix3d Js = J;
    Js.leftCols<2>() *= 1.0 / length;
    Eigen::Vector3d delta = r;
    if (!(solve3(Js, delta) > options.singular_pivot_ratio) || !delta.allFinite()) {
      summary.status = FkStatus::kSingular;
      break;
    }
    delta.head<2>() *= 1.0 / length;

    double step = 1.0;
    bool accepted = false;
    for (int k = 0; k <= options.max_backtracks; ++k) {
      e_try = e - step * delta;
      const double n2 = residual(model, e_try, target, r_try, &J_try);
      if (n2 < norm2 || (!polishing && r_try.cwiseAbs().maxCoeff() <= options.tolerance)) {
        accepted = true;
        norm2 = n2;
        break;
      }
      step *= 0.5;
      ++summary.backtracks;
    }
    ++summary.iterations;
    if (!accepted) {
      if (!polishing) summary.status = FkStatus::kNoConvergence;
      break;
    }
    e = e_try;
    r = r_try;
    J = J_try;
    if (polishing) {
      summary.max_residual = r.cwiseAbs().maxCoeff();
      break;
    }
  }
  e[0] = std::remainder(e[0], 2.0 * std::numbers::pi);
  e[1] = std::remainder(e[1], 2.0 * std::numbers::pi);
  evaluateTripod(model, data, e, model.tripod.deltaA, model.tripod.deltaC);
  return summary;
}

}  // namespace pkm::kinematics
