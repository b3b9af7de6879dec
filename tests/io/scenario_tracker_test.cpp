// Scenario files with laser-tracker measurements and Cartesian actuation
// (src/io/scenario_tracker.*): the seed004 tracker sets, the tracker frame and the actuation in
// truth.json, and located errors.
#include "io/scenario_tracker.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/scenario.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace sim = pkm::simulation;
using pkm::test::kTolExact;
using ::testing::HasSubstr;

/// A hexapod scenario with `measurement` as its only measurement.
std::string hexapodScenario(const std::string& measurement) {
  return "{\"type\": \"simulation_scenario\",\n \"machine\": {\"kind\": \"hexapod\"},\n"
         " \"measurements\": [\n" +
         measurement + "\n]}\n";
}

std::string errorOf(const std::string& text) {
  try {
    (void)io::parseScenarioJson(text, "s.json");
  } catch (const pkm::IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return {};
}

TEST(ScenarioTracker, Seed004HasTheCalibrationAndHeldOutSets) {
  const io::Scenario s = io::loadScenario("seed004-hexapod-calibration");
  ASSERT_EQ(s.campaign.trackers.size(), 3U);
  const sim::TrackerSetup& fit = s.campaign.trackers[0];
  EXPECT_EQ(fit.mode, sim::TrackerMode::kPose);
  EXPECT_EQ(fit.random_count, 200);
  EXPECT_EQ(s.campaign.trackers[1].random_count, 50);
  EXPECT_EQ(s.campaign.trackers[2].mode, sim::TrackerMode::kPoint);
  EXPECT_EQ(s.campaign.trackers[2].poses.size(), 5U);
  EXPECT_DOUBLE_EQ(fit.random_box.hi[5], pkm::degToRad(20.0));  // degrees in the file
  EXPECT_EQ(fit.world_T_tracker.translation(), Eigen::Vector3d(1500, -900, 350));
  const auto results = sim::runLaserTrackers(s.campaign, s.seed);
  ASSERT_EQ(results.size(), 3U);
  EXPECT_EQ(results[0].readings.size(), 200U);
  EXPECT_EQ(results[1].readings.size(), 50U);
  EXPECT_EQ(results[2].readings.size(), 105U);
  // The held-out poses differ from the fitted ones (their own random stream).
  EXPECT_FALSE(results[0].readings[0].command == results[1].readings[0].command);
  // The tracker sees the target about 1.7 m away, with the noise of a few µm the data promise.
  const double range = results[0].readings[0].truth.translation().norm();
  constexpr double kNearMm = 1200.0, kFarMm = 2300.0;
  EXPECT_GT(range, kNearMm);
  EXPECT_LT(range, kFarMm);
  constexpr double kFewMicrons = 0.005;  // mm
  EXPECT_LT(fit.noise.rangeSigma(range), kFewMicrons);
  EXPECT_LT(fit.noise.angle_sigma * range, kFewMicrons);
  // truth.json gives the tracker placement.
  const nlohmann::json t = nlohmann::json::parse(io::truthJson(s, s.seed));
  ASSERT_EQ(t["laser_trackers"].size(), 3U);
  const nlohmann::json& tr = t["laser_trackers"][0];
  EXPECT_EQ(tr["name"], "tracker-pose");
  EXPECT_EQ(tr["world_T_tracker"]["position"][0], 1500.0);
  EXPECT_NEAR(tr["world_T_tracker"]["rpy_deg"][2].get<double>(), 150.0, kTolExact);
  EXPECT_NEAR(tr["world_T_tracker"]["matrix"][0][0].get<double>(),
              fit.world_T_tracker.matrix()(0, 0),
              kTolExact);
  EXPECT_EQ(tr["smr_offset"][2], 80.0);
  EXPECT_EQ(tr["noise"]["orientation_sigma_urad"], 20.0);
  EXPECT_EQ(t["actuation"]["repeatability_sigma"], 0.002);  // the hexapod part is unchanged
}

TEST(ScenarioTracker, CartesianActuationIsReadAndInTheTruth) {
  const std::string text =
      "{\"type\": \"simulation_scenario\",\n"
      " \"machine\": {\"kind\": \"cartesian\", \"actuation\": {\"backlash\": [0.004, 0.002, 0],\n"
      "   \"repeatability_sigma\": [0, 0, 0.001]}},\n"
      " \"measurements\": [{\"name\": \"linear-x\", \"quantity\": \"linear\",\n"
      "   \"from\": [0, 0, 0], \"to\": [100, 0, 0], \"targets\": 5, \"runs\": 2, \"overshoot\": "
      "2}]}\n";
  const io::Scenario s = io::parseScenarioJson(text, "s.json");
  const auto& m = dynamic_cast<const sim::CartesianMachine&>(*s.campaign.machine);
  EXPECT_EQ(m.actuation().backlash, Eigen::Vector3d(0.004, 0.002, 0));
  EXPECT_EQ(m.actuation().repeatability_sigma, Eigen::Vector3d(0, 0, 0.001));
  // The X backlash shows as the ISO 230-2 reversal: the − approach reads b more than the +.
  const auto results = sim::runCampaign(s.campaign, s.seed);
  ASSERT_EQ(results.size(), 1U);
  for (const auto& run : results[0].runs) {
    const auto& r = run.readings;
    ASSERT_EQ(r.size(), 10U);  // 5 targets up, then down
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_NEAR(
          (r[i].reading - r[i].target) - (r[9 - i].reading - r[9 - i].target), -0.004, kTolExact);
  }
  const nlohmann::json t = nlohmann::json::parse(io::truthJson(s, 1));
  EXPECT_EQ(t["actuation"]["backlash"][0], 0.004);
  EXPECT_EQ(t["actuation"]["repeatability_sigma"][2], 0.001);
  EXPECT_THAT(errorOf("{\"type\": \"simulation_scenario\",\n \"machine\": {\"kind\": "
                      "\"cartesian\",\n \"actuation\": {\"backlash\": -1}},\n"
                      " \"measurements\": []}\n"),
              HasSubstr("s.json:3: /machine/actuation: backlash must be finite and >= 0"));
}

TEST(ScenarioTracker, BadTrackerMeasurementsAreLocated) {
  const std::string base = R"({"name": "t", "instrument": "laser_tracker", )";
  EXPECT_THAT(errorOf(hexapodScenario(base + "\n\"poses\": [[0, 0, 200, 0, 0]]}")),
              HasSubstr("s.json:5: /measurements/0/poses/0: expected [x, y, z, a, b, c]"));
  EXPECT_THAT(errorOf(hexapodScenario(base + "\n\"mode\": \"6dof\", \"poses\": []}")),
              HasSubstr("s.json:5: /measurements/0/mode: must be \"pose\""));
  EXPECT_THAT(errorOf(hexapodScenario(base + "\"poses\": []}")),
              HasSubstr("/measurements/0: give \"poses\" or \"random_poses\""));
  EXPECT_THAT(errorOf(hexapodScenario(base + "\n\"random_poses\": {\"count\": 5, \"x\": [0, 1]}}")),
              HasSubstr("/measurements/0/random_poses: missing key 'y'"));
  EXPECT_THAT(
      errorOf(hexapodScenario(base + "\"poses\": [[0, 0, 200, 0, 0, 0]],\n\"noise\": \"xl80\"}")),
      HasSubstr("s.json:5: /measurements/0/noise: unknown tracker noise 'xl80'"));
  EXPECT_THAT(errorOf(hexapodScenario(base + "\"poses\": [[0, 0, 200, 0, 0, 0]],\n\"smr\": 1}")),
              HasSubstr("s.json:5: /measurements/0/smr: unknown key 'smr'"));
  EXPECT_THAT(errorOf(hexapodScenario(base + "\"poses\": [[0, 0, 200, 0, 0, 0]]},\n" + base +
                                      "\"poses\": [[0, 0, 200, 0, 0, 0]]}")),
              HasSubstr("two measurements are named 't'"));
  EXPECT_THAT(errorOf("{\"type\": \"simulation_scenario\",\n \"machine\": {\"kind\": "
                      "\"cartesian\"},\n \"measurements\": [" +
                      base + "\"poses\": [[0, 0, 200, 0, 0, 0]]}]}\n"),
              HasSubstr("t: a laser tracker measurement needs a hexapod"));
}

}  // namespace PKM_TEST_NS

