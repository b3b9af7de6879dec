// workflow::machineUnit / unitMismatchWarnings: the unit from an INI, a machine file or a built-in
// machine; warnings only for unstated units on an inch machine.
#include "pkm/workflow/machine_unit.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "pkm/core/error.hpp"
#include "support/linuxcnc_sample.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST(MachineUnit, FromTheIniFirstThenTheMachine) {
  EXPECT_EQ(machineUnit("", ""), std::nullopt);
  EXPECT_EQ(machineUnit("hexapod-default", "")->unit, LengthUnit::kMillimetre);
  EXPECT_EQ(machineUnit("hexapod-linuxcnc-sim", "")->unit, LengthUnit::kInch);
  const std::string ini = test::scratchPath("machine_unit", "trivkins.ini").string();
  std::ofstream(ini) << "[EMC]\nMACHINE = mill\n[TRAJ]\nLINEAR_UNITS = inch\n";
  const std::optional<MachineUnit> u = machineUnit("hexapod-default", ini);  // the INI wins
  ASSERT_TRUE(u);
  EXPECT_EQ(u->unit, LengthUnit::kInch);
  EXPECT_EQ(u->source, ini + " [TRAJ] LINEAR_UNITS");
  const std::string none = test::scratchPath("machine_unit", "none.ini").string();
  std::ofstream(none) << "[EMC]\nMACHINE = mill\n";
  EXPECT_THROW((void)machineUnit("", none), IoError);
  EXPECT_THROW((void)machineUnit("no-such-machine.json", ""), IoError);
}

TEST(MachineUnit, TheSampleConfigurationIsInInches) {
  const auto sample = test::linuxcncHexapodSim();
  if (!std::filesystem::is_directory(sample))
    GTEST_SKIP() << sample << " not found (run scripts/fetch-linuxcnc.sh)";
  EXPECT_EQ(machineUnit((sample / "kinematics.hal").string(), "")->unit, LengthUnit::kInch);
  EXPECT_EQ(machineUnit("", (sample / "hexapod.ini").string())->unit, LengthUnit::kInch);
}

TEST(MachineUnit, WarnsOnlyForUnstatedUnitsOnAnInchMachine) {
  const std::vector<std::string> unstated{"a.csv", "b.csv"};
  EXPECT_TRUE(unitMismatchWarnings(unstated, std::nullopt).empty());
  EXPECT_TRUE(unitMismatchWarnings(unstated, MachineUnit{LengthUnit::kMillimetre, "m"}).empty());
  const auto w = unitMismatchWarnings(unstated, MachineUnit{LengthUnit::kInch, "sim.ini"});
  ASSERT_EQ(w.size(), 2u);
  EXPECT_THAT(w[1],
              HasSubstr("b.csv: its header states no length unit, so its positions were "
                        "read as mm, but the machine is in inch (sim.ini)"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
