// io::compensationTableText / compensationTableJson: the summary lines and keys.
#include "pkm/io/compensation_table_report.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

namespace pkm::io {
namespace PKM_TEST_NS {

CompensationTableSummary axisTable() {
  return {.format = "linuxcnc1",
          .out = "x.comp",
          .axis = "X",
          .input_axis = std::nullopt,
          .rows = 3,
          .input_rows = 3,
          .first = 0.0,
          .last = 128.0,
          .max_correction = 0.0078125,
          .iso = CompensationTableSummary::Iso{0.01, 0.004, 0.006}};
}

TEST(CompensationTableReport, Text) {
  EXPECT_EQ(compensationTableText(axisTable()),
            "compensation table (linuxcnc1, axis X)\nrows\t3\nrange\t0\t128 mm\n"
            "max_correction\t0.0078125 mm\nmeasured E\t0.01 mm\nwrote\tx.comp\n");
  CompensationTableSummary s = axisTable();
  s.iso.reset();
  s.input_axis = std::string(1, 'Y');
  EXPECT_EQ(compensationTableText(s),
            "compensation table (linuxcnc1, axis X over Y)\nrows\t3\nrange\t0\t128 mm\n"
            "max_correction\t0.0078125 mm\nwrote\tx.comp\n");
  s = axisTable();
  s.iso->E = NAN;  // no E line
  EXPECT_EQ(compensationTableText(s).find("measured E"), std::string::npos);
}

TEST(CompensationTableReport, Json) {
  const nlohmann::ordered_json j =
      nlohmann::ordered_json::parse(compensationTableJson(axisTable()));
  EXPECT_EQ(j.begin().key(), "format");
  EXPECT_EQ(j["rows"], 3);
  EXPECT_EQ(j["E"], 0.01);
  EXPECT_FALSE(j.contains("input_axis"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
