// workflow::calibrateHexapod from the library: on the simulator's tracker files of a machine with
// known errors it meets the held-out target and writes its three files; it passes the data
// files' notes on; refuses to overwrite; and a fit that cannot explain the data (readings in the
// wrong unit) writes nothing. Tracker-frame readings with the registration on the table's nests
// reach the true machine's world frame with no alignment; without it the result is marked
// unregistered and nothing that feeds a controller accepts it.
#include "pkm/workflow/calibrate_hexapod.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "pkm/calibration/uncertainty.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/workflow/linuxcnc_config.hpp"
#include "pkm/workflow/linuxcnc_install.hpp"
#include "pkm/workflow/simulate.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Acceptance: held-out TCP error after calibration ≤ 3× the tracker's noise (about 8 µm in 3-D
/// for the scenario's tracker at its distance) and at least 100× smaller than before.
constexpr double kHeldOutRmsLimit = 3 * 0.008;  ///< mm
constexpr double kImprovementAtLeast = 100.0;

class CalibrateHexapodWorkflow : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: CTest runs the cases of this suite in parallel processes.
    dir_ = fs::temp_directory_path() /
           ("pkm_workflow_calibrate_hexapod_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    SimulateOptions o;
    o.scenario = "seed004-hexapod-calibration";
    o.out = dir_ / "sim";
    (void)runSimulate(o);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static HexapodCalibrationRequest request(const std::string& out) {
    HexapodCalibrationRequest r;
    r.machine = "hexapod-default";
    r.data = {io::readNamedText((dir_ / "sim/tracker-pose.csv").string())};
    r.holdout = {io::readNamedText((dir_ / "sim/tracker-holdout.csv").string())};
    r.registration = io::readNamedText((dir_ / "sim/tracker-pose-registration.csv").string());
    r.out = (dir_ / out).string();
    return r;
  }
  /// A simulated tracker file without its '# frame:' line, as a tracker's own export comes.
  static io::NamedText withoutFrameLine(const std::string& name) {
    std::istringstream in(io::readFileText(dir_ / "sim" / name));
    std::string text;
    for (std::string line; std::getline(in, line);)
      if (line.rfind("# frame:", 0) != 0) text += line + '\n';
    return {name, text};
  }
  static fs::path dir_;
};
fs::path CalibrateHexapodWorkflow::dir_;

TEST_F(CalibrateHexapodWorkflow, MeetsTheHeldOutTargetAndWritesItsFiles) {
  std::vector<std::string> notices;
  RunControl control;
  control.notice = [&](const std::string& n) { notices.push_back(n); };
  const HexapodCalibrationResult r = calibrateHexapod(request("cal.json"), control);
  const io::HexapodCalibrationReport& rep = r.report;
  ASSERT_TRUE(rep.holdout.has_value());
  EXPECT_LT(rep.holdout->after.rms, kHeldOutRmsLimit);
  EXPECT_GT(rep.holdout->before.rms, kImprovementAtLeast * rep.holdout->after.rms);
  // Registered on the table's nests, the readings are world data: all 42 parameters.
  EXPECT_EQ(rep.fit.identifiability.parameters, 42);
  EXPECT_EQ(rep.fit.identifiability.rank, 42);
  EXPECT_EQ(rep.world_frame, "registered");
  ASSERT_TRUE(rep.registration.has_value());
  EXPECT_EQ(rep.registration->fit.references, 6);
  EXPECT_FALSE(r.calibrated.world_frame_unregistered);
  EXPECT_EQ(rep.worst.size(), 5u);
  EXPECT_THAT(rep.worst[0].source, HasSubstr("tracker-pose.csv:"));
  EXPECT_EQ(rep.workspace_poses, 200);
  EXPECT_EQ(r.calibrated.model.name, rep.machine + "-calibrated");
  // The notes reached the callback and the result, and the summary is the document written.
  EXPECT_FALSE(notices.empty());
  EXPECT_EQ(notices, r.notices);
  EXPECT_EQ(io::readFileText(dir_ / "cal.summary.json"), r.summary_json);
  EXPECT_EQ(r.summary_json, io::hexapodCalibrationJson(rep));
  EXPECT_TRUE(fs::is_regular_file(dir_ / "cal.json"));
  EXPECT_THAT(io::readFileText(dir_ / "cal.hal"), HasSubstr("setp"));
}

