// workflow::compensateGcode: the pre-distorted program drives the nominal controller's struts to
// where the calibrated machine needs them (round trip), a loaded machine as its file, the hybrid X2
// term, errors named after an upload, bad requests refused, no overwrite without force.
#include "pkm/workflow/gcode_compensate.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "pkm/cnc/joint_path.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using test::slurp;

class GcodeCompensateWorkflow : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ =
        fs::temp_directory_path() / ("pkm_workflow_gcode_compensate_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return (dir_ / name).string();
  }
  /// The built-in default machine renamed as a calibration result, one base joint moved 0.4 mm.
  std::string calibratedMachine() {
    std::string j = slurp(std::string(PKM_SOURCE_DIR) + "/data/machines/hexapod-default.json");
    const std::string name = "\"name\": \"pkm-hx1200\"";
    j.replace(j.find(name), name.size(), "\"name\": \"pkm-hx1200-calibrated\"");
    const std::string base = "[-124.747, 586.8886, 1200.0]";
    j.replace(j.find(base), base.size(), "[-124.347, 586.8886, 1200.0]");
    return write("cal.json", j);
  }
  GcodeCompensateRequest request(std::string text) {
    GcodeCompensateRequest r;
    r.program = {"upload.ngc", std::move(text)};
    r.interpreter.require_program_end = false;  // snippets; the CLI tests check the end
    r.machine = calibratedMachine();
    return r;
  }
  fs::path dir_;
};

TEST_F(GcodeCompensateWorkflow, TheNominalControllerReachesTheCalibratedStrutLengths) {
  const GcodeCompensateResult r =
      compensateGcode(request("(keep)\nG0 X0 Y0 Z200\nG1 X30 Y10 F600\nG1 Z150\nM2\n"));
  const cnc::ProgramCompensation& c = r.compensation;
  EXPECT_THAT(c.text, StartsWith("(keep)\n"));
  EXPECT_EQ(c.motion_lines, 3u);
  EXPECT_GT(c.max_correction, 0.01);
  EXPECT_THAT(r.note,
              StartsWith("nominal pkm-hx1200 -> calibrated pkm-hx1200-calibrated: 3 motion"));
  const io::HexapodMachine nominal = io::loadHexapodMachine("hexapod-default");
  const io::HexapodMachine cal = io::loadHexapodMachine(request("").machine);
  cnc::HexapodJointConverter controller(nominal.model), machine(cal.model);
  ASSERT_FALSE(c.points.empty());
  for (const cnc::CompensatedPoint& p : c.points) {
    const kinematics::StrutVector commanded = controller.solve(p.command);
    const kinematics::StrutVector needed = machine.solve(p.desired);
    EXPECT_LT((commanded - needed).cwiseAbs().maxCoeff(), 1e-6) << "line " << p.line;
  }
}

TEST_F(GcodeCompensateWorkflow, ALoadedMachineCompensatesAsItsFileDoes) {
  const std::string program = "G0 X0 Y0 Z200\nG1 X30 Y10 F600\nG2 X40 Y20 I10 J0\nM2\n";
  GcodeCompensateRequest from_file = request(program);
  GcodeCompensateRequest loaded = request(program);
  loaded.hexapod =
      std::make_shared<const io::HexapodMachine>(io::loadHexapodMachine(loaded.machine));
  loaded.machine.clear();
  EXPECT_EQ(loaded.machineName(), "pkm-hx1200-calibrated");
  const GcodeCompensateResult a = compensateGcode(from_file), b = compensateGcode(loaded);
  EXPECT_EQ(b.compensation.text, a.compensation.text);
  EXPECT_EQ(b.note, a.note);
  // An Exechon, loaded: the nominal is found from its name as from a file's.
  std::string j = slurp(std::string(PKM_SOURCE_DIR) + "/data/machines/mxt700s-like.json");
  const std::string name = "\"name\": \"mxt700s-like\"";
  j.replace(j.find(name), name.size(), "\"name\": \"mxt700s-like-calibrated\"");
  GcodeCompensateRequest exechon;
  exechon.program = {"upload.ngc",
                     slurp(std::string(PKM_SOURCE_DIR) + "/examples/gcode/exechon_contour.ngc")};
  exechon.machine = write("ex-cal.json", j);
  const std::string exechon_text = compensateGcode(exechon).compensation.text;
  exechon.exechon =
      std::make_shared<const io::ExechonMachine>(io::loadExechonMachine(exechon.machine));
  EXPECT_THROW(exechon.validate(), InvalidArgument);  // a file and a loaded machine
  exechon.machine.clear();
  EXPECT_TRUE(exechon.onExechon());
  EXPECT_EQ(compensateGcode(exechon).compensation.text, exechon_text);
  exechon.hexapod = loaded.hexapod;  // two loaded machines
  EXPECT_THROW(exechon.validate(), InvalidArgument);
}

