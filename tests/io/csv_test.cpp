// Tests of pkm::io::CsvReader and parseFiniteDouble (docs: include/pkm/io/csv.hpp): columns, line
// ends, comments, the errors, long lines and many read chunks, text in memory. addOptionalColumn
// and the plain-row fast path are in csv_optional_column_test.cpp.
#include "pkm/io/csv.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "io/csv_fixture.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::IoError;
using pkm::io::CsvReader;
using pkm::io::parseFiniteDouble;
using pkm::test::CsvTest;
using ::testing::HasSubstr;

TEST_F(CsvTest, ColumnsInAnyOrderWithExtraColumns) {
  const std::string path =
      write("p.csv", "c, extra ,a,label,b\n3,99,1,text is ignored,2\n-6, 0 ,-4,x,-5\n");
  CsvReader r(path, {"a", "b", "c"});
  EXPECT_THAT(r.header(), ::testing::ElementsAre("c", "extra", "a", "label", "b"));
  std::array<double, 3> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 3>{1, 2, 3}));
  EXPECT_EQ(r.line(), 2u);
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 3>{-4, -5, -6}));
  EXPECT_FALSE(r.next(v));
  EXPECT_EQ(r.name(), path);
}

TEST_F(CsvTest, CrlfLineEnds) {
  const std::string path = write("p.csv", "a,b\r\n1.5,2\r\n3,4.25\r\n");
  CsvReader r(path, {"a", "b"});
  EXPECT_THAT(r.header(), ::testing::ElementsAre("a", "b"));
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{1.5, 2}));
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{3, 4.25}));
  EXPECT_FALSE(r.next(v));
}

TEST_F(CsvTest, ByteOrderMarkIsSkipped) {
  const std::string path = write("p.csv",
                                 "\xEF\xBB\xBF"
                                 "a,b\n7,8\n");
  CsvReader r(path, {"a", "b"});
  EXPECT_THAT(r.header(), ::testing::ElementsAre("a", "b"));
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{7, 8}));
}

TEST_F(CsvTest, CommentsAndBlankLinesAreSkippedAndLinesCounted) {
  const std::string path = write("p.csv",
                                 "# written by a test\n"   // 1
                                 "\n"                      // 2
                                 "a,b\n"                   // 3
                                 "# a comment row\n"       // 4
                                 "   \n"                   // 5
                                 "\t\n"                    // 6
                                 "1,2\n"                   // 7
                                 "  # indented comment\n"  // 8
                                 "\n"                      // 9
                                 "3,4\n"                   // 10
                                 "\n");                    // 11
  CsvReader r(path, {"a", "b"});
  EXPECT_EQ(r.line(), 3u);
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{1, 2}));
  EXPECT_EQ(r.line(), 7u);
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{3, 4}));
  EXPECT_EQ(r.line(), 10u);
  EXPECT_FALSE(r.next(v));
}

TEST_F(CsvTest, LastLineWithoutNewline) {
  const std::string path = write("p.csv", "a,b\n1,2\n3,4");
  CsvReader r(path, {"a", "b"});
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{3, 4}));
  EXPECT_EQ(r.line(), 3u);
  EXPECT_FALSE(r.next(v));
  EXPECT_FALSE(r.next(v));  // stays at end of file
}

TEST_F(CsvTest, HeaderOnlyHasNoRows) {
  const std::string path = write("p.csv", "a,b");
  CsvReader r(path, {"a", "b"});
  std::array<double, 2> v{};
  EXPECT_FALSE(r.next(v));
}

TEST_F(CsvTest, MissingColumnNamesColumnAndFileLine) {
  const std::string msg =
      errorOf("# comment\nx,y,z,a,c\n1,2,3,4,5\n", {"x", "y", "z", "a", "b", "c"});
  EXPECT_THAT(msg, HasSubstr((dir_ / "data.csv").string() + ":2:"));
  EXPECT_THAT(msg, HasSubstr("missing column"));
  EXPECT_THAT(msg, HasSubstr("b"));
  EXPECT_THAT(msg, HasSubstr("x,y,z,a,c"));  // the header as read
}

TEST_F(CsvTest, DisplayNameIsUsedInMessages) {
  const std::string path = write("p.csv", "a\n");
  try {
    CsvReader r(path, {"a", "b"}, "<poses>");
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), ::testing::StartsWith("<poses>:1: "));
  }
}

TEST_F(CsvTest, DuplicateColumnIsAnError) {
  const std::string msg = errorOf("a,b,a\n1,2,3\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:1:"));
  EXPECT_THAT(msg, HasSubstr("'a' appears twice"));
}

