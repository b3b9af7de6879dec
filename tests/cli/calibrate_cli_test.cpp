// `pkm calibrate hexapod` on the simulator's seed004-hexapod-calibration data.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// Acceptance: held-out TCP error after calibration ≤ 3× the measurement noise. The scenario's
/// tracker reads ~3 µm per coordinate plus 20 µrad orientation noise, and the machine has 5 µm
/// backlash and 2 µm repeatability the 42-parameter model cannot absorb: 3 × ~5 µm.
constexpr double kHeldOutRmsLimit = 0.015;  ///< mm
constexpr double kBeforeAtLeast = 5.0;      ///< mm: the injected assembly errors are large

class CalibrateCli : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    const CliRun sim = pkm({"simulate", "seed004-hexapod-calibration", "--out", path("sim")});
    ASSERT_EQ(sim.code, 0) << sim.err;
  }
};

TEST_F(CalibrateCli, FullPoseTrackerCalibrationMeetsTheTarget) {
  const CliRun r = pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        path("sim/tracker-pose.csv"),
                        "--holdout",
                        path("sim/tracker-holdout.csv"),
                        "--registration",
                        path("sim/tracker-pose-registration.csv"),
                        "--out",
                        path("cal.json"),
                        "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["solver"]["converged"].get<bool>());
  // Registered on the table's nests: world data, all 42 parameters.
  EXPECT_EQ(j["identifiability"]["parameters"], 42);
  EXPECT_EQ(j["identifiability"]["rank"], 42);
  EXPECT_EQ(j["world_frame"], "registered");
  EXPECT_EQ(j["registration"]["references"], 6);
  EXPECT_LT(j["registration"]["residuals"]["max"].get<double>(), kHeldOutRmsLimit);
  EXPECT_GT(j["holdout"]["before"]["rms"].get<double>(), kBeforeAtLeast);
  EXPECT_LT(j["holdout"]["after"]["rms"].get<double>(), kHeldOutRmsLimit);
  ASSERT_EQ(j["worst_observations"].size(), 5u);
  EXPECT_THAT(j["worst_observations"][0]["source"].get<std::string>(),
              HasSubstr("tracker-pose.csv:"));
  // The calibrated machine file loads in every other command, and the HAL block exists.
  const CliRun describe = pkm({"hexapod", "describe", "--machine", path("cal.json")});
  EXPECT_EQ(describe.code, 0) << describe.err;
  EXPECT_THAT(slurp(path("cal.hal")), HasSubstr("setp genhexkins.base.0.x"));
  EXPECT_THAT(slurp(path("cal.pkmhexkins.hal")), HasSubstr("setp pkmhexkins.length-offset.5 "));
  EXPECT_TRUE(nlohmann::json::parse(slurp(path("cal.summary.json"))).contains("parameters"));
}

TEST_F(CalibrateCli, AnUnregisteredTrackerFrameGoesIntoNoController) {
  const CliRun r = pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        path("sim/tracker-pose.csv"),
                        "--out",
                        path("unreg.json"),
                        "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["identifiability"]["parameters"], 48);  // 42 + the tracker frame
  EXPECT_EQ(j["identifiability"]["rank"], 42);        // the base frame's 6 rigid-motion freedoms
  EXPECT_EQ(j["identifiability"]["unidentifiable"].size(), 6u);
  EXPECT_EQ(j["world_frame"], "unregistered");
  EXPECT_EQ(j["outputs"]["hal"], "");
  EXPECT_EQ(slurp(path("unreg.hal")), "");
  const CliRun config =
      pkm({"linuxcnc", "config", "--machine", path("unreg.json"), "--out", path("unreg-cfg")});
  EXPECT_EQ(config.code, 2);
  EXPECT_THAT(config.err, HasSubstr("--registration FILE"));
  const CliRun install = pkm({"linuxcnc",
                              "install",
                              "--calibration",
                              path("unreg.json"),
                              "--ini",
                              path("sim/truth.json")});
  EXPECT_EQ(install.code, 2);
  EXPECT_THAT(install.err, HasSubstr("pkm linuxcnc install: refused"));
  const CliRun world = pkm({"calibrate",
                            "hexapod",
                            "--machine",
                            "hexapod-default",
                            "--data",
                            path("sim/tracker-pose.csv"),
                            "--frame",
                            "world",
                            "--registration",
                            path("sim/tracker-pose-registration.csv"),
                            "--out",
                            path("w.json")});
  EXPECT_EQ(world.code, 2);
  EXPECT_THAT(world.err, HasSubstr("a registration places readings taken in the tracker's"));
}

