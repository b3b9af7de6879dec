// workflow::installIntoLinuxcnc on LinuxCNC's own hexapod-sim configuration (a copy in a scratch
// folder): nothing written without force, then the files patched in place with backups, and the
// patched configuration read back as the calibrated machine.
#include "pkm/workflow/linuxcnc_install.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/linuxcnc_config.hpp"
#include "pkm/io/linuxcnc_hal.hpp"
#include "pkm/io/linuxcnc_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/workflow/linuxcnc_config.hpp"
#include "support/linuxcnc_sample.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST(LinuxcncInstall, PatchesTheSampleConfigurationInPlace) {
  const fs::path sample = pkm::test::linuxcncHexapodSim();
  if (!fs::is_directory(sample))
    GTEST_SKIP() << sample << " not found (run scripts/fetch-linuxcnc.sh)";
  const fs::path dir = test::scratchPath("linuxcnc_install", "config");
  fs::remove_all(dir);
  fs::copy(sample, dir, fs::copy_options::recursive);
  const std::string hal_before = test::slurp(dir / "kinematics.hal");
  const std::string ini_before = test::slurp(dir / "hexapod.ini");

  io::HexapodMachine cal = io::loadHexapodMachine("hexapod-linuxcnc-sim");
  cal.model.name = "hexapod-linuxcnc-sim-calibrated";
  cal.model.struts[1].world_p_base.x() += 0.021;
  cal.model.struts[5].platform_p_joint.y() -= 0.0042;
  cal.model.struts[3].length_offset = -0.0017;
  io::writeFileAtomic(dir / "cal.json", io::writeHexapodJson(cal), io::Overwrite::kAllow);

  LinuxcncInstallRequest r{(dir / "cal.json").string(), (dir / "hexapod.ini").string(), false};
  const LinuxcncInstallResult preview = installIntoLinuxcnc(r);
  EXPECT_FALSE(preview.written);
  EXPECT_THAT(preview.diff,
              HasSubstr("-setp genhexkins.base.1.x  22.950\n+setp genhexkins.base.1.x  22.971\n"));
  EXPECT_EQ(test::slurp(dir / "kinematics.hal"), hal_before);  // nothing written
  EXPECT_FALSE(fs::exists(dir / "kinematics.hal.pkm-backup"));

  r.force = true;
  const LinuxcncInstallResult done = installIntoLinuxcnc(r);
  EXPECT_TRUE(done.written);
  EXPECT_EQ(test::slurp(dir / "kinematics.hal.pkm-backup"), hal_before);
  EXPECT_EQ(test::slurp(dir / "hexapod.ini.pkm-backup"), ini_before);
  const std::string hal_after = test::slurp(dir / "kinematics.hal");
  EXPECT_THAT(hal_after, HasSubstr("net tool-offset genhexkins.tool-offset motion.tooloffset.z\n"));
  EXPECT_EQ(hal_after.size(), hal_before.size() + 1);  // "22.950" → "22.971", "-4.884" → "-4.8882"

  // Read back as LinuxCNC will load it: the calibrated joints, and the INI's joint home.
  io::HalReadOptions options;
  options.ini_path = (dir / "hexapod.ini").string();
  const io::HexapodMachine back = io::readLinuxcncHal((dir / "kinematics.hal").string(), options);
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_EQ(back.model.struts[i].world_p_base, cal.model.struts[i].world_p_base) << i;
    EXPECT_EQ(back.model.struts[i].platform_p_joint, cal.model.struts[i].platform_p_joint) << i;
  }
  EXPECT_DOUBLE_EQ(back.model.struts[3].min_reading, cal.model.struts[3].min_reading - 0.0017);

  // Installed again: nothing to change. Changed and installed again: a second backup, the first
  // kept.
  EXPECT_TRUE(installIntoLinuxcnc(r).diff.empty());
  cal.model.struts[1].world_p_base.x() += 0.001;
  io::writeFileAtomic(dir / "cal.json", io::writeHexapodJson(cal), io::Overwrite::kAllow);
  const LinuxcncInstallResult again = installIntoLinuxcnc(r);
  EXPECT_EQ(again.backups.at(0), (dir / "kinematics.hal.pkm-backup.1").string());
  EXPECT_EQ(test::slurp(dir / "kinematics.hal.pkm-backup"), hal_before);
  fs::remove_all(dir);
}

TEST(LinuxcncInstall, RewritesAPkmhexkinsParameterFileAndKeepsTheIni) {
  const fs::path dir = test::scratchPath("linuxcnc_install", "pkmhexkins");
  fs::remove_all(dir);
  LinuxcncConfigRequest config;
  config.machine = "hexapod-default";
  config.out = (dir / "cfg").string();
  const LinuxcncConfigResult written = writeLinuxcncConfig(config);
  const std::string params = (dir / "cfg" / io::linuxcncConfigNames("pkm-hx1200").params).string();
  ASSERT_TRUE(fs::exists(params)) << params;
  const std::string params_before = test::slurp(params), ini_before = test::slurp(written.ini);

  io::HexapodMachine cal = io::loadHexapodMachine("hexapod-default");
  cal.model.struts[2].world_p_base.y() += 0.75;
  cal.model.struts[4].length_offset = 3.25;
  io::writeFileAtomic(dir / "cal.json", io::writeHexapodJson(cal), io::Overwrite::kAllow);
  LinuxcncInstallRequest r{(dir / "cal.json").string(), written.ini, false};
  const LinuxcncInstallResult preview = installIntoLinuxcnc(r);
  EXPECT_EQ(preview.kinematics, "pkmhexkins");
  ASSERT_EQ(preview.patches.size(), 1u);
  ASSERT_EQ(preview.patches[0].changes.size(), 2u);
  EXPECT_EQ(preview.patches[0].changes[0].key, "base.2");
  EXPECT_EQ(preview.patches[0].changes[1].key, "length-offset.4");
  EXPECT_EQ(preview.patches[0].changes[1].after, "3.25");
  EXPECT_EQ(test::slurp(params), params_before);

  r.force = true;
  const LinuxcncInstallResult done = installIntoLinuxcnc(r);
  EXPECT_TRUE(done.written);
  EXPECT_EQ(done.backups, std::vector<std::string>{params + ".pkm-backup"});
  EXPECT_EQ(test::slurp(params + ".pkm-backup"), params_before);
  EXPECT_EQ(test::slurp(written.ini), ini_before);  // the joints are the encoders' readings
  const io::LinuxcncHexapod back = io::readLinuxcncHexapod(written.ini);
  EXPECT_EQ(back.machine.model.struts[2].world_p_base, cal.model.struts[2].world_p_base);
  EXPECT_EQ(back.machine.model.struts[4].length_offset, 3.25);
  fs::remove_all(dir);
}

TEST(LinuxcncInstall, RefusesWhatItCannotInstall) {
  EXPECT_THROW((void)installIntoLinuxcnc({"", "x.ini", false}), InvalidArgument);
  EXPECT_THROW((void)installIntoLinuxcnc({"mxt700s-like", "x.ini", false}), InvalidArgument);
  const fs::path dir = test::scratchPath("linuxcnc_install", "bad");
  fs::create_directories(dir);
  io::writeFileAtomic(dir / "m.ini", "[HAL]\nHALFILE = nothing.hal\n", io::Overwrite::kAllow);
  try {
    (void)installIntoLinuxcnc({"hexapod-linuxcnc-sim", (dir / "m.ini").string(), false});
    FAIL() << "installed into a configuration without genhexkins";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("none of the files its [HAL] HALFILE lines load"));
  }
  fs::remove_all(dir);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
