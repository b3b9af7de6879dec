// `pkm gcode moves`: CSV format, --out/--force, tool table option, errors with FILE:LINE.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace {

using ::testing::HasSubstr;

class GcodeCli : public CliTest {};

TEST_F(GcodeCli, MovesCsvOnStdout) {
  const std::string prog =
      write("p.ngc", "G21 G90 G10 L2 P1 X100\nG0 X1 Y2\nG2 X11 Y2 I5 J0 F300\nM2\n");
  const CliRun r = pkm({"gcode", "moves", prog});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "line,kind,x,y,z,a,b,c,cx,cy,cz,turns,plane,feed");
  EXPECT_EQ(lines[1], "2,rapid,101,2,0,0,0,0,,,,0,XY,");
  const auto f = splitFields(lines[2]);
  ASSERT_EQ(f.size(), 14u);
  EXPECT_EQ(f[1], "arc");
  EXPECT_EQ(num(f[2]), 111.0);
  EXPECT_EQ(num(f[8]), 106.0);
  EXPECT_EQ(num(f[9]), 2.0);
  EXPECT_EQ(f[10], "");
  EXPECT_EQ(f[11], "-1");
  EXPECT_EQ(num(f[13]), 300.0);
  EXPECT_THAT(r.err, HasSubstr("2 moves"));
}

TEST_F(GcodeCli, OutRefusesToOverwriteWithoutForce) {
  const std::string prog = write("p.ngc", "G0 X1\nM2\n");
  const std::string out = write("moves.csv", "keep me");
  expectUsageError(pkm({"gcode", "moves", prog, "--out", out}), "--force");
  EXPECT_EQ(slurp(out), "keep me");
  const CliRun r = pkm({"gcode", "moves", prog, "--out", out, "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(slurp(out), HasSubstr("1,rapid,1,0,0"));
}

TEST_F(GcodeCli, ToolTableInInch) {
  const std::string prog = write("p.ngc", "T1 M6 G43\nG0 Z0\nM2\n");
  const std::string tbl = write("t.tbl", "T1 P1 Z1 ;one inch\n");
  const CliRun r = pkm({"gcode", "moves", prog, "--tool-table", tbl, "--tool-units", "inch"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("2,rapid,0,0,25.4,"));
  expectUsageError(pkm({"gcode", "moves", prog, "--tool-table", tbl, "--tool-units", "cm"}),
                   "--tool-units");
}

TEST_F(GcodeCli, ErrorsNameFileAndLine) {
  const std::string prog = write("bad.ngc", "G0 X1\nG1 X2 F100\nG33 X3\nM2\n");
  expectUsageError(pkm({"gcode", "moves", prog}), "bad.ngc:3: unsupported G code G33");
  const std::string loop = write("loop.ngc", "o1 while [1]\no1 endwhile\n");
  expectUsageError(pkm({"gcode", "moves", loop, "--max-iterations", "100"}),
                   "loop.ngc:2: loop o1 exceeded 100 iterations");
  expectUsageError(pkm({"gcode", "moves", path("missing.ngc")}), "cannot open");
  const std::string out = path("none.csv");
  expectUsageError(pkm({"gcode", "moves", prog, "--out", out}), "bad.ngc:3");
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST_F(GcodeCli, ShippedExamplesRun) {
  for (const char* name : {"sphere.ngc", "drilling.ngc", "pocket_loops.ngc"}) {
    const std::string tbl = std::string(PKM_SOURCE_DIR) + "/tests/cnc/corpus/tools_mm.tbl";
    const CliRun r = pkm({"gcode",
                          "moves",
                          std::string(PKM_SOURCE_DIR) + "/examples/gcode/" + name,
                          "--tool-table",
                          tbl});
    EXPECT_EQ(r.code, 0) << name << ": " << r.err;
    EXPECT_GT(splitLines(r.out).size(), 10u) << name;
  }
}

}  // namespace
}  // namespace pkm::test
