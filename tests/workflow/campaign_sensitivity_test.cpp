// workflow::runSensitivity: the swept values reach the simulation (an air-temperature sensor offset
// of the laser's compensation unit scales an error-free machine's X positioning by exactly
// (n_true − n_sensed)/n_sensed, slope ≈ L·|∂n/∂t| from Edlén), the files are written, bad sources
// and values are refused.
#include "pkm/workflow/campaign_sensitivity.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "pkm/core/air_refractive_index.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/html_report.hpp"
#include "pkm/io/scenario.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr double kTravelMm = 500.0;         // linear-x of seed001-diagonals: 0 .. 500 mm
constexpr double kExactTolMm = 1e-9;        // E against the closed form (no noise at all)
constexpr double kSlopeRelativeTol = 0.01;  // the finite-difference slope against ∂n/∂t
constexpr const char* kXRow = "X positioning (ISO 230-2 E)";

class SensitivityWorkflow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("pkm_workflow_sensitivity_" + std::to_string(::getpid()) + "_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  /// A campaign of one cartesian-diagonals step on seed001's machine without errors, noise or
  /// target jitter: the laser reads exactly what the environment makes it read.
  std::string flatCampaign() {
    nlohmann::json s = nlohmann::json::parse(io::loadScenario("seed001-diagonals").text);
    s["name"] = "flat";
    s["machine"].erase("errors");
    for (nlohmann::json& m : s["measurements"]) {
      m["noise"] = {{"sigma", 0.0}};
      m.erase("target_jitter");
    }
    std::ofstream(dir_ / "flat.json") << s.dump(1);
    std::ofstream(dir_ / "campaign.json")
        << R"({"schema": "pkm.campaign/1", "name": "flat", "steps":
 [{"id": "cart", "kind": "cartesian-diagonals", "scenario": "flat.json"}]})";
    return (dir_ / "campaign.json").string();
  }
  SensitivityOptions offsetSweep() {
    SensitivityOptions o;
    o.campaign = flatCampaign();
    o.source = "air.temperature_sensor.offset";
    o.values = {2.0, 0.5, 1.0};  // any order
    o.out = dir_ / "out";
    o.base = *simulation::environmentPreset("ideal");
    o.base_source = "ideal";
    return o;
  }
  fs::path dir_;
};

TEST_F(SensitivityWorkflow, ASensorOffsetScalesThePositioningErrorAsEdlenSays) {
  const SensitivityOptions o = offsetSweep();
  const SensitivityResult r = runSensitivity(o);
  EXPECT_EQ(r.campaign, "flat");
  EXPECT_EQ(r.source, "air.temperature_sensor.offset");
  EXPECT_EQ(r.unit, "K");
  std::map<double, double> e_before;
  for (const SensitivityRow& row : r.rows)
    if (row.row.quantity == kXRow) e_before[row.value] = row.row.before;
  ASSERT_EQ(e_before.size(), 3u);
  // The sensor reads t + δ: every reading is Δ·n(t)/n(t + δ), so E = L·|n(t) − n(t + δ)|/n(t + δ).
  const AirConditions air{20.0, 101325.0, 50.0};
  const double n_true = refractiveIndexEdlen(air);
  for (const auto& [delta, e] : e_before) {
    const double n_sensed = refractiveIndexEdlen({20.0 + delta, 101325.0, 50.0});
    EXPECT_NEAR(e, kTravelMm * std::abs(n_true - n_sensed) / n_sensed, kExactTolMm) << delta;
  }
  // The slope of E against the offset: L·|∂n/∂t| (≈ 0.93 ppm/K, 0.47 µm/K over 500 mm).
  const double slope = (e_before[2.0] - e_before[0.5]) / 1.5;
  const double analytic = kTravelMm * std::abs(edlenSensitivity(air).per_kelvin);
  EXPECT_NEAR(slope, analytic, kSlopeRelativeTol * analytic);
  EXPECT_NEAR(analytic, 4.65e-4, 0.2e-4);
  // The coefficient (least-squares slope over the three values) is that slope: E is nearly linear.
  const auto c = std::find_if(r.coefficients.begin(),
                              r.coefficients.end(),
                              [](const SensitivityCoefficient& k) { return k.quantity == kXRow; });
  ASSERT_NE(c, r.coefficients.end());
  EXPECT_NEAR(c->before, slope, 1e-3 * slope);  // Edlén is nearly linear over 2 K
  // The compensation is made from readings with the same sensor error as the re-measurement's, so
  // the after-value cannot see it: d(after)/d(offset) is nil.
  EXPECT_LT(std::abs(c->after), 1e-3 * analytic);
}

