// LineReader: line numbers, empty and comment-only lines skipped, '%' delimiters, errors with
// FILE:LINE, and the conservative O-word scan.
#include "pkm/cnc/line_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::vector<std::size_t> lines(const std::string& text) {
  LineReader r(text, "t.ngc");
  std::vector<std::size_t> out;
  Block b;
  while (r.next(b)) out.push_back(b.line);
  return out;
}

std::string errorOf(const std::string& text) {
  try {
    (void)lines(text);
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LineReader, LineNumbersSkipEmptyAndCommentLines) {
  EXPECT_EQ(lines("G0 X1\n\n(comment)\n; note\nG1 X2 F100\n"), (std::vector<std::size_t>{1, 5}));
  LineReader r("G0 X1\nG1 X2 F9", "t.ngc");  // no newline at the end
  Block b;
  ASSERT_TRUE(r.next(b));
  ASSERT_TRUE(r.next(b));
  EXPECT_EQ(b.line, 2u);
  EXPECT_EQ(b.words.size(), 3u);
  EXPECT_FALSE(r.next(b));
  EXPECT_EQ(r.lines(), 2u);
}

TEST(LineReader, PercentDelimitsTheProgram) {
  EXPECT_EQ(lines("%\nG0 X1\n%\nthis is not g-code\n"), (std::vector<std::size_t>{2}));
  // A '%' that does not open the program ends the reading too (LinuxCNC's files put one after
  // M2); the program then needs its M2 (Interpreter's require_program_end).
  EXPECT_EQ(lines("G0 X1\nM2\n%\n(.\n"), (std::vector<std::size_t>{1, 2}));
}

TEST(LineReader, ErrorsNameFileAndLine) {
  EXPECT_THAT(errorOf("G0 X1\nG1 X2 (open\n"), HasSubstr("t.ngc:2: comment not closed"));
}

TEST(LineReader, OWordScanIsConservative) {
  EXPECT_FALSE(LineReader::mayHaveOWords("G0 X1 (a comment with o and O)\nG1 Y2 ; also o\n"));
  EXPECT_TRUE(LineReader::mayHaveOWords("o100 sub\n"));
  EXPECT_TRUE(LineReader::mayHaveOWords("G0 X1\nO<name> call\n"));
  EXPECT_TRUE(LineReader::mayHaveOWords("G1 X[cos[0]] F1\n"));  // a function name: conservative
  EXPECT_TRUE(LineReader::mayHaveOWords("(comment)o1 if [1]\n"));
  EXPECT_TRUE(LineReader::mayHaveOWords("; note\no1 endif\n"));  // ';' ends only its own line
  // A very long comment full of o's: bounded work, and a conservative answer.
  const std::string long_comment = "(" + std::string(1 << 20, 'o') + ")\n";
  EXPECT_TRUE(LineReader::mayHaveOWords(long_comment));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
