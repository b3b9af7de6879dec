// Cycle-time model against hand-computed trapezoids: a single feed line (feed-limited and
// joint-velocity-limited), triangle profiles, rotary-only length, bad limits.
#include "pkm/cnc/cycle_time.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::test::kTolRoundTrip;

constexpr double kLength = 100.0;  // mm, the single line
constexpr double kFeed = 600.0;    // mm/min = 10 mm/s

/// Start and end of one G1 line along X at the home height of the milling model.
std::vector<PathPoint> singleLine() {
  std::vector<PathPoint> pts(2);
  pts[0].pos = {0, 0, 200, 0, 0, 0};
  pts[1].pos = {kLength, 0, 200, 0, 0, 0};
  pts[1].kind = MoveKind::kLinear;
  pts[1].feed = kFeed;
  return pts;
}

TEST(TrapezoidTime, ClosedForms) {
  // Rest to rest, cruise reached: t = ds/v + v/a.
  EXPECT_NEAR(trapezoidTime(100, 0, 0, 10, 100), 10.0 + 0.1, kTolRoundTrip);
  // Triangle: ds = vp²/a, t = 2·vp/a with vp = sqrt(a·ds).
  EXPECT_NEAR(trapezoidTime(1, 0, 0, 100, 100), 2.0 * std::sqrt(100.0) / 100.0, kTolRoundTrip);
  // Constant speed.
  EXPECT_NEAR(trapezoidTime(5, 10, 10, 10, 100), 0.5, kTolRoundTrip);
}

TEST(CycleTime, SingleLineFeedLimited) {
  const kin::HexapodModel model = pkm::test::millingModel();
  HexapodJointConverter conv(model);
  const auto pts = singleLine();
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  const double g = (q[1] - q[0]).cwiseAbs().maxCoeff() / kLength;  // joint mm per path mm
  MotionLimits lim;
  lim.max_joint_velocity = 1000.0;  // not limiting
  lim.max_joint_acceleration = 50.0;
  const CycleTime t = estimateCycleTime(pts, q, lim);
  const double v = kFeed / 60.0, a = lim.max_joint_acceleration / g;
  ASSERT_GE(kLength, v * v / a);  // the cruise is reached
  EXPECT_NEAR(t.total, kLength / v + v / a, kTolRoundTrip);
  EXPECT_EQ(t.t.front(), 0.0);
}

TEST(CycleTime, SingleLineJointVelocityLimited) {
  const kin::HexapodModel model = pkm::test::millingModel();
  HexapodJointConverter conv(model);
  const auto pts = singleLine();
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  const double g = (q[1] - q[0]).cwiseAbs().maxCoeff() / kLength;
  MotionLimits lim;
  lim.max_joint_velocity = 2.0;  // mm/s: well below g·10 mm/s
  lim.max_joint_acceleration = 1000.0;
  const CycleTime t = estimateCycleTime(pts, q, lim);
  const double v = lim.max_joint_velocity / g, a = lim.max_joint_acceleration / g;
  ASSERT_LT(v, kFeed / 60.0);
  EXPECT_NEAR(t.total, kLength / v + v / a, kTolRoundTrip);
}

