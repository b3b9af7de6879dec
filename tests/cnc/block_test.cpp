// The line reader: comments, case and blanks, N, '/', '%', words, parameter settings, O-words.
#include "pkm/cnc/block.hpp"

#include <gtest/gtest.h>

#include "pkm/cnc/gcode_error.hpp"

namespace pkm::cnc {
namespace {

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

TEST(Block, MalformedLinesThrow) {
  for (const char* bad : {"G1 X1 X2",
                          "G1 (unclosed",
                          "G1 ) X1",
                          "G1 E5",
                          "G1 X1 N10",
                          "X[1+",
                          "#1 2",
                          "o100",
                          "o100 frobnicate",
                          "o100 if",
                          "o100 while [1] [2]",
                          "G1 @5 ^30",
                          "G1 X1 o100 call",
                          "G1 (a (nested) b)",
                          "G1 X$"}) {
    Block b;
    EXPECT_THROW(parseLine(bad, b), GcodeError) << bad;
  }
  Block b;
  EXPECT_THROW(parseLine(std::string(300, 'x'), b), GcodeError);
}

}  // namespace
}  // namespace pkm::cnc
