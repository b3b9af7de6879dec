// LinuxCNC COMP_FILE writer, reader and runtime model: exact text, the documented examples and the
// sample configuration's screwcompX.dat, limits (256 rows, increasing nominal, finite values),
// FILE:LINE errors, and the interpolation / end-hold / direction semantics of control.c.
#include "pkm/compensation/linuxcnc_comp.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace comp = pkm::compensation;
using pkm::test::kTolExact;
using ::testing::HasSubstr;

/// Errors x̄↑, x̄↓ of an axis that overshoots: +5 µm / +2 µm at 0, +3 µm / −1 µm at 100.
comp::AxisErrorTable smallTable() {
  return {"X", {0.0, 100.0, 250.0}, {0.005, 0.003, -0.002}, {0.002, -0.001, -0.004}};
}

std::string expectIoError(const std::string& text, int type) {
  try {
    (void)comp::parseLinuxcncComp(text, "xcomp.txt", type);
  } catch (const pkm::IoError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no IoError for:\n" << text;
  return {};
}

TEST(LinuxcncComp, Type1ExactText) {
  const auto f = comp::linuxcncCompFromTable(smallTable(), 1);
  EXPECT_EQ(comp::writeLinuxcncComp(f),
            "0 -0.005 -0.002\n"
            "100 -0.003 0.001\n"
            "250 0.002 0.004\n");
}

TEST(LinuxcncComp, Type0ExactText) {
  const auto f = comp::linuxcncCompFromTable(smallTable(), 0);
  EXPECT_EQ(comp::writeLinuxcncComp(f),
            "0 0.005 0.002\n"
            "100 100.003 99.999\n"
            "250 249.998 249.996\n");
}

TEST(LinuxcncComp, WriteParseRoundTripIsExact) {
  comp::AxisErrorTable t{"X", {}, {}, {}};
  for (int i = 0; i < 256; ++i) {
    t.nominal.push_back(-100.0 + 0.7 * i);
    t.error_up.push_back(1e-3 * std::sin(0.1 * i));
    t.error_down.push_back(-1e-5 * i);
  }
  for (int type : {0, 1}) {
    const auto f = comp::linuxcncCompFromTable(t, type);
    const auto g = comp::parseLinuxcncComp(comp::writeLinuxcncComp(f), "rt", type);
    EXPECT_EQ(g.nominal, f.nominal);
    EXPECT_EQ(g.forward, f.forward);
    EXPECT_EQ(g.reverse, f.reverse);
  }
}

TEST(LinuxcncComp, DocumentedExamples) {
  // LinuxCNC docs/src/config/ini-config.adoc: type 1 trims and type 0 actual positions.
  const auto t1 = comp::parseLinuxcncComp(
      "-1.000 0.005 -0.005\n0.000 0.002 -0.003\n1.000 0.003 -0.004\n", "type1.txt", 1);
  EXPECT_NEAR(comp::applyLinuxcncComp(t1, 0.0, 1), 0.002, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(t1, 0.5, -1), 0.5 - 0.0035, kTolExact);
  const auto t0 = comp::parseLinuxcncComp(
      "-1.000 -1.005 -0.995\n0.000 0.002 -0.003\n1.000 1.003 0.998\n", "type0.txt", 0);
  // Commanded to 1 while moving +, the axis reaches 1.003: the motor is sent 0.003 less.
  EXPECT_NEAR(comp::applyLinuxcncComp(t0, 1.0, 1), 1.0 - 0.003, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(t0, -1.0, -1), -1.0 - 0.005, kTolExact);
}

TEST(LinuxcncComp, ReadsLinuxcncSampleConfig) {
  const std::filesystem::path sample = std::filesystem::path(PKM_SOURCE_DIR) /
                                       ".cache/linuxcnc/usr/share/doc/linuxcnc/examples/"
                                       "sample-configs/sim/screwcompX.dat";
  if (!std::filesystem::exists(sample)) GTEST_SKIP() << "LinuxCNC package not unpacked";
  const auto f = comp::readLinuxcncComp(sample.string(), 0);  // servo_sim.ini: COMP_FILE_TYPE = 0
  ASSERT_EQ(f.nominal.size(), 11U);
  EXPECT_EQ(f.nominal.front(), -10.0);
  EXPECT_EQ(f.nominal.back(), 10.0);
  // Row "0 -0.003 0.002": moving + the axis falls 3 µm short, so the trim is +0.003.
  EXPECT_NEAR(comp::applyLinuxcncComp(f, 0.0, 1), 0.003, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(f, 0.0, -1), -0.002, kTolExact);
}

TEST(LinuxcncComp, ApplyInterpolatesHoldsEndsAndFollowsDirection) {
  const auto f = comp::linuxcncCompFromTable(smallTable(), 1);
  EXPECT_NEAR(comp::applyLinuxcncComp(f, 50.0, 1), 50.0 - 0.004, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(f, 50.0, -1), 50.0 - 0.0005, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(f, 175.0, 1), 175.0 - 0.0005, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(f, -20.0, 1), -20.0 - 0.005, kTolExact);
  EXPECT_NEAR(comp::applyLinuxcncComp(f, 400.0, -1), 400.0 + 0.004, kTolExact);
  // At a node the trim is the node's (exactly: commanded − error).
  EXPECT_EQ(comp::applyLinuxcncComp(f, 100.0, 1), 100.0 - 0.003);
  EXPECT_THROW((void)comp::applyLinuxcncComp(f, 1.0, 0), pkm::InvalidArgument);
  EXPECT_THROW((void)comp::applyLinuxcncComp(f, std::numeric_limits<double>::infinity(), 1),
               pkm::InvalidArgument);
}

TEST(LinuxcncComp, WriterLimits) {
  comp::AxisErrorTable t{"X", {}, {}, {}};
  for (int i = 0; i < 257; ++i) {
    t.nominal.push_back(i);
    t.error_up.push_back(0.0);
    t.error_down.push_back(0.0);
  }
  EXPECT_THROW((void)comp::linuxcncCompFromTable(t, 1), pkm::InvalidArgument);  // 257 rows
  EXPECT_THROW((void)comp::linuxcncCompFromTable(smallTable(), 2), pkm::InvalidArgument);
  comp::AxisErrorTable bad = smallTable();
  bad.nominal[1] = 0.0;
  EXPECT_THROW((void)comp::linuxcncCompFromTable(bad, 1), pkm::InvalidArgument);
  bad = smallTable();
  bad.error_up[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW((void)comp::linuxcncCompFromTable(bad, 0), pkm::InvalidArgument);
}

TEST(LinuxcncComp, ReaderErrorsNameFileAndLine) {
  EXPECT_THAT(expectIoError("0 0 0\n1 0\n", 1), HasSubstr("xcomp.txt:2:"));
  EXPECT_THAT(expectIoError("# header\n0 0 0\n", 1), HasSubstr("xcomp.txt:1:"));
  EXPECT_THAT(expectIoError("0 0 0\n1 0 0 0\n", 1), HasSubstr("xcomp.txt:2:"));
  EXPECT_THAT(expectIoError("0 0 0\n0 0 0\n", 1), HasSubstr("xcomp.txt:2: nominal 0 does not"));
  EXPECT_THAT(expectIoError("0 0 0\n1 nan 0\n", 0), HasSubstr("xcomp.txt:2:"));
  EXPECT_THAT(expectIoError("0 0 0\n\n1 0 0\n", 1), HasSubstr("xcomp.txt:2: blank line"));
  EXPECT_THAT(expectIoError("", 1), HasSubstr("xcomp.txt: no compensation rows"));
  std::string many;
  for (int i = 0; i < 257; ++i) many += std::to_string(i) + " 0 0\n";
  EXPECT_THAT(expectIoError(many, 1), HasSubstr("xcomp.txt:257: more than 256 rows"));
  // Trailing blank lines and CRLF are fine.
  EXPECT_EQ(comp::parseLinuxcncComp("0 0 0\r\n1 0 0\r\n\n", "ok", 1).nominal.size(), 2U);
  EXPECT_THROW((void)comp::readLinuxcncComp("/nonexistent/xcomp.txt", 1), pkm::IoError);
}

}  // namespace PKM_TEST_NS
