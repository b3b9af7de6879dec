// `pkm gcode run`: joint CSV format and rows, the report (text and JSON), exit codes 0/1/2,
// Exechon machines (tool-vector and wrist-axes modes, the B word refused), no overwrite without
// --force.
#include <algorithm>
#include <nlohmann/json.hpp>

#include "support/cli_fixture.hpp"
#include "support/linuxcnc_sample.hpp"

namespace PKM_TEST_NS {

using pkm::test::CliRun;
using pkm::test::CliTest;
using pkm::test::splitFields;
using pkm::test::splitLines;
using ::testing::HasSubstr;

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

TEST_F(GcodeRunCli, DwellsCountInTheCycleTime) {
  const std::string moves = "G0 X0 Y0 Z200\nG1 X10 F600\n";
  const std::string plain = write("a.ngc", moves + "G1 X20\nM2\n");
  const std::string dwell = write("b.ngc", moves + "G4 P1.5\nG1 X20\nM2\n");
  const auto a =
      pkm({"gcode", "run", "--machine", "hexapod-default", plain, "--report", path("a.json")});
  const auto b =
      pkm({"gcode", "run", "--machine", "hexapod-default", dwell, "--report", path("b.json")});
  ASSERT_EQ(a.code, 0) << a.err;
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_THAT(b.out, ::testing::HasSubstr("(dwells 1.500 s)"));
  const auto ja = nlohmann::json::parse(slurp(path("a.json")));
  const auto jb = nlohmann::json::parse(slurp(path("b.json")));
  EXPECT_EQ(ja["dwell_time_s"].get<double>(), 0.0);
  EXPECT_EQ(jb["dwell_time_s"].get<double>(), 1.5);
  // The wait, plus the exact stop at X10 that the plain program passes at full feed.
  EXPECT_GE(jb["cycle_time_s"].get<double>(), ja["cycle_time_s"].get<double>() + 1.5);
}

/// Seed 004's sphere (an O-word subroutine with G43 H1) runs through the hexapod with the shipped
/// tool table; without one, G43 H1 is an input error naming the line.
TEST_F(GcodeRunCli, ShippedSphereWithTheToolTable) {
  const std::string ex = std::string(PKM_SOURCE_DIR) + "/examples/gcode/";
  const auto r = pkm({"gcode",
                      "run",
                      "--machine",
                      "hexapod-default",
                      ex + "sphere.ngc",
                      "--tool-table",
                      ex + "tools.tbl"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("result: all checks pass"));
  // Away from its tools.tbl (which gcode run would take, docs/gcode.md), without a table: refused.
  const std::string alone = write("alone-sphere.ngc", slurp(ex + "sphere.ngc"));
  expectUsageError(pkm({"gcode", "run", "--machine", "hexapod-default", alone}),
                   "sphere.ngc:39: tool 1 (G43 H1) is not in the tool table");
  expectUsageError(pkm({"gcode",
                        "run",
                        "--machine",
                        "hexapod-default",
                        ex + "sphere.ngc",
                        "--tool-table",
                        ex + "tools.tbl",
                        "--tool-units",
                        "cm"}),
                   "--tool-units");
}

/// --stock: the machining preview's summary after the checks (docs/machining.md); bad specs.
TEST_F(GcodeRunCli, StockPreviewsTheMachining) {
  const std::string ex = std::string(PKM_SOURCE_DIR) + "/examples/gcode/";
  const auto r = pkm({"gcode",
                      "run",
                      ex + "sphere.ngc",
                      "--stock",
                      "box:25,15,-10,75,65,20",
                      "--stock-cell",
                      "0.5"});
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out,
              ::testing::HasSubstr("machining: stock box X 25..75 Y 15..65 Z -10..20 mm, "
                                   "100 x 100 cells of 0.5 mm"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("tool T1: ball end, diameter 6 mm"));
  EXPECT_THAT(r.out, ::testing::HasSubstr("no collision"));
  const std::string rapid =
      write("rapid.ngc", "G0 X0 Y0 Z210\nG1 Z200 F300\nG1 X40\nG1 Z199\nG1 X0\nG0 X20 Y5\nM2\n");
  const auto c = pkm({"gcode", "run", rapid, "--stock", "auto"});
  EXPECT_EQ(c.code, 0) << c.err;  // a collision is reported, not a failed check
  EXPECT_THAT(c.out, ::testing::HasSubstr("COLLISION rapid line 6: 1.000 mm deep"));
  expectUsageError(pkm({"gcode", "run", rapid, "--stock", "box:1,2"}), "--stock 'box:1,2'");
  expectUsageError(pkm({"gcode", "run", rapid, "--stock-cell", "1"}), "--stock-cell needs --stock");
  expectUsageError(
      pkm({"gcode", "run", rapid, "--stock", "box:0,0,0,1000,1000,10", "--stock-cell", "0.001"}),
      "choose a larger cell");
}

TEST_F(GcodeRunCli, StrokeViolationExitsOneWithLine) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 Z100 F600\nG1 Z-300\nM2\n");
  const auto r = pkm({"gcode", "run", prog, "--report", path("r.json")});
  EXPECT_EQ(r.code, kExitViolation) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr(prog + ":3: stroke violated"));
  const auto j = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_FALSE(j["ok"].get<bool>());
  EXPECT_EQ(j["checks"]["stroke"]["first_violation"]["line"].get<int>(), 3);
}

