#include "pkm/io/number_table.hpp"

#include <gtest/gtest.h>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/text_table.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

const std::vector<ColumnNames> kXy = {{"x", "x_mm"}, {"y", "y_mm"}};

std::string errorOf(const std::string& text, const std::vector<ColumnNames>& cols = kXy) {
  try {
    (void)NumberTable::parse(text, "in.csv", cols);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(NumberTable, ReadsWantedColumnsInTheirOrder) {
  const NumberTable t = NumberTable::parse(
      "\xEF\xBB\xBF# ring form mm: 0.0002\n\n label , y_mm,x\r\nA,1.5,-2\n# a comment\n\n"
      "B , +3e-3 , 4\r\n",
      "in.csv",
      kXy);
  EXPECT_EQ(t.header(), (std::vector<std::string>{"label", "y_mm", "x"}));
  EXPECT_EQ(t.meta("ring form mm").value(), "0.0002");
  EXPECT_TRUE(t.commaSeparated());
  ASSERT_EQ(t.rows(), 2u);
  ASSERT_EQ(t.width(), 2u);
  EXPECT_EQ(t.headerIndex(0), 2u);
  EXPECT_EQ(t.row(0)[0], -2.0);
  EXPECT_EQ(t.row(0)[1], 1.5);
  EXPECT_EQ(t.row(1)[0], 4.0);
  EXPECT_EQ(t.row(1)[1], 3e-3);
  EXPECT_EQ(t.line(0), 4u);
  EXPECT_EQ(t.line(1), 7u);
}

TEST(NumberTable, ReadsBlankSeparatedTables) {
  const NumberTable t =
      NumberTable::parse("# unit: mm\nx\ty  z\n1 2\t3\n  4   5 6  \n\n7 8 9", "in.txt", kXy);
  EXPECT_FALSE(t.commaSeparated());
  ASSERT_EQ(t.rows(), 3u);
  EXPECT_EQ(t.row(1)[0], 4.0);
  EXPECT_EQ(t.row(1)[1], 5.0);
  EXPECT_EQ(t.row(2)[1], 8.0);
  EXPECT_EQ(t.line(2), 6u);
  EXPECT_EQ(errorOf("x y\n1 2 3\n"), "in.csv:2: expected 2 fields, found 3");
  EXPECT_EQ(errorOf("x y\n1 y\n"), "in.csv:2: column 'y': 'y' is not a finite number");
}

TEST(NumberTable, NamesTheFileAndLineOfEveryError) {
  EXPECT_EQ(errorOf("x,y\n1,2\n3\n"), "in.csv:3: expected 2 fields, found 1");
  EXPECT_EQ(errorOf("x,y\n1,2,3\n"), "in.csv:2: expected 2 fields, found 3");
  EXPECT_EQ(errorOf("x,y\n1,nan\n"), "in.csv:2: column 'y': 'nan' is not a finite number");
  EXPECT_EQ(errorOf("x,y\n1,\n"), "in.csv:2: column 'y': '' is not a finite number");
  EXPECT_EQ(errorOf("x,y\n1,1e999\n"), "in.csv:2: column 'y': '1e999' is not a finite number");
  EXPECT_EQ(errorOf("x,y\n1, 2 3\n"), "in.csv:2: column 'y': '2 3' is not a finite number");
  EXPECT_EQ(errorOf("a,y\n1,2\n"), "in.csv:1: missing column 'x' (or 'x_mm')");
  EXPECT_EQ(errorOf("x,y\n"), "in.csv: no data rows (only a header)");
  EXPECT_EQ(errorOf("# only\n"), "in.csv: no header row");
  EXPECT_EQ(errorOf("x,x\n1,2\n"), "in.csv:1: column 'x' appears twice");
  EXPECT_EQ(errorOf("x,y\n1,2\n", {{"x"}, {"x"}}), "in.csv:1: column 'x' is asked for twice");
  EXPECT_NO_THROW((void)NumberTable::parse("x,y\n", "in.csv", kXy, false));
}

TEST(NumberTable, OtherFieldsMayHoldText) {
  const NumberTable t = NumberTable::parse("x,note,y\n1,a b c,2\n", "in.csv", kXy);
  EXPECT_EQ(t.row(0)[1], 2.0);
}

/// A large table (several chunks on the cores) agrees with TextTable and from_chars, row by row,
/// with blank and comment lines between the chunks and the first bad line reported.
TEST(NumberTable, LargeTablesAgreeWithTheRowReader) {
  std::mt19937 rng(42u);
  std::uniform_real_distribution<double> u(-1000.0, 1000.0);
  std::string text = "x,y,z\n";
  for (int r = 0; r < 150000; ++r) {
    if (r % 25000 == 7) text += "\n# a comment\n";
    char buf[96];
    const int n = std::snprintf(buf, sizeof buf, "%.17g,%.6f,%.3e\n", u(rng), u(rng), u(rng));
    text.append(buf, static_cast<std::size_t>(n));
  }
  const NumberTable t = NumberTable::parse(text, "big.csv", {{"z"}, {"x"}, {"y"}});
  const TextTable ref = TextTable::parse(text, "big.csv");
  ASSERT_EQ(t.rows(), ref.rows());
  for (std::size_t r = 0; r < t.rows(); ++r) {
    ASSERT_EQ(t.line(r), ref.line(r));
    ASSERT_EQ(t.row(r)[0], ref.number(r, 2));
    ASSERT_EQ(t.row(r)[1], ref.number(r, 0));
    ASSERT_EQ(t.row(r)[2], ref.number(r, 1));
    double v = 0.0;
    const std::string_view field = ref.text(r, 0);
    std::from_chars(field.data(), field.data() + field.size(), v);
    ASSERT_EQ(t.row(r)[1], v);
  }
  std::string bad = text;
  const std::size_t last_line = bad.rfind('\n', bad.size() - 2) + 1;
  bad.insert(last_line, "1,2\n");
  const auto line =
      static_cast<std::size_t>(std::count(bad.begin(), bad.begin() + last_line, '\n')) + 1;
  try {
    (void)NumberTable::parse(bad, "big.csv", {{"x"}});
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find(fmt::format("big.csv:{}: expected 3 fields", line)),
              std::string::npos)
        << e.what();
  }
  // Errors in two chunks at once (read on two threads): the earlier line's own message.
  const std::size_t middle = bad.find('\n', bad.size() / 2) + 1;
  bad.insert(middle, "abc,1,2\n");
  const auto middle_line =
      static_cast<std::size_t>(std::count(bad.begin(), bad.begin() + middle, '\n')) + 1;
  try {
    (void)NumberTable::parse(bad, "big.csv", {{"x"}});
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_EQ(std::string(e.what()),
              fmt::format("big.csv:{}: column 'x': 'abc' is not a finite number", middle_line));
  }
}

TEST(NumberTable, ReadsAFileThroughItsMapping) {
  const std::filesystem::path path =
      std::filesystem::temp_directory_path() / "pkm_number_table_test.csv";
  std::ofstream(path) << "x,y\n1,2\n3,4";
  const NumberTable t = NumberTable::read(path.string(), kXy);
  EXPECT_EQ(t.source(), path.string());
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.row(1)[1], 4.0);
  std::filesystem::remove(path);
  EXPECT_THROW((void)NumberTable::read(path.string(), kXy), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
