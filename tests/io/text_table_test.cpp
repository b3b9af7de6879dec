#include "pkm/io/text_table.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace {

std::string errorOf(const std::string& text) {
  try {
    (void)TextTable::parse(text, "in.csv");
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(TextTable, ReadsMetadataHeaderAndRows) {
  const TextTable t = TextTable::parse(
      "\xEF\xBB\xBF# format: test/1\n# axes: x, y\n\n target , direction,diagonal\r\n"
      "1.5,+,PPP\n# a comment\n-2e-3 , - ,NPP\n",
      "in.csv");
  ASSERT_EQ(t.header(), (std::vector<std::string>{"target", "direction", "diagonal"}));
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.metadata().size(), 2u);
  EXPECT_EQ(t.meta("axes").value(), "x, y");
  EXPECT_FALSE(t.meta("seed").has_value());
  const std::size_t target = t.column({"target_mm", "target"});
  EXPECT_EQ(target, 0u);
  EXPECT_DOUBLE_EQ(t.number(0, target), 1.5);
  EXPECT_DOUBLE_EQ(t.number(1, target), -2e-3);
  EXPECT_EQ(t.direction(0, 1), 1);
  EXPECT_EQ(t.direction(1, 1), -1);
  EXPECT_EQ(t.text(1, 2), "NPP");
  EXPECT_EQ(t.line(0), 5u);
  EXPECT_EQ(t.line(1), 7u);
}

TEST(TextTable, DataTablesNeedRows) {
  EXPECT_EQ(TextTable::parse("# k: v\nx,y\n", "h.csv").rows(), 0u);  // a table may be empty
  try {
    (void)TextTable::parseData("# k: v\nx,y\n", "h.csv");
    FAIL() << "accepted a header without rows";
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "h.csv: no data rows (only a header)");
  }
  EXPECT_EQ(TextTable::parseData("x,y\n1,2\n", "d.csv").rows(), 1u);
}

TEST(TextTable, SurvivesBeingMoved) {
  TextTable a = TextTable::parse("x\n1\n", "short.csv");
  std::vector<TextTable> tables;
  tables.push_back(std::move(a));
  tables.reserve(8);
  EXPECT_EQ(tables[0].text(0, 0), "1");
}

TEST(TextTable, IntegersAndDirections) {
  const TextTable t = TextTable::parse("run,d\n3,1\n2.5,x\n", "r.csv");
  EXPECT_EQ(t.integer(0, 0), 3);
  EXPECT_EQ(t.direction(0, 1), 1);
  const TextTable labels =
      TextTable::parse("d\nForward\nREVERSE\nf\nr\nUp\ndown\n+1\n-1\n", "labels.csv");
  const int expected[] = {1, -1, 1, -1, 1, -1, 1, -1};
  for (std::size_t r = 0; r < labels.rows(); ++r) EXPECT_EQ(labels.direction(r, 0), expected[r]);
  EXPECT_THROW((void)t.integer(1, 0), IoError);
  try {
    (void)t.direction(1, 1);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_STREQ(
        e.what(),
        "r.csv:3: column 'd': direction 'x' is not one of +, -, Forward, Reverse, F, R, Up, "
        "Down, 1, -1");
  }
}

TEST(TextTable, ErrorsNameFileAndLine) {
  EXPECT_EQ(errorOf("# only comments\n"), "in.csv: no header row");
  EXPECT_EQ(errorOf("a,b\n1,2\n3\n"), "in.csv:3: expected 2 fields, found 1");
  EXPECT_EQ(errorOf("a,a\n"), "in.csv:1: column 'a' appears twice");
  EXPECT_EQ(errorOf("a,,b\n"), "in.csv:1: header field 2 is empty");
  const TextTable t = TextTable::parse("\nx,y\n1,nan\n", "in.csv");
  try {
    (void)t.number(0, 1);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "in.csv:3: column 'y': 'nan' is not a finite number");
  }
  try {
    (void)t.column({"measured", "reading_mm"});
    FAIL();
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "in.csv:2: missing column 'measured' (or 'reading_mm')");
  }
}

TEST(TextTable, MissingFileIsAnIoError) {
  EXPECT_THROW((void)TextTable::read("/nonexistent/dir/file.csv"), IoError);
}

}  // namespace
}  // namespace pkm::io
