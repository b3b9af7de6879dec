// Tests of the LinuxCNC configuration files (pkm/io/linuxcnc_config.hpp): names, the INI's joints,
// home, units and axis limits against pkm's kinematics, the kinematics and simulator HAL files,
// compensation references, and the refusals.
#include "pkm/io/linuxcnc_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_exechon.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/io/number_format.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/kinematics/hexapod_checks.hpp"
#include "pkm/kinematics/hexapod_clearance.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace kin = pkm::kinematics;
using ::testing::HasSubstr;
using ::testing::Not;

/// section → key → value of an INI text (the last value of a repeated key).
using Ini = std::map<std::string, std::map<std::string, std::string>>;

Ini parseIni(const std::string& text) {
  Ini ini;
  std::string section;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] == '#') continue;
    if (line[0] == '[') {
      section = line.substr(1, line.find(']') - 1);
      continue;
    }
    const std::size_t eq = line.find(" = ");
    EXPECT_NE(eq, std::string::npos) << line;
    ini[section][line.substr(0, eq)] = line.substr(eq + 3);
  }
  return ini;
}

double number(const Ini& ini, const std::string& section, const std::string& key) {
  return std::stod(ini.at(section).at(key));
}

std::map<std::string, std::string> byName(const std::vector<io::NamedText>& files) {
  std::map<std::string, std::string> out;
  for (const io::NamedText& f : files) out[f.name] = f.text;
  return out;
}

TEST(LinuxcncConfig, HexapodFilesJointsAndHome) {
  const io::HexapodMachine m = io::builtinMachine("hexapod-default");
  const std::vector<io::NamedText> files = io::hexapodLinuxcncConfig(m, {});
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files[0].name, "pkm-hx1200.ini");
  EXPECT_EQ(files[1].name, "kinematics.hal");
  EXPECT_EQ(files[2].name, "sim.hal");
  EXPECT_EQ(files[3].name, "tool.tbl");
  EXPECT_EQ(files[4].name, "pkm-hx1200.params");
  EXPECT_EQ(files[4].text, io::linuxcncHexapodParameters(m));
  const Ini ini = parseIni(files[0].text);
  EXPECT_EQ(ini.at("KINS").at("KINEMATICS"), "pkmhexkins params=pkm-hx1200.params");
  EXPECT_EQ(ini.at("KINS").at("JOINTS"), "6");
  EXPECT_EQ(ini.at("TRAJ").at("LINEAR_UNITS"), "mm");
  EXPECT_EQ(ini.at("TRAJ").at("COORDINATES"), "X Y Z A B C");
  EXPECT_EQ(ini.at("TRAJ").at("HOME"), "0 0 200 0 0 0");
  EXPECT_EQ(ini.at("DISPLAY").at("DISPLAY"), "axis");
  EXPECT_EQ(ini.at("HAL").at("HALFILE"), "sim.hal");  // after kinematics.hal
  EXPECT_THAT(ini.at("RS274NGC").at("RS274NGC_STARTUP_CODE"), HasSubstr("G21"));
  kin::HexapodData data(m.model);
  const kin::StrutVector q = kin::inverseKinematics(m.model, data, m.model.home);
  for (int i = 0; i < 6; ++i) {
    const std::string s = "JOINT_" + std::to_string(i);
    EXPECT_EQ(number(ini, s, "HOME"), q[i]);  // exact: shortest round-trip numbers
    EXPECT_EQ(number(ini, s, "HOME_OFFSET"), q[i]);
    EXPECT_EQ(number(ini, s, "MIN_LIMIT"), 0.0);
    EXPECT_EQ(number(ini, s, "MAX_LIMIT"), 500.0);
    EXPECT_EQ(ini.at(s).at("TYPE"), "LINEAR");
    EXPECT_EQ(ini.at(s).count("COMP_FILE"), 0u);
  }
  EXPECT_THAT(files[1].text, HasSubstr("loadrt [KINS]KINEMATICS\n"));
  EXPECT_THAT(files[1].text, ::testing::Not(HasSubstr("setp pkmhexkins")));  // the file has it
  for (int j = 0; j < 6; ++j)
    EXPECT_THAT(files[2].text,
                HasSubstr("joint." + std::to_string(j) + ".motor-pos-cmd => joint." +
                          std::to_string(j) + ".motor-pos-fb\n"));
  EXPECT_THAT(files[2].text, HasSubstr("motion.tooloffset.z => pkmhexkins.tool-offset\n"));
}

