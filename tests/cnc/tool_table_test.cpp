// LinuxCNC tool table lines, units, errors.
#include "pkm/cnc/tool_table.hpp"

#include <gtest/gtest.h>

#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/program.hpp"
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

/// The interpreter says when it stopped at a tool its table lacks (gcode run then looks for the
/// tools.tbl beside the program), and only then.
TEST(ToolTable, TheInterpreterSaysWhenATableLacksATool) {
  const auto stops = [](const char* program, const char* table) {
    InterpreterOptions o;
    o.tools = ToolTable::parse(table, 1.0, "t.tbl");
    Interpreter interp(o);
    MoveCollector c;
    EXPECT_THROW(interp.run(Program::parse(program, "t.ngc"), c), IoError) << program;
    return interp.missingTool();
  };
  EXPECT_TRUE(stops("G43 H2\nM2\n", ""));
  EXPECT_TRUE(stops("T3 M6\nM2\n", "T1 Z5 D6\n"));
  EXPECT_TRUE(stops("G10 L1 P4 Z1\nM2\n", "T1 Z5 D6\n"));
  EXPECT_FALSE(stops("G1 X1\nM2\n", "T1 Z5 D6\n"));  // another error: no feed rate
  Interpreter fine;
  MoveCollector c;
  fine.run(Program::parse("G0 X1\nM2\n", "t.ngc"), c);
  EXPECT_FALSE(fine.missingTool());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
