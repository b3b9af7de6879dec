// io::parsePkmhexkinsParameters / pkmhexkinsParamsFile / readLinuxcncHexapod: the pkmhexkins
// parameter file pkm writes read back exactly, a configuration's machine found from its [KINS]
// line (pkmhexkins) or its HAL files (genhexkins), and bad files refused with their line.
#include "pkm/io/linuxcnc_machine.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_hexapod_params.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/scratch_files.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::string refusal(const std::string& text) {
  try {
    (void)parsePkmhexkinsParameters({"m.params", text});
  } catch (const IoError& e) {
    return e.what();
  }
  return "accepted";
}

TEST(PkmhexkinsParameters, WhatPkmWritesIsReadBackExactly) {
  HexapodMachine m = loadHexapodMachine("hexapod-default");
  m.model.struts[2].length_offset = 12.25;
  m.model.struts[4].world_p_base.x() += 0.1;
  m.fk.tolerance = 1e-10;
  const HexapodMachine back = parsePkmhexkinsParameters({"m.params", linuxcncHexapodParameters(m)});
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(back.model.struts[i].world_p_base, m.model.struts[i].world_p_base);
    EXPECT_EQ(back.model.struts[i].platform_p_joint, m.model.struts[i].platform_p_joint);
    EXPECT_EQ(back.model.struts[i].length_offset, m.model.struts[i].length_offset);
  }
  EXPECT_EQ(back.model.tool_offset, m.model.tool_offset);
  EXPECT_EQ(back.model.home.position, m.model.home.position);
  EXPECT_NEAR((back.model.home.rpy - m.model.home.rpy).norm(), 0.0, 1e-15);
  EXPECT_EQ(back.fk.tolerance, 1e-10);
  EXPECT_EQ(back.fk.max_iterations, m.fk.max_iterations);
  EXPECT_EQ(back.fk.max_step_rotation, m.fk.max_step_rotation);
}

TEST(PkmhexkinsParameters, BadLinesAreRefusedWithTheirLine) {
  const std::string good = linuxcncHexapodParameters(loadHexapodMachine("hexapod-default"));
  EXPECT_THAT(refusal(good + "speed 3\n"), HasSubstr("'speed' is not a pkmhexkins parameter"));
  EXPECT_THAT(refusal(good + "base.7 1 2 3\n"), HasSubstr("'base.7' is not"));
  EXPECT_THAT(refusal(good + "tool 1 2\n"), HasSubstr("tool: expected 3 numbers, found 2"));
  EXPECT_THAT(refusal(good + "home 0 0 1 nan 0 0\n"), HasSubstr("'nan' is not a finite number"));
  EXPECT_THAT(refusal(good + "base.0 1 2 3\n"), HasSubstr("base.0 is given again (first on line"));
  EXPECT_THAT(refusal("base.0 1 2 3 # a comment\n"), HasSubstr("m.params: no 'platform.0' line"));
  EXPECT_THAT(refusal("\n\nbogus 1\n"), HasSubstr("m.params:3:"));
  std::string zero = good;
  zero.replace(zero.find("limit-iterations 120"), 20, "limit-iterations 0");
  EXPECT_THAT(refusal(zero), HasSubstr("forward-kinematics settings"));
}

class LinuxcncMachineFiles : public pkm::test::ScratchDirTest {
 protected:
  LinuxcncMachineFiles() : ScratchDirTest("linuxcnc_machine") {}
};

TEST_F(LinuxcncMachineFiles, APkmhexkinsConfigurationIsReadFromItsParameterFile) {
  HexapodMachine m = loadHexapodMachine("hexapod-default");
  m.model.struts[1].length_offset = -3.5;
  write("cfg/m.params", linuxcncHexapodParameters(m));
  const std::string ini = write("cfg/m.ini",
                                "[KINS]\nJOINTS = 6\nKINEMATICS = pkmhexkins params=m.params\n"
                                "[TRAJ]\nLINEAR_UNITS = mm\n[JOINT_0]\nMIN_LIMIT = 1\n"
                                "MAX_LIMIT = 400\n");
  const LinuxcncHexapod got = readLinuxcncHexapod(ini);
  EXPECT_EQ(got.kinematics, "pkmhexkins");
  EXPECT_EQ(got.file, (dir_ / "cfg/m.params").string());
  EXPECT_EQ(got.machine.model.struts[1].length_offset, -3.5);
  EXPECT_EQ(got.machine.model.struts[0].min_reading, 1.0);
  EXPECT_EQ(got.machine.model.struts[0].max_reading, 400.0);
  EXPECT_EQ(got.machine.model.unit, LengthUnit::kMillimetre);
  // The parameter file as a machine (the server's live machine): with the INI that loads it, the
  // configuration's machine; alone, or with another INI, refused as no machine description.
  const std::string params = (dir_ / "cfg/m.params").string();
  HalReadOptions with_ini;
  with_ini.ini_path = ini;
  const HexapodMachine loaded = loadHexapodMachine(params, with_ini);
  EXPECT_EQ(loaded.model.struts[1].length_offset, -3.5);
  EXPECT_EQ(loaded.model.struts[0].max_reading, 400.0);
  EXPECT_THROW((void)loadHexapodMachine(params), IoError);
  with_ini.ini_path = write("other/m.ini", "[KINS]\nKINEMATICS = pkmhexkins params=m.params\n");
  write("other/m.params", linuxcncHexapodParameters(m));
  EXPECT_THROW((void)loadHexapodMachine(params, with_ini), IoError);
}

TEST_F(LinuxcncMachineFiles, AGenhexkinsConfigurationIsReadFromItsHalFile) {
  const HexapodMachine m = loadHexapodMachine("hexapod-default");
  write("cfg/kins.hal", writeLinuxcncSetp(m));
  const std::string ini =
      write("cfg/m.ini",
            "[KINS]\nKINEMATICS = genhexkins\n[TRAJ]\nLINEAR_UNITS = mm\n[HAL]\n"
            "HALFILE = kins.hal\n");
  const LinuxcncHexapod got = readLinuxcncHexapod(ini);
  EXPECT_EQ(got.kinematics, "genhexkins");
  EXPECT_NEAR((got.machine.model.struts[3].world_p_base - m.model.struts[3].world_p_base).norm(),
              0.0,
              1e-12);
}

TEST_F(LinuxcncMachineFiles, AMissingParameterFileNamesTheIniLine) {
  const std::string ini = write("m.ini", "[KINS]\nKINEMATICS = pkmhexkins params=gone.params\n");
  try {
    (void)readLinuxcncHexapod(ini);
    FAIL() << "accepted";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("m.ini:2: [KINS] KINEMATICS:"));
    EXPECT_THAT(e.what(), HasSubstr("gone.params"));
  }
  const std::string none = write("n.ini", "[KINS]\nKINEMATICS = trivkins\n");
  EXPECT_THROW((void)readLinuxcncHexapod(none), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
