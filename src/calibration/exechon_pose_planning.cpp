#include "pkm/calibration/exechon_pose_planning.hpp"

#include <algorithm>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::calibration {

void ExechonPosePlanOptions::validate() const {
  PKM_CHECK(count >= 1, "pose planning: count must be >= 1, got {}", count);
  PKM_CHECK(exchange_passes >= 0, "pose planning: exchange_passes must be >= 0");
  PKM_CHECK(std::any_of(free.begin(), free.end(), [](bool f) { return f; }),
            "pose planning: no parameter is free");
  PKM_CHECK(target_offset.allFinite(), "pose planning: the target offset must be finite");
  std::string why;
  PKM_CHECK(fk.isValid(&why), "pose planning: invalid FK options: {}", why);
}

PosePlan planExechonPoses(const kinematics::ExechonModel& model,
                          const std::vector<kinematics::ExechonConfiguration>& candidates,
                          const ExechonPosePlanOptions& options) {
  options.validate();
  PKM_CHECK(candidates.size() >= static_cast<std::size_t>(options.count),
            "pose planning: {} candidates for {} poses",
            candidates.size(),
            options.count);
  std::vector<int> free;
  for (int k = 0; k < kExechonParameters; ++k)
    if (options.free[static_cast<std::size_t>(k)]) free.push_back(k);
  kinematics::ExechonData data(model);
  std::vector<Eigen::MatrixXd> blocks;
  blocks.reserve(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    kinematics::evaluateConfiguration(model, data, candidates[i]);
    const auto J = exechonTargetJacobian(
        model, kinematics::jointsOf(data), options.target_offset, candidates[i], options.fk);
    PKM_CHECK(J.has_value(), "pose planning: the forward kinematics fail at candidate {}", i);
    Eigen::MatrixXd b(3, static_cast<Eigen::Index>(free.size()));
    for (std::size_t c = 0; c < free.size(); ++c)
      b.col(static_cast<Eigen::Index>(c)) = J->col(free[c]);
    blocks.push_back(std::move(b));
  }
  return planFromJacobians(
      std::move(blocks), options.count, options.index, options.exchange_passes);
}

}  // namespace pkm::calibration
