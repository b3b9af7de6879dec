// The machining preview: removed volumes against closed forms, collisions, the frames.
#include "pkm/cnc/machining.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

/// A slot's volume on 0.1 mm cells: the cells cut along its outline, relative.
constexpr double kTolSlotVolume = 0.01;
/// A collision's depth: the height field's float heights and the sampling, mm.
constexpr double kTolDepth = 1e-3;

StockShape block() {
  StockShape s;
  s.min = {0.0, 0.0};
  s.max = {100.0, 50.0};
  s.bottom = 0.0;
  s.top = 20.0;
  return s;
}

CuttingTool tool(double d, ToolEnd end) {
  CuttingTool t;
  t.diameter = d;
  t.length = 40.0;
  t.end = end;
  return t;
}

const std::array<double, 3> kDown{0.0, 0.0, 1.0};

/// A slot from X20 to X80 at Y25, `depth` deep, cut with `t`; the volume removed.
double slot(const CuttingTool& t, double depth) {
  MachiningSimulator sim(block(), 0.1, {});
  sim.setTool(t);
  sim.moveTo({{20.0, 25.0, 30.0}, kDown}, 0.0, 1, true);
  sim.moveTo({{20.0, 25.0, 20.0 - depth}, kDown}, 1.0, 2, false);
  sim.moveTo({{80.0, 25.0, 20.0 - depth}, kDown}, 2.0, 3, false);
  sim.moveTo({{80.0, 25.0, 30.0}, kDown}, 3.0, 4, true);
  const MachiningResult r = sim.finish();
  EXPECT_TRUE(r.events.empty());
  return r.initial_volume - r.final_volume;
}

TEST(Machining, AFlatEndSlotRemovesItsVolume) {
  // A 10 mm flat end mill 2 mm deep over 60 mm: a box and two half discs.
  const double expected = 2.0 * (10.0 * 60.0 + std::numbers::pi * 25.0);
  EXPECT_NEAR(slot(tool(10.0, ToolEnd::kFlat), 2.0), expected, kTolSlotVolume * expected);
}

TEST(Machining, ABallEndSlotRemovesItsVolume) {
  // A 10 mm ball 2 mm deep: a circular segment swept 60 mm and a spherical cap at the two ends.
  const double r = 5.0, d = 2.0;
  const double segment = r * r * std::acos((r - d) / r) - (r - d) * std::sqrt(2.0 * r * d - d * d);
  const double cap = std::numbers::pi * d * d * (3.0 * r - d) / 3.0;
  const double expected = segment * 60.0 + cap;
  EXPECT_NEAR(slot(tool(10.0, ToolEnd::kBall), d), expected, kTolSlotVolume * expected);
}

TEST(Machining, ATiltedFlatEndCutsWithItsRim) {
  // Tilted 30° about Y, a flat end mill's lowest point is its rim, r·sin 30° below the tip.
  MachiningSimulator sim(block(), 0.1, {});
  sim.setTool(tool(10.0, ToolEnd::kFlat));
  const double s = std::sin(std::numbers::pi / 6.0), c = std::cos(std::numbers::pi / 6.0);
  sim.moveTo({{50.0, 25.0, 21.0}, {s, 0.0, c}}, 0.0, 1, false);
  double lowest = 20.0;
  for (const float h : sim.stock().heights()) lowest = std::min(lowest, static_cast<double>(h));
  EXPECT_NEAR(lowest, 21.0 - 5.0 * s, 0.1 * s + kTolDepth);  // within a cell's slope
}

