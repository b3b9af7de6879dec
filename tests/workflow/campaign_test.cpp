// workflow::runCampaign from the library: a one-step campaign file meets its target and reports
// its progress in order, cancellation stops it with nothing half-written, and bad campaigns and
// output folders are refused with messages that name them.
#include "pkm/workflow/campaign.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"
#include "pkm/simulation/environment.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class CampaignWorkflow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pkm_workflow_campaign_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  /// Writes `text` to dir_/name and returns the path.
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return (dir_ / name).string();
  }
  /// A campaign of the touch-probe step alone (seed 003: the shortest step).
  std::string probeCampaign() {
    return write("probe.json",
                 R"({"schema": "pkm.campaign/1", "name": "probe", "description": "one step",
 "steps": [{"id": "probe", "kind": "probe-offset", "scenario": "seed003-probe-offset"}]})");
  }
  fs::path dir_;
};

TEST(CampaignRow, AnImprovementSmallerThanTheCombinedUIsNotSignificant) {
  // before 0.010 ± 0.003, after 0.007 ± 0.004 mm: √(0.003² + 0.004²) = 0.005 > 0.003.
  CampaignRow row{"x", "mm", 0.010, 0.007, std::nullopt, "", ""};
  EXPECT_FALSE(row.significant().has_value());  // no U yet
  row.before_U = 0.003;
  row.after_U = 0.004;
  EXPECT_NEAR(row.combinedU(), 0.005, 1e-15);
  EXPECT_EQ(row.significant(), std::optional<bool>(false));
  row.before = 0.020;  // 0.013 > 0.005
  EXPECT_EQ(row.significant(), std::optional<bool>(true));
  row.after = std::nan("");  // not measured after
  EXPECT_FALSE(row.significant().has_value());
}

TEST(CampaignRow, AWorseningIsNeverASignificantImprovement) {
  // before 0.007, after 0.020 ± 0.005 combined: |before − after| = 0.013 > U, but it grew.
  CampaignRow row{"x", "mm", 0.007, 0.020, std::nullopt, "", ""};
  row.before_U = 0.003;
  row.after_U = 0.004;
  EXPECT_NEAR(row.improvement(), -0.013, 1e-15);
  EXPECT_EQ(row.significant(), std::optional<bool>(false));
  // Signed errors are compared by size: −0.042 mm to +0.003 mm is an improvement of 0.039 mm.
  row.before = -0.042;
  row.after = 0.003;
  EXPECT_NEAR(row.improvement(), 0.039, 1e-15);
  EXPECT_EQ(row.significant(), std::optional<bool>(true));
}

TEST_F(CampaignWorkflow, OneStepCampaignMeetsItsTargetAndReportsProgressInOrder) {
  CampaignOptions o;
  o.campaign = probeCampaign();
  o.out = dir_ / "out";
  std::vector<ProgressEvent> events;
  RunControl control;
  control.progress = [&](const ProgressEvent& e) { events.push_back(e); };
  const CampaignResult r = runCampaign(o, control);

  EXPECT_EQ(r.name, "probe");
  EXPECT_EQ(r.source, o.campaign);
  ASSERT_EQ(r.steps.size(), 1u);
  EXPECT_EQ(r.steps[0].id, "probe");
  EXPECT_TRUE(r.all_pass);
  EXPECT_EQ(r.targets, 1);
  for (const CampaignRow& row : r.steps[0].rows) {
    if (row.target) {
      EXPECT_LE(std::abs(row.after), *row.target) << row.quantity;
    }
  }
  for (const std::string& f : r.steps[0].files) EXPECT_TRUE(fs::is_regular_file(o.out / f)) << f;
  for (const char* f : {"summary.json", "report-data.json", "report.html"})
    EXPECT_TRUE(fs::is_regular_file(o.out / f)) << f;
  EXPECT_EQ(r.report, fs::absolute(o.out / "report.html").lexically_normal());
  std::ifstream summary(o.out / "summary.json", std::ios::binary);
  EXPECT_EQ(r.summary_json, std::string(std::istreambuf_iterator<char>(summary), {}));
  EXPECT_FALSE(fs::exists("pkm.db"));  // no store unless asked

  ASSERT_GE(events.size(), 3u);
  EXPECT_EQ(events.front().index, 0u);
  EXPECT_EQ(events.front().count, 1u);
  EXPECT_EQ(events.front().message, "probe");
  for (std::size_t k = 1; k < events.size(); ++k) {
    EXPECT_EQ(events[k].stage, "probe");
    EXPECT_EQ(events[k].index, 1u);
    EXPECT_GE(events[k].elapsed, events[k - 1].elapsed);
  }
  EXPECT_THAT(events.back().message, HasSubstr("done in"));
}