TEST_F(CalibrateHexapodWorkflow, WithoutOutWritesNothingAndWritesTheSameFilesLater) {
  HexapodCalibrationRequest r = request("direct.json");
  const HexapodCalibrationResult direct = calibrateHexapod(r);
  r.out.clear();
  HexapodCalibrationResult kept = calibrateHexapod(r);
  EXPECT_TRUE(kept.report.out_machine.empty());
  EXPECT_EQ(kept.summary_json, io::hexapodCalibrationJson(kept.report));
  EXPECT_FALSE(fs::exists(dir_ / "later.json"));
  writeHexapodCalibration(kept, (dir_ / "later.json").string(), false);
  EXPECT_EQ(kept.report.out_machine, (dir_ / "later.json").string());
  EXPECT_EQ(io::readFileText(dir_ / "later.summary.json"), kept.summary_json);
  for (const char* suffix : {".json", ".hal", ".pkmhexkins.hal"})
    EXPECT_EQ(io::readFileText(dir_ / (std::string("later") + suffix)),
              io::readFileText(dir_ / (std::string("direct") + suffix)))
        << suffix;
  EXPECT_THROW(writeHexapodCalibration(kept, (dir_ / "later.json").string(), false), IoError);
  // A machine already loaded is used as it is; a record needs the files it names.
  r.loaded = direct.calibrated;
  r.machine = "no-such-machine";
  EXPECT_EQ(calibrateHexapod(r).report.machine, direct.calibrated.model.name);
  r.db = (dir_ / "pkm.db").string();
  EXPECT_THROW((void)calibrateHexapod(r), InvalidArgument);
}

TEST_F(CalibrateHexapodWorkflow, RefusesToOverwriteWithoutForce) {
  io::writeFileAtomic(dir_ / "mine.hal", "the user's HAL file", io::Overwrite::kAllow);
  try {
    (void)calibrateHexapod(request("mine.json"));
    FAIL() << "overwrote mine.hal";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("mine.hal exists; pass --force to overwrite it"));
  }
  EXPECT_EQ(io::readFileText(dir_ / "mine.hal"), "the user's HAL file");
  EXPECT_FALSE(fs::exists(dir_ / "mine.json"));
}

TEST_F(CalibrateHexapodWorkflow, DataTheModelCannotExplainWritesNothing) {
  // The tracker positions given in µm instead of mm: no geometry explains them.
  std::istringstream in(io::readFileText(dir_ / "sim/tracker-pose.csv"));
  std::ostringstream bad;
  bool header = false;
  std::vector<std::string> columns;
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#' || !header) {
      header = header || (!line.empty() && line[0] != '#');
      bad << line << '\n';
      if (columns.empty() && header) {
        std::istringstream h(line);
        for (std::string c; std::getline(h, c, ',');) columns.push_back(c);
      }
      continue;
    }
    std::istringstream row(line);
    std::size_t k = 0;
    std::string out;
    for (std::string field; std::getline(row, field, ','); ++k) {
      const bool position = columns[k] == "x" || columns[k] == "y" || columns[k] == "z";
      out += (k ? "," : "") + (position ? std::to_string(1000.0 * std::stod(field)) : field);
    }
    bad << out << '\n';
  }
  HexapodCalibrationRequest r = request("um-cal.json");
  r.data = {{"um.csv", bad.str()}};  // an upload: text in memory, never on disk
  r.holdout.clear();
  try {
    (void)calibrateHexapod(r);
    FAIL() << "accepted positions in the wrong unit";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("does not explain the data"));
  }
  for (const char* f : {"um-cal.json", "um-cal.hal", "um-cal.summary.json"})
    EXPECT_FALSE(fs::exists(dir_ / f)) << f;
}

TEST_F(CalibrateHexapodWorkflow, AnUploadsErrorsNameTheUploadAndItsLine) {
  HexapodCalibrationRequest r = request("upload-cal.json");
  r.data = {{"upload.csv", "# frame: world\nl0,l1,l2,l3,l4,l5,x,y,z\n1,2,3,4,5,6,7,8,nine\n"}};
  try {
    (void)calibrateHexapod(r);
    FAIL() << "accepted a field that is not a number";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("upload.csv:3:"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "upload-cal.json"));
}

