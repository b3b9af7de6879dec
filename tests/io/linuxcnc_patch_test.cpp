// io::patchKinematicsHal / patchHexapodIni / unifiedDiff: values replaced in place, every other
// byte kept (a configuration written here for the test, not LinuxCNC's own).
#include "pkm/io/linuxcnc_patch.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "pkm/core/error.hpp"
#include "pkm/io/machine_loader.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// A kinematics HAL text with every genhexkins joint pin of `m`, odd spacing, comments, a net
/// line and CRLF line ends.
std::string halOf(const HexapodMachine& m) {
  std::string t = "# my machine\r\nloadkins genhexkins\r\n";
  for (const auto& [pin, value] : genhexkinsPins(m))
    if (pin != "spindle-offset")
      t += fmt::format("setp   genhexkins.{}\t {:.3f}  # as built\r\n", pin, value);
  return t + "net tool-offset genhexkins.tool-offset motion.tooloffset.z\r\n";
}

std::string iniOf(const char* units) {
  std::string t = fmt::format(
      "[TRAJ]\nLINEAR_UNITS = {}\n[HAL]\nHALFILE = LIB:basic_sim.tcl\n"
      "HALFILE = kins.hal\nPOSTGUI_HALFILE = post.hal\n",
      units);
  for (int i = 0; i < 6; ++i)
    t += fmt::format(
        "[JOINT_{}]\nMIN_LIMIT = -1000\nMAX_LIMIT = 1000\nHOME_OFFSET= 1\nHOME = 1\n"
        "HOME_SEQUENCE = 0\n",
        i);
  return t;
}

TEST(LinuxcncPatch, HalValuesChangeAndEveryOtherByteStays) {
  const HexapodMachine nominal = loadHexapodMachine("hexapod-linuxcnc-sim");
  HexapodMachine cal = nominal;
  cal.model.struts[0].world_p_base.y() += 0.0123;
  cal.model.struts[4].platform_p_joint.z() -= 0.001;
  const NamedText hal{"kins.hal", halOf(nominal)};
  const TextPatch p = patchKinematicsHal(hal, cal);
  ASSERT_EQ(p.changes.size(), 2u);
  EXPECT_EQ(p.changes[0].key, "genhexkins.base.0.y");
  EXPECT_EQ(p.changes[0].before, "13.250");
  EXPECT_EQ(p.changes[0].after, "13.2623");
  EXPECT_EQ(p.changes[0].line, 4u);
  EXPECT_EQ(p.changes[1].key, "genhexkins.platform.4.z");
  // Undo the two values by hand: the rest is the file as it was.
  std::string undone = p.after;
  undone.replace(undone.find("13.2623"), 7, "13.250");
  undone.replace(undone.find(p.changes[1].after), p.changes[1].after.size(), "0.000");
  EXPECT_EQ(undone, hal.text);
  // Unchanged values are left as written ("-22.950" is not rewritten as "-22.95").
  EXPECT_TRUE(patchKinematicsHal(hal, nominal).changes.empty());
  // A configuration without a joint's line is refused: lines are never added.
  std::string missing = hal.text;
  missing.erase(missing.find("setp   genhexkins.base.3.y"), 44);
  EXPECT_THROW((void)patchKinematicsHal({"short.hal", missing}, cal), IoError);
}

TEST(LinuxcncPatch, IniLinearUnits) {
  EXPECT_EQ(iniLinearUnits({"m.ini", iniOf("inch")}), LengthUnit::kInch);
  EXPECT_EQ(iniLinearUnits({"m.ini", "[TRAJ]\nLINEAR_UNITS = metric\n"}), LengthUnit::kMillimetre);
  EXPECT_EQ(iniLinearUnits({"m.ini", "[AXIS_X]\nLINEAR_UNITS = inch\n"}), std::nullopt);
  try {
    (void)iniLinearUnits({"m.ini", "# c\n[TRAJ]\nLINEAR_UNITS = furlong\n"});
    FAIL() << "accepted furlongs";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("m.ini:3: [TRAJ] LINEAR_UNITS 'furlong' not understood"));
  }
}

TEST(LinuxcncPatch, IniHomeAndLimitsFromTheCalibratedGeometry) {
  HexapodMachine cal = loadHexapodMachine("hexapod-linuxcnc-sim");
  cal.model.struts[2].length_offset = 0.0021;
  const NamedText ini{"m.ini", iniOf("inch")};
  EXPECT_EQ(iniHalFiles(ini),
            (std::vector<std::string>{"LIB:basic_sim.tcl", "kins.hal", "post.hal"}));
  const TextPatch p = patchHexapodIni(ini, cal);
  // HOME and HOME_OFFSET of six joints, and both limits of joint 2.
  ASSERT_EQ(p.changes.size(), 14u);
  EXPECT_EQ(p.changes[0].key, "[JOINT_0] HOME_OFFSET");
  EXPECT_THAT(p.after, HasSubstr("[JOINT_2]\nMIN_LIMIT = -999.9979\nMAX_LIMIT = 1000.0021\n"));
  EXPECT_THAT(p.after, HasSubstr("HOME_OFFSET= 29.7466"));  // the key's own spacing is kept
  const std::string diff = unifiedDiff(p);
  EXPECT_THAT(diff, HasSubstr("--- m.ini\n+++ m.ini\n@@ -"));
  EXPECT_THAT(diff, HasSubstr("\n-MIN_LIMIT = -1000\n+MIN_LIMIT = -999.9979\n"));
  EXPECT_EQ(unifiedDiff({"same", "a\n", "a\n", {}}), "");
  EXPECT_THROW((void)patchHexapodIni({"mm.ini", iniOf("mm")}, cal), IoError);
  std::string five = ini.text;
  five.erase(five.find("[JOINT_5]"));
  EXPECT_THROW((void)patchHexapodIni({"five.ini", five}, cal), IoError);
}

TEST(LinuxcncPatch, RoundLimitsStayRound) {
  // A calibration whose stroke and length offset sum to ±1000 up to rounding: the INI's limits
  // are left as they are, not rewritten as -999.9999999999973.
  HexapodMachine cal = loadHexapodMachine("hexapod-linuxcnc-sim");
  for (double offset : {0.0123456789, 0.3, 1.0 / 3.0}) {
    kinematics::Strut& s = cal.model.struts[3];
    s.length_offset = offset;
    s.min_reading = -1000.0 - offset;
    s.max_reading = 1000.0 - offset;
    const TextPatch p = patchHexapodIni({"m.ini", iniOf("inch")}, cal);
    for (const PatchedValue& v : p.changes)
      EXPECT_THAT(v.key, ::testing::Not(HasSubstr("LIMIT"))) << offset << " " << v.after;
    EXPECT_THAT(p.after, HasSubstr("[JOINT_3]\nMIN_LIMIT = -1000\nMAX_LIMIT = 1000\n"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
