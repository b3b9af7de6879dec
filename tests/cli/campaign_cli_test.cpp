// `pkm campaign run`: the built-in default campaign meets the campaign's targets on every paper
// scenario (seed 000 parallelism <= 0.010 mm and face diagonals <= 0.02 mm, seed 003 roundness
// down to the probe noise, seed 004 TCP error <= 0.05 mm), writes its report, summary,
// compensation files and measurements, stores its results, and refuses bad input with exit 2.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using Json = nlohmann::json;
using ::testing::HasSubstr;

class CampaignCli : public CliTest {
 protected:
  /// Every row of the summary `s` passes; a row with a target meets it after and missed it
  /// before; every row has its expanded uncertainties (k = 2), null where there is no value.
  static void expectTargetsMet(const Json& s) {
    std::map<std::string, int> targets;
    for (const Json& row : s["rows"]) {
      EXPECT_TRUE(row["pass"].get<bool>()) << row.dump();
      if (!row["target"].is_null()) {
        ++targets[row["step"].get<std::string>()];
        EXPECT_LE(std::abs(row["after"].get<double>()), row["target"].get<double>()) << row.dump();
        // Seed 003 runs on an uncalibrated PKM (as the paper did): its target is the paper's
        // compensated circle within a factor of 2, which the machine's own errors decide before
        // and after alike; the DRM compensation must still improve it beyond its U.
        if (row["step"] == "seed003")
          EXPECT_TRUE(row["significant"].get<bool>()) << row.dump();
        else
          EXPECT_GT(std::abs(row["before"].get<double>()), row["target"].get<double>())
              << row.dump();
      }
    }
    EXPECT_EQ(targets["seed000"], 6);
    EXPECT_EQ(targets["seed003"], 1);
    EXPECT_EQ(targets["seed004"], 1);
    EXPECT_EQ(targets["seed004-gauges"], 1);
    // Expanded uncertainties (k = 2) where a budget exists, null elsewhere; the parallelism's
    // improvement is far larger than its combined U.
    for (const Json& row : s["rows"]) {
      for (const char* key : {"before_U", "after_U", "significant"})
        EXPECT_TRUE(row.contains(key)) << key << row.dump();
      if (row["before"].is_null()) EXPECT_TRUE(row["before_U"].is_null()) << row.dump();
    }
    const Json& parallelism = s["rows"][0];
    EXPECT_GT(parallelism["before_U"].get<double>(), 0.0);
    EXPECT_LT(parallelism["before_U"].get<double>(), 0.01);
    EXPECT_TRUE(parallelism["significant"].get<bool>());
  }

  /// The paper's before and after values (seed 000 parallelism, seed 004 by dial gauges) and the
  /// hexapod's TCP error with its uncertainties, in the summary `s`.
  void expectPaperValuesAndTcpUncertainty(const Json& s) const {
    // The hexapod's TCP error: U from the tracker and registration before, plus the calibration's
    // predicted TCP U after (tens of µm with a typical tracker and 6-DOF probe).
    std::map<std::string, Json> by_quantity;
    for (const Json& row : s["rows"])
      by_quantity[row["step"].get<std::string>() + " " + row["quantity"].get<std::string>()] = row;
    const Json& tcp = by_quantity.at("seed004 TCP error, 50 held-out poses, max");
    // Seed 000 over the paper's 50 mm (its Table 3: 0.134 and 0.735 mm before): the virtual
    // machine's injected squareness gives the paper's before-values, the after-values are the
    // compensation's (docs/campaign.md explains the gap to the paper's 0.015 and 0.022 mm).
    const Json& h50 = by_quantity.at("seed000 parallelism Y2-PY, horizontal (50 mm)");
    const Json& v50 = by_quantity.at("seed000 parallelism Y2-PY, vertical (50 mm)");
    EXPECT_NEAR(h50["before"].get<double>(), 0.134, 0.134 * 0.1);
    EXPECT_NEAR(v50["before"].get<double>(), 0.735, 0.735 * 0.05);
    EXPECT_EQ(h50["paper"], "0.134 -> 0.015 mm");
    EXPECT_LT(v50["after"].get<double>(), 0.022);
    EXPECT_TRUE(by_quantity.at("seed000 parallelism Y2-PY, horizontal (300 mm)")["paper"] == "");
    // Seed 004 by the paper's method, dial gauges in constrained motion (its §4): x over 540 mm
    // from about 10.5 mm to below the paper's 0.5 mm; across the work volume, which the gauges do
    // not see, the TCP error still improves (no target), far from the tracker calibration's.
    const Json& gx =
        by_quantity.at("seed004-gauges linear-x positioning (ISO 230-2 M over 540 mm)");
    const Json& gt = by_quantity.at("seed004-gauges TCP error, 50 held-out poses, max");
    EXPECT_EQ(gx["paper"], "12 -> < 0.5 mm (540 mm along x)");
    EXPECT_GT(gx["before"].get<double>(), 9.0);
    EXPECT_LT(gx["after"].get<double>(), 0.5);
    EXPECT_TRUE(gt["target"].is_null());
    EXPECT_LT(gt["after"].get<double>(), gt["before"].get<double>());
    EXPECT_GT(gt["after"].get<double>(), 10 * tcp["after"].get<double>());
    EXPECT_TRUE(std::filesystem::is_regular_file(
        dir_ / "out/seed004-gauges/measured-before/constrained-motion.csv"));
    EXPECT_GT(tcp["before_U"].get<double>(), 0.01);
    EXPECT_LT(tcp["before_U"].get<double>(), 0.1);
    EXPECT_GT(tcp["after_U"].get<double>(), tcp["before_U"].get<double>());
    EXPECT_LT(tcp["after_U"].get<double>(), 0.1);
    EXPECT_TRUE(tcp["significant"].get<bool>());
  }