TEST_F(GcodeCompensateWorkflow, TheHybridFrameShiftsByTheX2Term) {
  GcodeCompensateRequest q;
  q.program = {"upload.ngc", "G21 G90\nN5 G1 X10 Y20 Z-1 F500 (cut)\nM2\n"};
  q.hybrid_frame =
      write("frame.txt", "base_rpy_rad = 0 0 0.003\nbase_offset_mm = 0 0 0\nper_x2 = 0 -4e-05 0\n");
  q.x2 = 1000.0;
  const GcodeCompensateResult r = compensateGcode(q);
  EXPECT_THAT(r.compensation.text, HasSubstr("Y19.96"));
  EXPECT_THAT(r.note, StartsWith("hybrid squareness correction at X2 = 1000 mm (X2 term;"));
  q.hybrid_frame = write("bad.txt", "base_rpy_rad = 0 0\n");
  try {
    (void)compensateGcode(q);
    FAIL() << "accepted a malformed frame";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.txt:1: expected 'key = a b c'"));
  }
}

TEST_F(GcodeCompensateWorkflow, ErrorsNameTheUploadAndItsLine) {
  try {
    (void)compensateGcode(request("G0 X0 Y0 Z200\nG33 X1\n"));
    FAIL() << "accepted G33";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:2:"));
  }
}

TEST_F(GcodeCompensateWorkflow, AProgramNeedingTooManyPointsIsRefusedAtItsLine) {
  GcodeCompensateRequest q = request("G0 X10 Y0 Z200\nG2 X10 Y0 I-10 J0 P100000000 F600\nM2\n");
  try {
    (void)compensateGcode(q);
    FAIL() << "accepted a hundred million turns";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:2: the path would need at least "));
    EXPECT_THAT(e.what(), HasSubstr("--max-points"));
  }
}

TEST_F(GcodeCompensateWorkflow, RejectsBadRequests) {
  GcodeCompensateRequest q = request("G0 X0 Y0 Z200\n");
  q.tolerance = -1.0;
  EXPECT_THROW(q.validate(), InvalidArgument);
  q = request("G0 X0 Y0 Z200\n");
  q.hybrid_frame = "frame.txt";  // both a machine and a frame
  EXPECT_THROW((void)compensateGcode(q), InvalidArgument);
  q.machine.clear();  // a frame without --x2
  EXPECT_THROW((void)compensateGcode(q), InvalidArgument);
  q = request("G0 X0 Y0 Z200\n");
  q.orientation = "axes";  // a hexapod
  EXPECT_THROW((void)compensateGcode(q), InvalidArgument);
  q = request("G0 X0 Y0 Z200\n");
  q.machine = "hexapod-default";  // its nominal cannot be told from its name
  EXPECT_THROW((void)compensateGcode(q), InvalidArgument);
}

