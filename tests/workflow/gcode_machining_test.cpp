// The machining preview of a run: examples/gcode/sphere.ngc's finished surface against the
// sphere it machines, the tools from the table, the auto stock, collisions on a hexapod, frames
// that replay to the part, bad requests.
#include "pkm/workflow/gcode_machining.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <numbers>
#include <sstream>

#include "pkm/core/error.hpp"
#include "pkm/workflow/gcode_run.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// The ball rolls on the tool-centre sphere: it touches the part's sphere and never enters it,
/// but for the chords the run cuts its arcs into (the chordal tolerance, 0.01 mm) and the float
/// heights; measured along the sphere's normal (on the steep flanks a vertical error is many
/// times the normal one), mm.
constexpr double kTolGouge = 0.011;
/// The sagitta of a 7.5° chord of the 23 mm tool-centre circle, 23·(1 − cos 3.75°), mm.
constexpr double kTolLevelStep = 0.05;
/// Near a level's contact circle the cut surface is the ball's, tangent to the sphere there: they
/// part by δ²·(1/3 − 1/20)/2 at δ along the meridian, 1.4e-3 mm at δ = 0.1 mm, plus the chords
/// as above, mm.
constexpr double kTolContact = 0.012;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

GcodeRunRequest sphereRun(double cell) {
  GcodeRunRequest r;
  const std::string path = std::string(PKM_SOURCE_DIR) + "/examples/gcode/sphere.ngc";
  r.program = {path, slurp(path)};
  r.machine = "hexapod-default";
  r.interpreter.tool_table = std::string(PKM_SOURCE_DIR) + "/examples/gcode/tools.tbl";
  r.machining.emplace();
  r.machining->stock = "box";
  r.machining->box = {25.0, 15.0, -10.0, 75.0, 65.0, 20.0};  // around the 20 mm sphere
  r.machining->cell = cell;
  r.machining->frames = 50;
  r.path_points = 1000;
  return r;
}

TEST(GcodeMachining, TheSphereIsFinishedWithoutGouging) {
  const GcodeRunResult r = runGcode(sphereRun(0.1));
  ASSERT_TRUE(r.machining);
  const MachiningReport& m = *r.machining;
  ASSERT_EQ(m.tools.size(), 1u);
  EXPECT_EQ(m.tools[0].tool.end, cnc::ToolEnd::kBall);  // ";6 mm ball-end mill" in tools.tbl
  EXPECT_DOUBLE_EQ(m.tools[0].tip_offset, 50.0);
  EXPECT_TRUE(m.result.events.empty());
  const double R = 20.0;
  std::size_t on_sphere = 0;
  for (std::size_t j = 0; j < m.ny; ++j)
    for (std::size_t i = 0; i < m.nx; ++i) {
      const double x = m.x0 + (static_cast<double>(i) + 0.5) * m.cell - 50.0;
      const double y = m.y0 + (static_cast<double>(j) + 0.5) * m.cell - 40.0;
      const double d = std::hypot(x, y);
      if (d >= R) continue;
      const double h = m.heights[j * m.nx + i];
      const double radial = std::hypot(d, h);  // the surface point's distance from the centre
      // The straight feeds from level to level (line 19) run along y = 40, x > 50: chords 7.5°
      // long of the tool-centre circle, which cut up to its sagitta into the sphere there.
      const bool step = std::abs(y) < 3.5 && x > 0.0;
      ASSERT_GE(radial, R - (step ? kTolLevelStep : kTolGouge)) << "gouge at x " << x << " y " << y;
      // Level k's ball centre circle has elevation 90·k/12 on the tool-centre sphere (radius
      // 23): it touches the part at radius 20·cos φ, height 20·sin φ.
      // Where the surface is no steeper than 60° (levels 4..11) a cell within half a cell of the
      // contact circle lies at most 0.1 mm from it along the meridian.
      for (int k = 4; k < 12; ++k) {
        const double phi = std::numbers::pi / 2.0 * k / 12.0;
        if (std::abs(d - R * std::cos(phi)) < m.cell / 2.0 && std::abs(y) > 1.0) {
          EXPECT_NEAR(radial, R, kTolContact) << "level " << k << " x " << x << " y " << y;
          ++on_sphere;
        }
      }
    }
  EXPECT_GT(on_sphere, 1000u);
  // The frames replay to the finished part.
  std::vector<float> replay = m.initial;
  for (const cnc::StockFrame& f : m.result.frames)
    for (std::size_t k = 0; k < f.cells.size(); ++k) replay[f.cells[k]] = f.heights[k];
  EXPECT_EQ(replay, m.heights);
  EXPECT_EQ(m.path_tools.size(), r.path.t.size());
  EXPECT_THAT(machiningText(m), HasSubstr("no collision"));
}