TEST_F(GcodeRunCli, UsageAndInputErrors) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X10 F600\nM2\n");
  expectUsageError(pkm({"gcode", "run", prog, "--tolerance", "0"}), "tolerance");
  expectUsageError(pkm({"gcode", "run", prog, "--max-joint-velocity", "-1"}), "velocity");
  expectUsageError(pkm({"gcode", "run", prog, "--orientation", "axes"}), "Exechon machines only");
  expectUsageError(pkm({"gcode", "run", prog, "--machine", "mxt700s-like", "--orientation", "ijk"}),
                   "orientation");
  const std::string b = write("b.ngc", "G0 X0 Y0 Z50\nG1 X10 B5 F600\nM2\n");
  expectUsageError(pkm({"gcode", "run", b, "--machine", "mxt700s-like"}), "b.ngc:2: B5");
  const std::string bad = write("bad.ngc", "G0 X0\nG1 X1 Q\nM2\n");
  expectUsageError(pkm({"gcode", "run", bad}), "bad.ngc:2:");
  expectUsageError(pkm({"gcode", "run"}), "program");
}

TEST_F(GcodeRunCli, ExechonLegsAreNamedAsInExechonIk) {
  // One naming of an Exechon's legs, q1, q2, q3 (legs A, B, C; docs/conventions.md), in every
  // command that prints joints; the same tool pose gives the same readings under the same names.
  const std::string prog = write("v.ngc", "G21 G90\nG0 X0 Y0 Z50 A0 C0\nM2\n");
  ASSERT_EQ(pkm({"gcode", "run", "--machine", "mxt700s-like", prog, "--out", path("v.csv")}).code,
            0);
  const auto run = splitLines(slurp(path("v.csv")));
  ASSERT_GE(run.size(), 2u);
  const auto run_names = splitFields(run[0]), run_row = splitFields(run[1]);
  const std::string poses = write("p.csv", "x,y,z,i,j,k\n0,0,50,0,0,-1\n");
  const auto ik = pkm({"exechon", "ik", "--machine", "mxt700s-like", "--poses", poses});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const auto ik_lines = splitLines(ik.out);
  ASSERT_GE(ik_lines.size(), 2u);
  const auto ik_names = splitFields(ik_lines[0]), ik_row = splitFields(ik_lines[1]);
  constexpr double kSameReading = 1e-9;  // mm: both solve the same pose from home
  for (const std::string leg : {"q1", "q2", "q3"}) {
    const auto at = [&leg](const std::vector<std::string>& names) {
      return static_cast<std::size_t>(std::find(names.begin(), names.end(), leg) - names.begin());
    };
    ASSERT_LT(at(run_names), run_names.size()) << leg << " missing in gcode run's CSV";
    ASSERT_LT(at(ik_names), ik_names.size()) << leg << " missing in exechon ik's output";
    EXPECT_NEAR(std::stod(run_row[at(run_names)]), std::stod(ik_row[at(ik_names)]), kSameReading)
        << leg;
  }
  EXPECT_EQ(std::find(run_names.begin(), run_names.end(), "q0"), run_names.end());
}