/// The pose of world coordinates X Y Z A B C (degrees).
kin::PoseRpy poseOf(const std::array<double, 6>& w) {
  kin::PoseRpy p;
  p.position = {w[0], w[1], w[2]};
  p.rpy = {pkm::degToRad(w[3]), pkm::degToRad(w[4]), pkm::degToRad(w[5])};
  return p;
}

/// Every corner of the INI's axis-limit box passes `pkm hexapod check`, keeps the platform
/// joints `margin` above the base plane and is on home's assembly branch.
void expectCornersAdmissible(const io::HexapodMachine& m, const Ini& ini, double margin) {
  kin::HexapodData data(m.model);
  const kin::BasePlane plane = kin::basePlane(m.model);
  const int home_branch = kin::assemblyBranch(m.model, data, m.model.home);
  const std::string letters = "XYZABC";
  for (int mask = 0; mask < 64; ++mask) {
    std::array<double, 6> w{};
    for (std::size_t k = 0; k < 6; ++k)
      w[k] = number(
          ini, std::string("AXIS_") + letters[k], (mask >> k) & 1 ? "MAX_LIMIT" : "MIN_LIMIT");
    const kin::PoseRpy pose = poseOf(w);
    EXPECT_TRUE(kin::checkPose(m.model, data, pose).ok()) << m.model.name << " corner " << mask;
    EXPECT_GE(kin::platformClearance(m.model, plane, pose), margin)
        << m.model.name << " corner " << mask;
    EXPECT_EQ(kin::assemblyBranch(m.model, data, pose), home_branch)
        << m.model.name << " corner " << mask;
  }
}

TEST(LinuxcncConfig, HexapodAxisLimitsBoxIsAdmissibleAtEveryCorner) {
  for (const char* name : {"hexapod-default", "hexapod-linuxcnc-sim", "mxt700s-like"}) {
    if (io::machineTypeOf(name) != "hexapod") continue;
    const io::HexapodMachine m = io::builtinMachine(name);
    std::vector<std::string> notices;
    const Ini ini = parseIni(io::hexapodLinuxcncConfig(m, {}, &notices)[0].text);
    const double margin = kin::kMirrorClearanceFraction * m.model.characteristicLength();
    expectCornersAdmissible(m, ini, margin);
    // A box shrunk from the reach is announced, and nothing else is.
    EXPECT_LE(notices.size(), 1U) << name;
    for (const std::string& n : notices) EXPECT_THAT(n, HasSubstr("axis limits shrunk to")) << name;
    // Home inside, and not a box collapsed onto it.
    for (const std::string s : {"AXIS_X", "AXIS_Y", "AXIS_Z", "AXIS_A", "AXIS_B", "AXIS_C"})
      EXPECT_LT(number(ini, s, "MIN_LIMIT"), number(ini, s, "MAX_LIMIT")) << name << " " << s;
  }
}

TEST(LinuxcncConfig, HexapodSimZLimitStaysAboveTheBasePlane) {
  // LinuxCNC's hexapod-sim: base joints at z = 0, platform joints in the platform's z = 0 plane,
  // home z = 20 in. A Z limit at or below 0 would let G0 reach the singular plane and the mirror
  // assembly beyond (same strut lengths, z negated).
  const io::HexapodMachine m = io::builtinMachine("hexapod-linuxcnc-sim");
  const Ini ini = parseIni(io::hexapodLinuxcncConfig(m, {})[0].text);
  const double margin = kin::kMirrorClearanceFraction * m.model.characteristicLength();
  EXPECT_GE(number(ini, "AXIS_Z", "MIN_LIMIT"), margin);
  EXPECT_GT(margin, 1.0);  // inch: the characteristic length is about 11.5 in
  EXPECT_LE(number(ini, "AXIS_Z", "MAX_LIMIT"), 20.0 + 2.0 * m.model.characteristicLength());
}

TEST(LinuxcncConfig, HexapodAxisLimitsAreAdmissibleAlongEachAxis) {
  // One axis at its limit, the others at home.
  const io::HexapodMachine m = io::builtinMachine("hexapod-default");
  const Ini ini = parseIni(io::hexapodLinuxcncConfig(m, {})[0].text);
  kin::HexapodData data(m.model);
  const kin::BasePlane plane = kin::basePlane(m.model);
  const double margin = kin::kMirrorClearanceFraction * m.model.characteristicLength();
  const std::string letters = "XYZABC";
  for (int k = 0; k < 6; ++k) {
    const std::string s = std::string("AXIS_") + letters[static_cast<std::size_t>(k)];
    for (const char* key : {"MIN_LIMIT", "MAX_LIMIT"}) {
      kin::PoseRpy p = m.model.home;
      const double limit = number(ini, s, key);
      if (k < 3)
        p.position[k] = limit;
      else
        p.rpy[k - 3] = pkm::degToRad(limit);
      EXPECT_TRUE(kin::checkPose(m.model, data, p).ok()) << s << " " << key;
      EXPECT_GE(kin::platformClearance(m.model, plane, p), margin) << s << " " << key;
    }
  }
}

TEST(LinuxcncConfig, InchMachine) {
  const io::HexapodMachine m = io::builtinMachine("hexapod-linuxcnc-sim");
  const Ini ini = parseIni(io::hexapodLinuxcncConfig(m, {.display = "linuxcncrsh"})[0].text);
  EXPECT_EQ(ini.at("TRAJ").at("LINEAR_UNITS"), "inch");
  EXPECT_THAT(ini.at("RS274NGC").at("RS274NGC_STARTUP_CODE"), HasSubstr("G20"));
  EXPECT_EQ(ini.at("DISPLAY").at("DISPLAY"), "linuxcncrsh");
  EXPECT_EQ(number(ini, "JOINT_0", "MAX_VELOCITY"), 20.0);  // the machine's joint_rates
  EXPECT_EQ(number(ini, "JOINT_0", "MAX_ACCELERATION"), 200.0);
  EXPECT_EQ(number(ini, "JOINT_3", "MIN_LIMIT"), -1000.0);
}

TEST(LinuxcncConfig, ExechonFilesJointsAndHome) {
  const io::ExechonMachine m = io::loadExechonMachine("mxt700s-like");
  const std::map<std::string, std::string> files = byName(io::exechonLinuxcncConfig(m, {}));
  ASSERT_EQ(files.size(), 5u);
  EXPECT_EQ(files.at("mxt700s-like.params"), io::linuxcncExechonParameters(m));
  const Ini ini = parseIni(files.at("mxt700s-like.ini"));
  EXPECT_EQ(ini.at("KINS").at("KINEMATICS"), "pkmexechonkins params=mxt700s-like.params");
  EXPECT_EQ(ini.at("KINS").at("JOINTS"), "5");
  EXPECT_EQ(ini.at("TRAJ").at("COORDINATES"), "X Y Z A C");
  kin::ExechonData home(m.model);
  kin::evaluateConfiguration(m.model, home, m.model.home);
  std::istringstream h(ini.at("TRAJ").at("HOME"));
  double v[6];
  for (double& x : v) h >> x;
  for (int k = 0; k < 3; ++k) EXPECT_EQ(v[k], home.world_p_tool[k]);
  EXPECT_EQ(v[3], 0.0);  // A = the wrist A reading at home
  EXPECT_EQ(v[5], 0.0);  // C
  for (int i = 0; i < 3; ++i) {
    const std::string s = "JOINT_" + std::to_string(i);
    EXPECT_EQ(number(ini, s, "HOME"), home.readings[i]);
    EXPECT_EQ(number(ini, s, "MIN_LIMIT"), 0.0);
    EXPECT_EQ(number(ini, s, "MAX_LIMIT"), 700.0);
  }
  EXPECT_EQ(ini.at("JOINT_3").at("TYPE"), "ANGULAR");
  EXPECT_EQ(number(ini, "JOINT_3", "MIN_LIMIT"), -270.0);  // wrist C
  EXPECT_EQ(number(ini, "JOINT_4", "MAX_LIMIT"), 100.0);   // wrist A
  EXPECT_EQ(number(ini, "AXIS_C", "MAX_LIMIT"), 270.0);
  EXPECT_THAT(files.at("sim.hal"), HasSubstr("=> pkmexechonkins.tool-offset\n"));
  EXPECT_THAT(files.at("sim.hal"), Not(HasSubstr("joint.5")));
  // X Y Z: the tool point reaches each limit with the wrist held, and not 2 steps beyond.
  kin::ExechonData data(m.model);
  for (int k = 0; k < 3; ++k)
    for (const char* key : {"MIN_LIMIT", "MAX_LIMIT"}) {
      const double limit = number(ini, std::string("AXIS_") + "XYZ"[k], key);
      Eigen::Vector3d p = home.world_p_tool;
      p[k] = limit;
      ASSERT_EQ(kin::toolPointInverseKinematics(m.model, data, p, 0.0, 0.0, home.e),
                kin::ExechonIkStatus::kOk);
      EXPECT_TRUE(kin::checkConfiguration(m.model, data).ok()) << k << key;
    }
}

