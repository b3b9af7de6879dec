// `pkm campaign run --environment / --uncertainty / --seed`, the result store's U in `pkm history`
// (also on a store written by the schema-1 pkm), and `pkm campaign sensitivity`: the settings are
// applied and recorded, bad files and values exit 2 naming the file and line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using Json = nlohmann::json;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

class CampaignSettingsCli : public CliTest {
 protected:
  /// A campaign of the touch-probe step alone (the shortest step).
  std::string probeCampaign() {
    return write("probe.json", R"({"schema": "pkm.campaign/1", "name": "probe",
    "steps": [{"id": "probe", "kind": "probe-offset", "scenario": "seed003-probe-offset"}]})");
  }
  /// The summary row of `summary` whose quantity contains `what`.
  static const Json& row(const Json& summary, const std::string& what) {
    for (const Json& r : summary["rows"])
      if (r["quantity"].get<std::string>().find(what) != std::string::npos) return r;
    throw std::runtime_error("no row " + what);
  }
};

TEST_F(CampaignSettingsCli, EnvironmentAndUncertaintyFilesAreAppliedAndRecorded) {
  const std::string campaign = probeCampaign();
  ASSERT_EQ(pkm({"campaign", "run", campaign, "--out", path("ideal"), "--no-db"}).code, 0);
  const std::string env = write("env.json", R"({"preset": "ideal",
  "setup": {"probe_lobing_um": 1.0, "probe_lobes": 4}})");
  const std::string sources = write("sources.json", R"({"probe": {"form_2d_mm": 0.001}})");
  const CliRun r = pkm({"campaign",
                        "run",
                        campaign,
                        "--out",
                        path("lobed"),
                        "--no-db",
                        "--environment",
                        env,
                        "--uncertainty",
                        sources,
                        "--seed",
                        "5"});
  ASSERT_TRUE(r.code == 0 || r.code == 1) << r.err;
  EXPECT_THAT(r.out, HasSubstr("environment of every simulated step: " + env + " (custom)"));
  EXPECT_THAT(r.out, HasSubstr("uncertainty budgets: instruments and environment of " + sources));
  const Json ideal = Json::parse(slurp(dir_ / "ideal/summary.json"));
  const Json lobed = Json::parse(slurp(dir_ / "lobed/summary.json"));
  EXPECT_FALSE(ideal.contains("environment"));
  EXPECT_EQ(lobed["environment"]["source"], env);
  EXPECT_EQ(lobed["environment"]["name"], "custom");
  EXPECT_EQ(lobed["uncertainty"]["source"], sources);
  EXPECT_EQ(lobed["seed"], 5);
  // ±1 µm of 4-lobe pre-travel: the roundness after compensation grows by about 2 µm; the probe's
  // 1 µm form raises its U.
  const Json& a = row(ideal, "roundness");
  const Json& b = row(lobed, "roundness");
  EXPECT_GT(b["after"].get<double>(), a["after"].get<double>() + 1.0);
  EXPECT_GT(b["after_U"].get<double>(), a["after_U"].get<double>());
  // The report's header names both.
  const std::string html = slurp(dir_ / "lobed/report.html");
  EXPECT_THAT(html, HasSubstr("Environment of every simulated step: " + env));
  EXPECT_THAT(html,
              HasSubstr("Instruments and environment of the uncertainty budgets: " + sources));
}

TEST_F(CampaignSettingsCli, BadEnvironmentsAndSourcesExit2NamingTheFileAndLine) {
  const std::string campaign = probeCampaign();
  const auto run = [&](const std::string& option, const std::string& value) {
    return pkm({"campaign", "run", campaign, "--out", path("o"), "--no-db", option, value});
  };
  expectUsageError(
      run("--environment",
          write("e1.json", "{\n  \"preset\": \"ideal\",\n  \"air\": {\"enabled\": 3}\n}\n")),
      "e1.json:3:");
  expectUsageError(run("--environment", write("e2.json", "{\n  \"setup\": {\n")), "e2.json:");
  expectUsageError(run("--environment", "stormy"), "not an environment preset (ideal, realistic)");
  expectUsageError(
      run("--uncertainty", write("u.json", "{\n  \"probe\": {\"form_2d_mm\": \"big\"}\n}\n")),
      "u.json:2: /probe/form_2d_mm");
  expectUsageError(run("--seed", "minus-one"), "--seed");
  EXPECT_FALSE(fs::exists(dir_ / "o" / "summary.json"));
}

