#include "pkm/io/text_table.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

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

/// A table large enough to be read in parallel chunks: rows "k,k*0.5,label" with a blank line
/// every 1000 rows and a comment every 777, and the line of each row.
std::string largeTable(std::size_t rows, std::vector<std::size_t>& lines) {
  std::string text = "# unit: mm\nx,y,name\n";
  std::size_t line = 2;
  for (std::size_t k = 0; k < rows; ++k) {
    if (k % 1000 == 999) {
      text += "\n";
      ++line;
    }
    if (k % 777 == 5) {
      text += "# comment, with, commas\n";
      ++line;
    }
    text += std::to_string(k) + ", " + std::to_string(static_cast<double>(k) * 0.5) + " ,r\r\n";
    lines.push_back(++line);
  }
  return text;
}

TEST(TextTable, LargeFileReadInChunksKeepsEveryRowAndLine) {
  std::vector<std::size_t> lines;
  const std::size_t n = 200000;  // several MB: more than one chunk
  const TextTable t = TextTable::parse(largeTable(n, lines), "big.csv");
  ASSERT_EQ(t.rows(), n);
  ASSERT_EQ(t.meta("unit"), "mm");
  const std::array<std::size_t, 2> cols{1, 0};
  std::array<double, 2> v{};
  for (std::size_t r = 0; r < n; r += 997) {
    ASSERT_EQ(t.line(r), lines[r]) << r;
    t.numbers(r, cols, v);
    ASSERT_EQ(v[1], static_cast<double>(r));
    ASSERT_EQ(v[0], static_cast<double>(r) * 0.5);
    ASSERT_EQ(t.number(r, 0), static_cast<double>(r));
    ASSERT_EQ(t.text(r, 2), "r");
  }
  EXPECT_EQ(t.line(n - 1), lines.back());
}

TEST(TextTable, LargeFileNamesTheFirstBadRowsLine) {
  std::vector<std::size_t> lines;
  std::string text = largeTable(200000, lines);
  // Break two rows, in different chunks: the earlier one is reported.
  for (const std::size_t row : {std::size_t{150000}, std::size_t{120000}}) {
    const std::string row_text = std::to_string(row) + ", ";
    const std::size_t at = text.find("\n" + row_text) + 1;
    text.insert(at + row_text.size(), "9,");
  }
  try {
    (void)TextTable::parse(text, "big.csv");
    FAIL();
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              "big.csv:" + std::to_string(lines[120000]) + ": expected 3 fields, found 4");
  }
}

TEST(TextTable, NumbersReadsColumnsInAnyOrderAndFallsBackForSigns) {
  const TextTable t = TextTable::parse("a,b,c\n +1.5 , x ,2e3\n-0.25,y,+7\n", "n.csv");
  const std::array<std::size_t, 3> cols{2, 0, 2};
  std::array<double, 3> v{};
  t.numbers(0, cols, v);
  EXPECT_EQ(v, (std::array<double, 3>{2000.0, 1.5, 2000.0}));
  t.numbers(1, cols, v);
  EXPECT_EQ(v, (std::array<double, 3>{7.0, -0.25, 7.0}));
  const std::array<std::size_t, 1> bad{1};
  std::array<double, 1> w{};
  try {
    t.numbers(1, bad, w);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_STREQ(e.what(), "n.csv:3: column 'b': 'y' is not a finite number");
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