TEST_F(GcodeCompensateWorkflow, TheIniStartupCodeRunsBeforeTheProgram) {
  // An INI whose RS274NGC_STARTUP_CODE is G20: the program's numbers are inches, exactly as if
  // the program began with G20 itself.
  const std::string ini = write("machine.ini",
                                "[RS274NGC]\nRS274NGC_STARTUP_CODE = G20 G17 G90\n"
                                "[TRAJ]\nLINEAR_UNITS = mm\n");
  const std::string body = "G0 X1 Y0.5 Z8\nG1 X2 F10\nM2\n";
  GcodeCompensateRequest q = request(body);
  q.ini = ini;
  const GcodeCompensateResult with_ini = compensateGcode(q);
  const GcodeCompensateResult with_g20 = compensateGcode(request("G20\n" + body));
  // The same words; the inserted lines' comments name source lines one further down.
  const std::string renumbered = std::regex_replace(
      with_g20.compensation.text, std::regex("line 3 segment"), "line 2 segment");
  EXPECT_EQ("G20\n" + with_ini.compensation.text, renumbered);
  EXPECT_GT(with_ini.compensation.max_correction, 0.0);
  EXPECT_THAT(with_ini.note, HasSubstr("RS274NGC_STARTUP_CODE \"G20 G17 G90\" of " + ini + ":2"));
  // Without the INI the same numbers are millimetres: a different program.
  EXPECT_NE(compensateGcode(request(body)).compensation.text, with_ini.compensation.text);
}

TEST_F(GcodeCompensateWorkflow, AnInchMachinesNoteSpeaksInches) {
  // LinuxCNC's sim hexapod (inch) calibrated with one base joint moved 0.05 in: tolerance, step
  // and largest correction in inches, the correction the mm figure / 25.4.
  std::string j = slurp(std::string(PKM_SOURCE_DIR) + "/data/machines/hexapod-linuxcnc-sim.json");
  const std::string name = "\"name\": \"hexapod-linuxcnc-sim\"";
  ASSERT_NE(j.find(name), std::string::npos);
  j.replace(j.find(name), name.size(), "\"name\": \"hexapod-linuxcnc-sim-calibrated\"");
  const std::string base = "\"base\": [-22.95, 13.25, 0]";
  ASSERT_NE(j.find(base), std::string::npos);
  j.replace(j.find(base), base.size(), "\"base\": [-22.95, 13.3, 0]");
  GcodeCompensateRequest q;
  q.program = {"inch.ngc", "G20 G0 X1 Y1 Z21\nG1 X2 F10\nM2\n"};
  q.machine = write("sim-cal.json", j);
  q.tolerance = 0.001;
  const GcodeCompensateResult r = compensateGcode(q);
  EXPECT_THAT(r.note, HasSubstr("(tolerance 0.001 inch, max step "));
  EXPECT_THAT(r.note,
              HasSubstr(fmt::format("largest correction {:.4g} inch",
                                    r.compensation.max_correction / 25.4)));
  EXPECT_GT(r.compensation.max_correction / 25.4, 1e-4);
  EXPECT_LT(r.compensation.max_correction / 25.4, 0.2);
}

TEST_F(GcodeCompensateWorkflow, TheIniMustAgreeWithTheMachine) {
  GcodeCompensateRequest q = request("G0 X0 Y0 Z200\n");
  q.ini = write("inch.ini", "[TRAJ]\nLINEAR_UNITS = inch\n");
  try {
    (void)compensateGcode(q);
    FAIL() << "accepted an inch INI for a millimetre machine";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("LINEAR_UNITS is inch"));
  }
  q.ini = write("moves.ini", "[RS274NGC]\nRS274NGC_STARTUP_CODE = G0 X1\n");
  try {
    (void)compensateGcode(q);
    FAIL() << "accepted start-up code that moves";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("moves.ini:2: RS274NGC_STARTUP_CODE moves the machine"));
  }
  q.ini = write("bad.ini", "[RS274NGC]\nRS274NGC_STARTUP_CODE = G20 Q\n");
  EXPECT_THROW((void)compensateGcode(q), IoError);
}

TEST_F(GcodeCompensateWorkflow, WritesTheFileAndRefusesToOverwriteIt) {
  GcodeCompensateRequest q = request("G0 X0 Y0 Z200\nG1 X30 F600\n");
  q.out = (dir_ / "out.ngc").string();
  const GcodeCompensateResult r = compensateGcode(q);
  EXPECT_EQ(slurp(q.out), r.compensation.text);
  write("out.ngc", "keep");
  EXPECT_THROW((void)compensateGcode(q), IoError);
  EXPECT_EQ(slurp(q.out), "keep");
  q.force = true;
  (void)compensateGcode(q);
  EXPECT_EQ(slurp(q.out), r.compensation.text);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
