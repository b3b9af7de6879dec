#include "pkm/simulation/hybrid_tracker.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "support/tolerances.hpp"

namespace pkm::simulation {
namespace PKM_TEST_NS {

HybridTrackerSetup setup() {
  HybridTrackerSetup s;
  s.name = "h";
  s.count = 30;
  s.x2 = Eigen::Vector2d(0, 3000);
  s.y2 = Eigen::Vector2d(0, 450);
  s.pkm_min = Eigen::Vector3d(-300, -300, -100);
  s.pkm_max = Eigen::Vector3d(300, 300, 300);
  s.smr_offset = Eigen::Vector3d(0, 0, 40);
  s.work_T_tracker.translation() = Eigen::Vector3d(1000, 2000, 0);
  return s;
}

TEST(HybridTracker, ReadsTheChainExactlyWithoutNoise) {
  const io::ExechonMachine m = io::loadExechonMachine("mxt700s-like");
  const kinematics::GeometricErrors errors = io::loadGeometricErrors("mxt700s-seed000");
  HybridVirtualMachine vm(*m.hybrid, errors);
  RandomStream rng(test::kSeed);
  const HybridTrackerSetup s = setup();
  const auto readings = simulateHybridTracker(vm, s, rng);
  ASSERT_EQ(readings.size(), 30u);
  for (const HybridTrackerReading& r : readings) {
    EXPECT_TRUE(kinematics::hybridWithinLimits(*m.hybrid, r.command));
    EXPECT_EQ(r.measured, r.truth);
    const Eigen::Vector3d work =
        kinematics::hybridActualPose(*m.hybrid, errors, r.command) * s.smr_offset;
    EXPECT_LT((s.work_T_tracker * r.truth - work).norm(), test::kTolRoundTrip);
  }
}

TEST(HybridTracker, NoiseIsDrawnAndSetupsAreChecked) {
  const io::ExechonMachine m = io::loadExechonMachine("mxt700s-like");
  HybridVirtualMachine vm(*m.hybrid, {});
  HybridTrackerSetup s = setup();
  s.noise.range_sigma = 0.01;
  RandomStream a(test::kSeed), b(test::kSeed);
  const auto first = simulateHybridTracker(vm, s, a);
  const auto second = simulateHybridTracker(vm, s, b);
  for (std::size_t k = 0; k < first.size(); ++k) {
    EXPECT_EQ(first[k].measured, second[k].measured);
    EXPECT_NE(first[k].measured, first[k].truth);
  }
  s.x2 = Eigen::Vector2d(10, 0);
  EXPECT_THROW((void)simulateHybridTracker(vm, s, a), InvalidArgument);
  s = setup();
  s.x2 = Eigen::Vector2d(9000, 9500);  // outside X2's stroke: gives up after the draw budget
  EXPECT_THROW((void)simulateHybridTracker(vm, s, a), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::simulation
