// Tests of the LinuxCNC genhexkins interop (pkm/io/linuxcnc_hal.hpp) around the INI: the INI given
// or absent, its HOME, units, joint limits and rates and their refusals; and the setp blocks
// written back (genhexkins and pkmhexkins), which carry those values as comment lines. Reading
// kinematics.hal itself is in linuxcnc_hal_test.cpp.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "io/linuxcnc_hal_fixture.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
using pkm::io::HalReadOptions;
using pkm::io::HexapodMachine;
using pkm::io::readLinuxcncHal;
using pkm::io::writeLinuxcncSetp;
using pkm::test::anyContains;
using pkm::test::kReference;
using pkm::test::kTolExact;
using pkm::test::kTolLinuxcnc;
using pkm::test::LinuxcncHalTest;
using pkm::test::poseOf;
using pkm::test::simHalLines;
using pkm::test::simIniLines;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// ---------------------------------------------------------------------------------------------
// The INI: given, absent, ambiguous; HOME, units, limits and rates

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

}  // namespace PKM_TEST_NS
