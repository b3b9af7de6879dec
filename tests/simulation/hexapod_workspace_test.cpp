// sampleHexapodWorkspace: poses inside the box and inside every limit, the same poses for the same
// seed, and an error for a box outside the workspace.
#include "pkm/simulation/hexapod_workspace.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
namespace sim = pkm::simulation;

constexpr int kCount = 100;

sim::PoseBox wideBox() {
  sim::PoseBox box;  // wider than the workspace, so that some draws are rejected
  box.lo << -400, -400, 0, -0.4, -0.4, -0.6;
  box.hi << 400, 400, 450, 0.4, 0.4, 0.6;
  return box;
}

TEST(HexapodWorkspace, PosesAreInTheBoxAndWithinEveryLimit) {
  const kin::HexapodModel model = pkm::test::millingModel();
  sim::RandomStream rng(pkm::test::kSeed);
  const sim::PoseBox box = wideBox();
  const auto poses = sim::sampleHexapodWorkspace(model, box, kCount, rng);
  ASSERT_EQ(poses.size(), static_cast<std::size_t>(kCount));
  kin::HexapodData data(model);
  for (const Eigen::VectorXd& c : poses) {
    ASSERT_EQ(c.size(), 6);
    EXPECT_TRUE((c.array() >= box.lo.array()).all() && (c.array() <= box.hi.array()).all());
    kin::PoseRpy pose;
    pose.position = c.head<3>();
    pose.rpy = c.tail<3>();
    EXPECT_TRUE(kin::checkPose(model, data, pose).ok());
  }
  // The box is wider than the workspace (its corner violates limits), so the checks above select.
  kin::PoseRpy corner;
  corner.position = box.lo.head<3>();
  corner.rpy = box.lo.tail<3>();
  EXPECT_FALSE(kin::checkPose(model, data, corner).ok());
}

TEST(HexapodWorkspace, SameSeedSamePoses) {
  const kin::HexapodModel model = pkm::test::millingModel();
  sim::RandomStream a(pkm::test::kSeed), b(pkm::test::kSeed);
  const auto pa = sim::sampleHexapodWorkspace(model, wideBox(), kCount, a);
  const auto pb = sim::sampleHexapodWorkspace(model, wideBox(), kCount, b);
  for (std::size_t i = 0; i < pa.size(); ++i) EXPECT_TRUE(pa[i] == pb[i]);
}

TEST(HexapodWorkspace, BadInputThrows) {
  const kin::HexapodModel model = pkm::test::millingModel();
  sim::RandomStream rng(pkm::test::kSeed);
  sim::PoseBox outside;  // every pose 3 m below the base: every strut out of its stroke
  outside.lo << 0, 0, -3000, 0, 0, 0;
  outside.hi << 10, 10, -2990, 0, 0, 0;
  EXPECT_THROW((void)sim::sampleHexapodWorkspace(model, outside, kCount, rng),
               pkm::InvalidArgument);
  sim::PoseBox inverted = wideBox();
  std::swap(inverted.lo[0], inverted.hi[0]);
  EXPECT_THROW((void)sim::sampleHexapodWorkspace(model, inverted, kCount, rng),
               pkm::InvalidArgument);
  EXPECT_THROW((void)sim::sampleHexapodWorkspace(model, wideBox(), -1, rng), pkm::InvalidArgument);
  EXPECT_TRUE(sim::sampleHexapodWorkspace(model, wideBox(), 0, rng).empty());
}

}  // namespace PKM_TEST_NS
