// Exechon path checks: a clean path (interference disabled, margins equal to the configuration
// checks'), a stroke violation with its line, an unreachable point, per-joint rate limits (a wrist
// rotation against its own limit, by hand), and bad arguments.
#include "pkm/cnc/exechon_path_checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::test::kTolRoundTrip;

constexpr double kFeed = 600.0;  // mm/min

/// Points of straight lines between `corners` (one motion each, line numbers 2, 3, ...),
/// interpolated for the model, and their samples.
struct Path {
  std::vector<PathPoint> points;
  std::vector<ExechonPathSample> samples;
};
Path makePath(const kin::ExechonModel& m, const std::vector<Axes>& corners) {
  Path p;
  const InterpolationOptions o = exechonInterpolation(m, 0.01);
  PathInterpolator interp(o, corners.front());
  p.points.push_back(PathPoint{1, 0, MoveKind::kRapid, corners.front(), NAN});
  for (std::size_t k = 1; k < corners.size(); ++k) {
    Move mv;
    mv.line = k + 1;
    mv.kind = MoveKind::kLinear;
    mv.end = corners[k];
    mv.feed = kFeed;
    interp.append(mv, static_cast<std::uint32_t>(k), p.points);
  }
  ExechonJointConverter conv(m, ExechonOrientation::kToolVector);
  conv.solveAll(p.points, p.samples);
  return p;
}

JointRateLimits generous() {
  MotionLimits legs;
  legs.max_joint_velocity = 1e4;
  legs.max_joint_acceleration = 1e6;
  return exechonRateLimits(legs, 1e4, 1e6);
}

TEST(ExechonPathChecks, CleanPathMatchesTheConfigurationChecks) {
  const kin::ExechonModel m = pkm::test::machineModel();
  const Path p = makePath(m, {{0, 0, 0, 30, 0, 0}, {50, 20, 0, 30, 0, 0}, {50, 20, 20, 35, 0, 40}});
  const PathCheckReport r = checkExechonPath(m, p.points, p.samples, generous());
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(r.points, p.points.size());
  EXPECT_TRUE(r[PathCheck::kReach].enabled);
  EXPECT_FALSE(r[PathCheck::kInterference].enabled);
  // The stroke and condition margins are the smallest of the per-point configuration checks.
  double stroke = std::numeric_limits<double>::infinity(), cond = stroke;
  kin::ExechonData d(m);
  for (const auto& s : p.samples) {
    kin::evaluateConfiguration(m, d, s.config);
    const kin::ExechonCheckResult c = kin::checkConfiguration(m, d);
    stroke = std::min(stroke, c.stroke_margin.minCoeff());
    cond = std::min(cond, c.condition_margin);
  }
  EXPECT_NEAR(r[PathCheck::kStroke].worst.margin, stroke, kTolRoundTrip);
  EXPECT_NEAR(r[PathCheck::kSingular].worst.margin, cond, kTolRoundTrip);
}

TEST(ExechonPathChecks, StrokeViolationNamesTheLine) {
  const kin::ExechonModel m = pkm::test::machineModel();
  // Down 600 mm: far beyond the legs' strokes.
  const Path p = makePath(m, {{0, 0, 0, 30, 0, 0}, {0, 0, 10, 30, 0, 0}, {0, 0, -600, 30, 0, 0}});
  const PathCheckReport r = checkExechonPath(m, p.points, p.samples, generous());
  const CheckStat& s = r[PathCheck::kStroke];
  ASSERT_GT(s.violations, 0u);
  EXPECT_EQ(s.first.line, 3u);
  EXPECT_LT(s.first.margin, 0.0);
  EXPECT_EQ(s.first.item.substr(0, 4), "leg ");
  EXPECT_FALSE(r.ok());
}

TEST(ExechonPathChecks, UnreachablePointIsAReachViolation) {
  const kin::ExechonModel m = pkm::test::machineModel();
  Path p = makePath(m, {{0, 0, 0, 30, 0, 0}, {5, 0, 0, 30, 0, 0}});
  p.samples[2].status = kin::ExechonIkStatus::kUnreachable;
  const PathCheckReport r = checkExechonPath(m, p.points, p.samples, generous());
  const CheckStat& s = r[PathCheck::kReach];
  EXPECT_EQ(s.violations, 1u);
  EXPECT_EQ(s.first.item, "unreachable");
  EXPECT_EQ(s.first.pos, p.points[2].pos);
  EXPECT_FALSE(r.ok());
}

/// A pure wrist rotation at fixed tool point: the wrist rates are checked against the wrist
/// limits, the legs' against theirs. At feed F (deg/min for a rotary-only move) a joint moving
/// Δθ_j over a path step of Δs degrees runs at |Δθ_j/Δs|·F/60.
TEST(ExechonPathChecks, WristRatesAgainstTheirOwnLimits) {
  const kin::ExechonModel m = pkm::test::machineModel();
  const Path p = makePath(m, {{0, 0, 0, 30, 0, 0}, {0, 0, 0, 30, 0, 90}});
  double expected = 0.0;  // fastest wrist rate along the path, deg/s
  for (std::size_t k = 1; k < p.points.size(); ++k) {
    const double ds = segmentLength(p.points[k - 1].pos, p.points[k].pos);
    const auto dq = (p.samples[k].joints - p.samples[k - 1].joints).cwiseAbs() / ds;
    expected = std::max({expected, dq(3) * kFeed / 60.0, dq(4) * kFeed / 60.0});
  }
  ASSERT_GT(expected, 0.0);
  MotionLimits legs;
  legs.max_joint_velocity = 1e4;
  legs.max_joint_acceleration = 1e6;
  const double wrist_limit = 0.5 * expected;
  const PathCheckReport r =
      checkExechonPath(m, p.points, p.samples, exechonRateLimits(legs, wrist_limit, 1e6));
  const CheckStat& v = r[PathCheck::kJointVelocity];
  ASSERT_GT(v.violations, 0u);
  EXPECT_EQ(v.worst.item.substr(0, 5), "wrist");
  EXPECT_NEAR(v.worst.value, expected, 1e-9 * expected);
  EXPECT_DOUBLE_EQ(v.worst.limit, wrist_limit);
  EXPECT_NEAR(v.worst.margin, wrist_limit - expected, 1e-9 * expected);
}

TEST(ExechonPathChecks, BadArguments) {
  const kin::ExechonModel m = pkm::test::machineModel();
  const Path p = makePath(m, {{0, 0, 0, 30, 0, 0}, {5, 0, 0, 30, 0, 0}});
  std::vector<ExechonPathSample> fewer(p.samples.begin(), p.samples.end() - 1);
  EXPECT_THROW((void)checkExechonPath(m, p.points, fewer, generous()), pkm::InvalidArgument);
  EXPECT_THROW((void)exechonRateLimits(MotionLimits{}, 0.0, 1.0), pkm::InvalidArgument);
  EXPECT_THROW((void)exechonRateLimits(MotionLimits{}, 1.0, NAN), pkm::InvalidArgument);
  EXPECT_EQ(exechonJointName(3), "wrist C");
  EXPECT_THROW((void)exechonJointName(6), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
