// `pkm calibrate exechon` on the simulator's exechon-calibration data.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// Acceptance: held-out error ≤ 3× the measurement noise. The scenario's tracker reads 5 µm in
/// range and 2 µrad per angle at ~2 m (4 µm across the line of sight): ~5 µm per coordinate, ~8 µm
/// in 3-D; the held-out RMS compares a prediction with a noisy measurement.
constexpr double kHeldOutRmsLimit = 3 * 0.008;  ///< mm
constexpr double kBeforeAtLeast = 0.2;          ///< mm: in the tracker frame (rigid part absorbed)

class CalibrateExechonCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const CliRun sim = pkm({"simulate", "exechon-calibration", "--out", path("sim")});
    ASSERT_EQ(sim.code, 0) << sim.err;
  }
  CliRun calibrate(const std::vector<std::string>& extra) {
    std::vector<std::string> args{"calibrate", "exechon"};
    if (std::find(extra.begin(), extra.end(), "--machine") == extra.end()) {
      args.push_back("--machine");
      args.push_back("mxt700s-like");
    }
    args.insert(args.end(), extra.begin(), extra.end());
    return pkm(args);
  }
};

TEST_F(CalibrateExechonCli, TrackerCalibrationMeetsTheTarget) {
  const CliRun r = calibrate({"--data",
                              path("sim/tracker-fit.csv"),
                              "--holdout",
                              path("sim/tracker-holdout.csv"),
                              "--out",
                              path("cal.json"),
                              "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["holdout"]["before"]["rms"].get<double>(), kBeforeAtLeast);
  EXPECT_LT(j["holdout"]["after"]["rms"].get<double>(), kHeldOutRmsLimit);
  EXPECT_EQ(j["identifiability"]["rank"].get<int>(), j["identifiability"]["parameters"].get<int>());
  EXPECT_TRUE(j.contains("measurement_frame"));
  EXPECT_EQ(j["parameters"].size(), 26u);
  EXPECT_THAT(j["worst_observations"][0]["source"].get<std::string>(),
              HasSubstr("tracker-fit.csv:"));
  // Every free parameter carries U (k = 2) with its budget; the held-out tool point its
  // predicted U, which covers the measured held-out error.
  const auto& u = j["uncertainty"];
  for (const auto& p : j["parameters"]) {
    if (!p["free"].get<bool>()) {
      EXPECT_TRUE(p["U"].is_null()) << p.dump();
      continue;
    }
    EXPECT_GT(p["U"].get<double>(), 0.0) << p.dump();
    EXPECT_FALSE(u["parameters"][p["name"].get<std::string>()]["budget"].empty());
  }
  EXPECT_EQ(u["tcp"]["poses"], "held-out");
  EXPECT_GT(u["tcp"]["U_max"].get<double>(), j["holdout"]["after"]["max"].get<double>());
  // A bad sources file: exit 2 naming it.
  const CliRun bad = calibrate({"--data",
                                path("sim/tracker-fit.csv"),
                                "--out",
                                path("cal2.json"),
                                "--uncertainty",
                                write("bad.json", "{\"schema\": \"other/1\"}\n")});
  EXPECT_EQ(bad.code, 2);
  EXPECT_THAT(bad.err, HasSubstr("bad.json:1:"));
  // --uncertainty-trials: the GUM S1 propagation beside the linear budgets, in the summary.
  const CliRun mc = calibrate({"--data",
                               path("sim/tracker-fit.csv"),
                               "--out",
                               path("cal3.json"),
                               "--uncertainty-trials",
                               "40",
                               "--json"});
  ASSERT_EQ(mc.code, 0) << mc.err;
  const auto jm = nlohmann::json::parse(mc.out);
  EXPECT_GE(jm["uncertainty"]["monte_carlo"]["trials"].get<int>(), 20);
  EXPECT_EQ(jm["uncertainty"]["monte_carlo"]["failures"].get<int>(), 0);
  for (const auto& [name, b] : jm["uncertainty"]["parameters"].items())
    EXPECT_GT(b["monte_carlo"]["u"].get<double>(), 0.0) << name;
  // The calibrated machine file loads and is a usable Exechon machine.
  const std::string poses = write("poses.csv", "x,y,z,i,j,k\n0,0,0,0,0,-1\n100,-50,200,0,0,-1\n");
  const CliRun ik = pkm({"exechon", "ik", "--machine", path("cal.json"), "--poses", poses});
  EXPECT_EQ(ik.code, 0) << ik.err;
  EXPECT_TRUE(std::filesystem::exists(path("cal.summary.json")));
}

/// The scenario's truth has leg B's base-joint offsets (l12B 0.7, l23B -0.45 mm, López-Custodio et
/// al. 2020): the 26-parameter fit finds them within their standard deviations, and the
/// 24-parameter model of Zoppi's closed form (the two held at 0) cannot absorb them.
TEST_F(CalibrateExechonCli, LegBBaseJointOffsetsAreIdentified) {
  constexpr double kSigmas = 5.0;        ///< agreement with the truth, in estimated σ
  constexpr double kWorseAtLeast = 2.0;  ///< held-out RMS ratio, offsets held at 0 vs identified
  const auto run = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args{"--data",
                                  path("sim/tracker-fit.csv"),
                                  "--holdout",
                                  path("sim/tracker-holdout.csv"),
                                  "--out",
                                  path("cal.json"),
                                  "--force",
                                  "--json"};
    args.insert(args.end(), extra.begin(), extra.end());
    const CliRun r = calibrate(args);
    EXPECT_EQ(r.code, 0) << r.err;
    return nlohmann::json::parse(r.out);
  };
  const auto truth = nlohmann::json::parse(slurp(path("sim/truth.json")))["tripod_errors"];
  const auto full = run({});
  for (const std::string key : {"l12B", "l23B"}) {
    const auto& params = full["parameters"];
    const auto it = std::find_if(
        params.begin(), params.end(), [&](const auto& p) { return p["name"] == "tripod." + key; });
    ASSERT_NE(it, params.end()) << key;
    const double sigma = (*it)["sigma"].get<double>();
    EXPECT_GT(sigma, 0.0) << key;
    EXPECT_NEAR((*it)["change"].get<double>(), truth[key].get<double>(), kSigmas * sigma) << key;
  }
  const auto zoppi = run({"--fix", "tripod.l12B", "--fix", "tripod.l23B"});
  const double with = full["holdout"]["after"]["rms"].get<double>();
  const double without = zoppi["holdout"]["after"]["rms"].get<double>();
  EXPECT_LT(with, kHeldOutRmsLimit);
  EXPECT_GT(without, kWorseAtLeast * with);
}

/// Seed 000's squareness (szX2 -0.034, sxP -14.74, syP 4.35, szP -2.85 mrad) from a tracker on the
/// table over all five axes, after the tripod calibration, with the PDGE tables known.
TEST_F(CalibrateExechonCli, HybridDataGiveTheFourSquarenessErrors) {
  constexpr double kSquarenessTolerance = 0.02e-3;  ///< rad: ~5 σ of the estimate
  constexpr double kHeldOutLimit = 0.03;            ///< mm
  const CliRun r = calibrate({"--data",
                              path("sim/tracker-fit.csv"),
                              path("sim/tracker-hybrid.csv"),
                              "--holdout",
                              path("sim/tracker-hybrid-holdout.csv"),
                              "--errors",
                              "mxt700s-seed000",
                              "--out",
                              path("cal.json"),
                              "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& s = j["hybrid"]["squareness"];
  EXPECT_NEAR(s["szX2"].get<double>(), -0.034e-3, kSquarenessTolerance);
  EXPECT_NEAR(s["sxP"].get<double>(), -14.74e-3, kSquarenessTolerance);
  EXPECT_NEAR(s["syP"].get<double>(), 4.35e-3, kSquarenessTolerance);
  EXPECT_NEAR(s["szP"].get<double>(), -2.85e-3, kSquarenessTolerance);
  EXPECT_TRUE(j["hybrid"]["tripod_error_motion"].get<bool>());
  EXPECT_LT(j["hybrid"]["holdout"]["after"]["rms"].get<double>(), kHeldOutLimit);
  EXPECT_FALSE(j["hybrid"].contains("errors_file"));
  // The errors file loads wherever geometric errors are accepted, with the estimate in it.
  const auto errors = nlohmann::json::parse(slurp(path("cal.errors.json")));
  EXPECT_NEAR(errors["squareness_urad"]["sxP"].get<double>(), -14740.0, 20.0);
  const CliRun vol = pkm({"volumetric",
                          "--machine",
                          "mxt700s-like",
                          "--errors",
                          path("cal.errors.json"),
                          "--commands",
                          write("c.csv", "x2,y2,xp,yp,zp\n100,50,0,0,0\n")});
  EXPECT_EQ(vol.code, 0) << vol.err;
}

TEST_F(CalibrateExechonCli, HybridDataNeedAHybridMachine) {
  expectUsageError(calibrate({"--machine",
                              "exechon-zoppi2010",
                              "--data",
                              path("sim/tracker-hybrid.csv"),
                              "--out",
                              path("x.json")}),
                   "hybrid");
}

/// The first `rows` observations of a scenario file, with its header: a lighter fit.
std::string headRows(const std::string& text, int rows) {
  std::string out;
  std::size_t pos = 0;
  int data = -1;  // the column-name line is not an observation
  while (pos < text.size() && data < rows) {
    const std::size_t end = std::min(text.find('\n', pos), text.size());
    const std::string line = text.substr(pos, end - pos);
    if (line.empty() || line[0] != '#') ++data;
    out += line + '\n';
    pos = end + 1;
  }
  return out;
}

TEST_F(CalibrateExechonCli, MonteCarloReportsTheSpreadTheCalibrationLeaves) {
  constexpr int kTrials = 3;  ///< few: each trial re-runs the fit
  constexpr int kRows = 40;   ///< of the scenario's 200 points: 120 equations for 30 unknowns
  const std::string data = write("fit40.csv", headRows(slurp(path("sim/tracker-fit.csv")), kRows));
  const CliRun r = calibrate({"--data",
                              data,
                              "--out",
                              path("cal.json"),
                              "--monte-carlo",
                              std::to_string(kTrials),
                              "--threads",
                              "2",
                              "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("monte_carlo"));
  const auto& mc = j["monte_carlo"];
  EXPECT_EQ(mc["trials"].get<int>(), kTrials);
  EXPECT_EQ(mc["failures"].get<int>(), 0);
  EXPECT_EQ(mc["parameter_sigma"].size(), 26u);
  EXPECT_EQ(mc["frame_sigma"].size(), 6u);  // the scenario's files are in the tracker frame
  EXPECT_DOUBLE_EQ(mc["sigma_position"].get<double>(), j["sigma"].get<double>());
  EXPECT_GT(mc["configurations"].get<int>(), 0);
  EXPECT_GT(mc["tool_sigma"]["mean"].get<double>(), 0.0);
  // The spread the calibration leaves is far below the error it removes (7.9 mm mean).
  EXPECT_LT(mc["tool_sigma"]["max"].get<double>(),
            j["tcp_error_map"]["before"]["mean"].get<double>());
  EXPECT_EQ(mc["tool_deviation"]["samples"].get<int>(), kTrials * mc["configurations"].get<int>());
  EXPECT_EQ(j["observations"]["points"].get<int>(), kRows);
  // One trial is no spread; a negative noise is refused.
  expectUsageError(
      calibrate(
          {"--data", path("sim/tracker-fit.csv"), "--out", path("m.json"), "--monte-carlo", "1"}),
      "--monte-carlo");
  expectUsageError(calibrate({"--data",
                              path("sim/tracker-fit.csv"),
                              "--out",
                              path("m.json"),
                              "--monte-carlo",
                              "2",
                              "--sigma-orientation",
                              "-1"}),
                   "direction_sigma");
}

TEST_F(CalibrateExechonCli, ReadableReportNamesTheLargestResidual) {
  const CliRun r = calibrate({"--data", path("sim/tracker-fit.csv"), "--out", path("cal.json")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("identifiable: 26 of 26"));
  EXPECT_THAT(r.out, HasSubstr("largest residual after the fit: "));
}

TEST_F(CalibrateExechonCli, RefusesBadDataAndOverwrites) {
  ASSERT_EQ(calibrate({"--data", path("sim/tracker-fit.csv"), "--out", path("cal.json")}).code, 0);
  expectUsageError(calibrate({"--data", path("sim/tracker-fit.csv"), "--out", path("cal.json")}),
                   "exists; pass --force");
  const std::string bad = write("bad.csv", "q0,q1,q2,c,a,x,y,z\n300,300,300,0,-20,1,2,zz\n");
  expectUsageError(calibrate({"--data", bad, "--out", path("bad.json")}), "bad.csv:2:");
  const std::string missing = write("missing.csv", "q0,q1,c,a,x,y,z\n300,300,0,-20,1,2,3\n");
  expectUsageError(calibrate({"--data", missing, "--out", path("bad.json")}),
                   "missing column 'q2'");
  const std::string few = write("few.csv",
                                "q0,q1,q2,c,a,x,y,z\n"
                                "300,300,300,0,-20,1,2,3\n"
                                "310,300,300,0,-20,1,2,3\n");
  expectUsageError(calibrate({"--data", few, "--out", path("few.json")}),
                   "few.csv: the tracker readings do not state their frame");
  expectUsageError(calibrate({"--data", few, "--frame", "world", "--out", path("few.json")}),
                   "too few observations");
  EXPECT_FALSE(std::filesystem::exists(path("bad.json")));
  EXPECT_FALSE(std::filesystem::exists(path("few.json")));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
