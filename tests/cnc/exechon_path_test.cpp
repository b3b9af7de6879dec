// Exechon joint-space conversion: the virtual head's tool vector against Eigen's rotations, IK
// round trips through the tool forward kinematics in both orientation modes, continuity along a
// path, failures (B word, singular point), the interpolation step rule checked by forward
// kinematics between samples, and the CSV row.
#include "pkm/cnc/exechon_path.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::degToRad;
using pkm::test::kSeed;
using pkm::test::kTolExact;
using pkm::test::kTolRoundTrip;

/// Readings tolerance of the forward kinematics below the round-trip tolerance (mm).
constexpr double kFkTolerance = 1e-12;

/// Tool forward kinematics of a sample: the tool point and direction its joints give.
kin::ExechonData forward(const kin::ExechonModel& m, const ExechonPathSample& s) {
  kin::ExechonData d(m);
  kin::ExechonJoints j{s.readings, s.config.c, s.config.a};
  kin::FkOptions options;
  options.tolerance = kFkTolerance;
  const kin::FkSummary fk = kin::toolForwardKinematics(m, d, j, s.config, options);
  EXPECT_TRUE(fk.ok());
  return d;
}

/// A random position near the home tool point (mm) with A in [20°, 40°] and C in ±180°.
Axes randomAxes(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return {60 * u(rng), 60 * u(rng), 40 * u(rng), 30 + 10 * u(rng), 0, 180 * u(rng)};
}

TEST(ExechonPath, ToolVectorOfTheVirtualHead) {
  for (const auto& [a, c] : {std::pair{0.0, 0.0}, {30.0, 0.0}, {25.0, 70.0}, {-40.0, -120.0}}) {
    const Eigen::Vector3d k = Eigen::AngleAxisd(degToRad(c), Eigen::Vector3d::UnitZ()) *
                              Eigen::AngleAxisd(degToRad(a), Eigen::Vector3d::UnitX()) *
                              Eigen::Vector3d::UnitZ();
    EXPECT_LT((toolDirectionFromAngles(a, c) + k).norm(), kTolExact) << a << " " << c;
  }
  EXPECT_EQ(parseExechonOrientation("axes"), ExechonOrientation::kWristAxes);
  EXPECT_EQ(toString(parseExechonOrientation("vector")), "vector");
  EXPECT_THROW((void)parseExechonOrientation("ijk"), pkm::InvalidArgument);
}

TEST(ExechonPath, ToolVectorModeRoundTripsThroughForwardKinematics) {
  const kin::ExechonModel m = pkm::test::machineModel();
  std::mt19937 rng(kSeed);
  for (int k = 0; k < 200; ++k) {
    ExechonJointConverter conv(m, ExechonOrientation::kToolVector);
    const Axes pos = randomAxes(rng);
    const ExechonPathSample s = conv.solve(pos);
    ASSERT_TRUE(s.ok()) << k;
    const kin::ExechonData d = forward(m, s);
    EXPECT_LT((d.world_p_tool - Eigen::Vector3d(pos[0], pos[1], pos[2])).norm(), kTolRoundTrip);
    EXPECT_LT((d.world_u_tool - toolDirectionFromAngles(pos[3], pos[5])).norm(), kTolRoundTrip);
    EXPECT_LT((s.direction - d.world_u_tool).norm(), kTolRoundTrip);
    EXPECT_EQ(s.joints(5), 0.0);
    EXPECT_DOUBLE_EQ(s.joints(3), pkm::radToDeg(s.config.c));
  }
}

TEST(ExechonPath, WristAxesModeKeepsTheReadingsAndReachesThePoint) {
  const kin::ExechonModel m = pkm::test::machineModel();
  std::mt19937 rng(kSeed + 1);
  for (int k = 0; k < 200; ++k) {
    ExechonJointConverter conv(m, ExechonOrientation::kWristAxes);
    const Axes pos = randomAxes(rng);
    const ExechonPathSample s = conv.solve(pos);
    ASSERT_TRUE(s.ok()) << k;
    EXPECT_NEAR(s.config.a, degToRad(pos[3]), kTolExact);
    EXPECT_NEAR(s.config.c, degToRad(pos[5]), kTolExact);
    const kin::ExechonData d = forward(m, s);
    EXPECT_LT((d.world_p_tool - Eigen::Vector3d(pos[0], pos[1], pos[2])).norm(), kTolRoundTrip);
  }
}