TEST_F(CampaignWorkflow, ACampaignGivenAsTextRunsAsItsFile) {
  CampaignOptions file;
  file.campaign = probeCampaign();
  file.out = dir_ / "file";
  CampaignOptions text;
  std::ifstream in(file.campaign, std::ios::binary);
  text.campaign_text.assign(std::istreambuf_iterator<char>(in), {});
  text.campaign = "mine";
  text.out = dir_ / "text";
  const CampaignResult a = runCampaign(file);
  const CampaignResult b = runCampaign(text);
  EXPECT_EQ(b.source, "mine");
  ASSERT_EQ(a.steps.size(), b.steps.size());
  ASSERT_EQ(a.steps[0].rows.size(), b.steps[0].rows.size());
  for (std::size_t k = 0; k < a.steps[0].rows.size(); ++k) {
    EXPECT_EQ(a.steps[0].rows[k].quantity, b.steps[0].rows[k].quantity);
    EXPECT_EQ(a.steps[0].rows[k].after, b.steps[0].rows[k].after);
  }
  text.campaign_text = "{\"schema\": \"other\", \"steps\": []}";
  text.out = dir_ / "bad";
  try {
    (void)runCampaign(text);
    FAIL() << "accepted another schema";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("mine"));
  }
}

/// The after-roundness row of a probe campaign's result.
const CampaignRow& roundnessRow(const CampaignResult& r) {
  for (const CampaignRow& row : r.steps.at(0).rows)
    if (row.quantity.find("roundness") != std::string::npos) return row;
  throw std::runtime_error("no roundness row");
}

TEST_F(CampaignWorkflow, TheCampaignEnvironmentReplacesEveryStepsOwn) {
  CampaignOptions ideal;
  ideal.campaign = probeCampaign();
  ideal.out = dir_ / "ideal";
  const CampaignResult a = runCampaign(ideal);
  // The realistic environment's probe lobing (±0.25 µm, 3 lobes) shows in the roundness after
  // compensation (peak-to-valley 2a = 0.5 µm on top of the trigger noise).
  CampaignOptions realistic = ideal;
  realistic.out = dir_ / "realistic";
  realistic.environment = simulation::environmentPreset("realistic");
  realistic.environment_source = "realistic";
  const CampaignResult b = runCampaign(realistic);
  EXPECT_GT(roundnessRow(b).after, roundnessRow(a).after + 0.2);
  EXPECT_EQ(b.environment_source, "realistic");
  EXPECT_EQ(b.environment_name, "realistic");
  EXPECT_THAT(b.summary_json, HasSubstr("\"environment\": {\n    \"source\": \"realistic\""));
  EXPECT_THAT(a.summary_json, ::testing::Not(HasSubstr("\"environment\"")));
  std::ifstream report(realistic.out / "report-data.json");
  const std::string data{std::istreambuf_iterator<char>(report), {}};
  EXPECT_THAT(data, HasSubstr("Environment of every simulated step: realistic (realistic)"));
  // A step's own "environment" gives way to the campaign's: ideal over a realistic step is the
  // ideal run exactly (the same seed).
  CampaignOptions over = ideal;
  over.campaign = write("probe-realistic.json",
                        R"({"schema": "pkm.campaign/1", "name": "probe", "steps": [{"id": "probe",
 "kind": "probe-offset", "scenario": "seed003-probe-offset", "environment": "realistic"}]})");
  over.out = dir_ / "over";
  over.environment = simulation::environmentPreset("ideal");
  const CampaignResult c = runCampaign(over);
  EXPECT_EQ(roundnessRow(c).before, roundnessRow(a).before);
  EXPECT_EQ(roundnessRow(c).after, roundnessRow(a).after);
  // An invalid environment is refused before anything runs.
  CampaignOptions bad = ideal;
  bad.out = dir_ / "bad";
  bad.environment = simulation::environmentPreset("ideal");
  bad.environment->duration_h = -1;
  EXPECT_THROW((void)runCampaign(bad), InvalidArgument);
  EXPECT_FALSE(fs::exists(bad.out));
}

