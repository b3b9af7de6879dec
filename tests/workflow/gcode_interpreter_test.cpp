// workflow::GcodeInterpreterSettings: the options checked, the tool table read in its unit.
#include "pkm/workflow/gcode_interpreter.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;

TEST(GcodeInterpreterSettings, DefaultsAreLinuxCncs) {
  const cnc::InterpreterOptions o = GcodeInterpreterSettings{}.options();
  EXPECT_FALSE(o.block_delete);
  EXPECT_EQ(o.max_loop_iterations, 10'000'000u);
  EXPECT_TRUE(o.tools.tools.empty());
}

TEST(GcodeInterpreterSettings, ReadsTheToolTableInItsUnit) {
  const fs::path tbl = fs::temp_directory_path() /
                       ("pkm_workflow_gcode_interpreter_" + std::to_string(::getpid()) + ".tbl");
  std::ofstream(tbl) << "T1 P1 Z2.0 D0.5 ;one\n";
  GcodeInterpreterSettings s;
  s.tool_table = tbl.string();
  s.tool_units = "inch";
  s.block_delete = true;
  s.max_iterations = 5;
  const cnc::InterpreterOptions o = s.options();
  ASSERT_NE(o.tools.find(1), nullptr);
  EXPECT_DOUBLE_EQ(o.tools.find(1)->offset[2], 50.8);
  EXPECT_TRUE(o.block_delete);
  EXPECT_EQ(o.max_loop_iterations, 5u);
  fs::remove(tbl);
  EXPECT_THROW((void)s.options(), IoError);
}

TEST(GcodeInterpreterSettings, RejectsBadSettings) {
  GcodeInterpreterSettings s;
  s.tool_units = "cm";
  EXPECT_THROW(s.validate(), InvalidArgument);
  s.tool_units = "mm";
  s.max_iterations = 0;
  EXPECT_THROW(s.validate(), InvalidArgument);
  EXPECT_THROW((void)s.options(), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
