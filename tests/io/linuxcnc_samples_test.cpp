// LinuxCNC's samples as machines: found where they are installed, absent otherwise, and loadable
// as hexapods with their INI.
#include "pkm/io/linuxcnc_samples.hpp"

#include <gtest/gtest.h>

#include "pkm/io/machine_loader.hpp"
#include "support/linuxcnc_sample.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

TEST(LinuxcncSamples, NoneWithoutLinuxcnc) {
  EXPECT_TRUE(installedLinuxcncSamples("/nonexistent/sample-configs").empty());
}

TEST(LinuxcncSamples, TheHexapodSimLoadsWithItsIni) {
  // The copy scripts/fetch-linuxcnc.sh unpacks, laid out as the installed examples.
  const std::filesystem::path sim = test::linuxcncHexapodSim();
  if (!std::filesystem::exists(sim)) GTEST_SKIP() << sim << " absent (scripts/fetch-linuxcnc.sh)";
  const std::filesystem::path root = sim.parent_path().parent_path().parent_path().parent_path();
  const std::vector<LinuxcncSample> s = installedLinuxcncSamples(root);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].name, "linuxcnc-hexapod-sim");
  EXPECT_EQ(s[0].ini.filename(), "hexapod.ini");
  HalReadOptions hal;
  hal.ini_path = s[0].ini.string();
  const HexapodMachine m = loadHexapodMachine(s[0].hal.string(), hal);
  EXPECT_NE(m.source.find("kinematics.hal"), std::string::npos);
  EXPECT_GT(m.model.struts[0].world_p_base.norm(), 0.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
