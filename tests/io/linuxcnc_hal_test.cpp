// Tests of the LinuxCNC genhexkins interop (pkm/io/linuxcnc_hal.hpp): reading kinematics.hal + INI,
// the spindle-/tool-offset semantics, and writing the setp block back.
#include "pkm/io/linuxcnc_hal.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/linuxcnc_sample.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace {

namespace fs = std::filesystem;
namespace kin = pkm::kinematics;
using pkm::IoError;
using pkm::io::HalReadOptions;
using pkm::io::HexapodMachine;
using pkm::io::readLinuxcncHal;
using pkm::io::writeLinuxcncSetp;
using pkm::test::kTolExact;
using pkm::test::kTolLinuxcnc;
using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// Reference strut lengths of the LinuxCNC hexapod-sim (genhexkins), inch, 6 decimals.
struct Reference {
  double pose[6];  ///< x y z (inch) a b c (deg)
  double lengths[6];
};
const Reference kReference[] = {
    {{0, 0, 20, 0, 0, 0}, {29.746680, 29.746680, 29.746715, 29.746363, 29.746363, 29.746715}},
    {{2, -1, 22, 3, -4, 10}, {31.597194, 31.713899, 29.975223, 32.850082, 27.921167, 33.441616}},
    {{-3, 2, 18, 10, 10, -15}, {30.022945, 29.402324, 29.682443, 25.351693, 33.820068, 24.667812}},
};

kin::PoseRpy poseOf(const double (&v)[6]) {
  kin::PoseRpy p;
  p.position = {v[0], v[1], v[2]};
  p.rpy = {pkm::degToRad(v[3]), pkm::degToRad(v[4]), pkm::degToRad(v[5])};
  return p;
}

void expectReferenceLengths(const kin::HexapodModel& model) {
  kin::HexapodData data(model);
  for (const Reference& r : kReference) {
    const kin::StrutVector& q = kin::inverseKinematics(model, data, poseOf(r.pose));
    for (int i = 0; i < kin::kStruts; ++i)
      EXPECT_NEAR(q[i], r.lengths[i], kTolLinuxcnc) << "pose z " << r.pose[2] << " strut " << i;
  }
}

/// kinematics.hal as in the hexapod-sim sample configuration (written here, not copied), one entry
/// per line: line n is lines[n - 1]. `platform_z` moves the platform joints along the platform z
/// axis: -20 gives a geometry that is not singular at home 0 0 0 0 0 0 (used where no INI supplies
/// HOME).
std::vector<std::string> simHalLines(double platform_z = 0.0) {
  const kin::HexapodModel sim = pkm::test::linuxcncSimModel();
  std::vector<std::string> lines;
  char buf[128];
  lines.emplace_back("# Base joints positions in base (world) coordinates");  // 1
  for (int i = 0; i < kin::kStruts; ++i)                                      // 2..19
    for (int a = 0; a < 3; ++a) {
      std::snprintf(buf,
                    sizeof buf,
                    "setp genhexkins.base.%d.%c %7.3f",
                    i,
                    "xyz"[a],
                    sim.struts[static_cast<std::size_t>(i)].world_p_base[a]);
      lines.emplace_back(buf);
    }
  lines.emplace_back("");                                                     // 20
  lines.emplace_back("# Platform joints positions in platform coordinates");  // 21
  for (int i = 0; i < kin::kStruts; ++i)                                      // 22..39
    for (int a = 0; a < 3; ++a) {
      std::snprintf(buf,
                    sizeof buf,
                    "setp genhexkins.platform.%d.%c %7.3f",
                    i,
                    "xyz"[a],
                    sim.struts[static_cast<std::size_t>(i)].platform_p_joint[a] +
                        (a == 2 ? platform_z : 0.0));
      lines.emplace_back(buf);
    }
  lines.emplace_back("");                                                            // 40
  lines.emplace_back("net tool-offset genhexkins.tool-offset motion.tooloffset.z");  // 41
  lines.emplace_back("# setp genhexkins.convergence-criterion 1e-9");                // 42
  return lines;
}

/// 1-based line number of the line starting with `prefix`.
std::size_t lineOf(const std::vector<std::string>& lines, const std::string& prefix) {
  for (std::size_t n = 0; n < lines.size(); ++n)
    if (lines[n].starts_with(prefix)) return n + 1;
  ADD_FAILURE() << "no line " << prefix;
  return 0;
}