  /// Every step's files of the summary `s` and the compensation files exist; the report holds
  /// every plot of its data.
  void expectFilesAndReport(const Json& s) const {
    // Every step's files exist: measurements before and after, the controller compensation.
    for (const Json& step : s["steps"])
      for (const Json& f : step["files"])
        EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "out" / f.get<std::string>())) << f;
    EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "out/seed004/compensation/kinematics.hal"));
    EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "out/seed000/compensation/x2.comp"));
    EXPECT_TRUE(
        std::filesystem::is_regular_file(dir_ / "out/seed000/compensation/pkm-base-frame.txt"));
    // The report holds every plot of the report data, and loads nothing from outside.
    const std::string html = slurp(dir_ / "out" / "report.html");
    const Json data = Json::parse(slurp(dir_ / "out" / "report-data.json"));
    int plots = 0;
    for (const Json& sec : data["sections"])
      for (const Json& p : sec["plots"]) {
        EXPECT_THAT(html, HasSubstr(p["id"].get<std::string>()));
        ++plots;
      }
    EXPECT_GE(plots, 8);
    EXPECT_THAT(html, ::testing::Not(HasSubstr("src=\"http")));
  }
};

TEST_F(CampaignCli, DefaultCampaignMeetsTheTargetsAndWritesEverything) {
  const CliRun r =
      pkm({"campaign", "run", "default", "--out", path("out"), "--db", path("pkm.db")});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_THAT(r.out, HasSubstr("all targets met"));
  EXPECT_THAT(r.out, HasSubstr("report.html"));
  const Json s = Json::parse(slurp(dir_ / "out" / "summary.json"));
  expectTargetsMet(s);
  expectPaperValuesAndTcpUncertainty(s);
  EXPECT_THAT(r.out, HasSubstr("uncertainty (k = 2): before -> after, improvement"));
  EXPECT_THAT(r.out, HasSubstr(" ± "));
  expectFilesAndReport(s);
  // The results are in the store: the hexapod's TCP error before and after.
  const CliRun h = pkm({"history", "--machine", "pkm-hx1200", "--db", path("pkm.db"), "--json"});
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_THAT(h.out, HasSubstr("TCP error"));
}

TEST_F(CampaignCli, RefusesANonEmptyOutputWithoutForce) {
  const std::string campaign = write("one.json", R"({"schema": "pkm.campaign/1", "name": "one",
    "steps": [{"id": "probe", "kind": "probe-offset", "scenario": "seed003-probe-offset"}]})");
  ASSERT_EQ(pkm({"campaign", "run", campaign, "--out", path("o"), "--no-db"}).code, 0);
  const std::string before = slurp(dir_ / "o" / "report.html");
  expectUsageError(pkm({"campaign", "run", campaign, "--out", path("o"), "--no-db"}), "--force");
  EXPECT_EQ(slurp(dir_ / "o" / "report.html"), before);
  EXPECT_EQ(pkm({"campaign", "run", campaign, "--out", path("o"), "--no-db", "--force"}).code, 0);
}

