// Program reading and the O-word structure checks, with line numbers in the errors.
#include "pkm/cnc/program.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::string errorOf(const std::string& text) {
  try {
    (void)Program::parse(text, "p.ngc");
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(Program, SkipsEmptyLinesAndKeepsLineNumbers) {
  const Program p = Program::parse("(header)\n\nG0 X1\n; c\nG1 X2 F1\n", "p.ngc");
  ASSERT_EQ(p.blocks().size(), 2u);
  EXPECT_EQ(p.blocks()[0].line, 3u);
  EXPECT_EQ(p.blocks()[1].line, 5u);
  EXPECT_EQ(p.lineCount(), 5u);
}

TEST(Program, PercentDelimitsTheProgram) {
  const Program p = Program::parse("%\nG0 X1\n%\nG0 X2\n", "p.ngc");
  EXPECT_EQ(p.blocks().size(), 1u);
}

TEST(Program, ResolvesSubsAndLoops) {
  const Program p = Program::parse(
      "o<s> sub\nG0 X1\no<s> endsub\no1 while [1]\no1 break\no1 endwhile\no<s> call\n", "p.ngc");
  const auto& b = p.blocks();
  EXPECT_EQ(p.findSub("s"), 0u);
  EXPECT_EQ(b[0].jump, 2u);
  EXPECT_EQ(b[3].jump, 5u);
  EXPECT_EQ(b[4].partner, 3u);
  EXPECT_EQ(b[5].partner, 3u);
  EXPECT_EQ(b[6].jump, 0u);
  EXPECT_EQ(p.findSub("none"), kNoBlock);
}

TEST(Program, IfChain) {
  const Program p =
      Program::parse("o1 if [1]\nG0 X1\no1 elseif [0]\nG0 X2\no1 else\nG0 X3\no1 endif\n", "p.ngc");
  const auto& b = p.blocks();
  EXPECT_EQ(b[0].jump, 2u);
  EXPECT_EQ(b[2].jump, 4u);
  EXPECT_EQ(b[2].partner, 6u);
  EXPECT_EQ(b[4].partner, 6u);
}

TEST(Program, StructureErrorsNameTheLine) {
  EXPECT_THAT(errorOf("G0 X1\no1 while [1]\nG0 X2\n"), HasSubstr("p.ngc:2: o1 is not closed"));
  EXPECT_THAT(errorOf("o1 endwhile\n"), HasSubstr("p.ngc:1:"));
  EXPECT_THAT(errorOf("o1 if [1]\no2 endif\n"), HasSubstr("p.ngc:2:"));
  EXPECT_THAT(errorOf("o<a> sub\no<b> sub\n"), HasSubstr("p.ngc:2:"));
  EXPECT_THAT(errorOf("G0\no1 return\n"), HasSubstr("p.ngc:2: o1 return outside a sub"));
  EXPECT_THAT(errorOf("o2 do\no1 break\no2 while [0]\n"), HasSubstr("p.ngc:2:"));
  EXPECT_THAT(errorOf("G0 X1\nG1 X[1+\n"), HasSubstr("p.ngc:2:"));
  EXPECT_THAT(errorOf("o<a> sub\no<a> endsub\no<a> sub\no<a> endsub\n"), HasSubstr("p.ngc:3:"));
}

TEST(Program, LoadMissingFileThrows) {
  EXPECT_THROW((void)Program::load("/nonexistent/x.ngc"), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