std::string join(const std::vector<std::string>& lines) {
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

/// hexapod.ini lines; HOME is line 10, LINEAR_UNITS line 11, [JOINT_n] MIN_LIMIT line 13 + 3n.
std::vector<std::string> simIniLines(const std::string& halfile = "kinematics.hal") {
  std::vector<std::string> lines = {
      "[EMC]",                        // 1
      "MACHINE = pkm test hexapod",   // 2
      "[KINS]",                       // 3
      "KINEMATICS = genhexkins",      // 4
      "JOINTS = 6",                   // 5
      "[HAL]",                        // 6
      "HALFILE = LIB:basic_sim.tcl",  // 7
      "HALFILE = " + halfile,         // 8
      "[TRAJ]",                       // 9
      "HOME = 0 0 20 0 0 0",          // 10
      "LINEAR_UNITS = inch",          // 11
  };
  for (int j = 0; j < 6; ++j) {
    lines.push_back("[JOINT_" + std::to_string(j) + "]");
    lines.emplace_back("MIN_LIMIT = -1000.0");
    lines.emplace_back("MAX_LIMIT = 1000.0");
  }
  return lines;
}

class LinuxcncHalTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           (std::string("pkm_hal_test_") + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  std::string write(const std::string& name, const std::string& content) const {
    const fs::path p = dir_ / name;
    fs::create_directories(p.parent_path());
    std::ofstream out(p, std::ios::binary);
    out << content;
    return p.string();
  }
  std::string writeHal(const std::vector<std::string>& lines,
                       const std::string& name = "kinematics.hal") const {
    return write(name, join(lines));
  }
  std::string writeIni(const std::vector<std::string>& lines,
                       const std::string& name = "hexapod.ini") const {
    return write(name, join(lines));
  }

  /// The IoError message of reading `hal` with `options` ("" when it does not throw).
  static std::string errorOf(const std::string& hal, const HalReadOptions& options = {}) {
    try {
      (void)readLinuxcncHal(hal, options);
    } catch (const IoError& e) {
      return e.what();
    }
    return {};
  }

  fs::path dir_;
};

bool anyContains(const std::vector<std::string>& notices, const std::string& text) {
  for (const auto& n : notices)
    if (n.find(text) != std::string::npos) return true;
  return false;
}

// ---------------------------------------------------------------------------------------------
// Reading

TEST_F(LinuxcncHalTest, DiscoversIniAndMatchesLinuxcncReference) {
  const std::string hal = writeHal(simHalLines());
  const std::string ini = writeIni(simIniLines());
  const HexapodMachine m = readLinuxcncHal(hal);
  EXPECT_EQ(m.source, hal);
  EXPECT_EQ(m.model.name, "kinematics");
  EXPECT_TRUE(anyContains(m.notices, "using INI " + ini)) << ::testing::PrintToString(m.notices);
  EXPECT_TRUE(anyContains(m.notices, hal + ":41: ignored: net tool-offset"));
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d(0, 0, 20));
  EXPECT_EQ(m.model.home.rpy, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.model.spindle_offset, 0.0);
  EXPECT_EQ(m.model.tool_offset, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.fk.tolerance, 1e-9);
  EXPECT_EQ(m.fk.max_iterations, 120);
  const kin::HexapodModel ref = pkm::test::linuxcncSimModel();
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(m.model.struts[i].world_p_base, ref.struts[i].world_p_base) << i;
    EXPECT_EQ(m.model.struts[i].platform_p_joint, ref.struts[i].platform_p_joint) << i;
    EXPECT_EQ(m.model.struts[i].length_offset, 0.0);
    EXPECT_EQ(m.model.struts[i].min_reading, -1000.0);
    EXPECT_EQ(m.model.struts[i].max_reading, 1000.0);
  }
  kin::HexapodData data(m.model);
  const kin::StrutVector& q = kin::inverseKinematics(m.model, data, m.model.home);
  const double want[6] = {29.746680, 29.746680, 29.746715, 29.746363, 29.746363, 29.746715};
  for (int i = 0; i < kin::kStruts; ++i) EXPECT_NEAR(q[i], want[i], kTolLinuxcnc) << i;
  expectReferenceLengths(m.model);
}

TEST_F(LinuxcncHalTest, ExplicitIniPath) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini_lines = simIniLines("somewhere-else.hal");
  ini_lines[9] = "HOME = 1 -2 21 3 4 5";
  const std::string ini = writeIni(ini_lines, "conf/other.ini");
  HalReadOptions opt;
  opt.ini_path = ini;
  const HexapodMachine m = readLinuxcncHal(hal, opt);
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d(1, -2, 21));
  EXPECT_NEAR(m.model.home.rpy.x(), pkm::degToRad(3), kTolExact);
  EXPECT_NEAR(m.model.home.rpy.y(), pkm::degToRad(4), kTolExact);
  EXPECT_NEAR(m.model.home.rpy.z(), pkm::degToRad(5), kTolExact);
  EXPECT_FALSE(anyContains(m.notices, "using INI"));
  EXPECT_FALSE(anyContains(m.notices, "no INI"));
}

