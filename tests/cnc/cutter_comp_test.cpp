// CutterComp checked by geometry, independently of LinuxCNC (rs274_compare_test compares it with
// rs274 move by move): every compensated point lies one tool radius from the programmed path, a
// convex corner gets an arc of the tool radius about the corner, concave corners end where the
// offset paths meet, and the errors LinuxCNC gives.
#include "pkm/cnc/cutter_comp.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

constexpr double kTol = 1e-9;  // mm: closed-form points, exact arithmetic up to rounding
constexpr double kR = 2.0;     // tool radius, mm
constexpr double kFeed = 600.0;

struct Recorder : MoveSink {
  std::vector<Move> moves;
  std::vector<int> order;  // 0 move, 1 dwell, 2 message
  void onMove(const Move& m) override {
    moves.push_back(m);
    order.push_back(0);
  }
  void onDwell(std::size_t, double) override { order.push_back(1); }
  void onMessage(std::size_t, CommentKind, const std::string&) override { order.push_back(2); }
};

Axes at(double x, double y, double z = 0.0) { return Axes{x, y, z, 0.0, 0.0, 0.0}; }

/// Runs programmed straight moves through the points `pts` (XY) with compensation on `side`,
/// then G40.
Recorder runLines(CompSide side, const std::vector<Axes>& pts, double radius = kR) {
  Recorder rec;
  CutterComp comp;
  comp.start(side, radius, Plane::kXY);
  for (std::size_t i = 1; i < pts.size(); ++i)
    comp.straight(i, false, pts[i - 1], pts[i], kFeed, rec, false);
  comp.stop(rec, false);
  return rec;
}

double distToLine(const Move& m, double ax, double ay, double bx, double by) {
  const double dx = bx - ax, dy = by - ay;
  return std::abs(dx * (m.end[1] - ay) - dy * (m.end[0] - ax)) / std::hypot(dx, dy);
}

TEST(CutterComp, EntryMoveEndsOneRadiusToTheLeftOfItsEnd) {
  const Recorder rec = runLines(CompSide::kLeft, {at(-10, 0), at(0, 0)});
  ASSERT_EQ(rec.moves.size(), 1u);
  EXPECT_NEAR(rec.moves[0].end[0], 0.0, kTol);
  EXPECT_NEAR(rec.moves[0].end[1], kR, kTol);  // left of +X is +Y
}

TEST(CutterComp, ConvexCornerGetsAnArcAboutTheCorner) {
  // Left of a path turning right: the tool passes outside the corner (10, 0).
  const Recorder rec = runLines(CompSide::kLeft, {at(0, 0), at(10, 0), at(10, -10)});
  ASSERT_EQ(rec.moves.size(), 3u);
  const Move& corner = rec.moves[1];
  EXPECT_EQ(corner.kind, MoveKind::kArc);
  EXPECT_NEAR(corner.centre[0], 10.0, kTol);
  EXPECT_NEAR(corner.centre[1], 0.0, kTol);
  EXPECT_EQ(corner.turns, -1);  // clockwise around the outside
  EXPECT_NEAR(corner.end[0], 10.0 + kR, kTol);
  EXPECT_NEAR(corner.end[1], 0.0, kTol);
  EXPECT_NEAR(rec.moves[2].end[0], 10.0 + kR, kTol);
  EXPECT_NEAR(rec.moves[2].end[1], -10.0, kTol);
}

TEST(CutterComp, ConcaveCornerEndsWhereTheOffsetLinesMeet) {
  // Left of a path turning left by 60 degrees: the meeting point is one radius from both lines.
  const double c = std::cos(M_PI / 3), s = std::sin(M_PI / 3);
  const Recorder rec = runLines(CompSide::kLeft, {at(0, 0), at(10, 0), at(10 + 10 * c, 10 * s)});
  ASSERT_EQ(rec.moves.size(), 2u);
  const Move& corner = rec.moves[0];
  EXPECT_NEAR(distToLine(corner, 0, 0, 10, 0), kR, kTol);
  EXPECT_NEAR(distToLine(corner, 10, 0, 10 + 10 * c, 10 * s), kR, kTol);
  EXPECT_NEAR(corner.end[0], 10.0 - kR * std::tan(M_PI / 6), kTol);  // r·tan(half the turn)
}

TEST(CutterComp, RightSideMirrorsLeftSide) {
  const Recorder left = runLines(CompSide::kLeft, {at(0, 0), at(10, 0), at(10, 10)});
  const Recorder right = runLines(CompSide::kRight, {at(0, 0), at(10, 0), at(10, -10)});
  ASSERT_EQ(left.moves.size(), right.moves.size());
  for (std::size_t i = 0; i < left.moves.size(); ++i) {
    EXPECT_NEAR(left.moves[i].end[0], right.moves[i].end[0], kTol);
    EXPECT_NEAR(left.moves[i].end[1], -right.moves[i].end[1], kTol);
  }
}

TEST(CutterComp, NegativeRadiusSwapsTheSide) {
  const Recorder neg = runLines(CompSide::kLeft, {at(0, 0), at(10, 0)}, -kR);
  const Recorder right = runLines(CompSide::kRight, {at(0, 0), at(10, 0)}, kR);
  ASSERT_EQ(neg.moves.size(), 1u);
  EXPECT_NEAR(neg.moves[0].end[1], right.moves[0].end[1], kTol);
  EXPECT_NEAR(neg.moves[0].end[1], -kR, kTol);
}

