// `pkm linuxcnc install`: the differences shown and nothing written without --force (exit 2),
// the files patched with --force (exit 0), on a copy of LinuxCNC's hexapod-sim configuration.
#include <filesystem>
#include <string>

#include "support/cli_fixture.hpp"
#include "support/linuxcnc_sample.hpp"

namespace pkm::test {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST_F(CliTest, LinuxcncInstallShowsThenPatches) {
  const fs::path sample = pkm::test::linuxcncHexapodSim();
  if (!fs::is_directory(sample))
    GTEST_SKIP() << sample << " not found (run scripts/fetch-linuxcnc.sh)";
  fs::copy(sample, path("cfg"), fs::copy_options::recursive);
  // A calibration of the sim hexapod: its machine file with one joint moved.
  std::string cal = slurp(fs::path(PKM_SOURCE_DIR) / "data/machines/hexapod-linuxcnc-sim.json");
  cal.replace(cal.find("\"base\": [-22.95, 13.25, 0]"), 26, "\"base\": [-22.95, 13.3, 0]");
  const std::string cal_path = write("cal.json", cal);
  const std::vector<std::string> args{
      "linuxcnc", "install", "--calibration", cal_path, "--ini", path("cfg/hexapod.ini")};
  const CliRun preview = pkm(args);
  EXPECT_EQ(preview.code, 2);
  EXPECT_THAT(preview.out,
              HasSubstr("-setp genhexkins.base.0.y  13.250\n+setp genhexkins.base.0.y  13.3\n"));
  EXPECT_THAT(preview.err, HasSubstr("nothing written"));
  EXPECT_FALSE(fs::exists(path("cfg/kinematics.hal.pkm-backup")));
  std::vector<std::string> forced = args;
  forced.push_back("--force");
  const CliRun done = pkm(forced);
  EXPECT_EQ(done.code, 0) << done.err;
  EXPECT_THAT(done.out, HasSubstr("backups: "));
  EXPECT_THAT(slurp(path("cfg/kinematics.hal")), HasSubstr("setp genhexkins.base.0.y  13.3\n"));
  EXPECT_EQ(pkm(args).code, 0);  // nothing left to change
}

}  // namespace
}  // namespace pkm::test
