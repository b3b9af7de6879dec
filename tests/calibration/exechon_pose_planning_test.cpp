// Exechon pose planning: the chosen tracker points identify all 26 parameters, beat random choice,
// respect the free mask and refuse bad input.
#include "pkm/calibration/exechon_pose_planning.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "pkm/calibration/exechon_calibration.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/tolerances.hpp"

namespace pkm::calibration {
namespace PKM_TEST_NS {

using kinematics::ExechonConfiguration;
using kinematics::ExechonModel;

constexpr int kCandidates = 150;
constexpr int kPoses = 30;

ExechonModel nominal() { return io::loadExechonMachine("mxt700s-like").model; }

/// Configurations about home: tripod angles ±10°, h ±100 mm, wrist ±25°.
std::vector<ExechonConfiguration> candidates(const ExechonModel& m) {
  std::mt19937 rng(test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double deg = M_PI / 180.0;
  std::vector<ExechonConfiguration> out;
  for (int i = 0; i < kCandidates; ++i) {
    ExechonConfiguration c = m.home;
    c.e += Eigen::Vector3d(10 * deg * u(rng), 10 * deg * u(rng), 100 * u(rng));
    c.c += 25 * deg * u(rng);
    c.a += 25 * deg * u(rng);
    out.push_back(c);
  }
  return out;
}

TEST(ExechonPosePlanning, ChosenPointsIdentifyEveryParameter) {
  const ExechonModel m = nominal();
  const auto pool = candidates(m);
  ExechonPosePlanOptions o;
  o.count = kPoses;
  o.target_offset = {40, 0, 0};
  const PosePlan plan = planExechonPoses(m, pool, o);
  ASSERT_EQ(plan.chosen.size(), static_cast<std::size_t>(kPoses));
  EXPECT_EQ(std::set<int>(plan.chosen.begin(), plan.chosen.end()).size(), plan.chosen.size());
  EXPECT_EQ(plan.rank, kExechonParameters);
  EXPECT_GT(plan.index_value, plan.random_baseline);
  // Independently: the stacked Jacobian of the chosen points has full rank.
  Eigen::MatrixXd J(3 * kPoses, kExechonParameters);
  kinematics::ExechonData data(m);
  std::vector<std::string> names;
  for (int k = 0; k < kExechonParameters; ++k) names.push_back(exechonParameterName(k));
  for (int i = 0; i < kPoses; ++i) {
    const ExechonConfiguration& c = pool[static_cast<std::size_t>(plan.chosen[i])];
    kinematics::evaluateConfiguration(m, data, c);
    const auto Ji = exechonTargetJacobian(m, kinematics::jointsOf(data), o.target_offset, c);
    ASSERT_TRUE(Ji.has_value());
    J.middleRows<3>(3 * i) = *Ji;
  }
  EXPECT_TRUE(analyseIdentifiability(J, names).fullRank());
}

TEST(ExechonPosePlanning, EveryIndexBeatsRandomChoice) {
  const ExechonModel m = nominal();
  const auto pool = candidates(m);
  for (const ObservabilityIndex index : {ObservabilityIndex::kO2,
                                         ObservabilityIndex::kO3,
                                         ObservabilityIndex::kO4,
                                         ObservabilityIndex::kO5}) {
    ExechonPosePlanOptions o;
    o.count = kPoses;
    o.index = index;
    o.exchange_passes = 1;
    const PosePlan plan = planExechonPoses(m, pool, o);
    EXPECT_GT(plan.index_value, plan.random_baseline) << toString(index);
  }
}

TEST(ExechonPosePlanning, FixedParametersAreLeftOut) {
  const ExechonModel m = nominal();
  ExechonPosePlanOptions o;
  o.count = 12;
  o.free.fill(false);
  for (const char* name : {"offsetA", "offsetB", "offsetC", "wrist.tool_length"})
    o.free[static_cast<std::size_t>(exechonParameterIndex(name))] = true;
  const PosePlan plan = planExechonPoses(m, candidates(m), o);
  EXPECT_EQ(plan.rank, 4);
}

TEST(ExechonPosePlanning, RejectsBadInput) {
  const ExechonModel m = nominal();
  const auto pool = candidates(m);
  ExechonPosePlanOptions o;
  o.count = kCandidates + 1;
  EXPECT_THROW((void)planExechonPoses(m, pool, o), InvalidArgument);
  o.count = 5;
  o.free.fill(false);
  EXPECT_THROW((void)planExechonPoses(m, pool, o), InvalidArgument);
  o.free = allExechonParametersFree();
  o.target_offset.x() = NAN;
  EXPECT_THROW((void)planExechonPoses(m, pool, o), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration
