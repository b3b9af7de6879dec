// Canned-cycle expansions against the motion sequences rs274 prints for the same blocks.
#include "pkm/cnc/canned_cycle.hpp"

#include <gtest/gtest.h>

#include "pkm/cnc/gcode_error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

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

std::vector<CycleStep> motions(const std::vector<CycleStep>& steps) {
  std::vector<CycleStep> out;
  for (const CycleStep& s : steps)
    if (s.kind == K::kRapid || s.kind == K::kFeed) out.push_back(s);
  return out;
}

TEST(CannedCycle, G84ReversesTheSpindleAndFeedsOutToTheClearLevel) {
  // rs274 (G98, IL 20): rapid (10,10,20), (10,10,2), overrides off, feed (10,10,-5), STOP, CCW,
  // DWELL(0.2), feed (10,10,20), STOP, CW, overrides on.
  CycleRequest q;
  q.code = 84;
  q.current = {0, 0, 20};
  q.initial_level = 20;
  q.retract_to_r = false;
  q.has_x = q.has_y = true;
  q.x = q.y = 10;
  q.r = 2;
  q.z = -5;
  q.p = 0.2;
  std::vector<CycleStep> s;
  const auto end = expandCycle(q, s);
  ASSERT_EQ(s.size(), 11u);
  EXPECT_EQ(s[2].action, CycleAction::kOverridesOff);
  expectStep(s[3], K::kFeed, 10, 10, -5);
  EXPECT_EQ(s[4].action, CycleAction::kSpindleStop);
  EXPECT_EQ(s[5].action, CycleAction::kSpindleCounterClockwise);
  EXPECT_EQ(s[6].kind, K::kDwell);
  EXPECT_EQ(s[6].seconds, 0.2);
  expectStep(s[7], K::kFeed, 10, 10, 20);
  EXPECT_EQ(s[9].kind, K::kAction);
  EXPECT_EQ(s[9].action, CycleAction::kSpindleClockwise);
  EXPECT_EQ(s[10].action, CycleAction::kOverridesOn);
  EXPECT_EQ(end[2], 20.0);
  // G74 is the mirror image: it needs M4 and reverses to clockwise. Overrides that were off
  // (M49) stay off.
  q.code = 74;
  q.spindle = SpindleDirection::kCounterClockwise;
  q.overrides_enabled = false;
  s.clear();
  expandCycle(q, s);
  ASSERT_EQ(s.size(), 10u);
  EXPECT_EQ(s[5].action, CycleAction::kSpindleClockwise);
  EXPECT_EQ(s[9].action, CycleAction::kSpindleCounterClockwise);
}

TEST(CannedCycle, G86StopsTheSpindleAndRapidsOut) {
  CycleRequest q;
  q.code = 86;
  q.current = {0, 0, 5};
  q.initial_level = 5;
  q.r = 2;
  q.z = -3;
  q.p = 0.5;
  q.spindle = SpindleDirection::kCounterClockwise;
  std::vector<CycleStep> s;
  expandCycle(q, s);
  // rapid (0,0,5), rapid (0,0,2), feed (0,0,-3), DWELL, STOP, rapid (0,0,2), restart M4.
  ASSERT_EQ(s.size(), 7u);
  expectStep(s[2], K::kFeed, 0, 0, -3);
  EXPECT_EQ(s[3].kind, K::kDwell);
  EXPECT_EQ(s[4].action, CycleAction::kSpindleStop);
  expectStep(s[5], K::kRapid, 0, 0, 2);
  EXPECT_EQ(s[6].action, CycleAction::kSpindleCounterClockwise);
}

TEST(CannedCycle, G87BackBoresFromBelow) {
  // The rs274 sequence of "G91 G87 X10 Y10 Z-5 R-18 I1 J2 K3" from (0,0,20), G99: R = 2,
  // bottom = -3, K = bottom + 3 = 0.
  CycleRequest q;
  q.code = 87;
  q.current = {0, 0, 20};
  q.initial_level = 20;
  q.incremental = true;
  q.has_x = q.has_y = true;
  q.x = q.y = 10;
  q.r = -18;
  q.z = -5;
  q.i = 1;
  q.j = 2;
  q.k = 3;
  std::vector<CycleStep> s;
  const auto end = expandCycle(q, s);
  const auto m = motions(s);
  const std::vector<std::array<double, 4>> want{{0, 10, 10, 20},
                                                {0, 10, 10, 2},
                                                {0, 11, 12, 2},
                                                {0, 11, 12, -3},
                                                {0, 10, 10, -3},
                                                {1, 10, 10, 0},
                                                {1, 10, 10, -3},
                                                {0, 11, 12, -3},
                                                {0, 11, 12, 2},
                                                {0, 10, 10, 2}};
  ASSERT_EQ(m.size(), want.size());
  for (std::size_t k = 0; k < want.size(); ++k)
    expectStep(m[k], want[k][0] == 0 ? K::kRapid : K::kFeed, want[k][1], want[k][2], want[k][3]);
  EXPECT_EQ(end[2], 2.0);
  std::size_t orients = 0;
  for (const CycleStep& c : s) orients += c.action == CycleAction::kSpindleOrient ? 1 : 0;
  EXPECT_EQ(orients, 2u);  // oriented before going down through the hole and before leaving
}

TEST(CannedCycle, G88LeavesTheRetractionToTheOperator) {
  CycleRequest q;
  q.code = 88;
  q.current = {0, 0, 30};
  q.initial_level = 30;
  q.has_x = q.has_y = true;
  q.x = q.y = 5;
  q.r = 2;
  q.z = -1;
  q.p = 1;
  q.repeats = 2;
  std::vector<CycleStep> s;
  const auto end = expandCycle(q, s);
  // rs274: (5,5,30) (5,5,2) feed (5,5,-1) DWELL STOP PROGRAM_STOP, then the second repeat
  // rapids to (5,5,2) as if the tool were there, feeds again; the program goes on from R.
  const auto m = motions(s);
  ASSERT_EQ(m.size(), 5u);
  expectStep(m[1], K::kRapid, 5, 5, 2);
  expectStep(m[2], K::kFeed, 5, 5, -1);
  expectStep(m[3], K::kRapid, 5, 5, 2);
  expectStep(m[4], K::kFeed, 5, 5, -1);
  std::size_t manual = 0;
  for (const CycleStep& c : s)
    if (c.kind == K::kManual) {
      ++manual;
      expectStep(c, K::kManual, 5, 5, 2);
    }
  EXPECT_EQ(manual, 2u);
  EXPECT_EQ(end[2], 2.0);
}

TEST(CannedCycle, SpindleMustTurnTheWayTheCycleNeeds) {
  CycleRequest q;
  q.r = 2;
  q.z = -3;
  std::vector<CycleStep> s;
  for (int code : {74, 84, 86, 87, 88}) {
    q.code = code;
    q.spindle = SpindleDirection::kStopped;
    EXPECT_THROW(expandCycle(q, s), GcodeError) << code;
  }
  q.code = 84;
  q.spindle = SpindleDirection::kCounterClockwise;
  EXPECT_THROW(expandCycle(q, s), GcodeError);
  q.code = 74;
  q.spindle = SpindleDirection::kClockwise;
  EXPECT_THROW(expandCycle(q, s), GcodeError);
  q.code = 81;
  q.spindle = SpindleDirection::kStopped;  // a drilling cycle does not look at the spindle
  EXPECT_NO_THROW(expandCycle(q, s));
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

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