TEST_F(CampaignCli, BadCampaignsAreUsageErrors) {
  expectUsageError(pkm({"campaign",
                        "run",
                        write("a.json", "{\n  \"schema\": \"pkm.campaign/1\",\n  \"steps\": [\n"),
                        "--out",
                        path("o"),
                        "--no-db"}),
                   "a.json:");
  expectUsageError(pkm({"campaign",
                        "run",
                        write("b.json", R"({"schema": "other", "steps": []})"),
                        "--out",
                        path("o"),
                        "--no-db"}),
                   "pkm.campaign/1");
  expectUsageError(
      pkm({"campaign",
           "run",
           write("c.json",
                 R"({"schema": "pkm.campaign/1", "steps": [{"id": "x", "kind": "teleport"}]})"),
           "--out",
           path("o"),
           "--no-db"}),
      "unknown \"kind\" 'teleport'");
  expectUsageError(pkm({"campaign",
                        "run",
                        write("d.json", R"({"schema": "pkm.campaign/1", "steps": [
                          {"id": "x", "kind": "probe-offset", "scenario": "seed003-probe-offset"},
                          {"id": "x", "kind": "probe-offset",
                           "scenario": "seed003-probe-offset"}]})"),
                        "--out",
                        path("o"),
                        "--no-db"}),
                   "used twice");
  expectUsageError(pkm({"campaign",
                        "run",
                        write("e.json", R"({"schema": "pkm.campaign/1", "steps": [
                          {"id": "x", "kind": "hexapod-calibration",
                           "scenario": "seed003-probe-offset"}]})"),
                        "--out",
                        path("o"),
                        "--no-db"}),
                   "not a hexapod scenario");
  expectUsageError(pkm({"campaign", "run", "no-such-campaign", "--out", path("o"), "--no-db"}),
                   "not a built-in campaign");
}

TEST_F(CampaignCli, MeasuredFilesAreCalibratedAndTheKinematicsWritten) {
  ASSERT_EQ(pkm({"simulate", "seed004-hexapod-calibration", "--out", path("sim")}).code, 0);
  const std::string campaign = write("real.json", R"({"schema": "pkm.campaign/1", "name": "real",
    "steps": [{"id": "hx", "kind": "hexapod-calibration", "machine": "default",
               "data": {"fit": ["sim/tracker-pose.csv"],
                        "holdout": ["sim/tracker-holdout.csv"]}}]})");
  const CliRun r = pkm({"campaign", "run", campaign, "--out", path("o"), "--no-db"});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const Json s = Json::parse(slurp(dir_ / "o" / "summary.json"));
  bool held = false;
  for (const Json& row : s["rows"])
    if (row["quantity"].get<std::string>().rfind("held-out residual RMS", 0) == 0) {
      held = true;
      // Seed 004's tracker (3 µm + 0.5 ppm at about 2 m) explains a held-out RMS of 10 µm.
      EXPECT_LT(row["after"].get<double>(), 0.01);
      EXPECT_GT(row["before"].get<double>(), 1.0);
    }
  EXPECT_TRUE(held);
  // The section shows the calibration's budget table with the predicted TCP U.
  const Json report = Json::parse(slurp(dir_ / "o" / "report-data.json"));
  bool budget = false;
  for (const Json& sec : report["sections"])
    for (const Json& t : sec["tables"])
      budget =
          budget || t["title"].get<std::string>().rfind("Calibration uncertainty (k = 2)", 0) == 0;
  EXPECT_TRUE(budget);
  EXPECT_TRUE(std::filesystem::is_regular_file(dir_ / "o/hx/compensation/kinematics.hal"));
  expectUsageError(pkm({"campaign",
                        "run",
                        write("bad.json", R"({"schema": "pkm.campaign/1", "steps": [{"id": "hx",
                          "kind": "hexapod-calibration", "data": {"fit": ["missing.csv"]}}]})"),
                        "--out",
                        path("o2"),
                        "--no-db"}),
                   "missing.csv: no such file");
}