TEST(ExechonPath, WristAxesModeAlongAPathAgreesWithVectorMode) {
  // Readings that change along a circle: each axes-mode sample keeps them and puts the tool on
  // the point, and vector mode, given the direction that sample found, solves to the same joints.
  const kin::ExechonModel m = pkm::test::machineModel();
  ExechonJointConverter axes(m, ExechonOrientation::kWristAxes);
  ExechonJointConverter vector(m, ExechonOrientation::kToolVector);
  for (int i = 0; i <= 720; ++i) {
    const double t = degToRad(0.5 * i);
    const Axes pos{40 * std::cos(t),
                   40 * std::sin(t),
                   5 * std::sin(3 * t),
                   25 + 10 * std::sin(t),
                   0,
                   0.5 * i - 90};
    const ExechonPathSample s = axes.solve(pos);
    ASSERT_TRUE(s.ok()) << i;
    EXPECT_NEAR(s.config.a, degToRad(pos[3]), kTolExact) << i;
    EXPECT_NEAR(s.config.c, degToRad(pos[5]), kTolExact) << i;
    const kin::ExechonData d = forward(m, s);
    EXPECT_LT((d.world_p_tool - Eigen::Vector3d(pos[0], pos[1], pos[2])).norm(), kTolRoundTrip);
    // toolDirectionFromAngles(a, c) = (−sin c·sin a, cos c·sin a, −cos a).
    const double a = pkm::radToDeg(std::acos(-s.direction.z()));
    const double c = pkm::radToDeg(std::atan2(-s.direction.x(), s.direction.y()));
    const ExechonPathSample v = vector.solve({pos[0], pos[1], pos[2], a, 0, c});
    ASSERT_TRUE(v.ok()) << i;
    EXPECT_LT((v.readings - s.readings).cwiseAbs().maxCoeff(), kTolRoundTrip) << i;
    EXPECT_NEAR(std::remainder(v.config.c - s.config.c, 2 * std::numbers::pi), 0.0, kTolRoundTrip);
    EXPECT_NEAR(v.config.a, s.config.a, kTolRoundTrip) << i;
  }
}

TEST(ExechonPath, WristAxesModeThroughReversalsAndUnevenSteps) {
  // The extrapolated Newton start overshoots where the path turns back or its step changes: every
  // point must still be reached with the readings held.
  const kin::ExechonModel m = pkm::test::machineModel();
  ExechonJointConverter conv(m, ExechonOrientation::kWristAxes);
  std::vector<Axes> path;
  for (int i = 0; i <= 40; ++i) path.push_back({0, 0, -2.0 * i, 20, 0, 10});  // plunge
  for (int i = 40; i >= 0; --i) path.push_back({0, 0, -2.0 * i, 20, 0, 10});  // retract
  for (int i = 0; i <= 30; ++i)
    path.push_back({i * i * 0.1, 0, 0, 20.0 + i, 0, 10.0 - i});  // growing
  path.push_back({0, 0, 0, 20, 0, 10});                          // a jump back
  for (std::size_t k = 0; k < path.size(); ++k) {
    const Axes& pos = path[k];
    const ExechonPathSample s = conv.solve(pos);
    ASSERT_TRUE(s.ok()) << k;
    EXPECT_NEAR(s.config.a, degToRad(pos[3]), kTolExact) << k;
    const kin::ExechonData d = forward(m, s);
    EXPECT_LT((d.world_p_tool - Eigen::Vector3d(pos[0], pos[1], pos[2])).norm(), kTolRoundTrip)
        << k;
  }
}

TEST(ExechonPath, WristAxesModeFailsOutsideTheWorkspaceAndRecovers) {
  const kin::ExechonModel m = pkm::test::machineModel();
  ExechonJointConverter conv(m, ExechonOrientation::kWristAxes);
  const ExechonPathSample good = conv.solve({10, 0, 0, 30, 0, 20});
  ASSERT_TRUE(good.ok());
  // A tool point on the base axis jb: the wrist point, within the tool length (250 mm) of it,
  // would be inside the cylinder |(Sx, Sz)| < hx (282.8 mm) that the tripod cannot reach.
  const Eigen::Vector3d far = m.world_T_zoppi * Eigen::Vector3d(0.0, 700.0, 0.0);
  const ExechonPathSample bad = conv.solve({far.x(), far.y(), far.z(), 30, 0, 20});
  EXPECT_FALSE(bad.ok());
  EXPECT_EQ(bad.joints, good.joints);
  const ExechonPathSample again = conv.solve({11, 0, 0, 30, 0, 20});
  ASSERT_TRUE(again.ok());
  EXPECT_LT((again.readings - good.readings).cwiseAbs().maxCoeff(), 2.0);
}

TEST(ExechonPath, ContinuityAlongAPathAndDrmAtTheStart) {
  const kin::ExechonModel m = pkm::test::machineModel();
  ExechonJointConverter conv(m, ExechonOrientation::kToolVector);
  // A circle of radius 50 mm with a constant tilted tool, 1° steps.
  ExechonPathSample prev;
  for (int i = 0; i <= 360; ++i) {
    const double t = degToRad(i);
    const ExechonPathSample s = conv.solve({50 * std::cos(t), 50 * std::sin(t), 0, 30, 0, 45});
    ASSERT_TRUE(s.ok()) << i;
    if (i == 0) {
      EXPECT_EQ(s.drm, 0.0);
    } else {
      // 1° on a 50 mm circle moves the tool 0.87 mm: no joint may jump (branch change).
      EXPECT_LT((s.readings - prev.readings).cwiseAbs().maxCoeff(), 3.0);
      EXPECT_LT(std::abs(s.config.c - prev.config.c), degToRad(3.0));
      EXPECT_LT(std::abs(s.config.a - prev.config.a), degToRad(3.0));
    }
    prev = s;
  }
}

