// Touch-probe files and the "touch_probe" scenario measurement: the CSV written is read back
// through TextTable with every number exact; the scenario reader's defaults, truth.json and errors.
#include "pkm/io/probe_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/scenario.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace sim = pkm::simulation;
using ::testing::HasSubstr;

const char* kScenario = R"({
  "type": "simulation_scenario",
  "name": "probe-mini",
  "machine": {"kind": "hybrid"},
  "measurements": [
    {"name": "tp", "instrument": "touch_probe", "circle_points": 8, "runs": 2,
     "noise": {"sigma": 0.000125}}
  ]
})";

TEST(ProbeFiles, WrittenNumbersReadBackExactly) {
  const io::Scenario s = io::parseScenarioJson(kScenario, "s.json");
  ASSERT_EQ(s.campaign.probes.size(), 1u);
  const sim::TouchProbeSetup& setup = s.campaign.probes[0];
  EXPECT_EQ(setup.circle_points, 8);
  EXPECT_EQ(setup.ring_diameter, 40.001);  // defaults: seed 003
  EXPECT_EQ(setup.stylus_offset, Eigen::Vector2d(-0.210, -0.160));
  const auto runs = sim::runTouchProbes(s.campaign.probes, 7);
  ASSERT_EQ(runs.size(), 1u);
  const auto files = io::touchProbeFiles("probe-mini", 7, setup, runs[0].result);
  ASSERT_EQ(files.size(), 3u);
  EXPECT_EQ(files[0].first, "tp_offset.csv");
  EXPECT_EQ(files[2].first, "tp_circle_compensated.csv");

  const io::TextTable off = io::TextTable::parse(files[0].second, files[0].first);
  ASSERT_EQ(off.rows(), runs[0].result.offset.size());
  EXPECT_EQ(off.meta("format"), "pkm.touch-probe/1");
  for (std::size_t r = 0; r < off.rows(); ++r) {
    const sim::TouchRecord& t = runs[0].result.offset[r];
    EXPECT_EQ(off.text(r, off.column({"touch"})), t.touch);
    EXPECT_EQ(off.number(r, off.column({"x"})), t.position.x());
    EXPECT_EQ(off.number(r, off.column({"y"})), t.position.y());
    EXPECT_EQ(off.number(r, off.column({"spindle_deg"})), pkm::radToDeg(t.spindle));
  }
  const io::TextTable circ = io::TextTable::parse(files[2].second, files[2].first);
  ASSERT_EQ(circ.rows(), 16u);
  for (std::size_t r = 0; r < circ.rows(); ++r) {
    const Eigen::Vector2d p =
        sim::reportedSurfacePoint(setup, runs[0].result.circle_compensated[r]);
    EXPECT_EQ(circ.number(r, circ.column({"x"})), p.x());
    EXPECT_EQ(circ.number(r, circ.column({"y"})), p.y());
  }
}

TEST(ProbeFiles, TruthJsonCarriesTheInjectedOffset) {
  const io::Scenario s = io::parseScenarioJson(kScenario, "s.json");
  const auto truth = nlohmann::json::parse(io::truthJson(s, 1));
  const auto& tp = truth["touch_probes"][0];
  EXPECT_EQ(tp["name"], "tp");
  EXPECT_EQ(tp["stylus_offset"][0].get<double>(), -0.21);
  EXPECT_EQ(tp["o_probe"][1].get<double>(), 0.16);
  EXPECT_EQ(tp["ball_path_radius"].get<double>(), 40.001 / 2.0 - 3.0);
}

TEST(ProbeFiles, ScenarioErrorsNameThePointer) {
  const auto message = [](std::string text) {
    try {
      (void)io::parseScenarioJson(text, "s.json");
    } catch (const pkm::IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  std::string bad = kScenario;
  bad.replace(bad.find("\"runs\": 2"), 9, "\"runz\": 2");
  EXPECT_THAT(message(bad), HasSubstr("/measurements/0/runz: unknown key"));
  bad = kScenario;
  bad.replace(bad.find("{\"kind\": \"hybrid\"}"), 18, "{\"kind\": \"cartesian\"}");
  EXPECT_THAT(message(bad), HasSubstr("needs a \"hybrid\""));
  bad = kScenario;
  bad.replace(bad.find("\"runs\": 2"), 9, "\"ball_radius\": 30");
  EXPECT_THAT(message(bad), HasSubstr("s.json:6: /measurements/0: tp: the ball radius"));
}

}  // namespace PKM_TEST_NS