namespace pkm::io {
namespace PKM_TEST_NS {

TEST(ScenarioExechonTracker, BuiltinParsesRunsAndWritesTruth) {
  const Scenario s = loadScenario("exechon-calibration");
  ASSERT_EQ(s.campaign.exechon_trackers.size(), 2u);
  const auto& t = s.campaign.exechon_trackers[0];
  EXPECT_EQ(t.name, "tracker-fit");
  EXPECT_EQ(t.count, 200);
  EXPECT_NEAR(t.max_tilt, degToRad(30.0), 1e-15);
  EXPECT_EQ(t.smr_offset, Eigen::Vector3d(40, 0, 0));
  EXPECT_EQ(t.world_T_tracker.translation(), Eigen::Vector3d(1500, -1200, 400));
  const auto results = simulation::runExechonTrackers(s.campaign, s.seed);
  ASSERT_EQ(results.size(), 2u);
  EXPECT_EQ(results[1].readings.size(), 50u);
  const std::string truth = truthJson(s, s.seed);
  EXPECT_NE(truth.find("\"exechon_trackers\""), std::string::npos);
  EXPECT_NE(truth.find("\"tripod_errors\""), std::string::npos);
  const nlohmann::json parsed = nlohmann::json::parse(truth);
  ASSERT_TRUE(parsed.contains("exechon_trackers"));
  EXPECT_EQ(parsed["exechon_trackers"][1]["name"], "tracker-holdout");
}

TEST(ScenarioExechonTracker, NeedsAHybridMachineWithTripodErrors) {
  const std::string text = R"({"type": "simulation_scenario", "machine": {"kind": "hybrid"},
    "measurements": [{"name": "t", "instrument": "laser_tracker", "count": 3,
                      "box": {"x": [0, 1], "y": [0, 1], "z": [0, 1]}}]})";
  try {
    (void)parseScenarioJson(text, "s.json");
    ADD_FAILURE() << "expected an error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("tripod_errors"), std::string::npos) << e.what();
  }
  const std::string bad_box = R"({"type": "simulation_scenario", "machine": {"kind": "hybrid",
    "tripod_errors": {"dA": 1}},
    "measurements": [{"name": "t", "instrument": "laser_tracker", "count": 3,
                      "box": {"x": [2, 1], "y": [0, 1], "z": [0, 1]}}]})";
  EXPECT_THROW((void)parseScenarioJson(bad_box, "s.json"), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
