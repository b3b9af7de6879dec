// Tests of the LinuxCNC configuration files (pkm/io/linuxcnc_config.hpp): names, the INI's joints,
// home, units and axis limits against pkm's kinematics, the kinematics and simulator HAL files,
// compensation references, and the refusals.
#include "pkm/io/linuxcnc_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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
#include "pkm/kinematics/hexapod_ik.hpp"

namespace {

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

TEST(LinuxcncConfig, HexapodAxisLimitsAreTheReachFromHome) {
  const io::HexapodMachine m = io::builtinMachine("hexapod-default");
  const Ini ini = parseIni(io::hexapodLinuxcncConfig(m, {})[0].text);
  kin::HexapodData data(m.model);
  const std::string letters = "XYZABC";
  for (int k = 0; k < 6; ++k) {
    const std::string s = std::string("AXIS_") + letters[static_cast<std::size_t>(k)];
    const double step = k < 3 ? 0.1 : 0.01;  // characteristic length 100..1000 mm; degrees
    for (const char* key : {"MIN_LIMIT", "MAX_LIMIT"}) {
      const double limit = number(ini, s, key);
      auto poseAt = [&](double v) {
        kin::PoseRpy p = m.model.home;
        if (k < 3)
          p.position[k] = v;
        else
          p.rpy[k - 3] = pkm::degToRad(v);
        return p;
      };
      EXPECT_TRUE(kin::checkPose(m.model, data, poseAt(limit)).ok()) << s << " " << key;
      // Not 2 steps further, unless the search stopped at its cap (2 characteristic lengths,
      // 90 degrees for A and B, 180 for C).
      const double cap = k < 3 ? 2.0 * m.model.characteristicLength() : k < 5 ? 90.0 : 180.0;
      const double home = k < 3 ? m.model.home.position[k] : 0.0;
      if (std::abs(limit - home) >= cap - step) continue;
      const double beyond = limit + (key[1] == 'I' ? -2.0 : 2.0) * step;
      EXPECT_FALSE(kin::checkPose(m.model, data, poseAt(beyond)).ok()) << s << " " << key;
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

}  // namespace