TEST_F(CampaignSettingsCli, HistoryShowsValueAndUncertainty) {
  const CliRun r =
      pkm({"campaign", "run", probeCampaign(), "--out", path("o"), "--db", path("pkm.db")});
  ASSERT_EQ(r.code, 0) << r.err;
  const CliRun j = pkm({"history", "--machine", "mxt700s-like", "--db", path("pkm.db"), "--json"});
  ASSERT_EQ(j.code, 0) << j.err;
  const Json h = Json::parse(j.out);
  const Json summary = Json::parse(slurp(dir_ / "o/summary.json"));
  bool found = false;
  for (const Json& stored : h["rows"])
    if (stored["quantity"].get<std::string>().find("roundness") != std::string::npos &&
        stored["stage"] == "after") {
      found = true;
      EXPECT_NEAR(stored["U"].get<double>(),
                  row(summary, "roundness")["after_U"].get<double>(),
                  0.05 * stored["U"].get<double>());  // summary.json rounds U to 2 digits
    }
  EXPECT_TRUE(found) << j.out;
  const CliRun t = pkm({"history", "--machine", "mxt700s-like", "--db", path("pkm.db")});
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_THAT(t.out, HasSubstr("value ± U (k = 2)"));
  EXPECT_THAT(t.out, HasSubstr(" ± "));
}

TEST_F(CampaignSettingsCli, AStoreOfTheOldSchemaKeepsWorking) {
  const fs::path db = dir_ / "old.db";
  fs::copy_file(fs::path(PKM_SOURCE_DIR) / "tests/data/store/schema1.db", db);
  const CliRun before = pkm({"history", "--machine", "pkm-hx1200", "--db", db.string(), "--json"});
  ASSERT_EQ(before.code, 0) << before.err;
  const Json old_rows = Json::parse(before.out)["rows"];
  ASSERT_EQ(old_rows.size(), 17u);
  for (const Json& r : old_rows) EXPECT_TRUE(r["U"].is_null()) << r.dump();
  // A campaign stores into it beside the old rows.
  ASSERT_EQ(pkm({"campaign", "run", probeCampaign(), "--out", path("o"), "--db", db.string()}).code,
            0);
  const CliRun t = pkm({"history", "--machine", "pkm-hx1200", "--db", db.string()});
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_THAT(t.out, HasSubstr("residuals.rms"));
  const CliRun p = pkm({"history", "--machine", "mxt700s-like", "--db", db.string()});
  ASSERT_EQ(p.code, 0) << p.err;
  EXPECT_THAT(p.out, HasSubstr(" ± "));
}

TEST_F(CampaignSettingsCli, SensitivityWritesItsFilesAndTable) {
  const CliRun r = pkm({"campaign",
                        "sensitivity",
                        probeCampaign(),
                        "--source",
                        "setup.probe_lobing_um",
                        "--values",
                        "0,0.5,1",
                        "--environment",
                        "ideal",
                        "--seed",
                        "3",
                        "--out",
                        path("s")});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_THAT(r.out,
              HasSubstr("after compensation ± U (k = 2) for each value of "
                        "setup.probe_lobing_um (µm)"));
  EXPECT_THAT(r.out, HasSubstr("roundness"));
  for (const char* f : {"sensitivity.json", "sensitivity.csv", "report.html", "report-data.json"})
    EXPECT_TRUE(fs::is_regular_file(dir_ / "s" / f)) << f;
  // The roundness after compensation grows with the lobing amplitude.
  const Json j = Json::parse(slurp(dir_ / "s/sensitivity.json"));
  EXPECT_EQ(j["seed"], 3);
  std::vector<double> after;
  for (const Json& row : j["rows"])
    if (row["quantity"].get<std::string>().find("roundness") != std::string::npos)
      after.push_back(row["after"].get<double>());
  ASSERT_EQ(after.size(), 3u);
  EXPECT_LT(after[0], after[1]);
  EXPECT_LT(after[1], after[2]);
  EXPECT_THAT(slurp(dir_ / "s/report.html"), ::testing::Not(HasSubstr("src=\"http")));
}

TEST_F(CampaignSettingsCli, SensitivityRefusesBadSourcesAndValues) {
  const std::string campaign = probeCampaign();
  const auto run = [&](const std::string& source, const std::string& values) {
    return pkm({"campaign",
                "sensitivity",
                campaign,
                "--source",
                source,
                "--values",
                values,
                "--out",
                path("s")});
  };
  const CliRun bad_path = run("air.temprature_sensor.offset", "0,1");
  expectUsageError(bad_path, "unknown environment parameter 'air.temprature_sensor.offset'");
  EXPECT_THAT(bad_path.err, HasSubstr("air.temperature_sensor.offset"));
  expectUsageError(run("air.temperature_sensor.offset", "0,a"), "--values");
  expectUsageError(run("air.temperature_sensor.offset", "1,1"), "repeated");
  expectUsageError(run("structure.white_sigma_um", "1,-1"), "structure.white_sigma_um");
  EXPECT_FALSE(fs::exists(dir_ / "s"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
