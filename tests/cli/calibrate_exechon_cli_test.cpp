// `pkm calibrate exechon` on the simulator's exechon-calibration data.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace {

using ::testing::HasSubstr;

/// Issue 6: held-out error ≤ 3× the measurement noise. The scenario's tracker reads 5 µm in range
/// and 2 µrad per angle at ~2 m (4 µm across the line of sight): ~5 µm per coordinate, ~8 µm in
/// 3-D; the held-out RMS compares a prediction with a noisy measurement.
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
    std::vector<std::string> args{"calibrate", "exechon", "--machine", "mxt700s-like"};
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
  EXPECT_EQ(j["parameters"].size(), 24u);
  EXPECT_THAT(j["worst_observations"][0]["source"].get<std::string>(),
              HasSubstr("tracker-fit.csv:"));
  // The calibrated machine file loads and is a usable Exechon machine.
  const std::string poses = write("poses.csv", "x,y,z,i,j,k\n0,0,0,0,0,-1\n100,-50,200,0,0,-1\n");
  const CliRun ik = pkm({"exechon", "ik", "--machine", path("cal.json"), "--poses", poses});
  EXPECT_EQ(ik.code, 0) << ik.err;
  EXPECT_TRUE(std::filesystem::exists(path("cal.summary.json")));
}

TEST_F(CalibrateExechonCli, ReadableReportNamesTheLargestResidual) {
  const CliRun r = calibrate({"--data", path("sim/tracker-fit.csv"), "--out", path("cal.json")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("identifiable: 24 of 24"));
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
  expectUsageError(calibrate({"--data", few, "--out", path("few.json")}), "too few observations");
  EXPECT_FALSE(std::filesystem::exists(path("bad.json")));
  EXPECT_FALSE(std::filesystem::exists(path("few.json")));
}

}  // namespace
}  // namespace pkm::test