TEST(RapidSpeedCap, TheSlowestAxisAlongTheMoveSetsTheRapidSpeed) {
  RapidAxisLimits lim;
  EXPECT_TRUE(std::isinf(rapidSpeedCap({0, 0, 0, 0, 0, 0}, {3, 4, 0, 0, 0, 0}, lim)));
  lim.axis_velocity = {10, 2, 50, 5, 5, 5};
  // 3-4-5 move: X needs 0.3 s, Y 2 s: the path (5 mm) takes 2 s, 2.5 mm/s.
  EXPECT_NEAR(rapidSpeedCap({0, 0, 0, 0, 0, 0}, {3, 4, 0, 0, 0, 0}, lim), 2.5, kTolRoundTrip);
  // X with A: A's 10 deg take 2 s, the 10 mm of X no less.
  EXPECT_NEAR(rapidSpeedCap({0, 0, 0, 0, 0, 0}, {10, 0, 0, 10, 0, 0}, lim), 5.0, kTolRoundTrip);
  // Rotary only: deg/s, and the angular rate (deg/min) on top.
  EXPECT_NEAR(rapidSpeedCap({0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 3}, lim), 5.0, kTolRoundTrip);
  lim.angular_rate = 120.0;
  EXPECT_NEAR(rapidSpeedCap({0, 0, 0, 0, 0, 0}, {0, 0, 0, 0, 0, 3}, lim), 2.0, kTolRoundTrip);
  EXPECT_TRUE(std::isinf(rapidSpeedCap({1, 0, 0, 0, 0, 0}, {1, 0, 0, 0, 0, 0}, lim)));
  lim.axis_velocity[1] = 0.0;
  EXPECT_THROW(lim.validate(), pkm::InvalidArgument);
}

TEST(CycleTime, ARapidRunsAtTheSlowestAxisAlongIt) {
  const kin::HexapodModel model = pkm::test::millingModel();
  HexapodJointConverter conv(model);
  auto pts = singleLine();
  pts[1].kind = MoveKind::kRapid;
  pts[1].feed = NAN;
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  MotionLimits lim;
  lim.max_joint_velocity = 1e6;  // not limiting
  lim.max_joint_acceleration = 1e9;
  lim.rapid_rate = 1200.0;  // 20 mm/s
  const double unbounded = estimateCycleTime(pts, q, lim).total;
  EXPECT_NEAR(unbounded, kLength / 20.0, 1e-3);  // the acceleration phases take microseconds
  lim.rapid_axes.axis_velocity[0] = 4.0;         // X at most 4 mm/s
  EXPECT_NEAR(estimateCycleTime(pts, q, lim).total, kLength / 4.0, 1e-3);
  lim.rapid_axes.axis_velocity[0] = 400.0;  // faster than the rate: the rate holds
  EXPECT_NEAR(estimateCycleTime(pts, q, lim).total, unbounded, kTolRoundTrip);
}

TEST(CycleTime, RotaryOnlyLengthIsDegrees) {
  Axes a{0, 0, 0, 0, 0, 0}, b{0, 0, 0, 3, 4, 0};
  EXPECT_NEAR(segmentLength(a, b), 5.0, kTolRoundTrip);
  b = {3, 4, 0, 90, 0, 0};
  EXPECT_NEAR(segmentLength(a, b), 5.0, kTolRoundTrip);  // XYZ wins when it moves
}

TEST(CycleTime, RejectsBadLimits) {
  MotionLimits lim;
  lim.max_joint_velocity = 0.0;
  EXPECT_THROW(lim.validate(), pkm::InvalidArgument);
  std::vector<PathPoint> pts(2);
  std::vector<kin::StrutVector> q(1);
  EXPECT_THROW((void)estimateCycleTime(pts, q, MotionLimits{}), pkm::InvalidArgument);
}

