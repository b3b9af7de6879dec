#include "pkm/kinematics/exechon_fk.hpp"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "kinematics/detail/newton.hpp"
#include "kinematics/exechon_tripod_math.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_ik.hpp"

namespace pkm::kinematics {

namespace {

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

  Eigen::Vector3d e = seed_e;
  Eigen::Matrix3d J;  // dq/de at the last evaluated e
  auto evaluate = [&](const Eigen::Vector3d& at, Eigen::Vector3d& r) {
    r = detail::legLengths(
            model.tripod, detail::trigOf(at), model.tripod.deltaA, model.tripod.deltaC, &J) -
        target;
    const double n2 = r.squaredNorm();
    return std::isfinite(n2) ? n2 : INFINITY;
  };
  auto solve = [&](Eigen::Vector3d& delta) {
    // The angular columns × 1/L (lengths per unit length) make the pivot test unit-free.
    Eigen::Matrix3d Js = J;
    Js.leftCols<2>() *= 1.0 / length;
    const double ratio = solve3(Js, delta);
    delta.head<2>() *= 1.0 / length;
    return ratio;
  };
  auto retract = [](const Eigen::Vector3d& at, const Eigen::Vector3d& delta, double step) {
    return Eigen::Vector3d(at - step * delta);
  };
  summary = detail::dampedNewton<kExechonLegs>(options, e, evaluate, solve, retract);
  e[0] = std::remainder(e[0], 2.0 * std::numbers::pi);
  e[1] = std::remainder(e[1], 2.0 * std::numbers::pi);
  evaluateTripod(model, data, e, model.tripod.deltaA, model.tripod.deltaC);
  return summary;
}

}  // namespace pkm::kinematics
