// LinuxCNC tool table lines, units, errors.
#include "pkm/cnc/tool_table.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using pkm::test::kTolExact;

TEST(ToolTable, ReadsLinuxcncLines) {
  const ToolTable t = ToolTable::parse(
      "T1 P1 D0.125000 Z+0.511000 ;1/8 end mill\n\nT99999 P123     Z+0.100000 ;big\n"
      "t2 p2 x1 z-2 a5\n",
      25.4,
      "t.tbl");
  ASSERT_EQ(t.tools.size(), 3u);
  EXPECT_NEAR(t.find(1)->offset[2], 0.511 * 25.4, kTolExact);
  EXPECT_NEAR(t.find(1)->diameter, 0.125 * 25.4, kTolExact);
  EXPECT_NEAR(t.find(99999)->offset[2], 2.54, kTolExact);
  EXPECT_EQ(t.find(99999)->pocket, 123);
  EXPECT_NEAR(t.find(2)->offset[0], 25.4, kTolExact);
  EXPECT_NEAR(t.find(2)->offset[3], 5.0, kTolExact);  // angles are not scaled
  EXPECT_EQ(t.find(3), nullptr);
  EXPECT_EQ(t.find(1)->comment, "1/8 end mill");  // trimmed; the machining preview reads it
  EXPECT_EQ(t.find(2)->comment, "");
}

TEST(ToolTable, ErrorsNameTheLine) {
  try {
    (void)ToolTable::parse("T1 Z1\nT2 Zabc\n", 1.0, "t.tbl");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("t.tbl:2:"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)ToolTable::parse("T1 Z1\nT1 Z2\n", 1.0, "t.tbl"), IoError);
  EXPECT_THROW((void)ToolTable::parse("T1 K1\n", 1.0, "t.tbl"), IoError);
  EXPECT_THROW((void)ToolTable::load("/nonexistent.tbl", 1.0), IoError);
}

// Found by fuzz_tool_table (fuzz/corpus/tool_table/regression-infinite-offset.tbl): 1e308 is a
// finite number, but 1e308 inch is not a finite length in mm.
TEST(ToolTable, OffsetBeyondADoubleInMmIsRefused) {
  EXPECT_NO_THROW((void)ToolTable::parse("T1 Z1e308 D1e308\n", 1.0, "t.tbl"));
  for (const char* text : {"T1 P1 Z1e308\n", "T1 D-1e308\n"}) {
    try {
      (void)ToolTable::parse(text, 25.4, "t.tbl");
      FAIL() << text;
    } catch (const IoError& e) {
      EXPECT_NE(std::string(e.what()).find("t.tbl:1:"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("is too large"), std::string::npos) << e.what();
    }
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
