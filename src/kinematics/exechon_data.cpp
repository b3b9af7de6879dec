#include "pkm/kinematics/exechon_data.hpp"

#include "kinematics/exechon_tripod_math.hpp"
#include "pkm/core/error.hpp"

namespace pkm::kinematics {

bool ExechonBranch::isValid() const {
  return detail::isUnitSign(delta1B) && detail::isUnitSign(delta2B) && detail::isUnitSign(deltaA) &&
         detail::isUnitSign(deltaC);
}

int ExechonBranch::index() const {
  return (delta1B < 0 ? 1 : 0) | (delta2B < 0 ? 2 : 0) | (deltaA < 0 ? 4 : 0) |
         (deltaC < 0 ? 8 : 0);
}

ExechonBranch ExechonBranch::fromIndex(int index) {
  PKM_CHECK(index >= 0 && index < 16, "Exechon branch index must be in [0, 16) (got {})", index);
  const auto sign = [index](int bit) { return (index & bit) != 0 ? -1 : 1; };
  return {sign(1), sign(2), sign(4), sign(8)};
}

ExechonBranch branchOf(const ExechonTripodGeometry& tripod) {
  return {tripod.delta1B, tripod.delta2B, tripod.deltaA, tripod.deltaC};
}

ExechonData::ExechonData(const ExechonModel& model) : branch(branchOf(model.tripod)) {
  const ExechonTripodGeometry& g = model.tripod;
  zoppi_p_base = {Eigen::Vector3d(0.0, g.dA, 0.0),
                  Eigen::Vector3d(g.dB, 0.0, 0.0),
                  Eigen::Vector3d(0.0, g.dC, 0.0)};
  zoppi_p_leg_start = zoppi_p_base;
  zoppi_p_platform_joint = zoppi_p_base;
}

ExechonConfiguration configurationOf(const ExechonData& data) { return {data.e, data.c, data.a}; }

}  // namespace pkm::kinematics