/// The tool left of a line from (0, 0) to (20, 0), then along the arc from (20, 0) to (30, 10)
/// about (cx, cy) with `turns` (radius 10), then G40.
Recorder lineThenArc(double cx, double cy, int turns) {
  Recorder rec;
  CutterComp comp;
  comp.start(CompSide::kLeft, kR, Plane::kXY);
  comp.straight(1, false, at(0, 0), at(20, 0), kFeed, rec, false);
  Move arc;
  arc.line = 2;
  arc.kind = MoveKind::kArc;
  arc.end = at(30, 10);
  arc.centre = {cx, cy, NAN};
  arc.turns = turns;
  arc.feed = kFeed;
  comp.arc(arc, at(20, 0), rec, false);
  comp.stop(rec, false);
  return rec;
}

TEST(CutterComp, LineIntoAnArcEndsOnBothOffsets) {
  // A counter-clockwise quarter circle about (20, 10), tangent to the line: no corner; the line
  // ends one radius above the arc's start, and the tool runs inside the arc (radius 10 − r).
  const Recorder rec = lineThenArc(20.0, 10.0, 1);
  ASSERT_EQ(rec.moves.size(), 2u);
  EXPECT_NEAR(rec.moves[0].end[0], 20.0, kTol);
  EXPECT_NEAR(rec.moves[0].end[1], kR, kTol);
  EXPECT_NEAR(std::hypot(rec.moves[1].end[0] - 20.0, rec.moves[1].end[1] - 10.0), 10.0 - kR, kTol);
}

TEST(CutterComp, ConcaveLineToArcMeetsAtOffsetDistances) {
  // A clockwise arc about (30, 0) leaving the line upwards: a left turn, concave for the tool on
  // the left, which runs outside the arc. The meeting point is r from the line and R + r from
  // the centre.
  const Recorder rec = lineThenArc(30.0, 0.0, -1);
  ASSERT_EQ(rec.moves.size(), 2u);
  const Move& meet = rec.moves[0];
  EXPECT_NEAR(meet.end[1], kR, kTol);
  EXPECT_NEAR(std::hypot(meet.end[0] - 30.0, meet.end[1]), 10.0 + kR, kTol);
  EXPECT_LT(meet.end[0], 20.0);  // shortened, not extended
}

TEST(CutterComp, EntryShorterThanTheRadiusIsRefused) {
  Recorder rec;
  CutterComp comp;
  comp.start(CompSide::kLeft, kR, Plane::kXY);
  EXPECT_THROW(comp.straight(1, false, at(0, 0), at(1, 0), kFeed, rec, false), GcodeError);
}

TEST(CutterComp, ReversedShortMoveIsAGougingError) {
  // A slot narrower than the tool: the move between the two concave corners would run backwards.
  Recorder rec;
  CutterComp comp;
  comp.start(CompSide::kLeft, kR, Plane::kXY);
  comp.straight(1, false, at(-10, 0), at(0, 0), kFeed, rec, false);
  comp.straight(2, false, at(0, 0), at(20, 0), kFeed, rec, false);
  comp.straight(3, false, at(20, 0), at(20, 1), kFeed, rec, false);
  EXPECT_THROW(comp.straight(4, false, at(20, 1), at(0, 1), kFeed, rec, false), GcodeError);
}

TEST(CutterComp, DwellWaitsForTheHeldMove) {
  Recorder rec;
  CutterComp comp;
  comp.dwell(1, 0.5, rec);  // nothing held: at once
  comp.start(CompSide::kLeft, kR, Plane::kXY);
  comp.straight(2, false, at(-10, 0), at(0, 0), kFeed, rec, false);
  comp.dwell(3, 0.5, rec);
  comp.message(4, CommentKind::kMsg, "hello", rec);
  comp.straight(5, false, at(0, 0), at(10, 0), kFeed, rec, false);
  comp.stop(rec, false);
  const std::vector<int> expected{1, 0, 1, 2, 0};
  EXPECT_EQ(rec.order, expected);
}

TEST(CutterComp, ArcAfterExitIsForbiddenUntilAStraightMove) {
  Recorder rec;
  CutterComp comp;
  comp.start(CompSide::kRight, kR, Plane::kXY);
  comp.straight(1, false, at(-10, 0), at(0, 0), kFeed, rec, false);
  comp.stop(rec, false);
  EXPECT_TRUE(comp.arcForbidden());
  comp.allowArc();
  EXPECT_FALSE(comp.arcForbidden());
  EXPECT_FALSE(comp.on());
}

TEST(CutterComp, StartRefusesYzAndASecondStart) {
  CutterComp comp;
  EXPECT_THROW(comp.start(CompSide::kLeft, kR, Plane::kYZ), GcodeError);
  comp.start(CompSide::kLeft, kR, Plane::kXZ);
  EXPECT_THROW(comp.start(CompSide::kRight, kR, Plane::kXZ), GcodeError);
}

TEST(CutterComp, ZeroRadiusDoesNotCompensate) {
  CutterComp comp;
  comp.start(CompSide::kLeft, 0.0, Plane::kXY);
  EXPECT_TRUE(comp.on());
  EXPECT_FALSE(comp.compensating());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
