// The line reader: comments, case and blanks, N, '/', '%', words, parameter settings, O-words.
#include "pkm/cnc/block.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

class NoParams : public ParameterSource {
 public:
  double numbered(int) override { return 0.0; }
  double named(const std::string&) override { return 0.0; }
  bool exists(const std::string&) override { return false; }
};

Block parse(const std::string& text) {
  Block b;
  parseLine(text, b);
  return b;
}

TEST(Block, BlanksCaseAndCommentsAreDropped) {
  NoParams p;
  const Block b = parse("g0X +0. 12 34y 7 (comment) ; rest");
  ASSERT_EQ(b.words.size(), 3u);
  EXPECT_EQ(b.words[0].letter, 'g');
  EXPECT_EQ(b.words[1].letter, 'x');
  EXPECT_DOUBLE_EQ(b.words[1].value.evaluate(p), 0.1234);
  EXPECT_DOUBLE_EQ(b.words[2].value.evaluate(p), 7.0);
}

TEST(Block, LineNumberBlockDeleteAndPercent) {
  const Block b = parse("/N56.78 G1 X1");
  EXPECT_TRUE(b.block_delete);
  EXPECT_EQ(b.words.size(), 2u);
  Block c;
  EXPECT_EQ(parseLine("  % ", c), LineMark::kPercent);
  EXPECT_TRUE(parse("(only a comment)").empty());
  EXPECT_TRUE(parse("").empty());
}

TEST(Block, ParameterSettings) {
  NoParams p;
  const Block b = parse("#1=2 #<Name>=[3*2] #[1+1]=4");
  ASSERT_EQ(b.assignments.size(), 3u);
  EXPECT_FALSE(b.assignments[0].named);
  EXPECT_TRUE(b.assignments[1].named);
  EXPECT_EQ(b.assignments[1].name, "name");
  EXPECT_DOUBLE_EQ(b.assignments[1].value.evaluate(p), 6.0);
  EXPECT_DOUBLE_EQ(b.assignments[2].index.evaluate(p), 2.0);
}

TEST(Block, OWords) {
  const Block call = parse("o<Sphere> call [1] [2+3] [#1]");
  EXPECT_EQ(call.o_kind, OKind::kCall);
  EXPECT_EQ(call.o_name, "sphere");
  EXPECT_EQ(call.o_args.size(), 3u);
  const Block w = parse("O100 WHILE [#1 LT 3]");
  EXPECT_EQ(w.o_kind, OKind::kWhile);
  EXPECT_EQ(w.o_name, "100");
  EXPECT_EQ(parse("o100 endwhile").o_kind, OKind::kEndWhile);
  EXPECT_EQ(parse("o1 do").o_kind, OKind::kDo);
  EXPECT_EQ(parse("o1 repeat [3]").o_kind, OKind::kRepeat);
  EXPECT_EQ(parse("o1 return [3]").o_kind, OKind::kReturn);
}

/// What parseLine makes of `text`: the words (letter=value), assignments, O-word and marks, or
/// "error: message".
std::string describe(const std::string& text) {
  NoParams p;
  Block b;
  std::string out;
  try {
    if (parseLine(text, b) == LineMark::kPercent) out += "% ";
  } catch (const GcodeError& e) {
    return std::string("error: ") + e.what();
  }
  if (b.block_delete) out += "/ ";
  for (const Word& w : b.words) {
    if (!w.value.isConstant()) {  // an expression: the same either way, its value aside
      out += std::string(1, w.letter) + "=expression ";
      continue;
    }
    char buf[40];
    std::snprintf(buf, sizeof buf, "%c=%.17g ", w.letter, w.value.evaluate(p));
    out += buf;
  }
  out += "assignments=" + std::to_string(b.assignments.size());
  out += " o=" + std::to_string(static_cast<int>(b.o_kind)) + b.o_name;
  return out;
}

// parseLine reads the common "N.. G1 X.. Y.." line without normalizing it first; anything else
// goes the general way. A leading "()" (an empty comment) forces the general way, so random
// lines built from the characters that matter must read the same with and without it, errors
// included.
TEST(Block, FastAndGeneralReadingAgree) {
  static const std::vector<std::string> kTokens{
      "G", "g",  "X",  "x",  "Y",   "Z",     "F", "M",     "N",
      "n", "O",  "E",  "e",  "I",   "T",     "1", "23",    "0.5",
      ".", "-",  "+",  "5.", ".25", "1.2.3", "7", "00012", "12345678901234567890",
      " ", "  ", "\t", "\r", "(c)", ";",     "#", "[",     "]",
      "/", "%",  "@",  "*",  "\x01"};
  std::mt19937_64 rng(42);
  std::uniform_int_distribution<std::size_t> pick(0, kTokens.size() - 1), count(0, 12);
  for (int k = 0; k < 200000; ++k) {
    std::string line;
    for (std::size_t n = count(rng); n > 0; --n) line += kTokens[pick(rng)];
    ASSERT_EQ(describe(line), describe("()" + line)) << "line '" << line << "'";
  }
  // Typical CAM lines, and lines close to them that the fast path must hand on.
  for (const char* line : {"N10 G1 X90.013 Y-1.5 Z-0.948 F1500",
                           "n20g1x1y2",
                           "X1 Y2\r",
                           "G1 X1 2",
                           "G1 X1 .5",
                           "G1 X 1",
                           "N 10 G1 X1",
                           "N10.5 G1 X1",
                           "G1 X1 X2",
                           "G1 G0 M3 M8 X1",
                           "G1 X-",
                           "G1 X1E5",
                           "G1 X1 (move)",
                           "   ",
                           ""}) {
    EXPECT_EQ(describe(line), describe(std::string("()") + line)) << line;
  }
  EXPECT_EQ(describe("N10 G1 X1 2 Y.5"), "g=1 x=12 y=0.5 assignments=0 o=0");
}

TEST(Block, MalformedLinesThrow) {
  for (const char* bad : {"G1 X1 X2",
                          "G1 (unclosed",
                          "G1 ) X1",
                          "G1 E5 E6",
                          "G1 X1 N10",
                          "X[1+",
                          "#1 2",
                          "o",
                          "o100 frobnicate",
                          "o100 if",
                          "o100 while [1] [2]",
                          "G1 @5 @6",
                          "G1 X1 o100 call",
                          "G1 (a (nested) b)",
                          "G1 X$"}) {
    Block b;
    EXPECT_THROW(parseLine(bad, b), GcodeError) << bad;
  }
  Block b;
  EXPECT_THROW(parseLine(std::string(300, 'x'), b), GcodeError);
}

TEST(Block, PolarWordsProgramLabelsAndEWords) {
  Block b;
  parseLine("G1 @5 ^30 E2", b);
  ASSERT_EQ(b.words.size(), 4u);
  EXPECT_EQ(b.words[1].letter, kPolarRadius);
  EXPECT_EQ(b.words[2].letter, kPolarAngle);
  EXPECT_EQ(writtenLetter(b.words[1].letter), '@');
  EXPECT_EQ(writtenLetter(b.words[2].letter), '^');
  EXPECT_EQ(b.words[3].letter, 'e');
  parseLine("O0100 (a Fanuc program label)", b);
  EXPECT_EQ(b.o_kind, OKind::kProgram);
  EXPECT_EQ(b.o_name, "0100");
  parseLine("o[#2 * 10] call [1]", b);
  EXPECT_EQ(b.o_kind, OKind::kCall);
  EXPECT_TRUE(b.o_label.has_value());
  EXPECT_THROW(parseLine("o[1] sub", b), GcodeError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