/// The scenario's struts have 5 µm backlash; the 200 poses are taken in file order.
TEST_F(CalibrateCli, BacklashIsIdentifiedFromTheMeasurementOrder) {
  constexpr double kTrueBacklash = 0.005;        ///< mm, the scenario's
  constexpr double kBacklashTolerance = 0.0015;  ///< mm, about 3σ of the estimate
  const CliRun r = pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        path("sim/tracker-pose.csv"),
                        "--holdout",
                        path("sim/tracker-holdout.csv"),
                        "--out",
                        path("cal.json"),
                        "--backlash",
                        "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_TRUE(j.contains("backlash"));
  ASSERT_EQ(j["backlash"]["values"].size(), 6u);
  for (const auto& b : j["backlash"]["values"])
    EXPECT_NEAR(b.get<double>(), kTrueBacklash, kBacklashTolerance);
  EXPECT_EQ(j["identifiability"]["parameters"], 54);  // 42 + frame + backlash
  EXPECT_LT(j["holdout"]["after"]["rms"].get<double>(), kHeldOutRmsLimit);
}

/// A ball bar on a pivot and an interferometer line, generated from the nominal machine: the
/// files load, the fit explains them exactly, and the rigid motions distances cannot see are named.
TEST_F(CliTest, DistanceFilesCalibrateShapeAndNameWhatTheyCannotSee) {
  const kinematics::HexapodModel m = io::loadHexapodMachine("hexapod-default").model;
  kinematics::HexapodData d(m);
  const auto readings = [&](double x, double y, double z) {
    kinematics::PoseRpy p = m.home;
    p.position += Eigen::Vector3d(x, y, z);
    return kinematics::inverseKinematics(m, d, p);
  };
  const auto tcp = [&](const kinematics::StrutVector& q) {
    EXPECT_TRUE(kinematics::forwardKinematics(m, d, q, m.home).ok());
    return Eigen::Vector3d(d.world_p_tcp);
  };
  const Eigen::Vector3d pivot = m.home.position + Eigen::Vector3d(0, 0, -120);
  std::string ballbar = fmt::format(
      "# pivot mm: ({}, {}, {})\nl0,l1,l2,l3,l4,l5,distance\n", pivot.x(), pivot.y(), pivot.z());
  std::string line = "l0,l1,l2,l3,l4,l5,distance\n";
  const kinematics::StrutVector q0 = readings(-100, -100, -40);
  const Eigen::Vector3d p0 = tcp(q0);
  const auto row = [](const kinematics::StrutVector& q, double dist) {
    return fmt::format("{},{},{},{},{},{},{}\n", q[0], q[1], q[2], q[3], q[4], q[5], dist);
  };
  line += row(q0, 0.0);
  for (int k = 0; k < 40; ++k) {
    const double a = 0.157 * k;
    const kinematics::StrutVector qb = readings(120 * std::cos(a), 120 * std::sin(a), 10 * (k % 5));
    ballbar += row(qb, (tcp(qb) - pivot).norm());
    const kinematics::StrutVector ql =
        readings(5.0 * k - 100, 4.0 * k - 100, 2.0 * k - 40 + (k % 3));
    line += row(ql, (tcp(ql) - p0).norm());
  }
  const CliRun r = pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        write("ballbar.csv", ballbar),
                        write("line.csv", line),
                        "--out",
                        path("cal.json"),
                        "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["observations"]["distances"], 80);
  EXPECT_LT(j["residuals"]["after"]["max"].get<double>(), 1e-6);
  EXPECT_GE(j["identifiability"]["unidentifiable"].size(), 6u);
  // A line whose first row is not its zero is an error naming the line.
  const std::string bad =
      write("bad.csv", "l0,l1,l2,l3,l4,l5,distance\n1,2,3,4,5,6,0.5\n1,2,3,4,5,7,1\n");
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        bad,
                        "--out",
                        path("bad.json")}),
                   "bad.csv:2:");
}