TEST_F(CampaignWorkflow, TheCampaignSeedAndUncertaintySourcesApplyToEveryStep) {
  CampaignOptions base;
  base.campaign = probeCampaign();
  base.out = dir_ / "base";
  const CampaignResult a = runCampaign(base);
  // --seed 7 is the step's "seed": 7.
  CampaignOptions seeded = base;
  seeded.out = dir_ / "seeded";
  seeded.seed = 7;
  const CampaignResult b = runCampaign(seeded);
  CampaignOptions own = base;
  own.campaign = write("probe-7.json",
                       R"({"schema": "pkm.campaign/1", "name": "probe", "steps": [{"id": "probe",
 "kind": "probe-offset", "scenario": "seed003-probe-offset", "seed": 7}]})");
  own.out = dir_ / "own";
  const CampaignResult c = runCampaign(own);
  EXPECT_NE(roundnessRow(b).after, roundnessRow(a).after);
  EXPECT_EQ(roundnessRow(b).after, roundnessRow(c).after);
  EXPECT_THAT(b.summary_json, HasSubstr("\"seed\": 7"));
  // A probe with 4 times the 2D form error: the roundness U (form at the two extreme points) grows,
  // the measured values stay.
  CampaignOptions coarse = base;
  coarse.out = dir_ / "coarse";
  coarse.uncertainty = metrology::UncertaintySources{};
  coarse.uncertainty->probe.form_2d_mm *= 4.0;
  coarse.uncertainty_source = "coarse-probe.json";
  const CampaignResult d = runCampaign(coarse);
  EXPECT_EQ(roundnessRow(d).after, roundnessRow(a).after);
  EXPECT_GT(roundnessRow(d).after_U, 1.5 * roundnessRow(a).after_U);
  EXPECT_THAT(d.summary_json, HasSubstr("coarse-probe.json"));
  std::ifstream report(coarse.out / "report-data.json");
  const std::string data{std::istreambuf_iterator<char>(report), {}};
  EXPECT_THAT(data, HasSubstr("with the instruments and environment of coarse-probe.json"));
}

TEST_F(CampaignWorkflow, CancellationStopsTheRunBeforeTheReport) {
  CampaignOptions o;
  o.campaign = probeCampaign();
  o.out = dir_ / "out";
  CancellationToken token;
  RunControl control;
  control.cancel = &token;
  int seen = 0;
  control.progress = [&](const ProgressEvent& e) {
    if (e.index == 1 && ++seen == 1) token.cancel();
  };
  EXPECT_THROW((void)runCampaign(o, control), Cancelled);
  EXPECT_FALSE(fs::exists(o.out / "summary.json"));
  EXPECT_FALSE(fs::exists(o.out / "report.html"));
  // Nothing half-written: no temporary file is left anywhere.
  for (const auto& e : fs::recursive_directory_iterator(o.out))
    EXPECT_NE(e.path().extension(), ".tmp") << e.path();
}