TEST_F(CalibrateHexapodWorkflow, TrackerFilesThatDoNotStateTheirFrameNeedTheFrameOption) {
  HexapodCalibrationRequest r = request("noframe.json");
  r.data = {withoutFrameLine("tracker-pose.csv")};
  r.holdout = {withoutFrameLine("tracker-holdout.csv")};
  try {
    (void)calibrateHexapod(r);
    FAIL() << "took readings of an unstated frame as the machine's";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("tracker-pose.csv: the tracker readings do not state their"));
    EXPECT_THAT(e.what(), HasSubstr("(and 1 more files)"));
    EXPECT_THAT(e.what(), HasSubstr("--frame tracker"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "noframe.json"));
  r.frame = "tracker";
  const HexapodCalibrationResult stated = calibrateHexapod(r);
  ASSERT_TRUE(stated.report.holdout.has_value());
  EXPECT_LT(stated.report.holdout->after.rms, kHeldOutRmsLimit);
  EXPECT_TRUE(stated.report.fit.large_changes.empty());
}

TEST_F(CalibrateHexapodWorkflow, ATrackerFrameTakenAsTheMachinesIsRefusedByName) {
  // Readings in the tracker's frame given as the machine's: the fit absorbs the tracker's
  // placement into the joint positions, explains the data, and would move the machine.
  HexapodCalibrationRequest r = request("asworld.json");
  r.frame = "world";
  EXPECT_THROW((void)calibrateHexapod(r), InvalidArgument);  // a registration of world data
  r.registration.reset();
  try {
    (void)calibrateHexapod(r);
    FAIL() << "wrote a geometry that absorbed the tracker's placement";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("implausibly far from the machine file"));
    EXPECT_THAT(e.what(), HasSubstr("Largest changes:\n  base1.x: -570.634 → "));
    EXPECT_THAT(e.what(), HasSubstr("--frame tracker"));
    EXPECT_THAT(e.what(), HasSubstr("--allow-large-changes"));
  }
  for (const char* f : {"asworld.json", "asworld.hal", "asworld.summary.json"})
    EXPECT_FALSE(fs::exists(dir_ / f)) << f;
  r.allow_large_changes = true;
  std::vector<std::string> notices;
  RunControl control;
  control.notice = [&](const std::string& n) { notices.push_back(n); };
  const HexapodCalibrationResult allowed = calibrateHexapod(r, control);
  EXPECT_FALSE(allowed.report.fit.large_changes.empty());
  EXPECT_TRUE(fs::exists(dir_ / "asworld.hal"));
  EXPECT_THAT(notices, ::testing::Contains(HasSubstr("--allow-large-changes")));
}

TEST_F(CalibrateHexapodWorkflow, RegisteredTrackerDataReachTheTrueMachinesWorldFrame) {
  // The calibrated controller on the TRUE machine over the workspace, no alignment of any kind:
  // within the calibration's own held-out residual. Without the registration the fit holds the
  // base at its nominal placement, and the machine misses by the base's rigid assembly error.
  const io::Scenario scenario = io::loadScenario("seed004-hexapod-calibration");
  const auto& vm =
      dynamic_cast<const simulation::HexapodVirtualMachine&>(*scenario.campaign.machine);
  std::vector<kinematics::PoseRpy> poses;
  for (const double x : {-150.0, 0.0, 150.0})
    for (const double y : {-150.0, 0.0, 150.0})
      for (const double z : {150.0, 300.0}) {
        kinematics::PoseRpy p;
        p.position = Eigen::Vector3d(x, y, z);
        p.rpy = Eigen::Vector3d(0.05 * x / 150.0, -0.05 * y / 150.0, 0.1);
        poses.push_back(p);
      }
  const HexapodCalibrationResult registered = calibrateHexapod(request("registered.json"));
  const double residual = registered.report.holdout->after.max;
  const calibration::TcpErrorStatistics reached =
      calibration::tcpErrorOverWorkspace(registered.calibrated.model, vm.truth(), poses);
  EXPECT_EQ(reached.samples, static_cast<int>(poses.size()));
  EXPECT_LT(reached.max, residual);
  HexapodCalibrationRequest r = request("unregistered-fit.json");
  r.registration.reset();
  const HexapodCalibrationResult unregistered = calibrateHexapod(r);
  EXPECT_EQ(unregistered.report.world_frame, "unregistered");
  EXPECT_GT(
      calibration::tcpErrorOverWorkspace(unregistered.calibrated.model, vm.truth(), poses).max,
      100.0 * residual);
}