TEST(LeastSquaresSlope, AgainstAHandCalculation) {
  // x = 0, 1, 2, 4; y = 1, 3, 5, 9 exactly 1 + 2x: slope 2. A NaN is left out.
  EXPECT_NEAR(leastSquaresSlope({0, 1, 2, 4, 5}, {1, 3, 5, 9, std::nan("")}), 2.0, 1e-15);
  // y = 0, 1, 0, 1 at x = 0..3: Σ(x − 1.5)(y − 0.5) = 1, Σ(x − 1.5)² = 5 -> 0.2.
  EXPECT_NEAR(leastSquaresSlope({0, 1, 2, 3}, {0, 1, 0, 1}), 0.2, 1e-15);
  EXPECT_TRUE(std::isnan(leastSquaresSlope({1, 2}, {3, std::nan("")})));
  EXPECT_TRUE(std::isnan(leastSquaresSlope({1, 1}, {3, 4})));
  EXPECT_THROW((void)leastSquaresSlope({1, 2}, {3}), InvalidArgument);
}

TEST_F(SensitivityWorkflow, WritesTheTableTheCsvAndTheReport) {
  const SensitivityOptions o = offsetSweep();
  std::vector<ProgressEvent> events;
  RunControl control;
  control.progress = [&](const ProgressEvent& e) { events.push_back(e); };
  const SensitivityResult r = runSensitivity(o, control);
  ASSERT_FALSE(r.rows.empty());
  EXPECT_EQ(r.rows.size() % 3, 0u);  // every summary row once per value
  const nlohmann::json j = nlohmann::json::parse(slurp(o.out / "sensitivity.json"));
  EXPECT_EQ(j["schema"], "pkm.sensitivity/1");
  EXPECT_EQ(j["base_environment"], "ideal");
  EXPECT_EQ(j["rows"].size(), r.rows.size());
  EXPECT_EQ(j["values"], nlohmann::json({2.0, 0.5, 1.0}));
  EXPECT_EQ(r.json, slurp(o.out / "sensitivity.json"));
  const std::string csv = slurp(o.out / "sensitivity.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "value,step,quantity,unit,before,after,before_U,after_U");
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), r.rows.size() + 1);
  EXPECT_THAT(csv, HasSubstr("\n0.5,cart,X positioning (ISO 230-2 E),mm,"));
  // The report: valid pkm.report/1, one line plot per summary quantity with a ±U band.
  const std::string data = slurp(o.out / "report-data.json");
  EXPECT_NO_THROW(io::validateReportData(data, "report-data.json"));
  const nlohmann::json doc = nlohmann::json::parse(data);
  std::size_t plots = 0, bands = 0;
  for (const nlohmann::json& sec : doc["sections"])
    for (const nlohmann::json& p : sec.value("plots", nlohmann::json::array())) {
      ++plots;
      EXPECT_EQ(p["kind"], "line");
      EXPECT_EQ(p["series"][0]["x"], nlohmann::json({0.5, 1.0, 2.0}));  // ascending
      bands += p["series"][0].contains("upper") ? 1 : 0;
    }
  EXPECT_EQ(plots, r.rows.size() / 3);
  EXPECT_EQ(j["coefficients"].size(), r.rows.size() / 3);
  EXPECT_EQ(doc["sections"][0]["id"], "coefficients");
  EXPECT_GE(bands, plots - 1);
  EXPECT_TRUE(fs::is_regular_file(r.report));
  EXPECT_THAT(slurp(r.report), HasSubstr("Swept error source: air.temperature_sensor.offset"));
  // Each run's own campaign output, with the environment it ran in.
  const nlohmann::json run1 = nlohmann::json::parse(slurp(o.out / "runs/value-1/summary.json"));
  EXPECT_EQ(run1["environment"]["source"], "ideal with air.temperature_sensor.offset = 2");
  EXPECT_EQ(run1["environment"]["name"], "custom");
  ASSERT_FALSE(events.empty());
  EXPECT_EQ(events.front().stage, "value-1");
  EXPECT_THAT(events.front().message, HasSubstr("air.temperature_sensor.offset = 2 K"));
  EXPECT_EQ(events.back().index, 3u);
}

TEST_F(SensitivityWorkflow, BadSourcesAndValuesAreRefusedBeforeAnythingRuns) {
  SensitivityOptions o = offsetSweep();
  o.source = "air.temperature.offset";
  try {
    (void)runSensitivity(o);
    FAIL() << "accepted an unknown source";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("unknown environment parameter 'air.temperature.offset'"));
    EXPECT_THAT(e.what(), HasSubstr("air.temperature_sensor.offset"));
  }
  o = offsetSweep();
  o.values = {};
  EXPECT_THROW((void)runSensitivity(o), InvalidArgument);
  o.values = {1.0, 1.0};
  EXPECT_THROW((void)runSensitivity(o), InvalidArgument);
  o.source = "air.temperature_sensor.noise";
  o.values = {0.1, -0.1};
  try {
    (void)runSensitivity(o);
    FAIL() << "accepted a negative noise";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("air.temperature_sensor.noise"));
  }
  o = offsetSweep();
  o.out.clear();
  EXPECT_THROW((void)runSensitivity(o), IoError);
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
