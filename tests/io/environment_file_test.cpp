// io::parseEnvironmentJson, loadEnvironment and the environment's parameters by dotted path: every
// path sets the same environment as the scenario reader given that one key, errors name the file
// and line, unknown paths list the valid ones.
#include "pkm/io/environment_file.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
namespace sim = pkm::simulation;

/// Every parameter and "enabled" flag of `e`, for comparisons.
std::vector<double> everything(const sim::Environment& e) {
  std::vector<double> v;
  for (const EnvironmentParameter& p : environmentParameters())
    v.push_back(environmentParameter(e, p.path));
  for (const bool on : {e.air.enabled, e.thermal.enabled, e.setup.enabled, e.structure.enabled})
    v.push_back(on ? 1.0 : 0.0);
  return v;
}

/// {"preset": "ideal", <path as nested keys>: value} (an array element of warmup_drift_mm or
/// warmup_tilt_urad within the ideal array).
std::string oneKeyDocument(const std::string& path, double value) {
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) keys.push_back(k);
  nlohmann::json doc = {{"preset", "ideal"}};
  nlohmann::json* at = &doc;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    if (keys[i] == "warmup_drift_mm" || keys[i] == "warmup_tilt_urad") {
      nlohmann::json drift = {0.0, 0.0, 0.0};
      drift[std::stoul(keys[i + 1])] = value;
      (*at)[keys[i]] = drift;
      return doc.dump();
    }
    at = &(*at)[keys[i]];
  }
  (*at)[keys.back()] = value;
  return doc.dump();
}

TEST(EnvironmentFile, EveryParameterSetsWhatTheScenarioReaderReadsForThatKey) {
  const sim::Environment realistic = *sim::environmentPreset("realistic");
  ASSERT_GE(environmentParameters().size(), 40u);
  for (const EnvironmentParameter& p : environmentParameters()) {
    // The realistic value (valid), or 2 for the integer lobe count; a value different from the
    // ideal one where the preset has one.
    double value = environmentParameter(realistic, p.path);
    if (value == environmentParameter(*sim::environmentPreset("ideal"), p.path))
      value = value == 0.0 ? 0.5 : value * 1.01;
    if (p.path == "setup.probe_lobes") value = 2;
    sim::Environment set = *sim::environmentPreset("ideal");
    setEnvironmentParameter(set, p.path, value);
    const std::string doc = oneKeyDocument(p.path, value);
    const sim::Environment read = parseEnvironmentJson({"one-key.json", doc});
    EXPECT_EQ(everything(set), everything(read)) << p.path << ": " << doc;
    EXPECT_NEAR(environmentParameter(set, p.path), value, 1e-15 * std::abs(value)) << p.path;
    EXPECT_EQ(set.name, "custom");
  }
}

TEST(EnvironmentFile, SettingAParameterSwitchesOnItsGroupOnly) {
  sim::Environment e = *sim::environmentPreset("ideal");
  setEnvironmentParameter(e, "air.temperature_sensor.offset", 0.3);
  EXPECT_TRUE(e.air.enabled);
  EXPECT_FALSE(e.thermal.enabled || e.setup.enabled || e.structure.enabled);
  EXPECT_EQ(e.air.temperature_sensor.offset, 0.3);
  setEnvironmentParameter(e, "setup.beam_misalignment_urad", 150);
  EXPECT_TRUE(e.setup.enabled);
  EXPECT_DOUBLE_EQ(e.setup.beam_misalignment_rad, 150e-6);  // µrad in the JSON, rad inside
  // The realistic preset's other values stay.
  sim::Environment r = *sim::environmentPreset("realistic");
  setEnvironmentParameter(r, "air.dead_path_mm", 500);
  EXPECT_EQ(r.air.dead_path_mm, 500);
  EXPECT_EQ(r.air.temperature_sensor.offset, 0.1);
  EXPECT_EQ(r.setup.beam_misalignment_rad, 200e-6);
}

TEST(EnvironmentFile, BadPathsAndValuesAreRefusedWithTheReason) {
  sim::Environment e = *sim::environmentPreset("ideal");
  try {
    setEnvironmentParameter(e, "air.temperature_sensor.ofset", 1);
    FAIL() << "expected an error";
  } catch (const InvalidArgument& x) {
    EXPECT_THAT(x.what(),
                HasSubstr("unknown environment parameter 'air.temperature_sensor.ofset'"));
    EXPECT_THAT(x.what(), HasSubstr("air.temperature_sensor.offset"));
    EXPECT_THAT(x.what(), HasSubstr("setup.beam_misalignment_urad"));
  }
  EXPECT_THROW(setEnvironmentParameter(e, "air.pressure_sensor.noise", -1), InvalidArgument);
  EXPECT_THROW(setEnvironmentParameter(e, "setup.probe_lobes", 2.5), InvalidArgument);
  EXPECT_THROW(setEnvironmentParameter(e, "duration_h", std::nan("")), InvalidArgument);
  try {
    setEnvironmentParameter(e, "air.temperature_c.start", 200);  // outside Edlén's range
    FAIL() << "expected an error";
  } catch (const InvalidArgument& x) {
    EXPECT_THAT(x.what(), HasSubstr("air.temperature_c.start"));
  }
  EXPECT_FALSE(e.air.enabled);  // unchanged by the refused values
  EXPECT_EQ(e.name, "ideal");
}

TEST(EnvironmentFile, ErrorsNameTheFileAndLine) {
  try {
    (void)parseEnvironmentJson(
        {"env.json", "{\n  \"preset\": \"realistic\",\n  \"air\": {\"dead_path\": 5}\n}\n"});
    FAIL() << "expected an error";
  } catch (const IoError& x) {
    EXPECT_THAT(x.what(), HasSubstr("env.json:3:"));
    EXPECT_THAT(x.what(), HasSubstr("dead_path"));
  }
  EXPECT_THROW((void)parseEnvironmentJson({"e.json", "{\"preset\": \"windy\"}"}), IoError);
  EXPECT_THROW((void)parseEnvironmentJson({"e.json", "[1, 2]"}), IoError);
  try {
    (void)parseEnvironmentJson({"e.json", "{\n\"air\": {\n"});
    FAIL() << "expected an error";
  } catch (const IoError& x) {
    EXPECT_THAT(x.what(), HasSubstr("e.json:"));
  }
  EXPECT_EQ(parseEnvironmentJson({"e.json", "\"realistic\""}).name, "realistic");
}

TEST(EnvironmentFile, LoadsAPresetOrAFile) {
  EXPECT_EQ(loadEnvironment("ideal").name, "ideal");
  EXPECT_TRUE(loadEnvironment("realistic").active());
  const std::filesystem::path file =
      std::filesystem::temp_directory_path() / "pkm_environment_file_test.json";
  std::ofstream(file) << R"({"preset": "ideal", "setup": {"beam_misalignment_urad": 300}})";
  const sim::Environment e = loadEnvironment(file.string());
  EXPECT_EQ(e.name, "custom");
  EXPECT_TRUE(e.setup.enabled);
  EXPECT_FALSE(e.air.enabled);
  EXPECT_DOUBLE_EQ(e.setup.beam_misalignment_rad, 300e-6);
  std::filesystem::remove(file);
  try {
    (void)loadEnvironment("stormy");
    FAIL() << "expected an error";
  } catch (const IoError& x) {
    EXPECT_THAT(x.what(), HasSubstr("stormy: no such file, and not an environment preset"));
    EXPECT_THAT(x.what(), HasSubstr("realistic"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