TEST_F(CampaignCli, MeasuredTouchProbeFilesGiveTheSameRoundnessAsTheSimulation) {
  ASSERT_EQ(pkm({"simulate", "seed003-probe-offset", "--out", path("sim")}).code, 0);
  const std::string campaign = write("probe.json", R"({"schema": "pkm.campaign/1", "name": "p",
    "steps": [{"id": "probe", "kind": "probe-offset", "data": {"offset": "sim/probe_offset.csv",
      "circle_before": "sim/probe_circle_uncompensated.csv",
      "circle_after": "sim/probe_circle_compensated.csv"}}]})");
  const CliRun r = pkm({"campaign", "run", campaign, "--out", path("o"), "--no-db"});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  const CliRun sim = pkm({"campaign",
                          "run",
                          write("s.json", R"({"schema": "pkm.campaign/1",
    "steps": [{"id": "probe", "kind": "probe-offset", "scenario": "seed003-probe-offset"}]})"),
                          "--out",
                          path("s"),
                          "--no-db"});
  ASSERT_EQ(sim.code, 0) << sim.err;
  const Json files = Json::parse(slurp(dir_ / "o" / "summary.json"));
  const Json simulated = Json::parse(slurp(dir_ / "s" / "summary.json"));
  // The files hold the simulation's touches in shortest round-trip form: the same figures.
  ASSERT_FALSE(files["rows"].empty());
  EXPECT_EQ(files["rows"][0]["quantity"], simulated["rows"][0]["quantity"]);
  EXPECT_DOUBLE_EQ(files["rows"][0]["before"].get<double>(),
                   simulated["rows"][0]["before"].get<double>());
  EXPECT_DOUBLE_EQ(files["rows"][0]["after"].get<double>(),
                   simulated["rows"][0]["after"].get<double>());
  EXPECT_TRUE(files["rows"][0]["target"].is_null());  // no known probe noise in measured files
  std::string text = slurp(dir_ / "sim" / "probe_offset.csv");
  text.replace(text.find("# ring diameter mm: 40.001"), 26, "# ring diameter mm: 40.0x1");
  write("sim/probe_offset.csv", text);
  expectUsageError(pkm({"campaign", "run", campaign, "--out", path("o3"), "--no-db"}),
                   "probe_offset.csv:");
}

TEST_F(CampaignCli, MeasuredLaserFilesGiveTheSameCompensationAsTheSimulation) {
  // The step reads the files `pkm simulate` writes; from them it must estimate the same squareness
  // and write byte-identical compensation files as the step that simulates them itself.
  const std::string scenario = write("s.json", R"({"schema": "pkm.campaign/1", "steps": [
    {"id": "hyb", "kind": "hybrid-squareness", "scenario": "seed000-parallelism"}]})");
  ASSERT_EQ(pkm({"campaign", "run", scenario, "--out", path("s"), "--no-db"}).code, 0);
  const std::string files = write("f.json", R"({"schema": "pkm.campaign/1", "steps": [
    {"id": "hyb", "kind": "hybrid-squareness", "machine": "mxt700s-like",
     "data": {"folder": "s/hyb/measured-before"}}]})");
  const CliRun r = pkm({"campaign", "run", files, "--out", path("f"), "--no-db"});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  for (const char* f : {"pkm-base-frame.txt", "x2.comp", "y2.comp", "zp.comp", "x2-yp.cec.spf"})
    EXPECT_EQ(slurp(dir_ / "f/hyb/compensation" / f), slurp(dir_ / "s/hyb/compensation" / f)) << f;
  const Json summary = Json::parse(slurp(dir_ / "f" / "summary.json"));
  ASSERT_EQ(summary["rows"].size(), 4U);
  EXPECT_TRUE(summary["rows"][0]["after"].is_null());  // nothing measured after compensation
  expectUsageError(pkm({"campaign",
                        "run",
                        write("g.json", R"({"schema": "pkm.campaign/1", "steps": [
                          {"id": "hyb", "kind": "hybrid-squareness",
                           "data": {"folder": "nowhere"}}]})"),
                        "--out",
                        path("g"),
                        "--no-db"}),
                   "nowhere: no such folder");
}

