// io::readIniVelocityLimits: the [TRAJ] and [AXIS_L] velocities of a LinuxCNC INI, the older
// [TRAJ] MAX_VELOCITY as a fallback, bad values named with their line.
#include "pkm/io/ini_velocity_limits.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST(IniVelocityLimits, ReadsTrajAndAxisMaxima) {
  const IniVelocityLimits v = readIniVelocityLimits(
      {"m.ini",
       "[TRAJ]\nMAX_VELOCITY = 5\nMAX_LINEAR_VELOCITY = 10.5\nMAX_ANGULAR_VELOCITY = 6\n"
       "[JOINT_0]\nMAX_VELOCITY = 99\n[AXIS_X]\n# note\nMAX_VELOCITY = 20\n[AXIS_C]\n"
       "MAX_VELOCITY = 30 \n[AXIS_U]\nMAX_VELOCITY = 7\n"});
  EXPECT_TRUE(v.any());
  EXPECT_EQ(v.source, "m.ini");
  EXPECT_EQ(v.linear, 10.5);  // MAX_LINEAR_VELOCITY wins over MAX_VELOCITY
  EXPECT_EQ(v.angular, 6.0);
  EXPECT_EQ(v.axis[0], 20.0);
  EXPECT_TRUE(std::isnan(v.axis[1]));
  EXPECT_EQ(v.axis[5], 30.0);  // joints and U are not Cartesian XYZABC limits
}

TEST(IniVelocityLimits, TheOlderMaxVelocityAndNone) {
  EXPECT_EQ(readIniVelocityLimits({"o.ini", "[TRAJ]\nMAX_VELOCITY = 4\n"}).linear, 4.0);
  EXPECT_FALSE(readIniVelocityLimits({"e.ini", "[EMC]\nMACHINE = x\n"}).any());
}

TEST(IniVelocityLimits, BadValuesNameTheLine) {
  try {
    (void)readIniVelocityLimits({"b.ini", "[TRAJ]\n\n[AXIS_Y]\nMAX_VELOCITY = -2\n"});
    FAIL() << "accepted";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("b.ini:4: [AXIS_Y] MAX_VELOCITY: expected one number > 0"));
  }
  EXPECT_THROW((void)readIniVelocityLimits({"b.ini", "[TRAJ]\nMAX_LINEAR_VELOCITY = 1 2\n"}),
               IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