TEST_F(LinuxcncHalTest, FromMemoryAsFromFiles) {
  // parseLinuxcncHal reads texts held in memory (an upload, a fuzz input) as readLinuxcncHal reads
  // the files; messages use the names given.
  const std::string hal = writeHal(simHalLines());
  HalReadOptions opt;
  opt.ini_path = writeIni(simIniLines());
  const HexapodMachine from_files = readLinuxcncHal(hal, opt);
  const HexapodMachine m = pkm::io::parseLinuxcncHal(
      {hal, join(simHalLines())}, pkm::io::NamedText{"up.ini", join(simIniLines())});
  EXPECT_EQ(m.source, hal);
  EXPECT_EQ(m.model.name, "kinematics");
  EXPECT_EQ(m.model.unit, from_files.model.unit);
  EXPECT_EQ(m.model.home.position, from_files.model.home.position);
  EXPECT_EQ(m.notices, from_files.notices);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(m.model.struts[i].world_p_base, from_files.model.struts[i].world_p_base) << i;
    EXPECT_EQ(m.model.struts[i].platform_p_joint, from_files.model.struts[i].platform_p_joint);
    EXPECT_EQ(m.model.struts[i].min_reading, -1000.0);
    EXPECT_EQ(m.model.struts[i].base_cone.axis, from_files.model.struts[i].base_cone.axis);
  }
  // No INI is looked for next to an upload.
  const HexapodMachine bare = pkm::io::parseLinuxcncHal({"up.hal", join(simHalLines(-20.0))});
  EXPECT_TRUE(anyContains(bare.notices, "no INI file")) << ::testing::PrintToString(bare.notices);
  std::vector<std::string> bad_ini = simIniLines();
  bad_ini[10] = "LINEAR_UNITS = furlong";
  try {
    (void)pkm::io::parseLinuxcncHal({"up.hal", join(simHalLines())},
                                    pkm::io::NamedText{"up.ini", join(bad_ini)});
    FAIL() << "accepted furlongs";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("up.ini:11: [TRAJ] LINEAR_UNITS 'furlong'"));
  }
}

TEST_F(LinuxcncHalTest, WithoutIniAssumesMillimetresAndZeroHome) {
  // Platform joints 20 below the platform origin: at home 0 0 0 the legs are those of the sim at z
  // 20, mirrored in the base plane.
  const std::string hal = writeHal(simHalLines(-20.0));
  writeIni(simIniLines());
  HalReadOptions opt;
  opt.discover_ini = false;
  const HexapodMachine m = readLinuxcncHal(hal, opt);
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kMillimetre);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.model.home.rpy, Eigen::Vector3d::Zero());
  EXPECT_TRUE(anyContains(m.notices, "no INI file"));
  EXPECT_EQ(m.model.struts[0].min_reading, -std::numeric_limits<double>::infinity());
  kin::HexapodData data(m.model);
  const kin::StrutVector& q = kin::inverseKinematics(m.model, data, m.model.home);
  for (int i = 0; i < kin::kStruts; ++i)
    EXPECT_NEAR(q[i], kReference[0].lengths[i], kTolLinuxcnc) << i;
}

TEST_F(LinuxcncHalTest, WithoutIniTheSimGeometryIsSingularAtZeroHome) {
  // The sample geometry has base and platform joints in one plane at home 0 0 0: without [TRAJ]
  // HOME the reader must refuse it and say why.
  const std::string hal = writeHal(simHalLines());
  HalReadOptions opt;
  opt.discover_ini = false;
  const std::string msg = errorOf(hal, opt);
  EXPECT_THAT(msg, StartsWith(hal + ": "));
  EXPECT_THAT(msg, HasSubstr("singular"));
  EXPECT_THAT(msg, HasSubstr("no INI file was found"));
}

TEST_F(LinuxcncHalTest, IniThatDoesNotLoadTheHalFileIsNotUsed) {
  const std::string hal = writeHal(simHalLines(-20.0));
  writeIni(simIniLines("other-kinematics.hal"));
  const HexapodMachine m = readLinuxcncHal(hal);
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kMillimetre);
  EXPECT_TRUE(anyContains(m.notices, "no INI file"));
}

TEST_F(LinuxcncHalTest, SeveralMatchingInisAreAmbiguous) {
  const std::string hal = writeHal(simHalLines(-20.0));
  writeIni(simIniLines(), "a.ini");
  writeIni(simIniLines(), "b.ini");
  const HexapodMachine m = readLinuxcncHal(hal);
  EXPECT_TRUE(anyContains(m.notices, "several INI files"));
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kMillimetre);
}

TEST_F(LinuxcncHalTest, FkSettingsAreRead) {
  std::vector<std::string> lines = simHalLines();
  lines.emplace_back("setp genhexkins.convergence-criterion 1e-11");
  lines.emplace_back("setp genhexkins.limit-iterations 60");
  lines.emplace_back("setp genhexkins.screw-lead 0");  // 0 = no correction: accepted
  writeIni(simIniLines());
  const HexapodMachine m = readLinuxcncHal(writeHal(lines));
  EXPECT_EQ(m.fk.tolerance, 1e-11);
  EXPECT_EQ(m.fk.max_iterations, 60);
}