TEST_F(CampaignWorkflow, BadCampaignsAndOutputFoldersAreRefused) {
  CampaignOptions o;
  o.out = dir_ / "out";
  o.campaign = write("bad.json", "{\n\"schema\": \"pkm.campaign/1\",\n\"steps\": [\n");
  try {
    (void)runCampaign(o);
    FAIL() << "accepted invalid JSON";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.json:4: invalid JSON"));
  }
  o.campaign =
      write("kind.json", R"({"schema": "pkm.campaign/1", "steps": [{"id": "a", "kind": "nope"}]})");
  try {
    (void)runCampaign(o);
    FAIL() << "accepted an unknown kind";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("steps[0]: unknown \"kind\" 'nope'"));
  }
  EXPECT_THROW((void)describeCampaign("no-such-campaign"), IoError);
  o.campaign = probeCampaign();
  fs::create_directories(o.out);
  write("out/keep.txt", "the user's file");
  try {
    (void)runCampaign(o);
    FAIL() << "wrote into a non-empty folder";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("refusing to overwrite (use --force)"));
  }
  o.out.clear();
  EXPECT_THROW((void)runCampaign(o), IoError);
}

// Keys of the wrong JSON type and numbers out of range are pkm::IoError naming the file and the
// step, never a JSON library exception (found by fuzz_campaign: {"schema": [...]} and
// {"schema": 8888888888E8888} ended the program).
TEST_F(CampaignWorkflow, KeysOfTheWrongTypeAreRefusedWithIoError) {
  const auto errorOf = [](const std::string& spec) {
    try {
      (void)describeCampaign(spec);
    } catch (const IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(errorOf(write("s.json", R"({"schema": [{"id": "a", "kind": "probe-offset"}]})")),
              HasSubstr("s.json: not a campaign"));
  // A number beyond a double's range is invalid JSON, not a JSON library exception.
  EXPECT_THAT(errorOf(write("e.json", R"({"schema": 8888888888E8888, "steps": []})")),
              HasSubstr("e.json: invalid JSON ([json.exception.out_of_range.406] number overflow"));
  EXPECT_THAT(errorOf(write("n.json", R"({"schema": "pkm.campaign/1", "name": 5, "steps": [{}]})")),
              HasSubstr("n.json: \"name\" must be a string"));
  EXPECT_THAT(errorOf(write("d.json",
                            R"({"schema": "pkm.campaign/1", "description": null, "steps": [{}]})")),
              HasSubstr("d.json: \"description\" must be a string"));
  EXPECT_THAT(errorOf(write("i.json",
                            R"({"schema": "pkm.campaign/1", "steps": [{"id": 1, "kind": "x"}]})")),
              HasSubstr("i.json: steps[0]: \"id\" must be a string"));
  EXPECT_THAT(
      errorOf(
          write("k.json", R"({"schema": "pkm.campaign/1", "steps": [{"id": "a", "kind": [1]}]})")),
      HasSubstr("k.json: steps[0]: \"kind\" must be a string"));
  // A step's own keys, read when it runs.
  CampaignOptions o;
  o.out = dir_ / "out";
  o.campaign = write("p.json", R"({"schema": "pkm.campaign/1", "steps": [{"id": "cal",
 "kind": "hexapod-calibration", "scenario": "seed004-hexapod-calibration", "positioning": 5}]})");
  try {
    (void)runCampaign(o);
    FAIL() << "accepted a number for \"positioning\"";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("p.json: steps[0] (cal): "));
    EXPECT_THAT(e.what(), HasSubstr("type must be string"));
  }
}

TEST_F(CampaignWorkflow, BuiltInCampaignsAreListedAndDescribed) {
  const std::vector<std::string> names = builtinCampaignNames();
  ASSERT_FALSE(names.empty());
  EXPECT_EQ(names.front(), "default");
  const CampaignInfo info = describeCampaign("default");
  EXPECT_EQ(info.name, "default");
  EXPECT_EQ(info.steps, 5u);
  EXPECT_FALSE(info.description.empty());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
