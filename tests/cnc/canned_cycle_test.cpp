// Canned-cycle expansions against the motion sequences rs274 prints for the same blocks.
#include "pkm/cnc/canned_cycle.hpp"

#include <gtest/gtest.h>

#include "pkm/cnc/gcode_error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace {

using K = CycleStep::Kind;
using pkm::test::kTolRoundTrip;

void expectStep(const CycleStep& s, K kind, double x, double y, double z) {
  EXPECT_EQ(s.kind, kind);
  EXPECT_NEAR(s.to[0], x, kTolRoundTrip);
  EXPECT_NEAR(s.to[1], y, kTolRoundTrip);
  EXPECT_NEAR(s.to[2], z, kTolRoundTrip);
}

TEST(CannedCycle, G81FromBelowRRisesFirst) {
  // rs274: G0 X7 Z0 then G81 X1 Y1 Z-3 R2 -> (7,0,2) (1,1,2) feed (1,1,-3) (1,1,2).
  CycleRequest q;
  q.code = 81;
  q.current = {7, 0, 0};
  q.initial_level = 0;
  q.has_x = q.has_y = true;
  q.x = q.y = 1;
  q.r = 2;
  q.z = -3;
  std::vector<CycleStep> s;
  const auto end = expandCycle(q, s);
  ASSERT_EQ(s.size(), 4u);
  expectStep(s[0], K::kRapid, 7, 0, 2);
  expectStep(s[1], K::kRapid, 1, 1, 2);
  expectStep(s[2], K::kFeed, 1, 1, -3);
  expectStep(s[3], K::kRapid, 1, 1, 2);
  EXPECT_EQ(end[2], 2.0);
}

TEST(CannedCycle, G98ReturnsToTheInitialLevel) {
  CycleRequest q;
  q.code = 81;
  q.current = {0, 0, 10};
  q.initial_level = 10;
  q.retract_to_r = false;
  q.has_x = true;
  q.x = 1;
  q.r = 2;
  q.z = -3;
  std::vector<CycleStep> s;
  expandCycle(q, s);
  ASSERT_EQ(s.size(), 4u);
  expectStep(s[0], K::kRapid, 1, 0, 10);
  expectStep(s[1], K::kRapid, 1, 0, 2);
  expectStep(s[3], K::kRapid, 1, 0, 10);
}

TEST(CannedCycle, IncrementalRepeats) {
  // rs274: G0 Z10, G91 G81 X1 Y1 Z-3 R-4 L2: R plane 6, bottom 3, holes at (1,1), (2,2).
  CycleRequest q;
  q.code = 81;
  q.current = {0, 0, 10};
  q.initial_level = 10;
  q.incremental = true;
  q.has_x = q.has_y = true;
  q.x = q.y = 1;
  q.r = -4;
  q.z = -3;
  q.repeats = 2;
  std::vector<CycleStep> s;
  expandCycle(q, s);
  ASSERT_EQ(s.size(), 7u);
  expectStep(s[0], K::kRapid, 1, 1, 10);
  expectStep(s[1], K::kRapid, 1, 1, 6);
  expectStep(s[2], K::kFeed, 1, 1, 3);
  expectStep(s[3], K::kRapid, 1, 1, 6);
  expectStep(s[4], K::kRapid, 2, 2, 6);  // already at R: no second rapid down
  expectStep(s[5], K::kFeed, 2, 2, 3);
}

TEST(CannedCycle, G83PecksBackToR) {
  // rs274: G83 X1 Y1 Z-3 R2 Q1.2 at R: feeds to 0.8, -0.4, -1.6, -2.8, -3 with rapids to R and
  // back down to 0.254 mm above the last depth.
  CycleRequest q;
  q.code = 83;
  q.current = {1, 1, 2};
  q.initial_level = 2;
  q.has_x = q.has_y = true;
  q.x = q.y = 1;
  q.r = 2;
  q.z = -3;
  q.q = 1.2;
  std::vector<CycleStep> s;
  expandCycle(q, s);
  ASSERT_EQ(s.size(), 15u);
  expectStep(s[1], K::kFeed, 1, 1, 0.8);
  expectStep(s[2], K::kRapid, 1, 1, 2);
  expectStep(s[3], K::kRapid, 1, 1, 1.054);
  expectStep(s[4], K::kFeed, 1, 1, -0.4);
  expectStep(s[13], K::kFeed, 1, 1, -3);
  expectStep(s[14], K::kRapid, 1, 1, 2);
}

TEST(CannedCycle, G73ChipBreak) {
  CycleRequest q;
  q.code = 73;
  q.current = {1, 1, 2};
  q.initial_level = 2;
  q.r = 2;
  q.z = -3;
  q.q = 1.2;
  std::vector<CycleStep> s;
  expandCycle(q, s);
  ASSERT_EQ(s.size(), 11u);
  expectStep(s[2], K::kRapid, 1, 1, 1.054);
  expectStep(s[3], K::kFeed, 1, 1, -0.4);
}

TEST(CannedCycle, DwellAndFeedOut) {
  CycleRequest q;
  q.code = 89;
  q.current = {0, 0, 5};
  q.initial_level = 5;
  q.retract_to_r = false;
  q.r = 2;
  q.z = -3;
  q.p = 0.5;
  std::vector<CycleStep> s;
  expandCycle(q, s);
  // rs274: rapid (0,0,5), rapid (0,0,2), feed (0,0,-3), DWELL(0.5), feed out to (0,0,5).
  ASSERT_EQ(s.size(), 5u);
  expectStep(s[1], K::kRapid, 0, 0, 2);
  EXPECT_EQ(s[3].kind, K::kDwell);
  EXPECT_EQ(s[3].seconds, 0.5);
  expectStep(s[4], K::kFeed, 0, 0, 5);
}

TEST(CannedCycle, Errors) {
  CycleRequest q;
  q.code = 81;
  q.r = -5;
  q.z = -3;
  std::vector<CycleStep> s;
  EXPECT_THROW(expandCycle(q, s), GcodeError);  // R below bottom
  q.code = 83;
  q.r = 2;
  q.q = 0;
  EXPECT_THROW(expandCycle(q, s), GcodeError);  // Q <= 0
  q.q = 1e-9;
  EXPECT_THROW(expandCycle(q, s), GcodeError);  // runaway pecking
  q.code = 81;
  q.repeats = 1'000'000'000;
  EXPECT_THROW(expandCycle(q, s), GcodeError);  // runaway repeats
}

}  // namespace
}  // namespace pkm::cnc
