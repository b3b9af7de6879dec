#include "pkm/calibration/pose_planning.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

constexpr double kReach = 150.0;  ///< mm
constexpr double kTilt = 0.15;    ///< rad

std::vector<kinematics::PoseRpy> candidates(const kinematics::HexapodModel& model, int count) {
  std::mt19937 rng(test::kSeed);
  kinematics::HexapodData data(model);
  std::vector<kinematics::PoseRpy> out;
  while (static_cast<int>(out.size()) < count) {
    const auto pose = test::randomPose(rng, model.home, kReach, kTilt);
    if (kinematics::checkPose(model, data, pose).ok()) out.push_back(pose);
  }
  return out;
}

TEST(PosePlanning, BeatsRandomSelectionOnEveryIndex) {
  const kinematics::HexapodModel model = test::millingModel();
  const auto pool = candidates(model, 300);
  for (const ObservabilityIndex index : {ObservabilityIndex::kO1,
                                         ObservabilityIndex::kO2,
                                         ObservabilityIndex::kO3,
                                         ObservabilityIndex::kO4,
                                         ObservabilityIndex::kO5}) {
    PosePlanOptions options;
    options.count = 12;
    options.index = index;
    const PosePlan plan = planHexapodPoses(model, pool, options);
    ASSERT_EQ(plan.chosen.size(), 12u);
    EXPECT_EQ(std::set<int>(plan.chosen.begin(), plan.chosen.end()).size(), 12u);
    EXPECT_EQ(plan.rank, kHexapodParameters) << toString(index);
    EXPECT_GT(plan.index_value, plan.random_baseline) << toString(index);
    EXPECT_DOUBLE_EQ(plan.indices[static_cast<std::size_t>(index)], plan.index_value);
  }
}

TEST(PosePlanning, PlannedPosesAreWellConditionedForIdentification) {
  // The identifiability analysis of the planned set agrees with the planner's condition number.
  const kinematics::HexapodModel model = test::millingModel();
  const auto pool = candidates(model, 200);
  PosePlanOptions options;
  options.count = 10;
  options.index = ObservabilityIndex::kO2;
  const PosePlan plan = planHexapodPoses(model, pool, options);
  HexapodCalibrationData data;
  kinematics::HexapodData work(model);
  for (const int c : plan.chosen) {
    PoseObservation o;
    o.pose = pool[static_cast<std::size_t>(c)];
    data.poses.push_back(o);
  }
  std::vector<std::string> names;
  for (int k = 0; k < kHexapodParameters; ++k) names.push_back(hexapodParameterName(k));
  const Identifiability id = analyseIdentifiability(identificationJacobian(model, data), names);
  EXPECT_EQ(id.rank, kHexapodParameters);
  EXPECT_LT(id.condition_number, 1e3);
}

TEST(PosePlanning, RejectsBadOptions) {
  const kinematics::HexapodModel model = test::millingModel();
  const auto pool = candidates(model, 5);
  PosePlanOptions options;
  options.count = 6;
  EXPECT_THROW((void)planHexapodPoses(model, pool, options), InvalidArgument);
  options.count = 0;
  EXPECT_THROW((void)planHexapodPoses(model, pool, options), InvalidArgument);
  options.count = 3;
  options.free.fill(false);
  EXPECT_THROW((void)planHexapodPoses(model, pool, options), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration

namespace pkm::calibration {
namespace PKM_TEST_NS {

/// The generic planner on a hand-made problem: 40 candidates see only the first unknown, one
/// sees only the second; two poses must include that one (else the information is singular).
TEST(PlanFromJacobians, FindsTheOnlyCandidateThatSeesAParameter) {
  std::vector<Eigen::MatrixXd> blocks;
  for (int i = 0; i < 40; ++i)
    blocks.push_back((Eigen::MatrixXd(1, 2) << 1.0 + 0.01 * i, 0.0).finished());
  blocks.push_back((Eigen::MatrixXd(1, 2) << 0.0, 0.5).finished());
  for (const ObservabilityIndex index : {ObservabilityIndex::kO1, ObservabilityIndex::kO3}) {
    const PosePlan plan = planFromJacobians(blocks, 2, index, 1);
    EXPECT_NE(std::find(plan.chosen.begin(), plan.chosen.end(), 40), plan.chosen.end());
    EXPECT_EQ(plan.rank, 2);
  }
  EXPECT_THROW((void)planFromJacobians(blocks, 42, ObservabilityIndex::kO1, 0), InvalidArgument);
  blocks.push_back(Eigen::MatrixXd::Ones(2, 2));  // another shape
  EXPECT_THROW((void)planFromJacobians(blocks, 2, ObservabilityIndex::kO1, 0), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