TEST_F(LinuxcncHalTest, OtherLinesProduceNotices) {
  std::vector<std::string> lines = simHalLines();
  lines.emplace_back("loadrt genhexkins");                         // 43
  lines.emplace_back("setp motion.some-pin 1");                    // 44
  lines.emplace_back("setp genhexkins.max-error 100.0");           // 45
  lines.emplace_back("setp genhexkins.base-n.0.x 0.5");            // 46
  lines.emplace_back("   # an indented comment");                  // 47
  lines.emplace_back("addf genhexkins servo-thread  # trailing");  // 48
  const std::string hal = writeHal(lines);
  HalReadOptions opt;
  opt.ini_path = writeIni(simIniLines(), "given.ini");
  const HexapodMachine m = readLinuxcncHal(hal, opt);
  EXPECT_TRUE(anyContains(
      m.notices, hal + ":41: ignored: net tool-offset genhexkins.tool-offset motion.tooloffset.z"));
  EXPECT_TRUE(anyContains(m.notices, hal + ":43: ignored: loadrt genhexkins"));
  EXPECT_TRUE(anyContains(m.notices, hal + ":44: ignored: setp motion.some-pin 1"));
  EXPECT_TRUE(anyContains(m.notices, hal + ":45: ignored: genhexkins.max-error"));
  EXPECT_TRUE(anyContains(m.notices, hal + ":46: ignored: genhexkins.base-n.0.x"));
  EXPECT_TRUE(anyContains(m.notices, hal + ":48: ignored: addf genhexkins servo-thread"));
  EXPECT_FALSE(anyContains(m.notices, ":47:"));
  EXPECT_FALSE(anyContains(m.notices, ":42:"));  // commented-out setp
  EXPECT_FALSE(anyContains(m.notices, ":40:"));  // blank line
  // The six ignored HAL lines and nothing else (an INI given explicitly needs no notice).
  EXPECT_EQ(m.notices.size(), 6u) << ::testing::PrintToString(m.notices);
}

TEST_F(LinuxcncHalTest, CrlfAndTrailingComments) {
  std::vector<std::string> lines = simHalLines();
  for (auto& l : lines) l += "   # comment\r";
  std::vector<std::string> ini_lines = simIniLines();
  for (auto& l : ini_lines) l += "\r";
  writeIni(ini_lines);
  const HexapodMachine m = readLinuxcncHal(writeHal(lines));
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d(0, 0, 20));
  const kin::HexapodModel ref = pkm::test::linuxcncSimModel();
  for (std::size_t i = 0; i < kin::kStruts; ++i)
    EXPECT_EQ(m.model.struts[i].platform_p_joint, ref.struts[i].platform_p_joint);
}

// ---------------------------------------------------------------------------------------------
// spindle-offset and tool-offset