// The built-in Exechon (PKM frame: z up, origin at the home tool point of a vertical tool).
TEST_F(GcodeRunCli, ExechonToolVectorProgram) {
  const std::string prog = write("e.ngc",
                                 "G21 G90\nG0 X0 Y0 Z50 A0 C0\nG1 Z0 F1000\nG1 X100 Y50 F2000\n"
                                 "G2 X100 Y-50 I0 J-50\nG1 X0 Y0 A20 C45\nM2\n");
  const auto r = pkm({"gcode",
                      "run",
                      "--machine",
                      "mxt700s-like",
                      prog,
                      "--out",
                      path("e.csv"),
                      "--report",
                      path("e.json")});
  ASSERT_EQ(r.code, 0) << r.err << r.out;
  EXPECT_THAT(r.out, ::testing::HasSubstr("orientation: vector"));
  const auto lines = splitLines(slurp(path("e.csv")));
  ASSERT_GT(lines.size(), 10u);
  EXPECT_EQ(lines[0], "line,t,x,y,z,a,b,c,q1,q2,q3,wrist_c,wrist_a,ux,uy,uz,drm");
  const auto first = splitFields(lines[1]);
  ASSERT_EQ(first.size(), 17u);
  EXPECT_EQ(first[16], "0");  // the DRM is relative to the first point
  // A vertical tool (A = C = 0) points down: u = (0, 0, -1).
  EXPECT_NEAR(std::stod(first[15]), -1.0, 1e-12);
  const auto j = nlohmann::json::parse(slurp(path("e.json")));
  EXPECT_EQ(j["machine_type"], "exechon");
  EXPECT_EQ(j["orientation"], "vector");
  EXPECT_TRUE(j["ok"].get<bool>());
  EXPECT_FALSE(j["checks"]["interference"]["enabled"].get<bool>());
  EXPECT_EQ(j["checks"]["reach"]["violations"].get<int>(), 0);
  EXPECT_EQ(j["points"].get<std::size_t>(), lines.size() - 1);
}

TEST_F(GcodeRunCli, ExechonWristAxesAndStrokeViolation) {
  const std::string prog =
      write("a.ngc", "G0 X0 Y0 Z50 A-20 C0\nG1 X100 Y50 Z0 A-25 C10 F2000\nG1 X1500\nM2\n");
  const auto r = pkm({"gcode",
                      "run",
                      "--machine",
                      "mxt700s-like",
                      "--orientation",
                      "axes",
                      prog,
                      "--out",
                      path("a.csv")});
  EXPECT_EQ(r.code, kExitViolation) << r.err << r.out;
  EXPECT_THAT(r.out, ::testing::HasSubstr(prog + ":3: stroke violated"));
  // In axes mode the wrist columns are the programmed A and C.
  const auto lines = splitLines(slurp(path("a.csv")));
  const auto row = splitFields(lines[1]);
  EXPECT_EQ(row[11], "0");
  EXPECT_EQ(row[12], "-20");
}

/// The machine file's joint_rates are the default limits; an option overrides its own one.
TEST_F(GcodeRunCli, JointRatesFromTheMachineFile) {
  auto machine = nlohmann::json::parse(
      slurp(std::string(PKM_SOURCE_DIR) + "/data/machines/hexapod-default.json"));
  machine["joint_rates"] = {{"velocity", 5.0}, {"acceleration", 50.0}};
  const std::string file = write("m.json", machine.dump(2));
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X60 F3000\nM2\n");
  auto r = pkm({"gcode", "run", prog, "--machine", file, "--report", path("r.json")});
  EXPECT_EQ(r.code, kExitViolation) << r.err << r.out;  // 5 mm/s is too slow for F3000
  EXPECT_THAT(r.out, ::testing::HasSubstr("(velocity, acceleration from the machine file)"));
  auto j = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_EQ(j["max_joint_velocity"].get<double>(), 5.0);
  EXPECT_EQ(j["max_joint_acceleration"].get<double>(), 50.0);
  r = pkm({"gcode",
           "run",
           prog,
           "--machine",
           file,
           "--max-joint-velocity",
           "500",
           "--report",
           path("r.json"),
           "--force"});
  j = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_EQ(j["max_joint_velocity"].get<double>(), 500.0);
  EXPECT_EQ(j["max_joint_acceleration"].get<double>(), 50.0);
  EXPECT_EQ(j["limits_from_machine_file"], nlohmann::json::array({"acceleration"}));
}

