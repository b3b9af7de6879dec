#include "pkm/kinematics/exechon_model.hpp"

#include <algorithm>
#include <cmath>

#include "kinematics/exechon_tripod_math.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_ik.hpp"

namespace pkm::kinematics {

double AngleRange::margin(double value) const { return std::min(value - min, max - value); }

double ExechonModel::characteristicLength() const {
  const double l = std::max({std::abs(tripod.dA), std::abs(tripod.dB), std::abs(tripod.dC)});
  return l > 0.0 ? l : 1.0;
}

namespace {

void validateRange(const AngleRange& r, const char* name) {
  PKM_CHECK(!std::isnan(r.min) && !std::isnan(r.max) && r.min <= r.max,
            "limits.{}: range [{}, {}] is empty",
            name,
            r.min,
            r.max);
}

}  // namespace

void ExechonModel::validate() const {
  const ExechonTripodGeometry& g = tripod;
  const double values[] = {
      g.dA, g.dB, g.dC, g.l12A, g.l12C, g.l12B, g.l23B, g.pA, g.pB, g.pC, g.hA, g.hC, g.hx, g.hz};
  PKM_CHECK(
      std::all_of(std::begin(values), std::end(values), [](double v) { return std::isfinite(v); }),
      "tripod geometry is not finite");
  const double scale = characteristicLength();
  PKM_CHECK(std::abs(g.dB) > 1e-9 * scale,
            "tripod: dB must be != 0 (leg B's base joint is on the base axis)");
  PKM_CHECK(std::abs(g.dA - g.dC) > 1e-9 * scale,
            "tripod: dA and dC must differ (legs A and C share a base joint)");
  PKM_CHECK(detail::isUnitSign(g.delta1B) && detail::isUnitSign(g.delta2B) &&
                detail::isUnitSign(g.deltaA) && detail::isUnitSign(g.deltaC),
            "tripod: branch signs delta1B, delta2B, deltaA, deltaC must be +1 or -1");
  const char* leg_names[] = {"A", "B", "C"};
  for (int i = 0; i < kExechonLegs; ++i) {
    const ExechonLeg& leg = legs[static_cast<std::size_t>(i)];
    PKM_CHECK(
        std::isfinite(leg.length_offset), "leg {}: length offset is not finite", leg_names[i]);
    PKM_CHECK(!std::isnan(leg.min_reading) && !std::isnan(leg.max_reading) &&
                  leg.min_reading <= leg.max_reading,
              "leg {}: stroke [{}, {}] is empty",
              leg_names[i],
              leg.min_reading,
              leg.max_reading);
  }
  validateRange(limits.alpha, "alpha");
  validateRange(limits.beta, "beta");
  validateRange(limits.c, "c");
  validateRange(limits.a, "a");

  const ExechonWrist& w = wrist;
  PKM_CHECK(w.c_axis.allFinite() && w.a_axis.allFinite() && std::isfinite(w.c0) &&
                std::isfinite(w.a0) && std::isfinite(w.tool_length),
            "wrist is not finite");
  PKM_CHECK(w.c_axis.norm() > 1e-12 && w.a_axis.norm() > 1e-12,
            "wrist: c_axis and a_axis must be non-zero");
  PKM_CHECK(std::abs(w.c_axis.normalized().dot(w.a_axis.normalized())) < 1e-9,
            "wrist: a_axis must be perpendicular to c_axis");
  PKM_CHECK(detail::isUnitSign(w.c_sign) && detail::isUnitSign(w.a_sign),
            "wrist: c_sign and a_sign must be +1 or -1");
  PKM_CHECK(max_condition > 1.0, "max_condition must be > 1 (got {})", max_condition);
  PKM_CHECK(world_T_zoppi.matrix().allFinite(), "world_T_zoppi is not finite");
  const Eigen::Matrix3d R = world_T_zoppi.linear();
  PKM_CHECK(
      (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < 1e-9 && R.determinant() > 0.0,
      "world_T_zoppi must be a rigid transform (orthonormal rotation, det +1)");

  PKM_CHECK(home.e.allFinite() && std::isfinite(home.c) && std::isfinite(home.a),
            "home is not finite");
  ExechonData data(*this);
  evaluateTripod(*this, data, home.e, g.deltaA, g.deltaC);
  for (int i = 0; i < kExechonLegs; ++i)
    PKM_CHECK(data.lengths[i] > 1e-9 * scale,
              "leg {} has zero length at the home configuration",
              leg_names[i]);
  computeTripodJacobian(*this, data);
  const double cond = tripodConditionNumber(data);
  PKM_CHECK(std::isfinite(cond) && cond < 1e12,
            "the tripod is singular at the home configuration (condition number of dq/dS {:.3g})",
            cond);
}

}  // namespace pkm::kinematics