TEST_F(CalibrateCli, MonteCarloGivesTheWorkspaceTcpUncertainty) {
  const CliRun r = pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        path("sim/tracker-pose.csv"),
                        "--out",
                        path("mc.json"),
                        "--json",
                        "--monte-carlo",
                        "12",
                        "--threads",
                        "2",
                        "--sigma-position",
                        "0.004",
                        "--sigma-orientation",
                        "20"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["monte_carlo"]["trials"], 12);
  EXPECT_EQ(j["monte_carlo"]["failures"], 0);
  EXPECT_EQ(j["monte_carlo"]["parameter_sigma"].size(), 42u);
  const auto& map = j["tcp_error_map"];
  EXPECT_GT(map["before"]["mean"].get<double>(), kBeforeAtLeast);
  // What the calibration leaves from the tracker noise alone is far below the held-out limit.
  EXPECT_LT(map["after"]["p95"].get<double>(), kHeldOutRmsLimit);
  EXPECT_LE(map["after"]["p95"].get<double>(), map["after"]["max"].get<double>());
}

TEST_F(CalibrateCli, ParametersCarryUWithTheirBudgetAndTheTcpItsPredictedU) {
  const std::vector<std::string> base = {"calibrate",
                                         "hexapod",
                                         "--machine",
                                         "hexapod-default",
                                         "--data",
                                         path("sim/tracker-pose.csv"),
                                         "--holdout",
                                         path("sim/tracker-holdout.csv"),
                                         "--out",
                                         path("cal.json"),
                                         "--force"};
  std::vector<std::string> args = base;
  for (const char* a : {"--json", "--uncertainty-trials", "40", "--threads", "1"})
    args.emplace_back(a);
  const CliRun r = pkm(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& u = j["uncertainty"];
  EXPECT_EQ(u["coverage_factor"], 2.0);
  EXPECT_EQ(u["sources"], "typical datasheet values");
  // Every parameter row keeps its keys and gains U; its budget lists the tracker and the probe.
  for (const auto& p : j["parameters"]) {
    ASSERT_TRUE(p.contains("sigma")) << p.dump();
    const auto& b = u["parameters"][p["name"].get<std::string>()];
    EXPECT_GT(p["U"].get<double>(), 0.0) << p.dump();
    EXPECT_EQ(p["U"].get<double>(), b["U"].get<double>());
    EXPECT_NEAR(b["U"].get<double>(), 2.0 * b["u_c"].get<double>(), 1e-12);
    ASSERT_GE(b["budget"].size(), 2u) << b.dump();
    for (const char* key : {"name", "value", "distribution", "sensitivity", "contribution"})
      EXPECT_TRUE(b["budget"][0].contains(key)) << key;
    // GUM S1 re-fits agree with the linear propagation (40 trials: each u within ±35 %).
    EXPECT_NEAR(b["monte_carlo"]["U"].get<double>() / b["U"].get<double>(), 1.0, 0.35) << p["name"];
  }
  EXPECT_EQ(u["monte_carlo"]["trials"], 40);
  EXPECT_TRUE(u["parameters"].contains("frame.x"));  // the tracker frame's unknowns too
  // The predicted TCP uncertainty at the 50 held-out poses, rigid motion of the world removed:
  // tens of µm with a typical tracker and 6-DOF probe, above the measured held-out error.
  EXPECT_EQ(u["tcp"]["count"], 50);
  EXPECT_GT(u["tcp"]["U_max"].get<double>(), j["holdout"]["after"]["max"].get<double>());
  EXPECT_LT(u["tcp"]["U_max"].get<double>(), 0.1);
  // Text: value ± U per parameter, the largest budget, the TCP line.
  const CliRun t = pkm(base);
  ASSERT_EQ(t.code, 0) << t.err;
  EXPECT_THAT(t.out, HasSubstr("calibrated parameters (k = 2; sources: typical datasheet values)"));
  EXPECT_THAT(t.out, HasSubstr("  offset0      "));
  EXPECT_THAT(t.out, HasSubstr("6-DOF probe orientation\t0.000175 rad\trectangular"));
  EXPECT_THAT(t.out, HasSubstr("predicted TCP uncertainty after calibration (k = 2, 50 held-out"));
  // A worse tracker widens U; a bad sources file stops with FILE:LINE and exit 2.
  std::vector<std::string> worse = base;
  for (const std::string& a : {std::string("--json"),
                               std::string("--uncertainty"),
                               write("tracker.json", R"({"tracker": {"accuracy_mm": 0.1}})")})
    worse.push_back(a);
  const auto w = nlohmann::json::parse(pkm(worse).out);
  EXPECT_EQ(w["uncertainty"]["sources"].get<std::string>(), path("tracker.json"));
  EXPECT_GT(w["parameters"][0]["U"].get<double>(), j["parameters"][0]["U"].get<double>());
  std::vector<std::string> bad = base;
  bad.push_back("--uncertainty");
  bad.push_back(write("bad.json", "{\n  \"tracker\": {\"range\": 1}\n}\n"));
  const CliRun b = pkm(bad);
  EXPECT_EQ(b.code, 2);
  EXPECT_THAT(b.err, HasSubstr("bad.json:2: /tracker/range: unknown key"));
}

TEST_F(CalibrateCli, DialGaugeCalibrationNamesWhatItCannotSee) {
  // Without prior information the fit wanders along the directions the gauges see only weakly
  // (platform joints moved by ~80 mm): refused, naming the remedy.
  std::vector<std::string> args{"calibrate",
                                "hexapod",
                                "--machine",
                                "hexapod-default",
                                "--data",
                                path("sim/constrained-motion.csv"),
                                "--out",
                                path("gauge.json"),
                                "--json"};
  expectUsageError(pkm(args), "add --prior-sigma and --measurement-sigma");
  EXPECT_FALSE(std::filesystem::exists(path("gauge.json")));
  for (const char* a : {"--prior-sigma", "20", "--measurement-sigma", "0.002"}) args.push_back(a);
  const CliRun r = pkm(args);
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_LT(j["identifiability"]["rank"].get<int>(), 42);
  EXPECT_FALSE(j["identifiability"]["unidentifiable"].empty());
  EXPECT_LT(j["residuals"]["after"]["rms"].get<double>(),
            0.01 * j["residuals"]["before"]["rms"].get<double>());
}

TEST_F(CalibrateCli, RefusesToOverwriteAndRejectsBadData) {
  ASSERT_EQ(pkm({"calibrate",
                 "hexapod",
                 "--machine",
                 "hexapod-default",
                 "--data",
                 path("sim/tracker-pose.csv"),
                 "--out",
                 path("cal.json")})
                .code,
            0);
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        path("sim/tracker-pose.csv"),
                        "--out",
                        path("cal.json")}),
                   "exists; pass --force");
  // Too few poses for 48 unknowns.
  const std::string few = write("few.csv",
                                "l0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n"
                                "250,250,250,250,250,250,0,0,200,0,0,0\n"
                                "260,250,250,250,250,250,0,0,210,0,0,0\n");
  // A tracker export without a '# frame:' line and without --frame: refused, naming the option.
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        few,
                        "--out",
                        path("few.json")}),
                   "few.csv: the tracker readings do not state their frame");
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        few,
                        "--frame",
                        "world",
                        "--out",
                        path("few.json")}),
                   "too few observations");
  // A bad number names the file and line.
  const std::string bad =
      write("bad.csv", "l0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n1,2,3,4,5,6,7,8,x,0,0,0\n");
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--machine",
                        "hexapod-default",
                        "--data",
                        bad,
                        "--out",
                        path("bad.json")}),
                   "bad.csv:2:");
  EXPECT_FALSE(std::filesystem::exists(path("few.json")));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