TEST_F(LinuxcncHalTest, SpindleAndToolOffsetShiftEveryJointZ) {
  constexpr double kSpindle = 2.5, kTool = 1.5;
  std::vector<std::string> lines = simHalLines();
  lines.emplace_back("setp genhexkins.spindle-offset 2.5");
  lines.emplace_back("setp genhexkins.tool-offset 1.5");
  writeIni(simIniLines());
  const HexapodMachine m = readLinuxcncHal(writeHal(lines));
  EXPECT_EQ(m.model.spindle_offset, kSpindle + kTool);
  EXPECT_EQ(m.model.linuxcnc_tool_offset, kTool);

  // The same machine with the offset added to z of all base and platform joints by hand.
  kin::HexapodModel shifted = pkm::test::linuxcncSimModel();
  for (auto& s : shifted.struts) {
    s.world_p_base.z() += kSpindle + kTool;
    s.platform_p_joint.z() += kSpindle + kTool;
  }
  const kin::HexapodModel plain = pkm::test::linuxcncSimModel();
  kin::HexapodData d1(m.model), d2(shifted), d3(plain);
  const double poses[][6] = {
      {0, 0, 20, 0, 0, 0}, {1.5, -2, 21, 7, -5, 12}, {-3, 2, 18, 10, 10, -15}};
  for (const auto& v : poses) {
    const kin::PoseRpy pose = poseOf(v);
    const kin::StrutVector q1 = kin::inverseKinematics(m.model, d1, pose);
    const kin::StrutVector q2 = kin::inverseKinematics(shifted, d2, pose);
    const kin::StrutVector q3 = kin::inverseKinematics(plain, d3, pose);
    EXPECT_LT((q1 - q2).cwiseAbs().maxCoeff(), kTolExact)
        << q1.transpose() << " vs " << q2.transpose();
    if (v[3] != 0.0) {  // tilted: the offset changes the lengths
      EXPECT_GT((q1 - q3).cwiseAbs().maxCoeff(), 1e-3);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Writing the setp block and reading it back

TEST_F(LinuxcncHalTest, SetpRoundTripGivesIdenticalJoints) {
  std::vector<std::string> lines = simHalLines();
  lines.emplace_back("setp genhexkins.spindle-offset 2.5");
  lines.emplace_back("setp genhexkins.tool-offset -0.75");
  lines.emplace_back("setp genhexkins.convergence-criterion 1e-10");
  lines.emplace_back("setp genhexkins.limit-iterations 60");
  writeIni(simIniLines());
  const HexapodMachine m = readLinuxcncHal(writeHal(lines));
  ASSERT_EQ(m.model.unit, pkm::LengthUnit::kInch);
  const std::string setp = writeLinuxcncSetp(m);
  EXPECT_THAT(setp, HasSubstr("setp genhexkins.base.0.x -22.95\n"));
  EXPECT_THAT(setp, HasSubstr("setp genhexkins.tool-offset -0.75\n"));
  EXPECT_THAT(setp, HasSubstr("# [TRAJ] HOME = 0 0 20 0 0 0\n"));
  EXPECT_THAT(setp, HasSubstr("# [TRAJ] LINEAR_UNITS = inch\n"));
  EXPECT_THAT(setp, HasSubstr("MIN_LIMIT = -1000"));

  // Read back with an INI made from the values the block gives as comments.
  const std::string back_path = write("out/written.hal", setp);
  writeIni(
      {"[HAL]", "HALFILE = written.hal", "[TRAJ]", "HOME = 0 0 20 0 0 0", "LINEAR_UNITS = inch"},
      "out/m.ini");
  const HexapodMachine back = readLinuxcncHal(back_path);
  EXPECT_EQ(back.model.unit, pkm::LengthUnit::kInch);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(back.model.struts[i].world_p_base, m.model.struts[i].world_p_base) << i;
    EXPECT_EQ(back.model.struts[i].platform_p_joint, m.model.struts[i].platform_p_joint) << i;
  }
  EXPECT_EQ(back.model.spindle_offset, m.model.spindle_offset);
  EXPECT_EQ(back.model.linuxcnc_tool_offset, m.model.linuxcnc_tool_offset);
  EXPECT_EQ(back.fk.tolerance, 1e-10);
  EXPECT_EQ(back.fk.max_iterations, 60);
  kin::HexapodData d1(m.model), d2(back.model);
  const kin::PoseRpy pose = poseOf(kReference[2].pose);
  EXPECT_EQ(kin::inverseKinematics(m.model, d1, pose),
            kin::inverseKinematics(back.model, d2, pose));
}

TEST_F(LinuxcncHalTest, SetpLoadsOnItsOwnThroughPkmCommentLines) {
  writeIni(simIniLines());
  HexapodMachine m = readLinuxcncHal(writeHal(simHalLines()));
  m.model.home.rpy.z() = pkm::degToRad(5);  // a home that differs from the INI's
  const std::string setp = writeLinuxcncSetp(m);
  EXPECT_THAT(setp, HasSubstr("# pkm: units = inch\n"));
  EXPECT_THAT(setp, HasSubstr("# pkm: home = 0 0 20 0 0 5\n"));
  const HexapodMachine back = readLinuxcncHal(write("alone/k.hal", setp));  // no INI in that folder
  EXPECT_EQ(back.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(back.model.home.position, m.model.home.position);
  EXPECT_NEAR(back.model.home.rpy.z(), m.model.home.rpy.z(), kTolExact);
  EXPECT_FALSE(anyContains(back.notices, "no INI file"));
  // An INI next to it overrides the comment lines.
  writeIni({"[HAL]", "HALFILE = k.hal", "[TRAJ]", "HOME = 0 0 21 0 0 0", "LINEAR_UNITS = mm"},
           "alone/m.ini");
  const HexapodMachine with_ini = readLinuxcncHal(dir_.string() + "/alone/k.hal");
  EXPECT_EQ(with_ini.model.unit, pkm::LengthUnit::kMillimetre);
  EXPECT_EQ(with_ini.model.home.position.z(), 21.0);
}

TEST_F(LinuxcncHalTest, MalformedPkmCommentLineNamesFileAndLine) {
  std::vector<std::string> lines = simHalLines();
  lines.emplace_back("# pkm: home = 0 0 20");
  const std::string hal = writeHal(lines);
  EXPECT_THAT(
      errorOf(hal),
      HasSubstr(hal + ":" + std::to_string(lines.size()) + ": # pkm: home: expected 6 numbers"));
  lines.back() = "# pkm: units = furlong";
  EXPECT_THAT(errorOf(writeHal(lines)), HasSubstr("units 'furlong'"));
  lines.back() = "# pkm: colour = red";
  EXPECT_THAT(errorOf(writeHal(lines)), HasSubstr("'# pkm:' lines are"));
}

TEST_F(LinuxcncHalTest, SetpOfMachineWithToolOffsetAndLengthOffsets) {
  const HexapodMachine m =
      pkm::io::readHexapodJson(std::string(PKM_SOURCE_DIR) + "/data/machines/hexapod-default.json");
  const std::string setp = writeLinuxcncSetp(m);
  EXPECT_THAT(setp, HasSubstr("TCP offset of the pkm model is folded into the platform joints"));
  EXPECT_THAT(setp, HasSubstr("length offset 650"));
  EXPECT_THAT(setp, HasSubstr("# [TRAJ] LINEAR_UNITS = mm\n"));
  writeIni({"[HAL]", "HALFILE = w.hal", "[TRAJ]", "HOME = 0 0 200 0 0 0", "LINEAR_UNITS = mm"},
           "w.ini");
  const HexapodMachine back = readLinuxcncHal(write("w.hal", setp));
  ASSERT_EQ(back.model.tool_offset, Eigen::Vector3d::Zero());
  for (int i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(back.model.effectiveBase(i), m.model.effectiveBase(i)) << i;
    EXPECT_EQ(back.model.effectivePlatform(i), m.model.effectivePlatform(i)) << i;
  }
  // LinuxCNC joint positions are joint-centre distances: reading + length offset.
  kin::HexapodData d1(m.model), d2(back.model);
  kin::PoseRpy pose = m.model.home;
  pose.position += Eigen::Vector3d(20, -10, 15);
  pose.rpy += Eigen::Vector3d(0.05, -0.03, 0.1);
  const kin::StrutVector q1 = kin::inverseKinematics(m.model, d1, pose);
  const kin::StrutVector q2 = kin::inverseKinematics(back.model, d2, pose);
  for (int i = 0; i < kin::kStruts; ++i) EXPECT_NEAR(q2[i], q1[i] + 650.0, 1e3 * kTolExact) << i;
}

// ---------------------------------------------------------------------------------------------
// Errors

TEST_F(LinuxcncHalTest, MissingPinsAreListed) {
  std::vector<std::string> lines = simHalLines();
  lines[lineOf(lines, "setp genhexkins.platform.3.y") - 1] = "# removed";
  lines[lineOf(lines, "setp genhexkins.base.5.z") - 1] = "";
  const std::string hal = writeHal(lines);
  const std::string msg = errorOf(hal);
  EXPECT_THAT(msg, StartsWith(hal + ": "));
  EXPECT_THAT(msg, HasSubstr("platform.3.y"));
  EXPECT_THAT(msg, HasSubstr("base.5.z"));
  EXPECT_THAT(msg, ::testing::Not(HasSubstr("base.0.x")));
}

TEST_F(LinuxcncHalTest, NonNumberValueNamesFileAndLine) {
  std::vector<std::string> lines = simHalLines();
  const std::size_t n = lineOf(lines, "setp genhexkins.base.2.x");
  lines[n - 1] = "setp genhexkins.base.2.x abc";
  const std::string hal = writeHal(lines);
  const std::string msg = errorOf(hal);
  EXPECT_THAT(msg, StartsWith(hal + ":" + std::to_string(n) + ": "));
  EXPECT_THAT(msg, HasSubstr("'abc' is not a finite number"));
}

TEST_F(LinuxcncHalTest, NonFiniteValueIsAnError) {
  std::vector<std::string> lines = simHalLines();
  const std::size_t n = lineOf(lines, "setp genhexkins.platform.4.z");
  lines[n - 1] = "setp genhexkins.platform.4.z nan";
  const std::string hal = writeHal(lines);
  EXPECT_THAT(errorOf(hal), StartsWith(hal + ":" + std::to_string(n) + ": "));
}

TEST_F(LinuxcncHalTest, SetpWithoutValueIsAnError) {
  std::vector<std::string> lines = simHalLines();
  const std::size_t n = lineOf(lines, "setp genhexkins.base.1.y");
  lines[n - 1] = "setp genhexkins.base.1.y";
  const std::string hal = writeHal(lines);
  EXPECT_THAT(
      errorOf(hal),
      StartsWith(hal + ":" + std::to_string(n) + ": expected 'setp genhexkins.base.1.y VALUE'"));
}

TEST_F(LinuxcncHalTest, NonzeroScrewLeadIsAnError) {
  std::vector<std::string> lines = simHalLines();
  lines.emplace_back("setp genhexkins.screw-lead 0.2");  // line 43
  const std::string hal = writeHal(lines);
  const std::string msg = errorOf(hal);
  EXPECT_THAT(msg, StartsWith(hal + ":43: "));
  EXPECT_THAT(msg, HasSubstr("screw-lead"));
}

TEST_F(LinuxcncHalTest, UnknownGenhexkinsPinIsAnError) {
  for (const std::string bad : {"setp genhexkins.base.6.x 1",
                                "setp genhexkins.platform.0.w 1",
                                "setp genhexkins.base.0 1",
                                "setp genhexkins.wobble 1"}) {
    SCOPED_TRACE(bad);
    std::vector<std::string> lines = simHalLines();
    lines.insert(lines.begin() + 2, bad);  // line 3
    const std::string hal = writeHal(lines);
    const std::string msg = errorOf(hal);
    EXPECT_THAT(msg, StartsWith(hal + ":3: unknown pin genhexkins."));
  }
}

TEST_F(LinuxcncHalTest, BadFkSettings) {
  for (const std::string bad : {"setp genhexkins.convergence-criterion 0",
                                "setp genhexkins.limit-iterations 2.5",
                                "setp genhexkins.limit-iterations 0"}) {
    SCOPED_TRACE(bad);
    std::vector<std::string> lines = simHalLines();
    lines.push_back(bad);  // line 43
    const std::string hal = writeHal(lines);
    EXPECT_THAT(errorOf(hal), StartsWith(hal + ":43: "));
  }
}

TEST_F(LinuxcncHalTest, UnusableGeometryNamesTheFile) {
  std::vector<std::string> lines = simHalLines();
  // Platform joint 2 := platform joint 1: struts 1 and 2 become the same leg (same base joint).
  lines[lineOf(lines, "setp genhexkins.platform.2.x") - 1] = "setp genhexkins.platform.2.x 1";
  lines[lineOf(lines, "setp genhexkins.platform.2.y") - 1] = "setp genhexkins.platform.2.y 11.5";
  const std::string hal = writeHal(lines);
  const std::string msg = errorOf(hal);
  EXPECT_THAT(msg, StartsWith(hal + ": "));
  EXPECT_THAT(msg, HasSubstr("coincident"));
}

TEST_F(LinuxcncHalTest, MissingHalFile) {
  const std::string hal = (dir_ / "nope.hal").string();
  EXPECT_THAT(errorOf(hal), StartsWith(hal + ": "));
}

TEST_F(LinuxcncHalTest, BadIniHomeCount) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini_lines = simIniLines();
  ini_lines[9] = "HOME = 0 0 20 0 0";
  const std::string ini = writeIni(ini_lines);
  const std::string msg = errorOf(hal);
  EXPECT_THAT(msg, StartsWith(ini + ":10: "));
  EXPECT_THAT(msg, HasSubstr("expected 6 numbers"));
  EXPECT_THAT(msg, HasSubstr("found 5"));
}

TEST_F(LinuxcncHalTest, BadIniHomeValue) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini_lines = simIniLines();
  ini_lines[9] = "HOME = 0 0 twenty 0 0 0";
  const std::string ini = writeIni(ini_lines);
  EXPECT_THAT(errorOf(hal), StartsWith(ini + ":10: [TRAJ] HOME: 'twenty' is not a finite number"));
}

TEST_F(LinuxcncHalTest, BadIniUnits) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini_lines = simIniLines();
  ini_lines[10] = "LINEAR_UNITS = furlong";
  const std::string ini = writeIni(ini_lines);
  EXPECT_THAT(errorOf(hal), StartsWith(ini + ":11: "));
}