TEST(Machining, RapidsHoldersAndTheTableAreCollisions) {
  MachiningOptions o;
  MachiningSimulator sim(block(), 0.5, o);
  CuttingTool short_tool = tool(6.0, ToolEnd::kFlat);
  short_tool.length = 10.0;
  sim.setTool(short_tool);
  sim.moveTo({{10.0, 10.0, 30.0}, kDown}, 0.0, 1, true);
  sim.moveTo({{10.0, 10.0, 18.0}, kDown}, 1.0, 2, true);   // a G0 2 mm into the stock
  sim.moveTo({{10.0, 10.0, 5.0}, kDown}, 2.0, 3, false);   // the holder 5 mm in
  sim.moveTo({{10.0, 10.0, -1.0}, kDown}, 3.0, 4, false);  // 1 mm into the table
  const MachiningResult r = sim.finish();
  const auto find = [&r](const std::string& kind, std::size_t line) {
    for (const MachiningEvent& e : r.events)
      if (e.kind == kind && e.line == line) return e;
    ADD_FAILURE() << "no " << kind << " event on line " << line;
    return MachiningEvent{};
  };
  ASSERT_EQ(r.events.size(), 4u);  // and no rapid collision on the feed lines
  EXPECT_NEAR(find("rapid", 2).depth, 2.0, kTolDepth);
  EXPECT_NEAR(find("holder", 3).depth, 5.0, kTolDepth);
  EXPECT_NEAR(find("holder", 4).depth, 11.0, kTolDepth);
  EXPECT_NEAR(find("table", 4).depth, 1.0, kTolDepth);
  EXPECT_NEAR(find("table", 4).tip[2], -1.0, kTolDepth);
  EXPECT_GT(r.event_counts.at("rapid"), 1u);
}

TEST(Machining, APartBelowTheSurfaceCollides) {
  MachiningSimulator sim(block(), 1.0, {});
  sim.checkPart("platform", {{10, 10, 25}, {40, 10, 25}, {40, 40, 25}, {10, 40, 25}}, 0.0, 1);
  sim.checkPart("platform", {{10, 10, 18}, {40, 10, 19}, {40, 40, 19}, {10, 40, 18}}, 1.0, 2);
  const MachiningResult r = sim.finish();
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, "platform");
  EXPECT_EQ(r.events[0].line, 2u);
  EXPECT_NEAR(r.events[0].depth, 2.0, 0.05);  // at the low edge's cell centres
}

TEST(Machining, FramesReplayToTheFinishedPart) {
  MachiningOptions o;
  o.frame_times = {0.5, 1.0, 1.5, 2.0, 3.0};
  MachiningSimulator sim(block(), 0.25, o);
  sim.setTool(tool(6.0, ToolEnd::kBall));
  sim.moveTo({{10.0, 10.0, 25.0}, kDown}, 0.0, 1, true);
  sim.moveTo({{10.0, 10.0, 17.0}, kDown}, 1.0, 2, false);
  sim.moveTo({{60.0, 30.0, 16.0}, kDown}, 2.0, 3, false);
  sim.moveTo({{60.0, 30.0, 25.0}, kDown}, 3.0, 4, false);
  std::vector<float> replay(sim.stock().heights().size(), 20.0f);
  const MachiningResult r = sim.finish();
  EXPECT_TRUE(r.frames_complete);
  ASSERT_EQ(r.frames.size(), 5u);
  EXPECT_TRUE(r.frames[0].cells.empty());  // still above the stock at 0.5 s
  for (const StockFrame& f : r.frames)
    for (std::size_t k = 0; k < f.cells.size(); ++k) replay[f.cells[k]] = f.heights[k];
  EXPECT_EQ(replay, sim.stock().heights());
  o.max_changes = 10;
  MachiningSimulator capped(block(), 0.25, o);
  capped.setTool(tool(6.0, ToolEnd::kBall));
  capped.moveTo({{10.0, 10.0, 17.0}, kDown}, 0.0, 1, false);
  capped.moveTo({{60.0, 30.0, 16.0}, kDown}, 3.0, 2, false);
  EXPECT_FALSE(capped.finish().frames_complete);
}

TEST(Machining, BadOptionsAreRefused) {
  MachiningOptions o;
  o.frame_times = {1.0, 1.0};
  EXPECT_THROW(MachiningSimulator(block(), 1.0, o), InvalidArgument);
  o.frame_times.clear();
  o.max_step = -1.0;
  EXPECT_THROW(MachiningSimulator(block(), 1.0, o), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
