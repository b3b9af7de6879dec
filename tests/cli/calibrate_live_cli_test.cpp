// `pkm calibrate hexapod --live`: its options are checked before LinuxCNC is asked anything
// (exit 2, the option named, nothing written); the routine itself runs in
// tests/linuxcnc/live_calibration_test.py.
#include <gtest/gtest.h>

#include <filesystem>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

TEST_F(CliTest, CalibrateLiveOptionsAreCheckedBeforeLinuxcncIsAsked) {
  const std::string data = write("poses.csv", "l0,l1,l2,l3,l4,l5,x,y,z,a,b,c\n");
  expectUsageError(pkm({"calibrate", "hexapod", "--out", path("x.json")}),
                   "--data is required (or --live)");
  expectUsageError(pkm({"calibrate", "hexapod", "--live", "--out", path("run")}),
                   "--live needs --ini");
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--live",
                        "--ini",
                        "cfg.ini",
                        "--data",
                        data,
                        "--out",
                        path("run")}),
                   "--live measures its own data");
  expectUsageError(
      pkm({"calibrate", "hexapod", "--live", "--ini", "cfg.ini", "--out", path("run")}),
      "--gauges: give the three gauges' HAL pins");
  expectUsageError(pkm({"calibrate",
                        "hexapod",
                        "--live",
                        "--ini",
                        "cfg.ini",
                        "--gauges",
                        "a,b,c",
                        "--out",
                        path("run"),
                        "--stations",
                        "0"}),
                   "stations: the count must be >= 1");
  EXPECT_FALSE(std::filesystem::exists(path("run")));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