TEST_F(CalibrateHexapodWorkflow, WithoutARegistrationNothingForAControllerIsWritten) {
  HexapodCalibrationRequest r = request("unregistered.json");
  r.registration.reset();
  std::vector<std::string> notices;
  RunControl control;
  control.notice = [&](const std::string& n) { notices.push_back(n); };
  const HexapodCalibrationResult result = calibrateHexapod(r, control);
  // 42 parameters and the tracker's 6-DOF placement: the base frame's rigid motion is the one
  // thing tracker data cannot see.
  EXPECT_EQ(result.report.fit.identifiability.parameters, 48);
  EXPECT_EQ(result.report.fit.identifiability.rank, 42);
  EXPECT_TRUE(result.calibrated.world_frame_unregistered);
  EXPECT_THAT(result.summary_json, HasSubstr("\"world_frame\": \"unregistered\""));
  EXPECT_THAT(io::readFileText(dir_ / "unregistered.json"),
              HasSubstr("\"world_frame\": \"unregistered\""));
  EXPECT_FALSE(fs::exists(dir_ / "unregistered.hal"));
  EXPECT_FALSE(fs::exists(dir_ / "unregistered.pkmhexkins.hal"));
  EXPECT_THAT(result.notices, ::testing::Contains(HasSubstr("--registration FILE")));
  LinuxcncConfigRequest config;
  config.machine = (dir_ / "unregistered.json").string();
  config.out = (dir_ / "unregistered-cfg").string();
  try {
    (void)writeLinuxcncConfig(config);
    FAIL() << "configured a controller with an unregistered world frame";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("pkm linuxcnc config: refused"));
    EXPECT_THAT(e.what(), HasSubstr("fiducial nests"));
    EXPECT_THAT(e.what(), HasSubstr("--registration FILE"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "unregistered-cfg"));
  LinuxcncInstallRequest install;
  install.calibration = config.machine;
  install.ini = (dir_ / "no-such.ini").string();
  try {
    (void)installIntoLinuxcnc(install);
    FAIL() << "installed an unregistered world frame";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("pkm linuxcnc install: refused"));
  }
}

TEST_F(CalibrateHexapodWorkflow, ARegistrationThatIsNotRigidIsRefusedWithItsLine) {
  HexapodCalibrationRequest r = request("badreg.json");
  r.registration = io::NamedText{"reg.csv",
                                 "nest,x_table,y_table,z_table,x,y,z\n"
                                 "a,0,0,0,0,0,0\nb,500,0,0,500,0,0\nc,0,500,0,0,500,0\n"
                                 "d,500,500,0,500,520,0\n"};
  try {
    (void)calibrateHexapod(r);
    FAIL() << "accepted nests that do not fit one rigid placement";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("reg.csv:"));
    EXPECT_THAT(e.what(), HasSubstr("do not describe one rigid placement"));
  }
  r.registration = io::NamedText{"reg.csv", "nest,x_table,y_table,z_table,x,y,z\na,0,0,0,0,0,x\n"};
  try {
    (void)calibrateHexapod(r);
    FAIL() << "accepted a field that is not a number";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("reg.csv:2:"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "badreg.json"));
}

TEST_F(CalibrateHexapodWorkflow, RequestsAreChecked) {
  HexapodCalibrationRequest r = request("x.json");
  r.frame = "sideways";
  EXPECT_THROW(r.validate(), InvalidArgument);
  r = request("x.json");
  r.data.clear();
  EXPECT_THROW(r.validate(), InvalidArgument);
  r = request("x.json");
  r.monte_carlo = 1;
  EXPECT_THROW(r.validate(), InvalidArgument);
  EXPECT_EQ(calibrationOutputs("a/cal.json").hal, "a/cal.hal");
  EXPECT_EQ(calibrationOutputs("a/cal.json").summary, "a/cal.summary.json");
  EXPECT_EQ(calibrationOutputs("cal").summary, "cal.summary.json");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