TEST_F(LinuxcncHalTest, IniMinLimitAboveMaxLimit) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini_lines = simIniLines();
  ini_lines[13 + 3 * 2 - 1] = "MIN_LIMIT = 5";  // [JOINT_2]
  ini_lines[14 + 3 * 2 - 1] = "MAX_LIMIT = 1";
  const std::string ini = writeIni(ini_lines);
  const std::string msg = errorOf(hal);
  EXPECT_THAT(msg, StartsWith(ini + ": "));
  EXPECT_THAT(msg, HasSubstr("[JOINT_2] MIN_LIMIT 5 > MAX_LIMIT 1"));
}

TEST_F(LinuxcncHalTest, IniLimitsAreStroke) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini_lines = simIniLines();
  ini_lines[13 + 3 * 4 - 1] = "MIN_LIMIT = 20";  // [JOINT_4]
  ini_lines[14 + 3 * 4 - 1] = "MAX_LIMIT = 40";
  writeIni(ini_lines);
  const HexapodMachine m = readLinuxcncHal(hal);
  EXPECT_EQ(m.model.struts[4].min_reading, 20.0);
  EXPECT_EQ(m.model.struts[4].max_reading, 40.0);
  EXPECT_EQ(m.model.struts[3].min_reading, -1000.0);
}

