// The CLI contract of `pkm compensate table`: each format's file from ISO 230-2 or straightness
// input (exact text where the numbers are exact binary fractions), the summary and JSON, exit code
// 2 with FILE:LINE on bad input, --force, --max-points and the LinuxCNC 256-row limit.
#include <fmt/format.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pkm/compensation/linuxcnc_comp.hpp"
#include "pkm/compensation/siemens_comp.hpp"
#include "support/cli_fixture.hpp"
#include "support/tolerances.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using Json = nlohmann::json;
using ::testing::HasSubstr;

constexpr double kTolText = 5e-10;  ///< SINUMERIK / ISG numbers carry 9 decimals (mm)

class CompensateCli : public CliTest {
 protected:
  /// Targets 0, 64, 128; deviations (exact binary fractions) ↑ 2⁻⁷, 2⁻⁸, −2⁻⁹ and ↓ 0, −2⁻⁸,
  /// −2⁻⁷, two identical runs each.
  std::string positioning() const {
    std::string text = "target,direction,run,measured\n";
    const double t[3] = {0, 64, 128}, up[3] = {0.0078125, 0.00390625, -0.001953125},
                 down[3] = {0, -0.00390625, -0.0078125};
    for (int run = 1; run <= 2; ++run) {
      for (int i = 0; i < 3; ++i) text += fmt::format("{},+,{},{}\n", t[i], run, t[i] + up[i]);
      for (int i = 2; i >= 0; --i) text += fmt::format("{},-,{},{}\n", t[i], run, t[i] + down[i]);
    }
    return write("pos.csv", text);
  }
  /// Straightness of Y over X: deviations 2⁻¹⁰, −2⁻⁹, 3·2⁻¹⁰ at 0, 100, 200.
  std::string straightness() const {
    return write("str.csv",
                 "position,deviation\n0,0.0009765625\n100,-0.001953125\n200,0.0029296875\n");
  }
};

TEST_F(CompensateCli, Linuxcnc1ExactFileAndSummary) {
  const CliRun r = pkm({"compensate",
                        "table",
                        "--data",
                        positioning(),
                        "--format",
                        "linuxcnc1",
                        "--axis",
                        "X",
                        "--out",
                        path("x.comp")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("x.comp")),
            "0 -0.0078125 0\n"
            "64 -0.00390625 0.00390625\n"
            "128 0.001953125 0.0078125\n");
  EXPECT_THAT(r.out, HasSubstr("rows\t3\n"));
  EXPECT_THAT(r.out, HasSubstr("range\t0\t128 mm\n"));
  EXPECT_THAT(r.out, HasSubstr("max_correction\t0.0078125 mm\n"));
  // The file loads as LinuxCNC would and corrects the command by −error.
  const auto f = compensation::readLinuxcncComp(path("x.comp"), 1);
  EXPECT_EQ(compensation::applyLinuxcncComp(f, 64.0, 1), 64.0 - 0.00390625);
}

TEST_F(CompensateCli, Linuxcnc0ExactFile) {
  const CliRun r = pkm({"compensate",
                        "table",
                        "--data",
                        positioning(),
                        "--format",
                        "linuxcnc0",
                        "--axis",
                        "X",
                        "--out",
                        path("x0.comp")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("x0.comp")),
            "0 0.0078125 0\n"
            "64 64.00390625 63.99609375\n"
            "128 127.998046875 127.9921875\n");
}

