// The composite machining commands' G-code: the sphere against its geometry (interpreted and
// interpolated: the ball never enters the sphere, and reaches it at every level), the other
// shapes' moves, whole programs the interpreter accepts, bad parameters.
#include "pkm/cnc/shapes.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/path_interpolation.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

/// The chordal tolerance the path is cut with: a chord lies this far inside its arc at most, mm.
constexpr double kTolChord = 0.01;
/// Coordinates are written with 4 decimals, mm.
constexpr double kTolWritten = 1e-4;

/// The interpolated points of `program`.
std::vector<PathPoint> pointsOf(const std::string& program) {
  Interpreter interp;
  MoveCollector c;
  interp.run(Program::parse(program, "shape.ngc"), c);
  InterpolationOptions o;
  o.tolerance = kTolChord;
  o.max_step = 0.5;
  PathInterpolator p(o);
  std::vector<PathPoint> out;
  for (std::size_t i = 0; i < c.moves.size(); ++i)
    p.append(c.moves[i], static_cast<std::uint32_t>(i), out);
  return out;
}

TEST(Shapes, TheSphereIsItsOwnGeometry) {
  const ShapeSpec s{"sphere", {{"radius", 10}, {"z", 190}, {"tool_radius", 2}, {"levels", 2}}};
  EXPECT_THAT(shapeLines(s),
              ElementsAre("G0 X12 Y0 Z205",
                          "G1 Z188",
                          "G17 G3 X12 Y0 I-12 J0",
                          "G18 G2 X8.4853 Z196.4853 I-12 K0",
                          "G17 G3 X8.4853 Y0 I-8.4853 J0",
                          "G18 G2 X0 Z200 I-8.4853 K-8.4853",
                          "G17 G0 Z205"));
  // Interpreted and interpolated, the ball (centre 2 mm above the tip) never enters the sphere of
  // radius 12 about (0, 0, 190) and touches it all along the cut.
  const ShapeSpec big{"sphere", {{"radius", 20}, {"x", 5}, {"y", -3}, {"z", 100}, {"levels", 7}}};
  double closest = 1e9, lowest = 1e9;
  std::size_t on = 0;
  for (const PathPoint& p : pointsOf(shapeProgram(big))) {
    if (p.kind == MoveKind::kRapid) continue;  // the approach from wherever the machine is
    const double d = std::hypot(p.pos[0] - 5.0, p.pos[1] + 3.0, p.pos[2] + 3.0 - 100.0);
    closest = std::min(closest, d);
    lowest = std::min(lowest, p.pos[2] + 3.0);
    if (std::abs(d - 23.0) < kTolChord) ++on;
  }
  EXPECT_GE(closest, 23.0 - kTolChord - kTolWritten);
  EXPECT_GT(on, 200u);
  // The meridian arcs go up the short way (G2 in G18 turns from X towards Z), never under it.
  EXPECT_GE(lowest, 100.0 - kTolWritten);
}

TEST(Shapes, PocketDrillAndFace) {
  const auto pocket = shapeLines(
      {"pocket", {{"radius", 10}, {"depth", 3}, {"stepover", 4}, {"stepdown", 2}, {"top", 50}}});
  // Two passes (48, then the bottom 47), each with circles of radius 4, 8 and 10.
  EXPECT_EQ(pocket.size(), 1u + 2u * (1u + 3u * 2u) + 1u);
  EXPECT_EQ(pocket[1], "G1 X0 Y0 Z48");
  EXPECT_EQ(pocket[8], "G1 X0 Y0 Z47");
  EXPECT_EQ(pocket[14], "G3 X10 Y0 I-10 J0");
  const auto drill = shapeLines({"drill", {{"holes", 4}, {"radius", 10}, {"top", 0}}});
  ASSERT_EQ(drill.size(), 12u);
  EXPECT_EQ(drill[3], "G0 X0 Y10 Z2");
  EXPECT_EQ(drill[4], "G1 Z-8");
  const auto face = shapeLines({"face", {{"y0", 0}, {"y1", 25}, {"step", 10}}});
  EXPECT_THAT(face,
              ElementsAre("G0 X-30 Y0 Z197",
                          "G1 Z195",
                          "G1 Y0",
                          "G1 X30",
                          "G1 Y10",
                          "G1 X-30",
                          "G1 Y20",
                          "G1 X30",
                          "G1 Y25",
                          "G1 X-30",
                          "G0 Z197"));
  for (const std::string& kind : shapeKinds())
    EXPECT_FALSE(pointsOf(shapeProgram({kind, {}})).empty()) << kind;
}

TEST(Shapes, BadParametersAreNamed) {
  const auto message = [](const ShapeSpec& s) {
    try {
      (void)shapeLines(s);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(message({"cube", {}}), HasSubstr("unknown shape 'cube'"));
  EXPECT_THAT(message({"sphere", {{"radius_mm", 3}}}), HasSubstr("unknown parameter 'radius_mm'"));
  EXPECT_THAT(message({"sphere", {{"levels", 1.5}}}), HasSubstr("levels must be a whole number"));
  EXPECT_THAT(message({"sphere", {{"tool_radius", 0}}}), HasSubstr("tool_radius must be > 0"));
  EXPECT_THAT(message({"pocket", {{"stepover", 1e-6}}}), HasSubstr("choose a larger step"));
  EXPECT_THAT(message({"face", {{"x1", -40}}}), HasSubstr("x1 and y1 must be >= x0 and y0"));
  EXPECT_THAT(message({"drill", {{"depth", std::nan("")}}}), HasSubstr("finite"));
  EXPECT_THROW((void)shapeProgram({"face", {}}, 0.0), InvalidArgument);
  EXPECT_EQ(shapeParameters("drill").front().name, "holes");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
