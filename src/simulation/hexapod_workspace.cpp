#include "pkm/simulation/hexapod_workspace.hpp"

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_data.hpp"

namespace pkm::simulation {

void PoseBox::validate() const {
  PKM_CHECK(lo.allFinite() && hi.allFinite(), "pose box: bounds must be finite");
  PKM_CHECK((lo.array() <= hi.array()).all(), "pose box: a lower bound is above its upper bound");
}

std::vector<Eigen::VectorXd> sampleHexapodWorkspace(const kinematics::HexapodModel& model,
                                                    const PoseBox& box,
                                                    int count,
                                                    RandomStream& rng,
                                                    int max_draws_per_pose) {
  box.validate();
  PKM_CHECK(count >= 0, "pose count {} must be >= 0", count);
  PKM_CHECK(max_draws_per_pose >= 1, "max draws per pose {} must be >= 1", max_draws_per_pose);
  kinematics::HexapodData data(model);
  std::vector<Eigen::VectorXd> poses;
  poses.reserve(static_cast<std::size_t>(count));
  const long long max_draws = static_cast<long long>(max_draws_per_pose) * count;
  long long draws = 0;
  while (static_cast<int>(poses.size()) < count) {
    PKM_CHECK(draws < max_draws,
              "only {} of {} random poses satisfy the machine's limits after {} draws: the box is "
              "mostly outside the workspace",
              poses.size(),
              count,
              draws);
    ++draws;
    Eigen::VectorXd c(6);
    for (Eigen::Index k = 0; k < 6; ++k) c[k] = rng.uniform(box.lo[k], box.hi[k]);
    kinematics::PoseRpy pose;
    pose.position = c.head<3>();
    pose.rpy = c.tail<3>();
    if (kinematics::checkPose(model, data, pose).ok()) poses.push_back(c);
  }
  return poses;
}

}  // namespace pkm::simulation