TEST_F(LinuxcncHalTest, JointRatesAreTheSmallestOfTheJoints) {
  const std::string hal = writeHal(simHalLines());
  std::vector<std::string> ini = simIniLines();
  EXPECT_FALSE(readLinuxcncHal(hal, {writeIni(ini), false}).joint_rates.has_value());
  for (int j = 0; j < 6; ++j) {
    ini.push_back("[JOINT_" + std::to_string(j) + "]");
    ini.push_back("MAX_VELOCITY = " + std::to_string(j == 4 ? 15 : 20));
    ini.push_back("MAX_ACCELERATION = " + std::to_string(j == 2 ? 150 : 200));
  }
  const HexapodMachine m = readLinuxcncHal(hal, {writeIni(ini), false});
  ASSERT_TRUE(m.joint_rates.has_value());
  EXPECT_EQ(m.joint_rates->velocity, 15.0);
  EXPECT_EQ(m.joint_rates->acceleration, 150.0);
  ini.push_back("[JOINT_5]");
  ini.push_back("MAX_VELOCITY = 0");
  const std::string bad = writeIni(ini);
  EXPECT_THAT(errorOf(hal, {bad, false}),
              ::testing::HasSubstr(bad + ":" + std::to_string(ini.size()) +
                                   ": [JOINT_5] MAX_VELOCITY: expected one number > 0"));
}

// ---------------------------------------------------------------------------------------------
// The genuine LinuxCNC sample configuration (scripts/fetch-linuxcnc.sh unpacks it into .cache/)