TEST_F(CsvTest, DuplicateExtraColumnIsAnErrorToo) {
  const std::string msg = errorOf("a,b,note,note\n1,2,3,4\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:1:"));
  EXPECT_THAT(msg, HasSubstr("'note' appears twice"));
}

TEST_F(CsvTest, NonNumberNamesColumnAndLine) {
  const std::string msg = errorOf("a,b\n1,2\n\n3,four\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:4:"));
  EXPECT_THAT(msg, HasSubstr("column 'b'"));
  EXPECT_THAT(msg, HasSubstr("'four' is not a finite number"));
}

TEST_F(CsvTest, EmptyFieldIsAnError) {
  const std::string msg = errorOf("a,b\n1,\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:2:"));
  EXPECT_THAT(msg, HasSubstr("column 'b'"));
}

TEST_F(CsvTest, NanAndInfAreRejected) {
  for (const std::string bad : {"nan", "NaN", "-nan", "inf", "-inf", "+inf", "infinity", "1e999"}) {
    SCOPED_TRACE(bad);
    const std::string msg = errorOf("a,b\n1,2\n" + bad + ",3\n", {"a", "b"});
    EXPECT_THAT(msg, HasSubstr("data.csv:3:"));
    EXPECT_THAT(msg, HasSubstr("column 'a'"));
    EXPECT_THAT(msg, HasSubstr("not a finite number"));
  }
}

TEST_F(CsvTest, TooFewFields) {
  const std::string msg = errorOf("a,b,c\n1,2,3\n1,2\n", {"a", "b", "c"});
  EXPECT_THAT(msg, HasSubstr("data.csv:3:"));
  EXPECT_THAT(msg, HasSubstr("expected 3 fields, found 2"));
}

TEST_F(CsvTest, TooFewFieldsWhenMissingFieldIsAnExtraColumn) {
  const std::string msg = errorOf("a,b,extra\n1,2\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:2:"));
  EXPECT_THAT(msg, HasSubstr("expected 3 fields, found 2"));
}

TEST_F(CsvTest, TooManyFields) {
  const std::string msg = errorOf("a,b\n1,2\n1,2,3\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:3:"));
  EXPECT_THAT(msg, HasSubstr("too many fields"));
}

TEST_F(CsvTest, TrailingCommaIsTooManyFields) {
  const std::string msg = errorOf("a,b\n1,2,\n", {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:2:"));
  EXPECT_THAT(msg, HasSubstr("too many fields"));
}

TEST_F(CsvTest, EmptyFileIsAnError) {
  for (const std::string content :
       {"", "\n\n", "# only a comment\n\n# and another\n", "\xEF\xBB\xBF"}) {
    SCOPED_TRACE(content);
    const std::string msg = errorOf(content, {"a"});
    EXPECT_THAT(msg, HasSubstr((dir_ / "data.csv").string()));
    EXPECT_THAT(msg, HasSubstr("empty file"));
  }
}

TEST_F(CsvTest, NonexistentFileIsAnError) {
  const std::string path = (dir_ / "no-such.csv").string();
  try {
    CsvReader r(path, {"a"});
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path));
    EXPECT_THAT(e.what(), HasSubstr("cannot open"));
  }
}

TEST_F(CsvTest, WrongOutputSizeIsInvalidArgument) {
  const std::string path = write("p.csv", "a,b\n1,2\n");
  CsvReader r(path, {"a", "b"});
  std::array<double, 3> v{};
  EXPECT_THROW((void)r.next(v), pkm::InvalidArgument);
}

TEST_F(CsvTest, LineLongerThanLimitIsAnError) {
  std::string content = "a,b\n1,2\n";
  content += std::string(CsvReader::kMaxLineBytes + 10, ' ');
  content += "3,4\n5,6\n";
  const std::string msg = errorOf(content, {"a", "b"});
  EXPECT_THAT(msg, HasSubstr("data.csv:3:"));
  EXPECT_THAT(msg, HasSubstr("line longer than"));
}

TEST_F(CsvTest, LongLineBelowLimitSpanningChunksIsRead) {
  // Padding makes one line span many 64 KiB read chunks while staying under the limit.
  const std::size_t pad = CsvReader::kMaxLineBytes - 100;
  std::string content = "a,b\n";
  content += std::string(pad / 2, ' ') + "1.25," + std::string(pad / 2, ' ') + "-2\n7,8";
  const std::string path = write("p.csv", content);
  CsvReader r(path, {"a", "b"});
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{1.25, -2}));
  EXPECT_EQ(r.line(), 2u);
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{7, 8}));
  EXPECT_EQ(r.line(), 3u);
  EXPECT_FALSE(r.next(v));
}

