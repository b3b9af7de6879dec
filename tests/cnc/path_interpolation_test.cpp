// Interpolation of motions against closed forms: arc chords within the sagitta tolerance, exact
// end points, points on the circle, helix pitch, multi-turn sweeps, line steps, bad options.
#include "pkm/cnc/path_interpolation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
using pkm::test::kTolExact;
using pkm::test::kTolRoundTrip;

constexpr double kTol = 0.01;  // mm, chordal tolerance of these tests

std::vector<PathPoint> interpolate(const char* text, const InterpolationOptions& o) {
  const Program p = Program::parse(text, "t.ngc");
  MoveCollector moves;
  Interpreter interp;
  (void)interp.run(p, moves);
  PathInterpolator cut(o, moves.moves.front().end);
  std::vector<PathPoint> pts;
  for (std::size_t m = 0; m < moves.moves.size(); ++m)
    cut.append(moves.moves[m], static_cast<std::uint32_t>(m), pts);
  return pts;
}

TEST(ArcSteps, SagittaOfEveryChordWithinTolerance) {
  for (double r : {0.5, 3.0, 25.0, 400.0}) {
    for (double sweep : {0.3, std::numbers::pi, 2 * std::numbers::pi, 7.0}) {
      const std::size_t n = arcSteps(r, sweep, kTol);
      const double step = sweep / static_cast<double>(n);
      EXPECT_LE(r * (1 - std::cos(step / 2)), kTol * (1 + kTolRoundTrip)) << r << " " << sweep;
      if (n > 1) {  // one step fewer would break the tolerance (the count is minimal)
        const double coarser = sweep / static_cast<double>(n - 1);
        EXPECT_GT(r * (1 - std::cos(coarser / 2)), kTol * (1 - kTolRoundTrip));
      }
    }
  }
}

TEST(ArcSweep, DirectionsAndTurns) {
  const double pi = std::numbers::pi;
  EXPECT_NEAR(arcSweep(0, pi / 2, 1), pi / 2, kTolExact);
  EXPECT_NEAR(arcSweep(0, pi / 2, -1), -1.5 * pi, kTolExact);
  EXPECT_NEAR(arcSweep(1.0, 1.0, 1), 2 * pi, kTolExact);    // full circle
  EXPECT_NEAR(arcSweep(1.0, 1.0, -2), -4 * pi, kTolExact);  // two clockwise turns
  EXPECT_NEAR(arcSweep(pi / 2, 0, 3), 1.5 * pi + 4 * pi, kTolExact);
}

TEST(PathInterpolator, MovesThatGoNowhereAddNoPoint) {
  InterpolationOptions o;
  o.tolerance = kTol;
  const char* const still = "G0 X0 Y0 Z200\nG1 F150\nG1 X10\nG1 F200\nG0\nM2\n";
  EXPECT_EQ(interpolate(still, o).size(), 5u);  // by default one point per motion
  o.skip_still_moves = true;
  const auto with = interpolate(still, o);
  const auto without = interpolate("G0 X0 Y0 Z200\nF150\nG1 X10\nM2\n", o);
  ASSERT_EQ(with.size(), without.size());
  ASSERT_EQ(with.size(), 2u);  // the first point, then X10
  for (std::size_t i = 1; i < with.size(); ++i) EXPECT_NE(with[i].pos, with[i - 1].pos);
}

