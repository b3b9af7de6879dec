// io::ExportColumns: columns of instrument exports recognised by name and unit.
#include "pkm/io/export_columns.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST(ExportColumns, HeaderFieldsSplitIntoNameAndUnit) {
  const auto check = [](std::string_view field, std::string_view name, std::string_view unit) {
    const HeaderField h = splitHeaderField(field);
    EXPECT_EQ(h.name, name) << field;
    EXPECT_EQ(h.unit, unit) << field;
  };
  check("Target (mm)", "target", "mm");
  check("Error [µm]", "error", "um");
  check("Error [μm]", "error", "um");  // Greek mu as well as the micro sign
  check("reading_mm", "reading", "mm");
  check("Run", "run", "");
  check("  Actual   Position  (in) ", "actual position", "in");
  check("sub_step", "sub step", "");
  check("Deviation um", "deviation", "um");
}

TEST(ExportColumns, LengthUnits) {
  EXPECT_EQ(millimetresPer("mm"), 1.0);
  EXPECT_EQ(millimetresPer("µm"), 1e-3);
  EXPECT_EQ(millimetresPer("Microns"), 1e-3);
  EXPECT_EQ(millimetresPer("IN"), 25.4);
  EXPECT_EQ(millimetresPer("m"), 1000.0);
  EXPECT_FALSE(millimetresPer("deg").has_value());
  EXPECT_FALSE(millimetresPer("").has_value());
}

TEST(ExportColumns, AssignmentsParseAndRejectBadItems) {
  const ColumnAssignments a = parseColumnAssignments("target=Target Pos, Error = Dev (um)");
  ASSERT_EQ(a.size(), 2u);
  EXPECT_EQ(a[0], (std::pair<std::string, std::string>{"target", "Target Pos"}));
  EXPECT_EQ(a[1], (std::pair<std::string, std::string>{"error", "Dev (um)"}));
  EXPECT_THROW((void)parseColumnAssignments("target"), InvalidArgument);
  EXPECT_THROW((void)parseColumnAssignments("=x"), InvalidArgument);
  EXPECT_THROW((void)parseColumnAssignments("a=b,"), InvalidArgument);
}

TEST(ExportColumns, RolesByAliasOrAssignment) {
  const TextTable t = TextTable::parse("Nominal (mm),Dev [um],Cycle,Comment\n1,2,3,x\n", "e.csv");
  const std::vector<ColumnRole> roles = {
      {"target", {"target", "nominal"}}, {"error", {"error", "dev"}}, {"run", {"run"}}};
  const ExportColumns c(t, roles);
  EXPECT_EQ(c.find("target"), 0u);
  EXPECT_EQ(c.unit("target"), "mm");
  EXPECT_EQ(c.find("error"), 1u);
  EXPECT_EQ(c.unit("error"), "um");
  EXPECT_FALSE(c.find("run").has_value());
  try {
    c.require({{"target"}, {"run"}});
    FAIL() << "run is missing";
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(),
                 "e.csv:1: missing column: run ('run'); found 'Nominal (mm)', 'Dev [um]', "
                 "'Cycle', 'Comment' (names are case-insensitive and may carry a unit, e.g. "
                 "'Target (mm)'; --columns ROLE=COLUMN assigns one)");
  }
  const ExportColumns assigned(t, roles, {{"run", "cycle"}});
  EXPECT_EQ(assigned.find("run"), 2u);
  EXPECT_NO_THROW(assigned.require({{"target"}, {"run"}, {"error", "target"}}));
  EXPECT_DOUBLE_EQ(columnScale(t, assigned, "error", "", "--error-unit", true), 1e-3);
  EXPECT_THROW(ExportColumns(t, roles, {{"speed", "Cycle"}}), IoError);
  EXPECT_THROW(ExportColumns(t, roles, {{"run", "Counter"}}), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
