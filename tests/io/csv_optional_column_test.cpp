// Tests of pkm::io::CsvReader (docs: include/pkm/io/csv.hpp): addOptionalColumn (present, absent,
// order, refusals) and rows of plain numbers read as the general rows are.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "io/csv_fixture.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/csv.hpp"

namespace PKM_TEST_NS {

using pkm::IoError;
using pkm::io::CsvReader;
using pkm::test::CsvTest;
using ::testing::HasSubstr;

// ---------------------------------------------------------------------------------------------
// addOptionalColumn

TEST_F(CsvTest, OptionalColumnPresentComesAfterRequiredColumns) {
  const std::string path = write("p.csv", "x2,x,y,note\n7,1,2,n\n-8,3,4,m\n");
  CsvReader r(path, {"x", "y"});
  EXPECT_TRUE(r.addOptionalColumn("x2"));
  std::array<double, 3> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 3>{1, 2, 7}));
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 3>{3, 4, -8}));
  EXPECT_FALSE(r.next(v));
}

TEST_F(CsvTest, OptionalColumnAbsentLeavesTheRowSize) {
  const std::string path = write("p.csv", "x,y\n1,2\n");
  CsvReader r(path, {"x", "y"});
  EXPECT_FALSE(r.addOptionalColumn("x2"));
  EXPECT_FALSE(r.addOptionalColumn("X"));  // names are case-sensitive
  std::array<double, 3> three{};
  EXPECT_THROW((void)r.next(three), pkm::InvalidArgument);  // still two values per row
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{1, 2}));
}

TEST_F(CsvTest, OptionalColumnsTakeIndicesInTheOrderAdded) {
  // Header order y2, b, x2, a; requested a, b, then x2, an absent z, then y2.
  const std::string path = write("p.csv", "y2, b ,x2,a\n40,20,30,10\n");
  CsvReader r(path, {"a", "b"});
  EXPECT_TRUE(r.addOptionalColumn("x2"));
  EXPECT_FALSE(r.addOptionalColumn("z"));
  EXPECT_TRUE(r.addOptionalColumn("y2"));
  std::array<double, 4> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 4>{10, 20, 30, 40}));
}

TEST_F(CsvTest, OptionalColumnThatIsAlreadyRequiredTakesNoNewIndex) {
  const std::string path = write("p.csv", "a,b,c\n1,2,3\n");
  CsvReader r(path, {"a", "b"});
  EXPECT_TRUE(r.addOptionalColumn("b"));
  EXPECT_TRUE(r.addOptionalColumn("c"));
  EXPECT_TRUE(r.addOptionalColumn("c"));  // twice: still one value
  std::array<double, 3> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 3>{1, 2, 3}));
}

TEST_F(CsvTest, OptionalColumnRowsStillNeedEveryField) {
  const std::string path = write("p.csv", "a,x2,b\n1,2,3\n4,5\n");
  CsvReader r(path, {"a", "b"});
  ASSERT_TRUE(r.addOptionalColumn("x2"));
  std::array<double, 3> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 3>{1, 3, 2}));
  try {
    (void)r.next(v);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ":3:"));
    EXPECT_THAT(e.what(), HasSubstr("expected 3 fields, found 2"));
  }
}

TEST_F(CsvTest, OptionalColumnTooManyFields) {
  const std::string path = write("p.csv", "a,x2\n1,2,3\n");
  CsvReader r(path, {"a"});
  ASSERT_TRUE(r.addOptionalColumn("x2"));
  std::array<double, 2> v{};
  try {
    (void)r.next(v);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr(path + ":2:"));
    EXPECT_THAT(e.what(), HasSubstr("too many fields"));
  }
}

TEST_F(CsvTest, NonNumberInOptionalColumnNamesTheColumn) {
  for (const std::string bad : {"abc", "", "nan", "1e999"}) {
    SCOPED_TRACE(bad);
    const std::string path = write("p.csv", "a,y2,b\n1,2,3\n\n4," + bad + ",6\n");
    CsvReader r(path, {"a", "b"});
    ASSERT_TRUE(r.addOptionalColumn("y2"));
    std::array<double, 3> v{};
    ASSERT_TRUE(r.next(v));
    try {
      (void)r.next(v);
      FAIL() << "no error";
    } catch (const IoError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path + ":4:"));
      EXPECT_THAT(e.what(), HasSubstr("column 'y2'"));
      EXPECT_THAT(e.what(), HasSubstr("'" + bad + "' is not a finite number"));
    }
  }
}

TEST_F(CsvTest, UnrequestedColumnMayHoldText) {
  // Without addOptionalColumn the same column is ignored, text and all.
  const std::string path = write("p.csv", "a,y2,b\n1,abc,3\n");
  CsvReader r(path, {"a", "b"});
  std::array<double, 2> v{};
  ASSERT_TRUE(r.next(v));
  EXPECT_EQ(v, (std::array<double, 2>{1, 3}));
}

TEST_F(CsvTest, PlainAndOtherRowsReadTheSame) {
  // Rows of plain numbers take a one-pass reading; rows with blanks, '+', CR line ends, long
  // numbers or exponents the general one. Both give from_chars's values.
  const std::string content =
      "a,b\n"
      "1.5,-2\n"
      " 1.5 , -2 \n"
      "+1.5,-2\r\n"
      "29.74668048707284,29.746714726167661\n"
      "1.2345678901234567890123,1e-30\n"
      "-0,.5\n"
      "5.,1E3\n";
  CsvReader r(write("mixed.csv", content), {"b", "a"});
  std::vector<std::array<double, 2>> rows;
  std::vector<double> v(2);
  while (r.next(v)) rows.push_back({v[0], v[1]});
  const std::vector<std::array<double, 2>> expected = {{-2.0, 1.5},
                                                       {-2.0, 1.5},
                                                       {-2.0, 1.5},
                                                       {29.746714726167661, 29.74668048707284},
                                                       {1e-30, 1.2345678901234567890123},
                                                       {0.5, -0.0},
                                                       {1e3, 5.0}};
  ASSERT_EQ(rows.size(), expected.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i][0], expected[i][0]) << i;
    EXPECT_EQ(rows[i][1], expected[i][1]) << i;
  }
  EXPECT_EQ(r.line(), 8u);
  EXPECT_THAT(errorOf("a,b\n1,2\n1,2,\n", {"a", "b"}), HasSubstr("data.csv:3"));
  EXPECT_THAT(errorOf("a,b\n1,2\n1\n", {"a", "b"}), HasSubstr("data.csv:3"));
  EXPECT_THAT(errorOf("a,b\n1,2\n1,2x\n", {"a", "b"}), HasSubstr("data.csv:3"));
}

}  // namespace PKM_TEST_NS
