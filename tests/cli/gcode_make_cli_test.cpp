// `pkm gcode make SHAPE`: the program on standard output or --out (never over a file without
// --force), options from the library's parameter table, errors naming the parameter (exit 2).
#include <gtest/gtest.h>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

class GcodeMakeCli : public CliTest {};

TEST_F(GcodeMakeCli, TheSphereOnStandardOutput) {
  const CliRun r = pkm({"gcode",
                        "make",
                        "sphere",
                        "--radius",
                        "10",
                        "--z",
                        "190",
                        "--tool-radius",
                        "2",
                        "--levels",
                        "2",
                        "--feed",
                        "500"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out,
            "G21 G90 G17 F500 (pkm gcode make sphere)\nG0 X12 Y0 Z205\nG1 Z188\n"
            "G17 G3 X12 Y0 I-12 J0\nG18 G2 X8.4853 Z196.4853 I-12 K0\n"
            "G17 G3 X8.4853 Y0 I-8.4853 J0\nG18 G2 X0 Z200 I-8.4853 K-8.4853\nG17 G0 Z205\nM2\n");
}

TEST_F(GcodeMakeCli, OutIsNeverOverwrittenWithoutForce) {
  const std::string out = write("face.ngc", "keep me");
  expectUsageError(pkm({"gcode", "make", "face", "--out", out}), "--force");
  EXPECT_EQ(slurp(out), "keep me");
  const CliRun r = pkm({"gcode", "make", "face", "--step", "20", "--out", out, "--force"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(slurp(out), HasSubstr("G1 Y-10\nG1 X-30\n"));
  // The written program runs on the default hexapod.
  const CliRun run = pkm({"gcode", "run", out});
  EXPECT_EQ(run.code, 0) << run.out << run.err;
}

TEST_F(GcodeMakeCli, BadValuesAreUsageErrors) {
  expectUsageError(pkm({"gcode", "make", "drill", "--holes", "2.5"}),
                   "drill: holes must be a whole number");
  expectUsageError(pkm({"gcode", "make", "pocket", "--stepover", "1e-6"}), "choose a larger step");
  expectUsageError(pkm({"gcode", "make", "sphere", "--feed", "0"}), "the feed must be > 0");
  EXPECT_EQ(pkm({"gcode", "make", "cube"}).code, 2);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