TEST(ExechonPath, FailuresHoldTheLastJoints) {
  const kin::ExechonModel m = pkm::test::machineModel();
  ExechonJointConverter conv(m, ExechonOrientation::kToolVector);
  const ExechonPathSample good = conv.solve({10, 0, 0, 30, 0, 0});
  ASSERT_TRUE(good.ok());
  const ExechonPathSample b = conv.solve({10, 0, 0, 30, 5, 0});  // a B word
  EXPECT_EQ(b.status, kin::ExechonIkStatus::kInvalidInput);
  EXPECT_EQ(b.joints, good.joints);
  // The wrist point on the base axis jb (Zoppi origin): the tripod IK is singular there.
  const Eigen::Vector3d u = toolDirectionFromAngles(30, 0);
  const Eigen::Vector3d p = m.world_T_zoppi.translation() + m.wrist.tool_length * u;
  const ExechonPathSample sing = conv.solve({p.x(), p.y(), p.z(), 30, 0, 0});
  EXPECT_FALSE(sing.ok());
  EXPECT_EQ(sing.joints, good.joints);
  std::string row;
  appendExechonJointCsv(row, PathPoint{7, 0, MoveKind::kLinear, {1, 2, 3, 30, 0, 0}, 600}, 0.5, b);
  EXPECT_EQ(row, "7,0.5,1,2,3,30,0,0,,,,,,,,,\n");
  // Still continuous after the failures.
  EXPECT_TRUE(conv.solve({11, 0, 0, 30, 0, 0}).ok());
}

TEST(ExechonPath, CsvRowHasEveryField) {
  const kin::ExechonModel m = pkm::test::machineModel();
  ExechonJointConverter conv(m, ExechonOrientation::kToolVector);
  const ExechonPathSample s = conv.solve({0, 0, 0, 30, 0, 0});
  std::string row;
  appendExechonJointCsv(row, PathPoint{3, 0, MoveKind::kRapid, {0, 0, 0, 30, 0, 0}, NAN}, 0, s);
  std::size_t commas = 0;
  for (char ch : row) commas += ch == ',' ? 1 : 0;
  std::size_t header_commas = 0;
  for (const char* c = kExechonJointCsvHeader; *c != 0; ++c) header_commas += *c == ',' ? 1 : 0;
  EXPECT_EQ(commas, header_commas);
  EXPECT_EQ(row.back(), '\n');
}

/// The step rule: joints interpolated linearly between samples stay within the tolerance of the
/// programmed line (forward kinematics at the midpoints), for a translation and a reorientation.
TEST(ExechonPath, InterpolationStepKeepsLinearJointsNearThePath) {
  const kin::ExechonModel m = pkm::test::machineModel();
  constexpr double kTol = 0.01;  // mm
  const InterpolationOptions o = exechonInterpolation(m, kTol);
  EXPECT_GT(o.max_step, 0.0);
  EXPECT_LT(o.max_angle_step, 1.0);
  EXPECT_THROW((void)exechonInterpolation(m, 0.0), pkm::InvalidArgument);
  const Axes start{-80, -40, 0, 30, 0, 0};
  for (const Axes& end : {Axes{80, 50, 30, 30, 0, 0}, Axes{-80, -40, 0, 40, 0, 60}}) {
    PathInterpolator interp(o, start);
    std::vector<PathPoint> pts{PathPoint{1, 0, MoveKind::kRapid, start, NAN}};
    Move mv;
    mv.kind = MoveKind::kLinear;
    mv.end = end;
    mv.feed = 1000;
    interp.append(mv, 1, pts);
    ExechonJointConverter conv(m, ExechonOrientation::kToolVector);
    std::vector<ExechonPathSample> s;
    conv.solveAll(pts, s);
    double worst = 0.0;
    for (std::size_t i = 1; i < s.size(); ++i) {
      ASSERT_TRUE(s[i].ok());
      ExechonPathSample mid = s[i];
      mid.readings = 0.5 * (s[i - 1].readings + s[i].readings);
      mid.config.c = 0.5 * (s[i - 1].config.c + s[i].config.c);
      mid.config.a = 0.5 * (s[i - 1].config.a + s[i].config.a);
      const kin::ExechonData d = forward(m, mid);
      // Distance of the midpoint's tool point from the programmed (straight) tool path.
      const Eigen::Vector3d a(pts[i - 1].pos[0], pts[i - 1].pos[1], pts[i - 1].pos[2]);
      const Eigen::Vector3d b(pts[i].pos[0], pts[i].pos[1], pts[i].pos[2]);
      const Eigen::Vector3d ab = b - a;
      const double len2 = ab.squaredNorm();
      const Eigen::Vector3d foot =
          len2 > 0 ? Eigen::Vector3d(a + ab * ((d.world_p_tool - a).dot(ab) / len2)) : a;
      worst = std::max(worst, (d.world_p_tool - foot).norm());
    }
    EXPECT_LE(worst, kTol) << "end " << end[0];
  }
}

}  // namespace PKM_TEST_NS
