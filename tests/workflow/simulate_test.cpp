// workflow::simulateScenario / runSimulate: deterministic files per seed, written only when every
// one may be, and the built-in scenarios listed.
#include "pkm/workflow/simulate.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "pkm/core/error.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

using test::slurp;

TEST(SimulateWorkflow, TheSameSeedGivesTheSameFilesAndAnotherSeedOtherReadings) {
  const SimulateResult a = simulateScenario("seed003-probe-offset", std::nullopt);
  const SimulateResult b = simulateScenario("seed003-probe-offset", a.seed);
  const SimulateResult c = simulateScenario("seed003-probe-offset", a.seed + 1);
  EXPECT_EQ(a.scenario, "seed003-probe-offset");
  ASSERT_EQ(a.files.size(), b.files.size());
  ASSERT_EQ(a.files.size(), c.files.size());
  bool differs = false;
  for (std::size_t k = 0; k < a.files.size(); ++k) {
    EXPECT_EQ(a.files[k].name, b.files[k].name);
    EXPECT_EQ(a.files[k].text, b.files[k].text) << a.files[k].name;
    differs = differs || a.files[k].text != c.files[k].text;
  }
  EXPECT_TRUE(differs);
  EXPECT_EQ(a.files[a.files.size() - 2].name, "truth.json");
  EXPECT_EQ(a.files.back().name, "scenario.json");
}

TEST(SimulateWorkflow, WritesEveryFileOrNone) {
  const fs::path dir =
      fs::temp_directory_path() / ("pkm_workflow_simulate_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  SimulateOptions o;
  o.scenario = "seed003-probe-offset";
  o.out = dir;
  const SimulateResult r = runSimulate(o);
  for (const SimulatedFile& f : r.files) EXPECT_EQ(slurp(dir / f.name), f.text) << f.name;
  // A second run refuses, naming the first file that exists, and changes nothing.
  std::ofstream(dir / r.files.back().name) << "the user's edit";
  try {
    (void)runSimulate(o);
    FAIL() << "overwrote without force";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(r.files.front().name + ": exists; refusing to overwrite"));
  }
  EXPECT_EQ(slurp(dir / r.files.back().name), "the user's edit");
  o.force = true;
  (void)runSimulate(o);
  EXPECT_EQ(slurp(dir / r.files.back().name), r.files.back().text);
  fs::remove_all(dir);
}

TEST(SimulateWorkflow, MissingFieldsAndUnknownScenariosAreRefused) {
  SimulateOptions o;
  EXPECT_THROW(o.validate(), IoError);
  o.scenario = "seed003-probe-offset";
  EXPECT_THROW(o.validate(), IoError);
  EXPECT_THROW((void)simulateScenario("no-such-scenario", std::nullopt), IoError);
}

TEST(SimulateWorkflow, ListsTheBuiltInScenarios) {
  const std::vector<ScenarioInfo> list = listScenarios();
  ASSERT_GE(list.size(), 5u);
  for (const ScenarioInfo& s : list) {
    EXPECT_GT(s.measurements, 0u) << s.name;
    EXPECT_FALSE(s.description.empty()) << s.name;
  }
}

TEST(SimulateWorkflow, AScenarioGivenAsTextGivesTheFilesOfItsFile) {
  const SimulateResult a = simulateScenario("seed003-probe-offset", 7);
  // scenario.json is the scenario with its seed: simulated again it gives the same files.
  const SimulateResult b = simulateScenarioText({"mine.json", a.files.back().text}, std::nullopt);
  EXPECT_EQ(b.seed, 7u);
  ASSERT_EQ(a.files.size(), b.files.size());
  for (std::size_t k = 0; k < a.files.size(); ++k) {
    EXPECT_EQ(a.files[k].name, b.files[k].name);
    EXPECT_EQ(a.files[k].text, b.files[k].text) << a.files[k].name;
  }
  try {
    (void)simulateScenarioText(
        {"mine.json", "{\n  \"type\": \"simulation_scenario\",\n  \"x\": 1\n}"}, std::nullopt);
    FAIL() << "accepted an unknown key";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("mine.json:"));
  }
}

/// The text of the file `name` of `r`, or "" when there is none.
std::string fileText(const SimulateResult& r, const std::string& name) {
  for (const SimulatedFile& f : r.files)
    if (f.name == name) return f.text;
  return {};
}

TEST(SimulateWorkflow, TheFrameLineSaysWhereTheTrackerWasAndAPlacedTrackerReadsTheNests) {
  const std::string tracker =
      R"({"name": "t", "instrument": "laser_tracker", "mode": "point",
          "poses": [[0, 0, 200, 0, 0, 0], [100, 0, 200, 0, 0, 0], [0, 100, 250, 0, 0, 0]],
          "noise": {"range_sigma": 0.003}PLACE})";
  const auto scenario = [&](const std::string& place) {
    std::string t = tracker;
    t.replace(t.find("PLACE"), 5, place);
    return R"({"schema": "pkm.scenario/1", "type": "simulation_scenario", "name": "frames",
               "machine": {"kind": "hexapod", "machine": "hexapod-default"},
               "measurements": [)" +
           t + "]}";
  };
  // Without a placement the tracker stands at the world frame: its readings are world data.
  const SimulateResult at_origin = simulateScenarioText({"o.json", scenario("")}, std::nullopt);
  EXPECT_THAT(fileText(at_origin, "t.csv"), HasSubstr("# frame: world ("));
  EXPECT_EQ(fileText(at_origin, "t-registration.csv"), "");
  const SimulateResult placed = simulateScenarioText(
      {"p.json",
       scenario(R"(, "tracker_frame": {"position": [1500, -900, 350], "rpy_deg": [0, 0, 150]})")},
      std::nullopt);
  EXPECT_THAT(fileText(placed, "t.csv"), HasSubstr("# frame: tracker ("));
  const std::string reg = fileText(placed, "t-registration.csv");
  EXPECT_THAT(reg, HasSubstr("# format: pkm.tracker-registration/1\n"));
  EXPECT_THAT(reg, HasSubstr("nest,x_table,y_table,z_table,x,y,z\n1,-500,-500,0,"));
  // The nests' readings have their own stream: the tracker file is the one at the origin's
  // neighbour with the same draws (only the frame differs), and a scenario's own nests are used.
  const SimulateResult own = simulateScenarioText(
      {"n.json",
       scenario(R"(, "tracker_frame": {"position": [1500, -900, 350], "rpy_deg": [0, 0, 150]},
                   "registration_nests": [[0, 0, 0], [300, 0, 0], [0, 300, 10]])")},
      std::nullopt);
  EXPECT_EQ(fileText(own, "t.csv"), fileText(placed, "t.csv"));
  EXPECT_THAT(fileText(own, "t-registration.csv"), HasSubstr("\n3,0,300,10,"));
}

TEST(SimulateWorkflow, WriteSimulationCreatesTheFolder) {
  const fs::path dir =
      fs::temp_directory_path() / ("pkm_workflow_write_sim_" + std::to_string(::getpid())) / "a";
  fs::remove_all(dir.parent_path());
  const SimulateResult r = simulateScenario("seed003-probe-offset", std::nullopt);
  writeSimulation(r, dir, false);
  for (const SimulatedFile& f : r.files) EXPECT_EQ(slurp(dir / f.name), f.text) << f.name;
  EXPECT_THROW(writeSimulation(r, dir, false), IoError);
  writeSimulation(r, dir, true);
  fs::remove_all(dir.parent_path());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