TEST(LinuxcncConfig, CompensationTablesAreReferenced) {
  const io::HexapodMachine m = io::builtinMachine("hexapod-default");
  io::LinuxcncConfigOptions options;
  options.comp_files = {{2, "joint2.comp", 0}, {5, "joint5.comp", 1}};
  const Ini ini = parseIni(io::hexapodLinuxcncConfig(m, options)[0].text);
  EXPECT_EQ(ini.at("JOINT_2").at("COMP_FILE"), "joint2.comp");
  EXPECT_EQ(ini.at("JOINT_2").at("COMP_FILE_TYPE"), "0");
  EXPECT_EQ(ini.at("JOINT_5").at("COMP_FILE_TYPE"), "1");
  EXPECT_EQ(ini.at("JOINT_0").count("COMP_FILE"), 0u);
}

TEST(LinuxcncConfig, OptionsAreChecked) {
  EXPECT_NO_THROW(io::LinuxcncConfigOptions{}.validate(6));
  auto bad = [](io::LinuxcncConfigOptions o, int joints) {
    EXPECT_THROW(o.validate(joints), pkm::InvalidArgument);
  };
  bad({.display = ""}, 6);
  bad({.display = "axis -x"}, 6);
  bad({.comp_files = {{6, "j.comp", 1}}}, 6);
  bad({.comp_files = {{5, "j.comp", 1}}}, 5);
  bad({.comp_files = {{-1, "j.comp", 1}}}, 6);
  bad({.comp_files = {{1, "a.comp", 1}, {1, "b.comp", 1}}}, 6);
  bad({.comp_files = {{1, "../a.comp", 1}}}, 6);
  bad({.comp_files = {{1, "a.comp", 2}}}, 6);
}

TEST(LinuxcncConfig, HomeOutsideTheStrokeIsRefused) {
  io::HexapodMachine m = io::builtinMachine("hexapod-default");
  m.model.struts[4].max_reading = 10.0;
  try {
    (void)io::hexapodLinuxcncConfig(m, {});
    FAIL() << "no exception";
  } catch (const pkm::InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("builtin:hexapod-default"));
    EXPECT_THAT(e.what(), HasSubstr("strut 4"));
  }
}

TEST(LinuxcncConfig, NamesComeFromTheMachineName) {
  EXPECT_EQ(io::linuxcncConfigNames("my hexapod/2").ini, "my-hexapod-2.ini");
  EXPECT_EQ(io::linuxcncConfigNames("..").ini, "machine.ini");
  EXPECT_EQ(io::linuxcncConfigNames("x").params, "x.params");
}

}  // namespace PKM_TEST_NS