TEST(LinuxcncGenuineConfig, HexapodSimKinematicsHal) {
  const fs::path dir = pkm::test::linuxcncHexapodSim();
  if (!fs::is_directory(dir)) GTEST_SKIP() << dir << " not found (run scripts/fetch-linuxcnc.sh)";
  const std::string hal = (dir / "kinematics.hal").string();
  const HexapodMachine m = readLinuxcncHal(hal);
  EXPECT_TRUE(anyContains(m.notices, "hexapod.ini")) << ::testing::PrintToString(m.notices);
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d(0, 0, 20));
  const kin::HexapodModel ref = pkm::test::linuxcncSimModel();
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(m.model.struts[i].world_p_base, ref.struts[i].world_p_base) << i;
    EXPECT_EQ(m.model.struts[i].platform_p_joint, ref.struts[i].platform_p_joint) << i;
  }
  expectReferenceLengths(m.model);
  // [JOINT_N] MAX_VELOCITY = 20, MAX_ACCELERATION = 200 in the sample's hexapod.ini.
  ASSERT_TRUE(m.joint_rates.has_value());
  EXPECT_EQ(m.joint_rates->velocity, 20.0);
  EXPECT_EQ(m.joint_rates->acceleration, 200.0);
}

}  // namespace

namespace {

/// The `setp pkmhexkins.NAME VALUE` lines of a block, by NAME.
std::map<std::string, double> pkmhexkinsPins(const std::string& text) {
  std::map<std::string, double> pins;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.starts_with("setp pkmhexkins.")) continue;
    std::istringstream words(line.substr(16));
    std::string name, value;
    words >> name >> value;
    EXPECT_TRUE(pins.emplace(name, std::stod(value)).second) << "pin set twice: " << name;
  }
  return pins;
}

TEST(PkmhexkinsSetp, EveryParameterExactly) {
  HexapodMachine m = pkm::io::builtinMachine("hexapod-default");
  for (std::size_t i = 0; i < m.model.struts.size(); ++i) {
    m.model.struts[i].length_offset += 0.1 * static_cast<double>(i) + 1.0 / 3.0;
    m.model.struts[i].world_p_base.y() += 1.0 / 7.0;
  }
  m.model.tool_offset = {0.25, -1.0 / 3.0, -200.125};
  m.model.spindle_offset = 2.5;
  m.model.home.position = {1.5, -2.0, 210.0};
  m.model.home.rpy = {0.0, pkm::degToRad(2.0), 0.0};
  const std::string text = pkm::io::writePkmhexkinsSetp(m);
  const std::map<std::string, double> pins = pkmhexkinsPins(text);
  EXPECT_EQ(pins.size(), 18u + 18u + 6u + 3u + 1u + 6u + 2u);
  const char* xyz[] = {"x", "y", "z"};
  for (std::size_t i = 0; i < m.model.struts.size(); ++i) {
    const kin::Strut& s = m.model.struts[i];
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(pins.at(fmt::format("base.{}.{}", i, xyz[k])), s.world_p_base[k]);
      EXPECT_EQ(pins.at(fmt::format("platform.{}.{}", i, xyz[k])), s.platform_p_joint[k]);
    }
    EXPECT_EQ(pins.at(fmt::format("length-offset.{}", i)), s.length_offset);
  }
  for (int k = 0; k < 3; ++k)
    EXPECT_EQ(pins.at(fmt::format("tool.{}", xyz[k])), m.model.tool_offset[k]);
  EXPECT_EQ(pins.at("spindle-offset"), 2.5);
  EXPECT_EQ(pins.at("home.x"), 1.5);
  EXPECT_EQ(pins.at("home.z"), 210.0);
  EXPECT_NEAR(pins.at("home.b"), 2.0, kTolExact);
  EXPECT_EQ(pins.at("convergence-criterion"), m.fk.tolerance);
  EXPECT_EQ(pins.at("limit-iterations"), m.fk.max_iterations);
  // The joints' INI values are the strut readings (not joint-centre distances) at home.
  kin::HexapodData data(m.model);
  const kin::StrutVector q = kin::inverseKinematics(m.model, data, m.model.home);
  const auto joints = pkm::io::pkmhexkinsJointValues(m);
  for (std::size_t i = 0; i < joints.size(); ++i) {
    EXPECT_EQ(joints[i].home, q[static_cast<Eigen::Index>(i)]);
    EXPECT_EQ(joints[i].min_limit, m.model.struts[i].min_reading);
    EXPECT_EQ(joints[i].max_limit, m.model.struts[i].max_reading);
    EXPECT_THAT(text,
                HasSubstr(fmt::format("# [JOINT_{}] HOME = HOME_OFFSET = {}, MIN_LIMIT = 0, "
                                      "MAX_LIMIT = 500\n",
                                      i,
                                      pkm::io::formatNumber(joints[i].home))));
  }
}

TEST(PkmhexkinsSetp, OpenStrokeHasNoLimits) {
  HexapodMachine m = pkm::io::builtinMachine("hexapod-default");
  m.model.struts[2].min_reading = -std::numeric_limits<double>::infinity();
  const auto joints = pkm::io::pkmhexkinsJointValues(m);
  EXPECT_FALSE(joints[2].min_limit.has_value());
  EXPECT_TRUE(joints[2].max_limit.has_value());
}

}  // namespace
