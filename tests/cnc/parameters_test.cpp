// Parameter store: layout, scopes of named parameters, subroutine arguments.
#include "pkm/cnc/parameters.hpp"

#include <gtest/gtest.h>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

TEST(Parameters, LinuxcncLayout) {
  EXPECT_EQ(coordinateSystemBase(1), 5221);
  EXPECT_EQ(coordinateSystemBase(2), 5241);
  EXPECT_EQ(coordinateSystemBase(9), 5381);
  EXPECT_TRUE(isLengthParameter(5221));
  EXPECT_TRUE(isLengthParameter(5223));
  EXPECT_FALSE(isLengthParameter(5224));  // A
  EXPECT_FALSE(isLengthParameter(5230));  // R rotation
  EXPECT_TRUE(isLengthParameter(5211));
  EXPECT_FALSE(isLengthParameter(5220));
  EXPECT_FALSE(isLengthParameter(100));
  Parameters p;
  EXPECT_EQ(p.get(kActiveSystemParam), 1.0);
}

TEST(Parameters, NamedScopes) {
  Parameters p;
  p.setNamed("local", 1.0);
  p.setNamed("_global", 2.0);
  p.pushCall({});
  EXPECT_FALSE(p.exists("local"));  // locals of the caller are invisible (checked with rs274)
  EXPECT_TRUE(p.exists("_global"));
  EXPECT_THROW((void)p.named("local"), GcodeError);
  p.setNamed("local", 5.0);
  p.popCall();
  EXPECT_EQ(p.named("local"), 1.0);
}

TEST(Parameters, CallArgumentsAreLocal) {
  Parameters p;
  p.set(1, 9.0);
  p.set(31, 4.0);
  p.pushCall({7.0, 8.0});
  EXPECT_EQ(p.get(1), 7.0);
  EXPECT_EQ(p.get(2), 8.0);
  EXPECT_EQ(p.get(3), 0.0);
  EXPECT_EQ(p.callDepth(), 1u);
  p.set(31, 5.0);  // #31 and up are global
  p.popCall();
  EXPECT_EQ(p.get(1), 9.0);
  EXPECT_EQ(p.get(31), 5.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
