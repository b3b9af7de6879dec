// `pkm simulate seed004-hexapod-calibration` writes the laser-tracker files (the full-pose
// calibration data and held-out poses, and a point file), byte-identical for the same seed, with
// the tracker placement in truth.json; every built-in scenario simulates well under a second.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "pkm/io/scenario.hpp"
#include "pkm/io/tracker_files.hpp"
#include "support/cli_fixture.hpp"

namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using ::testing::StartsWith;

class SimulateTrackerCli : public pkm::test::CliTest {};

TEST_F(SimulateTrackerCli, Seed004WritesTheTrackerFiles) {
  ASSERT_EQ(pkm({"simulate", "seed004-hexapod-calibration", "--out", path("a")}).code, 0);
  ASSERT_EQ(
      pkm({"simulate", "seed004-hexapod-calibration", "--out", path("b"), "--seed", "4"}).code, 0);
  ASSERT_EQ(
      pkm({"simulate", "seed004-hexapod-calibration", "--out", path("c"), "--seed", "5"}).code, 0);
  const std::string pose = slurp(dir_ / "a" / "tracker-pose.csv");
  EXPECT_EQ(pose, slurp(dir_ / "b" / "tracker-pose.csv"));
  EXPECT_NE(pose, slurp(dir_ / "c" / "tracker-pose.csv"));
  EXPECT_THAT(pose, StartsWith("# format: pkm.tracker-pose/1\n"));
  EXPECT_THAT(pose, HasSubstr("\n# seed: 4\n"));
  EXPECT_THAT(pose, HasSubstr("\nl0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n"));
  const pkm::io::TrackerFile fit = pkm::io::readTrackerCsv(path("a/tracker-pose.csv"));
  EXPECT_EQ(fit.mode, pkm::simulation::TrackerMode::kPose);
  EXPECT_EQ(fit.lengths.size(), 200U);
  EXPECT_EQ(pkm::io::readTrackerCsv(path("a/tracker-holdout.csv")).lengths.size(), 50U);
  const pkm::io::TrackerFile point = pkm::io::readTrackerCsv(path("a/tracker-point.csv"));
  EXPECT_EQ(point.mode, pkm::simulation::TrackerMode::kPoint);
  EXPECT_EQ(point.lengths.size(), 105U);
  // The strut readings are on the 1 µm encoder grid and inside the 0..500 mm stroke.
  constexpr double kCountsPerMm = 1000.0, kStrokeMax = 500.0;
  for (const auto& l : fit.lengths)
    for (Eigen::Index i = 0; i < 6; ++i) {
      EXPECT_DOUBLE_EQ(l[i] * kCountsPerMm, std::round(l[i] * kCountsPerMm));
      EXPECT_GE(l[i], 0.0);
      EXPECT_LE(l[i], kStrokeMax);
    }
  const nlohmann::json truth = nlohmann::json::parse(slurp(dir_ / "a" / "truth.json"));
  ASSERT_EQ(truth["laser_trackers"].size(), 3U);
  EXPECT_EQ(truth["laser_trackers"][1]["name"], "tracker-holdout");
  // The dial-gauge and laser files are still there.
  EXPECT_TRUE(std::filesystem::exists(dir_ / "a" / "constrained-motion.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir_ / "a" / "linear-x_run1.csv"));
}

// The time budget (well under a second per scenario) is measured by benchmarks/
// simulate_whole_process.sh, not asserted here; the test prints the times.
TEST_F(SimulateTrackerCli, EveryBuiltinScenarioSimulates) {
  for (const std::string& name : pkm::io::builtinScenarioNames()) {
    const auto start = std::chrono::steady_clock::now();
    const pkm::test::CliRun r = pkm({"simulate", name, "--out", path(name)});
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_EQ(r.code, 0) << r.err;
    std::cerr << name << ": " << seconds << " s\n";
  }
}

TEST_F(SimulateTrackerCli, BadTrackerScenarioExitsWithCode2) {
  write("bad.json",
        "{\"type\": \"simulation_scenario\",\n \"machine\": {\"kind\": \"hexapod\"},\n"
        " \"measurements\": [{\"name\": \"t\", \"instrument\": \"laser_tracker\",\n"
        "   \"random_poses\": {\"count\": 10, \"x\": [0, 1], \"y\": [0, 1], \"z\": [5000, "
        "5001]}}]}\n");
  const pkm::test::CliRun r = pkm({"simulate", path("bad.json"), "--out", path("x")});
  expectUsageError(r, "the box is mostly outside the workspace");
  EXPECT_FALSE(std::filesystem::exists(dir_ / "x"));
}

}  // namespace PKM_TEST_NS