TEST_F(CompensateCli, SiemensEecAndIsgWriteTheMeanError) {
  CliRun r = pkm({"compensate",
                  "table",
                  "--data",
                  positioning(),
                  "--format",
                  "siemens-eec",
                  "--axis",
                  "X1",
                  "--out",
                  path("x.mpf")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto eec = compensation::parseSiemensEec(slurp(path("x.mpf")), "x.mpf");
  const std::vector<double> mean{0.00390625, 0.0, -0.0048828125};
  ASSERT_EQ(eec.values.size(), mean.size());
  for (std::size_t i = 0; i < mean.size(); ++i) EXPECT_NEAR(eec.values[i], mean[i], kTolText);
  EXPECT_EQ(eec.step, 64.0);
  EXPECT_THAT(r.err, HasSubstr("pkm: note: siemens-eec has one table"));
  r = pkm({"compensate",
           "table",
           "--data",
           positioning(),
           "--format",
           "isg",
           "--axis",
           "x",
           "--out",
           path("x.csv")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(slurp(path("x.csv")), HasSubstr("X EXX\n0 0.00390625\n64 0\n128 -0.004882812\n"));
}

TEST_F(CompensateCli, SiemensCecFromStraightness) {
  // Default --line endpoint: the line through the end points (0.0009765625 → 0.0029296875) is
  // removed, leaving 0, −0.00390625, 0.
  CliRun r = pkm({"compensate",
                  "table",
                  "--data",
                  straightness(),
                  "--format",
                  "siemens-cec",
                  "--input-axis",
                  "X1",
                  "--output-axis",
                  "Y1",
                  "--out",
                  path("cec.mpf"),
                  "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto cec = compensation::parseSiemensCec(slurp(path("cec.mpf")), "cec.mpf");
  EXPECT_EQ(cec.input_axis, "X1");
  EXPECT_EQ(cec.output_axis, "Y1");
  EXPECT_EQ(cec.values, (std::vector<double>{0.0, -0.00390625, 0.0}));
  const Json j = Json::parse(r.out);
  EXPECT_EQ(j["rows"].get<int>(), 3);
  EXPECT_EQ(j["input_axis"].get<std::string>(), "X1");
  EXPECT_EQ(j["max_correction"].get<double>(), 0.00390625);
  // --line raw keeps the measured deviations.
  r = pkm({"compensate",
           "table",
           "--data",
           straightness(),
           "--format",
           "isg",
           "--input-axis",
           "X",
           "--output-axis",
           "Y",
           "--line",
           "raw",
           "--out",
           path("eyx.csv")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(slurp(path("eyx.csv")),
              HasSubstr("X EYX\n0 0.000976562\n100 -0.001953125\n200 0.002929688\n"));
}

TEST_F(CompensateCli, RefusesToOverwriteWithoutForce) {
  const std::string out = write("x.comp", "keep me\n");
  const std::vector<std::string> args{"compensate",
                                      "table",
                                      "--data",
                                      positioning(),
                                      "--format",
                                      "linuxcnc1",
                                      "--axis",
                                      "X",
                                      "--out",
                                      out};
  expectUsageError(pkm(args), "exists; refusing to overwrite (use --force)");
  EXPECT_EQ(slurp(out), "keep me\n");
  std::vector<std::string> forced = args;
  forced.push_back("--force");
  const CliRun r = pkm(forced);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(slurp(out), HasSubstr("64 -0.00390625 0.00390625\n"));
}

TEST_F(CompensateCli, BadInputIsExitTwoWithFileAndLine) {
  const std::string bad = write("bad.csv", "target,direction,run,measured\n0,+,1,0\n0,+,2,x\n");
  expectUsageError(pkm({"compensate",
                        "table",
                        "--data",
                        bad,
                        "--format",
                        "linuxcnc1",
                        "--axis",
                        "X",
                        "--out",
                        path("o")}),
                   "bad.csv:3:");
  const std::string dup = write("dup.csv", "target,direction,run,measured\n0,+,1,0\n0,+,1,0\n");
  expectUsageError(pkm({"compensate",
                        "table",
                        "--data",
                        dup,
                        "--format",
                        "linuxcnc1",
                        "--axis",
                        "X",
                        "--out",
                        path("o")}),
                   "dup.csv:3: duplicate reading");
  const std::string nan = write("nan.csv", "position,deviation\n0,0\n1,nan\n");
  expectUsageError(pkm({"compensate",
                        "table",
                        "--data",
                        nan,
                        "--format",
                        "siemens-cec",
                        "--input-axis",
                        "X1",
                        "--output-axis",
                        "Y1",
                        "--out",
                        path("o")}),
                   "nan.csv:3:");
  EXPECT_FALSE(std::filesystem::exists(path("o")));
}

TEST_F(CompensateCli, UsageErrors) {
  const std::string data = positioning();
  expectUsageError(pkm({"compensate",
                        "table",
                        "--data",
                        data,
                        "--format",
                        "fanuc",
                        "--axis",
                        "X",
                        "--out",
                        path("o")}),
                   "--format");
  expectUsageError(
      pkm({"compensate", "table", "--data", data, "--format", "linuxcnc1", "--out", path("o")}),
      "--axis is required");
  expectUsageError(
      pkm({"compensate", "table", "--data", data, "--format", "siemens-cec", "--out", path("o")}),
      "--input-axis and --output-axis");
  expectUsageError(pkm({"compensate",
                        "table",
                        "--data",
                        data,
                        "--format",
                        "linuxcnc1",
                        "--axis",
                        "X",
                        "--max-points",
                        "300",
                        "--out",
                        path("o")}),
                   "256");
  expectUsageError(pkm({"compensate",
                        "table",
                        "--data",
                        data,
                        "--format",
                        "isg",
                        "--axis",
                        "A",
                        "--out",
                        path("o")}),
                   "X, Y, Z");
}

TEST_F(CompensateCli, MaxPointsResamples) {
  const CliRun r = pkm({"compensate",
                        "table",
                        "--data",
                        positioning(),
                        "--format",
                        "linuxcnc1",
                        "--axis",
                        "X",
                        "--max-points",
                        "2",
                        "--out",
                        path("x.comp")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(slurp(path("x.comp")), "0 -0.0078125 0\n128 0.001953125 0.0078125\n");
  EXPECT_THAT(r.err, HasSubstr("resampled 3 rows to 2"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