TEST(GcodeMachining, AutoStockAndRapidsThroughIt) {
  GcodeRunRequest r;
  r.program = {"cut.ngc",
               "G21 G90 G17\nG0 X0 Y0 Z210\nG1 Z200 F300\nG1 X40\nG0 X-10 Y5\nG0 Z230\nM2\n"};
  r.machine = "hexapod-default";
  r.machining.emplace();
  const GcodeRunResult res = runGcode(r);
  const MachiningReport& m = *res.machining;
  // The default 6 mm tool's tip at the controlled point; the top at the sideways feed (200).
  EXPECT_DOUBLE_EQ(m.stock.top, 200.0);
  EXPECT_DOUBLE_EQ(m.stock.bottom, 195.0);
  EXPECT_DOUBLE_EQ(m.stock.min[0], -8.0);
  EXPECT_DOUBLE_EQ(m.stock.max[0], 48.0);
  EXPECT_TRUE(m.result.events.empty()) << machiningText(m);  // G0 at the top: over the stock
  r.program.text =
      "G21 G90 G17\nG0 X0 Y0 Z210\nG1 Z200 F300\nG1 X40\nG1 Z199\nG1 X0\nG0 X20 Y5\nM2\n";
  const MachiningReport m2 = *runGcode(r).machining;
  // A G0 1 mm below the top leaves the slot the feeds cut and enters the stock beside it.
  ASSERT_EQ(m2.result.events.size(), 1u) << machiningText(m2);
  EXPECT_EQ(m2.result.events[0].kind, "rapid");
  EXPECT_EQ(m2.result.events[0].line, 7u);
  EXPECT_NEAR(m2.result.events[0].depth, 1.0, 1e-3);
  EXPECT_THAT(machiningText(m2), HasSubstr("COLLISION rapid line 7"));
}

TEST(GcodeMachining, TheExechonsToolPointsDownItsAxis) {
  // The Exechon example: a 50 mm circle at Z0 with a vertical tool, then a pass at Z10 tilted
  // 15°. The tool's solid reaches up the axis from the tip (the drawn direction, spindle to tip,
  // reversed): the circle cuts a groove to Z0, the centre of the ring keeps the top, and nothing
  // reaches the table or puts the holder in the stock.
  GcodeRunRequest r;
  const std::string path = std::string(PKM_SOURCE_DIR) + "/examples/gcode/exechon_contour.ngc";
  r.program = {path, slurp(path)};
  r.machine = "mxt700s-like";
  r.machining.emplace();
  r.machining->cell = 0.5;
  const MachiningReport m = *runGcode(r).machining;
  EXPECT_TRUE(m.result.events.empty()) << machiningText(m);
  const auto at = [&m](double x, double y) {
    const auto i = static_cast<std::size_t>((x - m.x0) / m.cell);
    const auto j = static_cast<std::size_t>((y - m.y0) / m.cell);
    return m.heights[j * m.nx + i];
  };
  EXPECT_NEAR(at(25.1, 0.1), 0.0, 1e-3);         // on the circle: down to the tip
  EXPECT_NEAR(at(0.1, 0.1), m.stock.top, 1e-3);  // inside the ring: untouched
}

TEST(GcodeMachining, BadRequestsAreRefused) {
  MachiningRequest q;
  EXPECT_THROW(setStock(q, "box:1,2,3"), InvalidArgument);
  EXPECT_THROW(setStock(q, "sphere:1,2,3,4,5"), InvalidArgument);
  EXPECT_THROW(setStock(q, "box:1,2,3,4,5,x"), InvalidArgument);
  setStock(q, "cylinder:1,2,3,4,5");
  EXPECT_EQ(q.stock, "cylinder");
  EXPECT_DOUBLE_EQ(q.cylinder[2], 3.0);
  q.stock = "cone";
  EXPECT_THROW(q.validate(), InvalidArgument);
  GcodeRunRequest r = sphereRun(0.0);
  r.interpreter.tool_table_text = "T1 Z50 ;no diameter\n";
  r.interpreter.tool_table.clear();
  try {
    (void)runGcode(r);
    FAIL() << "a tool without a diameter was accepted";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("tool T1: the diameter must be > 0"));
  }
  r = sphereRun(0.001);  // 50 000 x 50 000 cells
  EXPECT_THROW((void)runGcode(r), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
