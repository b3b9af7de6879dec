// `pkm gcode moves` and `pkm gcode flatten`: CSV format, --out/--force, tool table option, errors
// with FILE:LINE.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

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
  const std::string prog = write("bad.ngc", "G0 X1\nG1 X2 F100\nG5.2 X3\nM2\n");
  expectUsageError(pkm({"gcode", "moves", prog}), "bad.ngc:3: unsupported G code G5.2");
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

/// Every shipped hexapod example passes `gcode run` on the default machine as shipped, without
/// options: the sphere's G43 finds the tools.tbl beside it (with a note).
TEST_F(GcodeCli, ShippedHexapodExamplesPassAsShipped) {
  for (const char* name :
       {"sphere.ngc", "drilling.ngc", "pocket_loops.ngc", "hexapod_contour.ngc"}) {
    const CliRun r = pkm({"gcode", "run", std::string(PKM_SOURCE_DIR) + "/examples/gcode/" + name});
    EXPECT_EQ(r.code, 0) << name << ": " << r.out << r.err;
    EXPECT_THAT(r.out, HasSubstr("result: all checks pass")) << name;
  }
  const CliRun sphere =
      pkm({"gcode", "run", std::string(PKM_SOURCE_DIR) + "/examples/gcode/sphere.ngc"});
  EXPECT_THAT(sphere.err, HasSubstr("no --tool-table was given: using"));
}

/// The shipped sphere (an O-word subroutine called twice) flattens into a program without
/// O-words that `gcode moves` runs to the same motions.
TEST_F(GcodeCli, FlattenUnrollsTheSphereSubroutine) {
  const std::string ex = std::string(PKM_SOURCE_DIR) + "/examples/gcode/";
  const std::string tbl = ex + "tools.tbl";
  const CliRun f =
      pkm({"gcode", "flatten", ex + "sphere.ngc", "--tool-table", tbl, "--out", path("flat.ngc")});
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_THAT(f.err, HasSubstr("executed blocks written"));
  const std::string flat = slurp(path("flat.ngc"));
  EXPECT_EQ(flat.find("o<hemisphere> call"), std::string::npos);
  EXPECT_EQ(flat.find("o<hemisphere> sub"), std::string::npos);
  EXPECT_EQ(flat.find("#<"), std::string::npos);
  EXPECT_THAT(flat, HasSubstr("\nG3 X73 Y40 I-23 J0\n"));  // the equator circle of sphere 1
  const CliRun a = pkm({"gcode", "moves", ex + "sphere.ngc", "--tool-table", tbl});
  const CliRun b = pkm({"gcode", "moves", path("flat.ngc"), "--tool-table", tbl});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  const auto la = splitLines(a.out), lb = splitLines(b.out);
  ASSERT_EQ(la.size(), lb.size());
  for (std::size_t i = 1; i < la.size(); ++i)  // same motions; the line column differs
    EXPECT_EQ(la[i].substr(la[i].find(',')), lb[i].substr(lb[i].find(','))) << i;
  // No overwrite without --force; errors name the file and line.
  expectUsageError(pkm({"gcode", "flatten", ex + "sphere.ngc", "--out", path("flat.ngc")}),
                   "--force");
  EXPECT_EQ(slurp(path("flat.ngc")), flat);
  expectUsageError(pkm({"gcode", "flatten", ex + "sphere.ngc"}), "sphere.ngc:39: tool 1");
  const std::string bad = write("bad.ngc", "o1 sub\nG1 X[1/0]\no1 endsub\no1 call\n");
  expectUsageError(pkm({"gcode", "flatten", bad}), "bad.ngc:2:");
}

TEST_F(GcodeCli, IniSetsTheInterpreterUpAndMessagesAreNotes) {
  write("sim.var", "5220 2\n5241 10\n");
  std::filesystem::create_directories(path("subs"));
  write("subs/corner.ngc", "o<corner> sub\nG0 X#1\no<corner> endsub\nM2\n");
  const std::string ini = write("machine.ini",
                                "[RS274NGC]\nPARAMETER_FILE = sim.var\nSUBROUTINE_PATH = subs\n"
                                "RS274NGC_STARTUP_CODE = G21 G90\n[SETUP]\nXPOS = 3\n");
  const std::string prog = write("p.ngc",
                                 "(debug, x from the INI: #<_ini[setup]xpos>)\n"
                                 "G0 X#<_ini[setup]xpos>\no<corner> call [5]\nM2\n");
  const CliRun r = pkm({"gcode", "moves", prog, "--ini", ini});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("2,rapid,13,0,0,"));  // G55 from the parameter file: X 10 + 3
  EXPECT_THAT(r.out, HasSubstr("3,rapid,15,0,0,"));  // the sub file from SUBROUTINE_PATH
  EXPECT_THAT(r.err, HasSubstr("p.ngc:1: debug: x from the INI: 3.000000"));
  const std::string flat = write("f.ngc", "G0 X1\nM2\n");
  EXPECT_EQ(pkm({"gcode", "flatten", flat, "--ini", ini}).code, 0);
  const std::string remap = write("remap.ini", "[RS274NGC]\nREMAP=M6 modalgroup=6 ngc=change\n");
  const std::string change = write("change.ngc", "G0 X1\nT1 M6\nM2\n");
  expectUsageError(pkm({"gcode", "moves", change, "--ini", remap}),
                   "change.ngc:2: M6 is remapped by the INI (");
  const std::string abort = write("abort.ngc", "G0 X1\n(abort, no stock)\nM2\n");
  expectUsageError(pkm({"gcode", "moves", abort}), "abort.ngc:2: program aborted: no stock");
  const std::string open = write("open.ngc", "G0 X1\nG0 X2\n");
  expectUsageError(pkm({"gcode", "moves", open}), "open.ngc:2: the file ended with no percent");
}

TEST_F(GcodeCli, DebugSwitchAndTextAfterTheEnd) {
  // #5599 = 0 silences (DEBUG, ...) as in LinuxCNC; text after M2 is never read (LinuxCNC stops
  // there), but a line after an end that is not reached is still an error when it runs.
  const std::string quiet = write("quiet.ngc",
                                  "(debug, shown)\n#5599 = 0\n(debug, hidden)\nG0 X1\nM2\n"
                                  "These are notes, not G-code.\n");
  const CliRun r = pkm({"gcode", "moves", quiet});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("quiet.ngc:1: debug: shown"));
  EXPECT_EQ(r.err.find("hidden"), std::string::npos) << r.err;
  const std::string skipped = write("skipped.ngc", "G0 X1\no1 if [0]\nM2\no1 endif\njunk\nM2\n");
  expectUsageError(pkm({"gcode", "moves", skipped}), "skipped.ngc:5: unknown word");
  expectUsageError(pkm({"gcode", "moves", write("w.ngc", "#5221 = 3\nM2\n")}),
                   "w.ngc:1: parameter #5221 is read-only here");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
