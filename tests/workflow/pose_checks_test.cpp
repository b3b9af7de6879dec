// workflow::checkPoses: hexapod and Exechon poses with readings, margins and the joint centres to
// draw; a violation's status; bad requests refused.
#include "pkm/workflow/pose_checks.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

constexpr double kTol = 1e-9;

double distance(const WorldPoint& a, const WorldPoint& b) {
  return std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
}

TEST(PoseChecks, HexapodStrutsJoinTheirJointCentres) {
  PoseCheckRequest q;
  q.machine = "hexapod-default";
  q.poses = {{0, 0, 200, 0, 0, 0}, {20, -10, 190, 3, -2, 10}, {0, 0, -300, 0, 0, 0}};
  const PoseCheckResult r = checkPoses(q);
  EXPECT_EQ(r.machine_type, "hexapod");
  EXPECT_EQ(r.units, "mm");
  ASSERT_EQ(r.rows.size(), 3u);
  const kinematics::HexapodModel m = io::loadHexapodMachine("hexapod-default").model;
  for (std::size_t k = 0; k < 2; ++k) {
    const PoseCheckRow& row = r.rows[k];
    EXPECT_EQ(row.status, "ok");
    ASSERT_EQ(row.joints.size(), 6u);
    for (std::size_t i = 0; i < 6; ++i)
      EXPECT_NEAR(distance(row.base_points[i], row.moving_points[i]),
                  row.joints[i] + m.struts[i].length_offset,
                  kTol);
    EXPECT_GT(row.stroke_margin[0], 0.0);
    EXPECT_GT(row.clearance, 0.0);
    EXPECT_GT(row.condition_number, 1.0);
  }
  EXPECT_EQ(r.rows[0].tool_direction, (WorldPoint{0, 0, 1}));
  EXPECT_EQ(r.rows[2].status, "stroke");
  EXPECT_THAT(r.rows[2].violations[0], HasSubstr("stroke strut"));
}

TEST(PoseChecks, ExechonLegsAndWristAtHome) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  kinematics::ExechonData data(machine.model);
  kinematics::evaluateConfiguration(machine.model, data, machine.model.home);
  const Eigen::Vector3d p = data.world_p_tool, u = data.world_u_tool;
  PoseCheckRequest q;
  q.machine = "mxt700s-like";
  q.poses = {{p.x(), p.y(), p.z(), u.x(), u.y(), u.z()}};
  const PoseCheckResult r = checkPoses(q);
  EXPECT_EQ(r.machine_type, "exechon");
  ASSERT_EQ(r.joint_names.size(), 5u);
  const PoseCheckRow& row = r.rows[0];
  EXPECT_EQ(row.status, "ok");
  ASSERT_EQ(row.joints.size(), 5u);
  EXPECT_EQ(row.base_points.size(), 3u);
  EXPECT_EQ(row.angle_margin.size(), 4u);
  ASSERT_EQ(row.wrist_points.size(), 1u);
  EXPECT_NEAR(
      distance(row.wrist_points[0], {data.world_p_S.x(), data.world_p_S.y(), data.world_p_S.z()}),
      0.0,
      1e-6);
}

TEST(PoseChecks, BadRequestsAreRefused) {
  PoseCheckRequest q;
  EXPECT_THROW((void)checkPoses(q), InvalidArgument);  // no poses
  q.poses = {{0, 0, NAN, 0, 0, 0}};
  EXPECT_THROW((void)checkPoses(q), InvalidArgument);
  q.poses = {{0, 0, 200, 0, 0, 0}};
  q.machine = "no-such-machine";
  EXPECT_THROW((void)checkPoses(q), IoError);
  q.machine = "mxt700s-like";
  q.poses = {{0, 0, 200, 0, 0, 0}};  // a zero tool direction
  EXPECT_THROW((void)checkPoses(q), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
