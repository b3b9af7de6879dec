// Path checks triggered by crafted programs, each with its line asserted: stroke exceeded,
// leg interference, singularity proximity, joint velocity and acceleration at the programmed
// feed; a clean program passes every check.
#include "pkm/cnc/joint_checks.hpp"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;

using pkm::test::kTolRoundTrip;

constexpr double kTol = 0.01;  // mm

/// Interpolates `text` for `model` and runs every check.
PathCheckReport check(const kin::HexapodModel& model,
                      const std::string& text,
                      const MotionLimits& lim = {},
                      std::size_t keep = 0) {
  const Program p = Program::parse(text, "t.ngc");
  MoveCollector moves;
  Interpreter interp;
  (void)interp.run(p, moves);
  PathInterpolator cut(jointSpaceInterpolation(model, kTol), moves.moves.front().end);
  std::vector<PathPoint> pts;
  for (std::size_t m = 0; m < moves.moves.size(); ++m)
    cut.append(moves.moves[m], static_cast<std::uint32_t>(m), pts);
  HexapodJointConverter conv(model);
  std::vector<kin::StrutVector> q;
  conv.solveAll(pts, q);
  return checkPath(model, pts, q, lim, keep);
}

// Home (0, 0, 200) twice, then to a pose P on line 3 (G-code axes, mm and degrees).
const char* const kToPoseP = "G0 X0 Y0 Z200\nG1 X0 F600\nG1 X40 Y-30 Z180 A6 C25\n";

/// The check value at home and at P of `field` (checkPose).
template <class F>
std::pair<double, double> homeAndP(const kin::HexapodModel& model, F field) {
  kin::HexapodData data(model);
  const double home = field(kin::checkPose(model, data, model.home));
  const double p =
      field(kin::checkPose(model, data, poseFromAxes({40, -30, 180, 6, 0, 25}, model.unit)));
  return {home, p};
}

TEST(CheckPath, CleanProgramPasses) {
  const PathCheckReport r = check(pkm::test::millingModel(), "G0 X0 Y0 Z200\nG1 X20 F600\n");
  EXPECT_TRUE(r.ok());
  EXPECT_TRUE(r[PathCheck::kStroke].enabled);
  EXPECT_GT(r[PathCheck::kStroke].worst.margin, 0.0);
  EXPECT_EQ(r.points,
            1u + static_cast<std::size_t>(std::ceil(
                     20.0 / jointSpaceInterpolation(pkm::test::millingModel(), kTol).max_step)));
}

TEST(CheckPath, StrokeExceededAtLine3) {
  // Z -300 needs a reading above the 500 mm stroke.
  const PathCheckReport r =
      check(pkm::test::millingModel(), "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nG1 Z200\n");
  const CheckStat& s = r[PathCheck::kStroke];
  ASSERT_GT(s.violations, 0u);
  EXPECT_EQ(s.first.line, 3u);
  EXPECT_LT(s.first.margin, 0.0);
  EXPECT_EQ(s.first.limit, 500.0);
  EXPECT_EQ(s.worst.line, 3u);
  EXPECT_EQ(s.worst.pos[2], -300.0);  // the deepest point
  EXPECT_FALSE(r.ok());
}

TEST(CheckPath, KeepsTheFirstViolationsWhenAsked) {
  const char* const program = "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nG1 Z200\n";
  const PathCheckReport none = check(pkm::test::millingModel(), program);
  EXPECT_TRUE(none[PathCheck::kStroke].events.empty());
  const PathCheckReport all = check(pkm::test::millingModel(), program, {}, 1'000'000);
  const CheckStat& s = all[PathCheck::kStroke];
  ASSERT_EQ(s.events.size(), s.violations);  // every one, in path order
  EXPECT_EQ(s.events.front().pos, s.first.pos);
  for (const CheckEvent& e : s.events) EXPECT_LT(e.margin, 0.0);
  const PathCheckReport three = check(pkm::test::millingModel(), program, {}, 3);
  ASSERT_EQ(three[PathCheck::kStroke].events.size(), 3u);
  EXPECT_EQ(three[PathCheck::kStroke].events[2].pos, s.events[2].pos);
  EXPECT_EQ(three[PathCheck::kStroke].worst.pos, s.worst.pos);  // the rest unchanged
}

TEST(CheckPath, InterferenceAtLine3) {
  // The candidate pose that brings two struts closest (at home the closest points are the base
  // joints of a pair, which no pose moves), then a strut diameter between home and it.
  kin::HexapodModel model = pkm::test::millingModel();
  kin::HexapodData data(model);
  const double home = kin::checkPose(model, data, model.home).min_leg_distance;
  Axes best{};
  double p = home;
  for (double c : {-35.0, 35.0})
    for (double a : {-12.0, 0.0, 12.0})
      for (double x : {-120.0, 0.0, 120.0}) {
        const Axes pos{x, 0, 150, a, 0, c};
        const double d =
            kin::checkPose(model, data, poseFromAxes(pos, model.unit)).min_leg_distance;
        if (d < p) {
          p = d;
          best = pos;
        }
      }
  ASSERT_LT(p, home - 1.0);
  model.strut_diameter = 0.5 * (home + p);
  const std::string text = fmt::format("G0 X0 Y0 Z200\nG1 X0 F600\nG1 X{} Y{} Z{} A{} B{} C{}\n",
                                       best[0],
                                       best[1],
                                       best[2],
                                       best[3],
                                       best[4],
                                       best[5]);
  const PathCheckReport r = check(model, text);
  const CheckStat& s = r[PathCheck::kInterference];
  ASSERT_GT(s.violations, 0u) << home << " " << p;
  EXPECT_EQ(s.first.line, 3u);
  EXPECT_NEAR(s.worst.value, p, kTolRoundTrip);
}

TEST(CheckPath, SingularityProximityAtLine3) {
  kin::HexapodModel model = pkm::test::millingModel();
  const auto [home, p] =
      homeAndP(model, [](const kin::HexapodCheckResult& c) { return c.condition_number; });
  ASSERT_GT(p, home);
  model.max_condition = 0.5 * (home + p);
  const PathCheckReport r = check(model, kToPoseP);
  const CheckStat& s = r[PathCheck::kSingular];
  ASSERT_GT(s.violations, 0u);
  EXPECT_EQ(s.first.line, 3u);
}

TEST(CheckPath, JointVelocityAndAccelerationAtProgrammedFeed) {
  MotionLimits lim;
  lim.max_joint_velocity = 5.0;  // mm/s; F6000 = 100 mm/s along X moves struts faster
  lim.max_joint_acceleration = 50.0;
  const PathCheckReport r = check(pkm::test::millingModel(),
                                  "G0 X0 Y0 Z200\nG1 X1 F60\nG1 X100 F6000\n"
                                  "G1 X110 F60\nG2 X130 Y0 I10 J0 F6000\n",
                                  lim);
  EXPECT_EQ(r[PathCheck::kJointVelocity].first.line, 3u);
  // Inside the arc the centripetal joint acceleration at 100 mm/s is far above 50 mm/s².
  EXPECT_EQ(r[PathCheck::kJointAcceleration].first.line, 5u);
}

}  // namespace PKM_TEST_NS