TEST_F(GcodeRunCli, AChecksOffSaysWhyAndTheOptionTurnsItOn) {
  // A LinuxCNC hexapod configuration states no strut diameter and no joint cones.
  const std::string prog = write("p.ngc", "G20 G0 X0 Y0 Z20\nG1 X1 F20\nM2\n");
  const std::string report = path("r.json");
  const CliRun off =
      pkm({"gcode", "run", "--machine", "hexapod-linuxcnc-sim", "--report", report, prog});
  ASSERT_EQ(off.code, 0) << off.err;
  EXPECT_THAT(off.out,
              HasSubstr("interference        n/a       (the machine has no strut "
                        "diameter; a LinuxCNC configuration states none: give "
                        "--strut-diameter D"));
  EXPECT_THAT(off.out, HasSubstr("joint_angle         n/a       (the machine has no joint cone"));
  EXPECT_THAT(slurp(report), HasSubstr("\"off_reason\": \"(the machine has no strut diameter"));
  const CliRun on = pkm({"gcode",
                         "run",
                         "--machine",
                         "hexapod-linuxcnc-sim",
                         "--strut-diameter",
                         "1",
                         "--report",
                         report,
                         "--force",
                         prog});
  ASSERT_EQ(on.code, 0) << on.err;
  EXPECT_THAT(on.out, HasSubstr("interference        ok"));
  expectUsageError(
      pkm({"gcode", "run", "--machine", "mxt700s-like", "--strut-diameter", "1", prog}),
      "apply to hexapods only");
}

TEST_F(GcodeRunCli, AnInchConfigurationIsCheckedInInchesWithItsStartupCode) {
  // LinuxCNC's hexapod-sim: LINEAR_UNITS inch and RS274NGC_STARTUP_CODE = G20 ...; a program
  // without G20 runs in inches there, and the report speaks inches.
  const std::filesystem::path sample = pkm::test::linuxcncHexapodSim();
  if (!std::filesystem::is_directory(sample))
    GTEST_SKIP() << sample << " not found (run scripts/fetch-linuxcnc.sh)";
  const std::string prog = write("far.ngc", "G0 X-5 Y3 Z22\nG1 X-5.5 F10\nG1 X2000\nM2\n");
  const CliRun r = pkm({"gcode",
                        "run",
                        "--machine",
                        (sample / "kinematics.hal").string(),
                        "--ini",
                        (sample / "hexapod.ini").string(),
                        "--tolerance",
                        "0.001",
                        prog});
  EXPECT_EQ(r.code, kExitViolation) << r.err;
  EXPECT_THAT(r.err, HasSubstr("RS274NGC_STARTUP_CODE \"G20"));
  EXPECT_THAT(r.out, HasSubstr("interpolation: tolerance 0.001 inch, max step "));
  // The rapid rate is the INI's [TRAJ] MAX_LINEAR_VELOCITY (10 in/s), lowered along each move to
  // the axes' MAX_VELOCITY (20 in/s, 20 deg/s) and rotary-only moves to MAX_ANGULAR_VELOCITY.
  EXPECT_THAT(r.out, HasSubstr("rapid 600 inch/min ("));
  EXPECT_THAT(r.out, HasSubstr("rapid rate from the machine file)"));
  EXPECT_THAT(r.out, HasSubstr("rapid limits: each G0 at most X 20 inch/s, Y 20 inch/s"));
  EXPECT_THAT(
      r.out, HasSubstr("rotary-only 6 deg/s along the move (" + (sample / "hexapod.ini").string()));
  // X2000 inches leaves the 1000-inch stroke (2000 mm would not): reported in inches.
  EXPECT_THAT(r.out, HasSubstr("far.ngc:3: stroke violated first at X977."));
  EXPECT_THAT(r.out, HasSubstr(" Y3 Z22 A0 B0 C0: strut 0 value 1000."));
}

TEST_F(GcodeRunCli, RefusesToOverwrite) {
  const std::string prog = write("p.ngc", "G0 X0 Y0 Z200\nG1 X10 F600\nM2\n");
  write("q.csv", "keep");
  expectUsageError(pkm({"gcode", "run", prog, "--out", path("q.csv")}), "--force");
  EXPECT_EQ(slurp(path("q.csv")), "keep");
  EXPECT_EQ(pkm({"gcode", "run", prog, "--out", path("q.csv"), "--force"}).code, 0);
  EXPECT_NE(slurp(path("q.csv")), "keep");
}

}  // namespace PKM_TEST_NS
