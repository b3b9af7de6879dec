// `pkm gcode run`: joint CSV format and rows, the report (text and JSON), exit codes 0/1/2,
// Exechon machines rejected, no overwrite without --force.
#include <nlohmann/json.hpp>

#include "support/cli_fixture.hpp"

namespace {

using pkm::test::CliTest;
using pkm::test::splitFields;
using pkm::test::splitLines;

constexpr int kExitViolation = 1;

class GcodeRunCli : public CliTest {};

TEST_F(GcodeRunCli, CleanProgramWritesCsvAndReport) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X10 F600\nG2 X20 Y0 I5 J0\nM2\n");
  const auto r = pkm({"gcode",
                      "run",
                      "--machine",
                      "hexapod-default",
                      prog,
                      "--out",
                      path("q.csv"),
                      "--report",
                      path("r.json")});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_THAT(r.out, ::testing::HasSubstr("result: all checks pass"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("cycle time:"));
  const auto lines = splitLines(slurp(path("q.csv")));
  ASSERT_GT(lines.size(), 3u);
  EXPECT_EQ(lines[0], "line,t,x,y,z,a,b,c,q0,q1,q2,q3,q4,q5");
  const auto first = splitFields(lines[1]);
  ASSERT_EQ(first.size(), 14u);
  EXPECT_EQ(first[0], "1");
  EXPECT_EQ(first[1], "0");
  const auto last = splitFields(lines.back());
  EXPECT_EQ(last[0], "3");
  EXPECT_EQ(last[2], "20");
  const auto j = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_EQ(j["points"].get<std::size_t>(), lines.size() - 1);
  EXPECT_GT(j["cycle_time_s"].get<double>(), 0.0);
  EXPECT_EQ(j["checks"]["stroke"]["violations"].get<int>(), 0);
}

TEST_F(GcodeRunCli, StrokeViolationExitsOneWithLine) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\n");
  const auto r = pkm({"gcode", "run", prog, "--report", path("r.json")});
  EXPECT_EQ(r.code, kExitViolation) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr(prog + ":3: stroke violated"));
  const auto j = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["checks"]["stroke"]["first_violation"]["line"].get<int>(), 3);
}

TEST_F(GcodeRunCli, UsageAndInputErrors) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X10 F600\n");
  expectUsageError(pkm({"gcode", "run", prog, "--tolerance", "0"}), "tolerance");
  expectUsageError(pkm({"gcode", "run", prog, "--max-joint-velocity", "-1"}), "velocity");
  expectUsageError(pkm({"gcode", "run", prog, "--machine", "mxt700s-like"}),
                   "hexapod machines only");
  const std::string bad = write("bad.ngc", "G0 X0\nG1 X1 Q\n");
  expectUsageError(pkm({"gcode", "run", bad}), "bad.ngc:2:");
  expectUsageError(pkm({"gcode", "run"}), "program");
}

TEST_F(GcodeRunCli, RefusesToOverwrite) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X10 F600\n");
  write("q.csv", "keep");
  expectUsageError(pkm({"gcode", "run", prog, "--out", path("q.csv")}), "--force");
  EXPECT_EQ(slurp(path("q.csv")), "keep");
  EXPECT_EQ(pkm({"gcode", "run", prog, "--out", path("q.csv"), "--force"}).code, 0);
  EXPECT_NE(slurp(path("q.csv")), "keep");
}

}  // namespace
