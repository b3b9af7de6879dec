// The moves CSV row format; the tool changes a MoveCollector receives from the interpreter.
#include "pkm/cnc/move.hpp"

#include <gtest/gtest.h>

#include <array>
#include <charconv>
#include <cmath>
#include <limits>
#include <random>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/program.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

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

TEST(Move, WriteMoveCsvWritesTheRowOfAppendMoveCsvWithinItsBound) {
  Move m;
  m.line = std::numeric_limits<std::size_t>::max();
  m.kind = MoveKind::kLinear;
  m.end = {-std::numeric_limits<double>::max(), -1.2345678901234567e-300, 1e300, -0.1, 1.5, 1e-7};
  m.centre = {-2.2250738585072014e-308, -1.7976931348623157e308, -4.9e-324};
  m.turns = std::numeric_limits<int>::min();
  m.plane = Plane::kYZ;
  m.feed = -1.2345678901234567e-123;
  std::string appended;
  appendMoveCsv(appended, m);
  std::array<char, kMaxMoveCsvRow + 1> buf{};
  const char* end = writeMoveCsv(buf.data(), m);
  EXPECT_EQ(std::string(buf.data(), static_cast<std::size_t>(end - buf.data())), appended);
  EXPECT_LT(appended.size(), kMaxMoveCsvRow);
  EXPECT_EQ(appended.back(), '\n');
}

/// The x field of a rapid to (v, 0, 0).
std::string xField(double v) {
  Move m;
  m.end = {v, 0, 0, 0, 0, 0};
  std::string s;
  appendMoveCsv(s, m);
  const auto a = s.find(',', s.find(',') + 1) + 1;
  return s.substr(a, s.find(',', a) - a);
}

std::string toChars(double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return {buf, r.ptr};
}

/// The fields are std::to_chars' shortest round-trip form: random numbers with 1 to 6 decimals
/// (the fast path) and with full precision, in and around the fast path's range [0.001, 1e9).
TEST(Move, NumbersAreShortestRoundTrip) {
  std::mt19937_64 rng(pkm::test::kSeed);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-5, 10), decimals(1, 6);
  for (int k = 0; k < 200000; ++k) {
    const double scale = std::pow(10.0, exponent(rng));
    double v = mantissa(rng) * scale;
    if (k % 2 == 0) {  // a number with few decimals, as G-code coordinates have
      const double p = std::pow(10.0, decimals(rng));
      v = std::round(v * p) / p;
    }
    if (v == 0.0 || v == std::trunc(v)) continue;  // integers are written as integers
    const std::string f = xField(v);
    ASSERT_EQ(f, toChars(v)) << "value " << toChars(v);
    double back = 0.0;
    std::from_chars(f.data(), f.data() + f.size(), back);
    ASSERT_EQ(back, v);
  }
  EXPECT_EQ(xField(0.001), "0.001");
  EXPECT_EQ(xField(-123456.75), "-123456.75");
  EXPECT_EQ(xField(0.0005), "5e-04");
  EXPECT_EQ(xField(100000.0), "100000");
}

TEST(Move, TheCollectorKeepsToolChangesWithTheMotionsBeforeThem) {
  InterpreterOptions options;
  options.tools = ToolTable::parse("T1 Z50 D6 ;ball\nT2 Z60 D8\n", 1.0, "t.tbl");
  Interpreter interp(options);
  MoveCollector c;
  interp.run(Program::parse("G0 Z10\nT1 M6\nG1 X5 F100\nT2 M6 G0 Z20\nM61 Q0\nM2\n", "t.ngc"), c);
  // The start's tool (none), then each change with the motions made before it.
  ASSERT_EQ(c.tool_changes.size(), 4u);
  EXPECT_EQ(c.tool_changes[0].tool, 0);
  EXPECT_EQ(c.tool_changes[0].after_moves, 0u);
  EXPECT_EQ(c.tool_changes[1].tool, 1);
  EXPECT_EQ(c.tool_changes[1].line, 2u);
  EXPECT_EQ(c.tool_changes[1].after_moves, 1u);
  EXPECT_EQ(c.tool_changes[2].tool, 2);
  EXPECT_EQ(c.tool_changes[2].after_moves, 2u);  // before its own block's G0 Z20
  EXPECT_EQ(c.tool_changes[3].tool, 0);
  EXPECT_EQ(c.tool_changes[3].line, 5u);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