TEST_F(CampaignCli, MeasuredCartesianFilesGiveTheSameCompensationAsTheSimulation) {
  const std::string scenario = write("s.json", R"({"schema": "pkm.campaign/1", "steps": [
    {"id": "c", "kind": "cartesian-diagonals", "scenario": "seed001-diagonals"}]})");
  ASSERT_EQ(pkm({"campaign", "run", scenario, "--out", path("s"), "--no-db"}).code, 0);
  const std::string files = write("f.json", R"({"schema": "pkm.campaign/1", "steps": [
    {"id": "c", "kind": "cartesian-diagonals", "data": {"folder": "s/c/measured-before"}}]})");
  const CliRun r = pkm({"campaign", "run", files, "--out", path("f"), "--no-db"});
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  for (const char* f : {"squareness.txt", "x.comp", "y.comp", "x.eec.spf"})
    EXPECT_EQ(slurp(dir_ / "f/c/compensation" / f), slurp(dir_ / "s/c/compensation" / f)) << f;
  expectUsageError(pkm({"campaign",
                        "run",
                        write("g.json", R"({"schema": "pkm.campaign/1", "steps": [
                          {"id": "c", "kind": "cartesian-diagonals", "order": "XXY",
                           "data": {"folder": "s/c/measured-before"}}]})"),
                        "--out",
                        path("g"),
                        "--no-db"}),
                   "\"order\"");
}

TEST_F(CampaignCli, ListNamesTheBuiltInCampaigns) {
  const CliRun r = pkm({"campaign", "list"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("default\t5 steps"));
  EXPECT_THAT(r.out, HasSubstr("realistic\t5 steps"));
}

TEST_F(CampaignCli, TheRealisticEnvironmentLeavesLargerAfterFigures) {
  // The default campaign runs with every unmodelled source on; the `ideal` campaign, the same
  // scenarios without them: compensation works in both, but the figures after it are no longer
  // those of a perfectly modelled machine, and they are what the built-in `realistic` gives.
  const auto after = [&](const std::string& campaign) {
    const CliRun r =
        pkm({"campaign", "run", campaign, "--out", path(campaign), "--no-db", "--force"});
    EXPECT_TRUE(r.code == 0 || r.code == 1) << r.err;
    std::map<std::string, double> v;
    const Json summary = Json::parse(slurp(dir_ / campaign / "summary.json"));
    for (const Json& row : summary["rows"])
      if (row["after"].is_number())
        v[row["step"].get<std::string>() + " " + row["quantity"].get<std::string>()] =
            row["after"].get<double>();
    return v;
  };
  const std::map<std::string, double> ideal = after("ideal");
  const std::map<std::string, double> real = after("default");
  EXPECT_EQ(real, after("realistic"));
  ASSERT_EQ(ideal.size(), real.size());
  EXPECT_GT(real.at("seed001 X positioning (ISO 230-2 E)"),
            2.0 * ideal.at("seed001 X positioning (ISO 230-2 E)"));
  // Where seed 000 (Table 3) landed after compensation, 0.015 and 0.022 mm: between 0.005 and
  // 0.03 mm, from the PKM's thermal tilt between the two passes.
  EXPECT_GT(real.at("seed000 parallelism Y2-PY, horizontal (300 mm)"), 0.005);
  EXPECT_LT(real.at("seed000 parallelism Y2-PY, horizontal (300 mm)"), 0.03);
  EXPECT_GT(real.at("seed000 parallelism Y2-PY, vertical (300 mm)"), 0.005);
  EXPECT_LT(real.at("seed000 parallelism Y2-PY, vertical (300 mm)"), 0.03);
  EXPECT_GT(real.at("seed003 roundness of the 40.001 mm ring, 180 touches (LSC)"),
            ideal.at("seed003 roundness of the 40.001 mm ring, 180 touches (LSC)"));
  // The hexapod's unmodelled geometry (strut lead errors) is what its calibration cannot remove.
  EXPECT_GT(real.at("seed004 TCP error, held-out poses, RMS"),
            2.0 * ideal.at("seed004 TCP error, held-out poses, RMS"));
  // Deterministic per seed.
  EXPECT_EQ(real, after("default"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