TEST(PathInterpolator, APathAboveTheLimitIsRefusedBeforeItsPointsAreMade) {
  InterpolationOptions o;
  o.tolerance = kTol;
  o.max_points = 1000;
  const Program p = Program::parse("G0 X10 Y0 Z200\nG2 X10 Y0 I-10 J0 P100000000 F600\n", "h.ngc");
  MoveCollector moves;
  Interpreter interp;
  (void)interp.run(p, moves);
  PathInterpolator cut(o, moves.moves.front().end);
  std::vector<PathPoint> pts;
  cut.append(moves.moves[0], 0, pts);
  try {
    cut.append(moves.moves[1], 1, pts);
    FAIL() << "made a path of a hundred million turns";
  } catch (const PathTooLong& e) {
    EXPECT_GT(e.needed, 1'000'000'000u);  // about 70 points per turn at 0.01 mm on r = 10 mm
    EXPECT_EQ(e.limit, 1000u);
  }
  EXPECT_EQ(pts.size(), 1u);  // nothing added
  // Lengths far beyond any count saturate instead of overflowing.
  EXPECT_EQ(arcSteps(1.0, 1e300, kTol), static_cast<std::size_t>(1e18));
}

TEST(PathInterpolator, ArcPointsOnCircleWithExactEnd) {
  InterpolationOptions o;
  o.tolerance = kTol;
  const auto pts = interpolate("G0 X10 Y0\nG3 X-10 Y0 I-10 J0 F600\n", o);
  ASSERT_GT(pts.size(), 3u);
  EXPECT_EQ(pts.back().pos[0], -10.0);  // the programmed end, not a computed one
  EXPECT_EQ(pts.back().pos[1], 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) {
    EXPECT_NEAR(std::hypot(pts[i].pos[0], pts[i].pos[1]), 10.0, kTolRoundTrip);
    EXPECT_GE(pts[i].pos[1], -kTolRoundTrip);  // G3 from +X to -X goes through +Y
    EXPECT_EQ(pts[i].line, 2u);
    // Chord midpoint to circle: the sagitta.
    const double mx = 0.5 * (pts[i].pos[0] + pts[i - 1].pos[0]);
    const double my = 0.5 * (pts[i].pos[1] + pts[i - 1].pos[1]);
    EXPECT_LE(10.0 - std::hypot(mx, my), kTol * (1 + kTolRoundTrip));
  }
  EXPECT_EQ(pts.size() - 1, arcSteps(10.0, std::numbers::pi, kTol));
}

TEST(PathInterpolator, HelixPitchAndRotaryLinearInAngle) {
  InterpolationOptions o;
  o.tolerance = kTol;
  // Two full turns (P2) of radius 5 rising 8 mm: pitch 4 mm per turn; C turns 90 degrees.
  const auto pts = interpolate("G0 X5 Y0 Z0\nG2 X5 Y0 Z8 I-5 J0 P2 C90 F600\n", o);
  const double pitch = 4.0;
  double unwrapped = 0.0, prev = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) {
    const double a = std::atan2(pts[i].pos[1], pts[i].pos[0] - 0.0);
    double d = a - prev;
    while (d > std::numbers::pi) d -= 2 * std::numbers::pi;
    while (d < -std::numbers::pi) d += 2 * std::numbers::pi;
    unwrapped += d;
    prev = a;
    const double turns = -unwrapped / (2 * std::numbers::pi);  // clockwise
    EXPECT_NEAR(pts[i].pos[2], pitch * turns, kTolRoundTrip) << i;
    EXPECT_NEAR(pts[i].pos[5], 90.0 * turns / 2.0, kTolRoundTrip) << i;
  }
  EXPECT_NEAR(unwrapped, -4 * std::numbers::pi, kTolRoundTrip);
  EXPECT_EQ(pts.back().pos[2], 8.0);
}

TEST(PathInterpolator, LineStepsAndRotaryStep) {
  InterpolationOptions o;
  o.max_step = 3.0;
  o.max_angle_step = 2.0;
  const auto pts = interpolate("G0 X0\nG1 X10 F100\nG1 A9\n", o);
  // Line 2: ceil(10/3) = 4 equal steps; line 3: ceil(9/2) = 5 steps.
  ASSERT_EQ(pts.size(), 1u + 4u + 5u);
  EXPECT_NEAR(pts[1].pos[0], 2.5, kTolExact);
  EXPECT_EQ(pts[4].pos[0], 10.0);
  EXPECT_NEAR(pts[5].pos[3], 1.8, kTolExact);
  EXPECT_EQ(pts[9].pos[3], 9.0);
  EXPECT_EQ(pts[9].line, 3u);
  EXPECT_EQ(pts[9].move, 2u);
}

TEST(PathInterpolator, RejectsBadOptions) {
  InterpolationOptions o;
  o.tolerance = 0.0;
  EXPECT_THROW(PathInterpolator{o}, pkm::InvalidArgument);
  o.tolerance = kTol;
  o.max_step = -1.0;
  EXPECT_THROW(PathInterpolator{o}, pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
