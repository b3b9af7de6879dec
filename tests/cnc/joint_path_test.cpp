// Joint-space conversion: readings equal the hexapod IK called directly (degrees converted, inch
// machines scaled), the joint-space step rule holds against FK of a dense reference, CSV rows.
#include "pkm/cnc/joint_path.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::test::kSeed;
using pkm::test::kTolExact;
using pkm::test::kTolRoundTrip;

constexpr double kTol = 0.01;     // mm, chordal tolerance
constexpr int kDenseSamples = 8;  // reference points per sample interval
constexpr int kRandomLines = 40;  // random straight lines of the dense-reference test
constexpr double kReach = 150.0;  // mm, random end points about home
constexpr double kTiltDeg = 8.0;  // degrees, random orientations

TEST(HexapodJointConverter, MatchesInverseKinematics) {
  const kin::HexapodModel model = pkm::test::millingModel();
  HexapodJointConverter conv(model);
  const Axes pos{12.5, -30.0, 180.0, 3.0, -4.0, 25.0};
  kin::HexapodData data(model);
  kin::PoseRpy pose;
  pose.position = {12.5, -30.0, 180.0};
  pose.rpy = {pkm::degToRad(3.0), pkm::degToRad(-4.0), pkm::degToRad(25.0)};
  const kin::StrutVector direct = kin::inverseKinematics(model, data, pose);
  const kin::StrutVector q = conv.solve(pos);
  for (int i = 0; i < kin::kStruts; ++i) EXPECT_NEAR(q(i), direct(i), kTolExact);
}

TEST(HexapodJointConverter, InchMachineGetsInches) {
  kin::HexapodModel mm = pkm::test::millingModel();
  kin::HexapodModel inch = mm;
  inch.unit = pkm::LengthUnit::kInch;
  for (auto& s : inch.struts) {
    s.world_p_base /= 25.4;
    s.platform_p_joint /= 25.4;
    s.length_offset /= 25.4;
    s.min_reading /= 25.4;
    s.max_reading /= 25.4;
  }
  inch.tool_offset /= 25.4;
  inch.strut_diameter /= 25.4;
  inch.home.position /= 25.4;
  HexapodJointConverter a(mm), b(inch);
  const Axes pos{10, 20, 150, 1, 2, 3};
  const kin::StrutVector qa = a.solve(pos), qb = b.solve(pos);
  for (int i = 0; i < kin::kStruts; ++i) EXPECT_NEAR(qb(i) * 25.4, qa(i), kTolRoundTrip);
}

// The documented step rule: a controller that interpolates linearly in joint space between two
// samples keeps the TCP within the tolerance of the straight programmed line (FK of dense
// joint-space points, distance to the line).
TEST(JointSpaceInterpolation, LinearJointInterpolationStaysWithinTolerance) {
  const kin::HexapodModel model = pkm::test::millingModel();
  const InterpolationOptions o = jointSpaceInterpolation(model, kTol);
  ASSERT_TRUE(std::isfinite(o.max_step));
  std::mt19937 rng(kSeed);
  HexapodJointConverter conv(model);
  kin::HexapodData data(model);
  double worst = 0.0;
  for (int l = 0; l < kRandomLines; ++l) {
    const kin::PoseRpy p0 = pkm::test::randomPose(rng, model.home, kReach, pkm::degToRad(kTiltDeg));
    const kin::PoseRpy p1 = pkm::test::randomPose(rng, model.home, kReach, pkm::degToRad(kTiltDeg));
    Axes a{}, b{};
    for (std::size_t k = 0; k < 3; ++k) {
      a[k] = p0.position[static_cast<Eigen::Index>(k)];
      b[k] = p1.position[static_cast<Eigen::Index>(k)];
      a[k + 3] = pkm::radToDeg(p0.rpy[static_cast<Eigen::Index>(k)]);
      b[k + 3] = pkm::radToDeg(p1.rpy[static_cast<Eigen::Index>(k)]);
    }
    PathInterpolator cut(o, a);
    Move m;
    m.kind = MoveKind::kLinear;
    m.end = b;
    std::vector<PathPoint> pts{PathPoint{}};
    pts[0].pos = a;
    cut.append(m, 0, pts);
    const Eigen::Vector3d pa(a[0], a[1], a[2]), pb(b[0], b[1], b[2]);
    const Eigen::Vector3d dir = (pb - pa).normalized();
    kin::PoseRpy seed = p0;
    for (std::size_t i = 1; i < pts.size(); ++i) {
      const kin::StrutVector q0 = conv.solve(pts[i - 1].pos), q1 = conv.solve(pts[i].pos);
      for (int s = 1; s < kDenseSamples; ++s) {
        const double u = static_cast<double>(s) / kDenseSamples;
        const kin::StrutVector q = q0 + u * (q1 - q0);
        kin::PoseRpy x = seed;
        const kin::FkSummary fk = kin::forwardKinematics(model, data, q, x);
        ASSERT_TRUE(fk.ok());
        x = data.pose;
        seed = x;
        const Eigen::Vector3d d = x.position - pa;
        worst = std::max(worst, (d - d.dot(dir) * dir).norm());
      }
    }
  }
  RecordProperty("worst_deviation_mm", std::to_string(worst));
  EXPECT_LE(worst, kTol);
}

TEST(JointCsv, RowFormat) {
  PathPoint p;
  p.line = 7;
  p.pos = {1.5, -2, 0, 0, 0, 90};
  kin::StrutVector q;
  q << 1, 2, 3, 4, 5, 6.25;
  std::string s;
  appendJointCsv(s, p, 0.5, q);
  EXPECT_EQ(s, "7,0.5,1.5,-2,0,0,0,90,1,2,3,4,5,6.25\n");
  EXPECT_STREQ(kJointCsvHeader, "line,t,x,y,z,a,b,c,q0,q1,q2,q3,q4,q5");
}

TEST(JointSpaceInterpolation, RejectsBadTolerance) {
  EXPECT_THROW((void)jointSpaceInterpolation(pkm::test::millingModel(), 0.0), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
