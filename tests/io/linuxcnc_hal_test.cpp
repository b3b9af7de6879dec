// Tests of reading LinuxCNC's genhexkins kinematics.hal (pkm/io/linuxcnc_hal.hpp): the geometry
// against genhexkins, the INI found beside it, FK settings, notices, the spindle-/tool-offset
// semantics, the refusals of a bad HAL file, and LinuxCNC's own hexapod-sim sample. The INI's
// values and the setp blocks written back are in linuxcnc_hal_ini_test.cpp.
#include "pkm/io/linuxcnc_hal.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "io/linuxcnc_hal_fixture.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/linuxcnc_sample.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace fs = std::filesystem;
namespace kin = pkm::kinematics;
using pkm::IoError;
using pkm::io::HalReadOptions;
using pkm::io::HexapodMachine;
using pkm::io::readLinuxcncHal;
using pkm::test::anyContains;
using pkm::test::expectReferenceLengths;
using pkm::test::join;
using pkm::test::kTolExact;
using pkm::test::kTolLinuxcnc;
using pkm::test::lineOf;
using pkm::test::LinuxcncHalTest;
using pkm::test::poseOf;
using pkm::test::simHalLines;
using pkm::test::simIniLines;
using ::testing::HasSubstr;
using ::testing::StartsWith;

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

}  // namespace PKM_TEST_NS