/// Per-joint limits: a rotary-only move in which only joint 3 moves (1 unit per degree of C) is
/// timed by joint 3's own limits; the others' limits do not matter, and uniform limits give the
/// MotionLimits result.
TEST(CycleTime, PerJointLimits) {
  std::vector<PathPoint> pts(2);
  pts[0].pos = {0, 0, 0, 0, 0, 0};
  pts[1].pos = {0, 0, 0, 0, 0, 90};
  pts[1].kind = MoveKind::kLinear;
  pts[1].feed = 6000.0;  // deg/min = 100 deg/s: not limiting
  std::vector<kin::StrutVector> q(2, kin::StrutVector::Zero());
  q[1](3) = 90.0;
  JointRateLimits lim;
  lim.max_velocity.setConstant(1e-3);  // would dominate if the idle joints counted
  lim.max_acceleration.setConstant(1e-3);
  lim.max_velocity(3) = 30.0;
  lim.max_acceleration(3) = 60.0;
  const CycleTime t = estimateCycleTime(pts, q, lim);
  EXPECT_NEAR(t.total, 90.0 / 30.0 + 30.0 / 60.0, kTolRoundTrip);  // cruise + ramps
  MotionLimits uniform;
  uniform.max_joint_velocity = 30.0;
  uniform.max_joint_acceleration = 60.0;
  EXPECT_NEAR(estimateCycleTime(pts, q, uniform).total,
              estimateCycleTime(pts, q, JointRateLimits::uniform(uniform)).total,
              kTolRoundTrip);
  lim.max_acceleration(0) = 0.0;
  EXPECT_THROW((void)estimateCycleTime(pts, q, lim), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS

namespace PKM_TEST_NS {

/// A 100 mm G1 line along X cut into 10 points (move 0 is the start, moves 1 and 2 the halves).
std::vector<PathPoint> tenPointLine() {
  std::vector<PathPoint> pts(11);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    pts[i].pos = {10.0 * static_cast<double>(i), 0, 200, 0, 0, 0};
    pts[i].kind = MoveKind::kLinear;
    pts[i].feed = kFeed;
    pts[i].move = i == 0 ? 0u : (i <= 5 ? 1u : 2u);
  }
  return pts;
}

TEST(CycleTime, DwellsStopTheMachineAndAddTheirTime) {
  const kin::HexapodModel model = pkm::test::millingModel();
  HexapodJointConverter conv(model);
  const auto pts = tenPointLine();
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  const MotionLimits lim;
  // An exact stop at point 5 splits the profile into two independent rest-to-rest profiles.
  const CycleTime with = estimateCycleTime(pts, q, lim, {{5, 2.0}});
  const std::vector<PathPoint> a(pts.begin(), pts.begin() + 6), b(pts.begin() + 5, pts.end());
  const std::vector<kin::StrutVector> qa(q.begin(), q.begin() + 6), qb(q.begin() + 5, q.end());
  const double split =
      estimateCycleTime(a, qa, lim).total + 2.0 + estimateCycleTime(b, qb, lim).total;
  EXPECT_NEAR(with.total, split, kTolRoundTrip);
  EXPECT_EQ(with.dwell, 2.0);
  EXPECT_GT(with.total, estimateCycleTime(pts, q, lim).total + 2.0);  // and stopping costs time
  // The arrival times: the dwell starts at point 5's arrival and delays every later point.
  EXPECT_NEAR(with.t[5], estimateCycleTime(a, qa, lim).total, kTolRoundTrip);
  EXPECT_NEAR(with.t[6] - with.t[5], 2.0 + estimateCycleTime(b, qb, lim).t[1], kTolRoundTrip);
  // A dwell at the end adds to the total only.
  const CycleTime end = estimateCycleTime(pts, q, lim, {{10, 1.5}});
  EXPECT_NEAR(end.total, estimateCycleTime(pts, q, lim).total + 1.5, kTolRoundTrip);
  EXPECT_THROW((void)estimateCycleTime(pts, q, lim, {{11, 1.0}}), pkm::InvalidArgument);
  EXPECT_THROW((void)estimateCycleTime(pts, q, lim, {{3, -1.0}}), pkm::InvalidArgument);
}

TEST(CycleTime, DwellsOnPathFollowTheMotionCount) {
  const auto pts = tenPointLine();
  const std::vector<PathDwell> d = dwellsOnPath(pts, {{1, 0, 0.5}, {2, 1, 1.0}, {3, 2, 2.0}});
  ASSERT_EQ(d.size(), 3u);
  EXPECT_EQ(d[0].point, 0u);  // before any motion: at the start
  EXPECT_EQ(d[1].point, 0u);  // after motion 0 (the start point itself)
  EXPECT_EQ(d[2].point, 5u);  // after motion 1: its last point
  EXPECT_EQ(d[2].seconds, 2.0);
}

}  // namespace PKM_TEST_NS
