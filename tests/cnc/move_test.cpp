// The moves CSV row format.
#include "pkm/cnc/move.hpp"

#include <gtest/gtest.h>

namespace pkm::cnc {
namespace {

TEST(Move, CsvRowOfARapidLeavesCentreAndFeedEmpty) {
  Move m;
  m.line = 12;
  m.end = {1.5, -2, 0, 0, 90, -0.0};
  std::string s;
  appendMoveCsv(s, m);
  EXPECT_EQ(s, "12,rapid,1.5,-2,0,0,90,0,,,,0,XY,\n");
}

TEST(Move, CsvRowOfAnArc) {
  Move m;
  m.line = 3;
  m.kind = MoveKind::kArc;
  m.end = {10, 0, -1, 0, 0, 0};
  m.centre = {5, std::numeric_limits<double>::quiet_NaN(), 0.1};
  m.turns = -2;
  m.plane = Plane::kXZ;
  m.feed = 250;
  std::string s;
  appendMoveCsv(s, m);
  EXPECT_EQ(s, "3,arc,10,0,-1,0,0,0,5,,0.1,-2,XZ,250\n");
  EXPECT_STREQ(kMoveCsvHeader, "line,kind,x,y,z,a,b,c,cx,cy,cz,turns,plane,feed");
  EXPECT_STREQ(toString(MoveKind::kLinear), "linear");
  EXPECT_STREQ(toString(Plane::kYZ), "YZ");
}

}  // namespace
}  // namespace pkm::cnc