TEST_F(CsvTest, ManyChunksAreReadBackExactly) {
  constexpr int kRows = 100000;
  std::mt19937 rng(pkm::test::kSeed);
  std::uniform_real_distribution<double> u(-1e4, 1e4);
  std::vector<std::array<double, 3>> rows(kRows);
  std::string content = "id,x,y\n";
  char buf[128];
  for (int i = 0; i < kRows; ++i) {
    rows[static_cast<std::size_t>(i)] = {static_cast<double>(i), u(rng), u(rng) * 1e-7};
    const auto& r = rows[static_cast<std::size_t>(i)];
    // Alternate line ends so that CRLF pairs also straddle chunk boundaries.
    std::snprintf(
        buf, sizeof buf, "%.0f,%.17g, %.17g%s", r[0], r[1], r[2], i % 3 == 0 ? "\r\n" : "\n");
    content += buf;
  }
  ASSERT_GT(content.size(), 50u * 65536u);  // spans many read chunks
  const std::string path = write("big.csv", content);
  CsvReader r(path, {"y", "id", "x"});
  std::array<double, 3> v{};
  int n = 0;
  while (r.next(v)) {
    ASSERT_LT(n, kRows);
    const auto& want = rows[static_cast<std::size_t>(n)];
    ASSERT_EQ(v[1], want[0]) << "row " << n;
    ASSERT_EQ(v[2], want[1]) << "row " << n;
    ASSERT_EQ(v[0], want[2]) << "row " << n;
    ++n;
    ASSERT_EQ(r.line(), static_cast<std::size_t>(n) + 1);
  }
  EXPECT_EQ(n, kRows);
}

TEST(ParseFiniteDouble, AcceptsNumbers) {
  double v = 0;
  EXPECT_TRUE(parseFiniteDouble("+1", v));
  EXPECT_EQ(v, 1.0);
  EXPECT_TRUE(parseFiniteDouble(" 2.5 ", v));
  EXPECT_EQ(v, 2.5);
  EXPECT_TRUE(parseFiniteDouble("1e3", v));
  EXPECT_EQ(v, 1000.0);
  EXPECT_TRUE(parseFiniteDouble("\t-0.125\t", v));
  EXPECT_EQ(v, -0.125);
  EXPECT_TRUE(parseFiniteDouble("-1.5E-3", v));
  EXPECT_EQ(v, -1.5e-3);
  EXPECT_TRUE(parseFiniteDouble(".5", v));
  EXPECT_EQ(v, 0.5);
  EXPECT_TRUE(parseFiniteDouble("0.1", v));
  EXPECT_EQ(v, 0.1);
}

TEST(ParseFiniteDouble, RejectsEverythingElse) {
  for (const char* bad :
       {"",     " ",   "abc", "1.5x", "x1.5", "1 2",      "+",   "++1",   "+-1",    "--1", "1,5",
        "0x10", "nan", "inf", "-inf", "+inf", "infinity", "NaN", "1e999", "-1e999", "1e"}) {
    double v = 42.0;
    EXPECT_FALSE(parseFiniteDouble(bad, v)) << "'" << bad << "'";
  }
}

/// A reader of text in memory reads as the reader of the same file does, over many buffer
/// chunks, and names the text in its messages.
TEST_F(CsvTest, TextInMemoryReadsAsTheFile) {
  std::string text = "\xEF\xBB\xBF# comment\nb,a\r\n";
  for (int i = 0; i < 20000; ++i) text += std::to_string(i) + "," + std::to_string(-i) + "\n";
  text += "1,2";  // no final newline
  const std::string path = write("big.csv", text);
  CsvReader file(path, {"a", "b"});
  CsvReader memory(pkm::io::NamedText{"upload.csv", text}, {"a", "b"});
  std::array<double, 2> f{}, m{};
  std::size_t rows = 0;
  while (file.next(f)) {
    ASSERT_TRUE(memory.next(m));
    ASSERT_EQ(f, m);
    ASSERT_EQ(file.line(), memory.line());
    ++rows;
  }
  EXPECT_FALSE(memory.next(m));
  EXPECT_EQ(rows, 20001u);
  try {
    CsvReader bad(pkm::io::NamedText{"upload.csv", "a\n1\nx\n"}, {"a"});
    std::array<double, 1> v{};
    while (bad.next(v)) {
    }
    FAIL();
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("upload.csv:3:"));
  }
  EXPECT_THROW(CsvReader(pkm::io::NamedText{"empty.csv", ""}, {"a"}), IoError);
}

}  // namespace PKM_TEST_NS
