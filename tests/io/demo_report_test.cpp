// io::hexapodDemoText / exechonDemoText: the lines of `pkm demo` from a report built by hand.
#include "pkm/io/demo_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;
using ::testing::StartsWith;

TEST(DemoReport, HexapodText) {
  HexapodDemoReport r;
  r.description = "machine      m (builtin:m)\n";
  r.points = 4;
  r.radius = 60.0;
  r.tilt = degToRad(10.0);
  r.statuses = {{"ok", 3}, {"stroke", 1}};
  r.iterations = {{3, 1}, {2, 3}};
  r.converged = 4;
  r.seconds = 4e-6;
  r.pass = true;
  const std::string t = hexapodDemoText(r);
  EXPECT_THAT(t,
              StartsWith("machine      m (builtin:m)\n\npath         4 poses: circle of radius 60 "
                         "mm with z wave, tilt up to 20 deg\n\nsummary\n"));
  EXPECT_THAT(t, HasSubstr("  IK + checks  status counts: ok 3 stroke 1\n"));
  EXPECT_THAT(t, HasSubstr("  FK (servo)   4 of 4 converged; iterations: 3x2 1x3\n"));
  EXPECT_THAT(t, HasSubstr("  speed        1.00 us per forward solve (4 solves in 0.000 s)\n"));
  EXPECT_THAT(t, HasSubstr("  result       PASS: FK(IK(pose)) returns every pose\n"));
}

TEST(DemoReport, ExechonTextLeavesOutThePathWhenItWasNotSolved) {
  ExechonDemoReport r;
  r.machine = "mxt";
  r.source = "builtin:mxt";
  r.x2_max = 4000.0;
  r.y2_max = 450.0;
  r.drm_status = "unreachable";
  const std::string t = exechonDemoText(r);
  EXPECT_THAT(t,
              StartsWith("\nExechon       mxt (builtin:mxt): tripod with C/A wrist on X2 0..4000 "
                         "mm and Y2 0..450 mm\n"));
  EXPECT_EQ(t.find("tool path"), std::string::npos);
  EXPECT_THAT(t, HasSubstr("  DRM          circle failed: unreachable\n"));
  EXPECT_THAT(t, HasSubstr("  result       FAIL\n"));
  r.path_solved = true;
  r.drm_status = "ok";
  EXPECT_THAT(exechonDemoText(r), HasSubstr("  tool path    0 poses"));
  EXPECT_THAT(exechonDemoText(r), HasSubstr("  DRM          40 mm ring"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
