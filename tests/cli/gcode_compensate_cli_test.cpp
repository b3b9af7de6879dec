// `pkm gcode compensate`: a calibrated machine (as `pkm calibrate hexapod` names it) with the
// nominal found by name, the output's line structure, no overwrite without --force, usage errors.
#include <fstream>
#include <iterator>
#include <string>

#include "support/cli_fixture.hpp"

namespace PKM_TEST_NS {

using pkm::test::CliTest;
using pkm::test::splitLines;

class GcodeCompensateCli : public CliTest {
 protected:
  /// The built-in default machine renamed as a calibration result, one base joint moved 0.4 mm.
  static std::string calibratedJson() {
    std::string j = slurp(std::string(PKM_SOURCE_DIR) + "/data/machines/hexapod-default.json");
    const std::string name = "\"name\": \"pkm-hx1200\"";
    j.replace(j.find(name), name.size(), "\"name\": \"pkm-hx1200-calibrated\"");
    const std::string base = "[-124.747, 586.8886, 1200.0]";
    j.replace(j.find(base), base.size(), "[-124.347, 586.8886, 1200.0]");
    return j;
  }
};

TEST_F(GcodeCompensateCli, RewritesMotionLinesOnly) {
  const std::string cal = write("cal.json", calibratedJson());
  const std::string prog =
      write("p.ngc", "(keep me)\nN1 G0 X0 Y0 Z200\nN2 G1 X30 F600 (cut)\nM2\n");
  const auto r = pkm({"gcode", "compensate", "--machine", cal, prog});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_GE(lines.size(), 4u);
  EXPECT_EQ(lines[0], "(keep me)");
  EXPECT_EQ(lines[1].rfind("N1 G0 X", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("N2 G1 X", 0), 0u) << lines[2];
  EXPECT_THAT(lines[2], ::testing::HasSubstr("F600 (cut)"));
  EXPECT_EQ(lines.back(), "M2");
  EXPECT_THAT(r.err,
              ::testing::HasSubstr("nominal pkm-hx1200 -> calibrated pkm-hx1200-calibrated"));
}

TEST_F(GcodeCompensateCli, RefusesToOverwriteAndReportsErrors) {
  const std::string cal = write("cal.json", calibratedJson());
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X30 F600\nM2\n");
  write("out.ngc", "keep");
  expectUsageError(pkm({"gcode", "compensate", "--machine", cal, prog, "--out", path("out.ngc")}),
                   "--force");
  EXPECT_EQ(slurp(path("out.ngc")), "keep");
  ASSERT_EQ(
      pkm({"gcode", "compensate", "--machine", cal, prog, "--out", path("out.ngc"), "--force"})
          .code,
      0);
  EXPECT_THAT(slurp(path("out.ngc")), ::testing::HasSubstr("G1 X"));
  // A machine whose nominal cannot be told from its name needs --nominal.
  expectUsageError(pkm({"gcode", "compensate", "--machine", "hexapod-default", prog}), "--nominal");
  EXPECT_EQ(pkm({"gcode",
                 "compensate",
                 "--machine",
                 "hexapod-default",
                 "--nominal",
                 "hexapod-default",
                 prog})
                .code,
            0);
  const std::string g92 = write("g92.ngc", "G0 X0 Y0 Z200\nG92 X[#1]\nM2\n");
  expectUsageError(pkm({"gcode", "compensate", "--machine", cal, g92}), "g92.ngc:2:");
  expectUsageError(pkm({"gcode", "compensate", prog}), "--machine");
}

/// The drilling example (G81..G89, G73, L repeats in G91) is expanded, and the result runs.
TEST_F(GcodeCompensateCli, DrillingCyclesAreExpandedAndTheResultRuns) {
  const std::string cal = write("cal.json", calibratedJson());
  const auto r = pkm({"gcode",
                      "compensate",
                      "--machine",
                      cal,
                      std::string(PKM_SOURCE_DIR) + "/examples/gcode/drilling.ngc",
                      "--out",
                      path("drill.ngc")});
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string out = slurp(path("drill.ngc"));
  const std::string body = out.substr(out.find('\n'));  // line 1 is a comment that names them
  for (const char* cycle : {"G81", "G82", "G83", "G73", "G85", "G89"})
    EXPECT_EQ(body.find(cycle), std::string::npos) << cycle;
  EXPECT_THAT(out, ::testing::HasSubstr("\nG4 P0.5 (pkm: line 12 dwell)\n"));
  EXPECT_THAT(out, ::testing::HasSubstr("\nG4 P0.2 (pkm: line 16 dwell)\n"));
  EXPECT_THAT(r.err, ::testing::HasSubstr("14 motion lines rewritten"));
  // The output is a program the interpreter runs, and passes on the default hexapod as the
  // source does.
  const auto run = pkm({"gcode", "run", "--machine", "hexapod-default", path("drill.ngc")});
  EXPECT_EQ(run.code, 0) << run.err << run.out;
  EXPECT_THAT(run.out, ::testing::HasSubstr("result: all checks pass"));
}

/// A program with a subroutine called in a loop is flattened before it is rewritten.
TEST_F(GcodeCompensateCli, OWordProgramsAreFlattened) {
  const std::string cal = write("cal.json", calibratedJson());
  const std::string prog = write("loops.ngc",
                                 "G21 G90\n"
                                 "o<side> sub\n"
                                 "  G1 X#1 Y0 Z#2 F600\n"
                                 "o<side> endsub\n"
                                 "G0 X0 Y0 Z200\n"
                                 "o1 repeat [3]\n"
                                 "  o<side> call [[#5 + 1] * 10] [200 - #5]\n"
                                 "  #5 = [#5 + 1]\n"
                                 "o1 endrepeat\n"
                                 "M2\n");
  const auto r = pkm({"gcode", "compensate", "--machine", cal, prog});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("O-words: its 6 executed blocks were flattened first"));
  EXPECT_EQ(r.out.find("o1"), std::string::npos) << r.out;
  const auto lines = splitLines(r.out);
  // G21 G90, G0, three passes of one motion cut into segments, M2; the segment comments name
  // lines of the flattened program (G21 G90, G0, the three G1, M2).
  ASSERT_GE(lines.size(), 6u) << r.out;
  EXPECT_EQ(lines[0], "G21 G90");
  EXPECT_EQ(lines[1].rfind("G0 X", 0), 0u) << lines[1];
  for (std::size_t i = 2; i + 1 < lines.size(); ++i)
    EXPECT_EQ(lines[i].rfind("G1 X", 0), 0u) << lines[i];
  EXPECT_THAT(r.out, ::testing::HasSubstr("(pkm: line 5 segment"));
  EXPECT_EQ(lines.back(), "M2");
}

/// Seed 004's sphere: flattened (two calls of an O-word subroutine), read with the tool table
/// (G43 H1), pre-distorted; the result runs through the machine without a violation.
TEST_F(GcodeCompensateCli, ShippedSphereWithTheToolTable) {
  const std::string cal = write("cal.json", calibratedJson());
  const std::string ex = std::string(PKM_SOURCE_DIR) + "/examples/gcode/";
  const auto r = pkm({"gcode",
                      "compensate",
                      "--machine",
                      cal,
                      ex + "sphere.ngc",
                      "--tool-table",
                      ex + "tools.tbl",
                      "--out",
                      path("sphere.ngc")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, ::testing::HasSubstr("its 110 executed blocks were flattened first"));
  const std::string out = slurp(path("sphere.ngc"));
  EXPECT_THAT(out, ::testing::HasSubstr("\nG43 H1\n"));
  EXPECT_EQ(out.find("o<hemisphere> call"), std::string::npos);
  const auto run = pkm({"gcode",
                        "run",
                        "--machine",
                        "hexapod-default",
                        path("sphere.ngc"),
                        "--tool-table",
                        ex + "tools.tbl"});
  EXPECT_EQ(run.code, 0) << run.err << run.out;
  expectUsageError(pkm({"gcode", "compensate", "--machine", cal, ex + "sphere.ngc"}),
                   "sphere.ngc:39: tool 1");
}

TEST_F(GcodeCompensateCli, HybridFrameShiftsThePkmProgramByTheX2Term) {
  const std::string frame = write("frame.txt",
                                  "# pkm-base-frame\nbase_rpy_rad = 0 0 0.003\n"
                                  "base_offset_mm = 0 0 0\nper_x2 = 0 -4e-05 0\n");
  const std::string prog = write("p.ngc", "G21 G90\nN5 G1 X10 Y20 Z-1 F500 (cut)\nM2\n");
  const auto r = pkm({"gcode", "compensate", "--hybrid-frame", frame, "--x2", "1000", prog});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3U);
  EXPECT_EQ(lines[0], "G21 G90");
  // y shifted by 1000 · (−4e-5) = −0.04 mm; the base frame stays in the controller.
  EXPECT_NE(lines[1].find("Y19.96"), std::string::npos) << lines[1];
  EXPECT_NE(lines[1].find("(cut)"), std::string::npos) << lines[1];
  expectUsageError(pkm({"gcode", "compensate", "--hybrid-frame", frame, prog}), "--x2");
  expectUsageError(pkm({"gcode", "compensate", prog}), "--hybrid-frame");
  const std::string bad = write("bad.txt", "base_rpy_rad = 0 0\n");
  expectUsageError(pkm({"gcode", "compensate", "--hybrid-frame", bad, "--x2", "1", prog}),
                   "bad.txt:1:");
}

/// The built-in mxt700s-like renamed as a calibration result, with leg A's base 0.3 mm off and
/// a 0.2 mm longer tool.
std::string calibratedExechonJson() {
  std::ifstream in(std::string(PKM_SOURCE_DIR) + "/data/machines/mxt700s-like.json");
  std::string j((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto swap = [&j](const std::string& from, const std::string& to) {
    const std::size_t at = j.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) j.replace(at, from.size(), to);
  };
  swap("\"name\": \"mxt700s-like\"", "\"name\": \"mxt700s-like-calibrated\"");
  swap("\"dA\": -443.4", "\"dA\": -443.1");
  swap("\"tool_length\": 200", "\"tool_length\": 200.2");
  return j;
}

TEST_F(GcodeCompensateCli, ExechonProgramsInBothOrientations) {
  const std::string cal = write("cal.json", calibratedExechonJson());
  const std::string prog = std::string(PKM_SOURCE_DIR) + "/examples/gcode/exechon_contour.ngc";
  for (const char* orientation : {"vector", "axes"}) {
    const auto r =
        pkm({"gcode", "compensate", "--machine", cal, "--orientation", orientation, prog});
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("Exechon, --orientation " + std::string(orientation)), std::string::npos)
        << r.err;
    EXPECT_EQ(r.out.find(" B"), std::string::npos);                 // an Exechon has no B axis
    EXPECT_NE(r.out.find("N40 G1 X"), std::string::npos) << r.out;  // the arc, as line segments
    // The result is a valid program for the nominal machine.
    const std::string out = write(std::string("out-") + orientation + ".ngc", r.out);
    const auto run = pkm({"gcode",
                          "run",
                          "--machine",
                          "mxt700s-like",
                          "--orientation",
                          orientation,
                          out,
                          "--out",
                          path(std::string("joints-") + orientation + ".csv")});
    EXPECT_EQ(run.code, 0) << run.err;
  }
  // --orientation belongs to Exechon machines; the nominal must be one.
  const std::string hex = write("p.ngc", "G0 X0 Y0 Z200\nM2\n");
  expectUsageError(pkm({"gcode",
                        "compensate",
                        "--machine",
                        "hexapod-default",
                        "--nominal",
                        "hexapod-default",
                        "--orientation",
                        "axes",
                        hex}),
                   "--orientation");
  expectUsageError(
      pkm({"gcode", "compensate", "--machine", cal, "--nominal", "hexapod-default", prog}),
      "not an Exechon");
  const std::string b = write("b.ngc", "G0 X0 Y0 Z50\nG1 B3 F100\nM2\n");
  expectUsageError(pkm({"gcode", "compensate", "--machine", cal, b}), "b.ngc:2:");
}

}  // namespace PKM_TEST_NS
