// Flattening: the flattened program makes exactly the source's motions and dwells, has no O-word,
// parameter or expression left, keeps comments where the source runs through them, and its
// numbers read back to the same doubles.
#include "pkm/cnc/flatten.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using pkm::test::kSeed;

const fs::path kRoot = PKM_SOURCE_DIR;

MoveCollector movesOf(const std::string& text, const InterpreterOptions& options = {}) {
  Interpreter interp(options);
  MoveCollector c;
  (void)interp.run(Program::parse(text, "t.ngc"), c);
  return c;
}

/// Same motions (kind, end, centre, turns, plane, feed) and dwells; lines may differ.
void expectSameMotion(const MoveCollector& a, const MoveCollector& b, const std::string& what) {
  ASSERT_EQ(a.moves.size(), b.moves.size()) << what;
  for (std::size_t i = 0; i < a.moves.size(); ++i) {
    const Move& x = a.moves[i];
    const Move& y = b.moves[i];
    EXPECT_EQ(x.kind, y.kind) << what << " move " << i;
    EXPECT_EQ(x.turns, y.turns) << what << " move " << i;
    EXPECT_EQ(x.plane, y.plane) << what << " move " << i;
    for (std::size_t k = 0; k < 6; ++k) EXPECT_EQ(x.end[k], y.end[k]) << what << " move " << i;
    for (std::size_t k = 0; k < 3; ++k) {
      if (!std::isnan(x.centre[k]) || !std::isnan(y.centre[k])) {
        EXPECT_EQ(x.centre[k], y.centre[k]) << what << " move " << i;
      }
    }
    if (!std::isnan(x.feed) || !std::isnan(y.feed)) {
      EXPECT_EQ(x.feed, y.feed) << what;
    }
  }
  ASSERT_EQ(a.dwells.size(), b.dwells.size()) << what;
  for (std::size_t i = 0; i < a.dwells.size(); ++i) {
    EXPECT_EQ(a.dwells[i].after_moves, b.dwells[i].after_moves) << what;
    EXPECT_EQ(a.dwells[i].seconds, b.dwells[i].seconds) << what;
  }
}

TEST(FormatGcodeNumber, ShortestExactAndNoExponent) {
  EXPECT_EQ(formatGcodeNumber(0.0), "0");
  EXPECT_EQ(formatGcodeNumber(-0.0), "0");
  EXPECT_EQ(formatGcodeNumber(92.1), "92.1");
  EXPECT_EQ(formatGcodeNumber(-3.0), "-3");
  EXPECT_EQ(formatGcodeNumber(1e-5), "0.00001");
  EXPECT_EQ(formatGcodeNumber(2.5e20), "250000000000000000000");
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> mantissa(-10.0, 10.0);
  std::uniform_int_distribution<int> exponent(-12, 12);
  for (int i = 0; i < 2000; ++i) {
    const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
    const std::string s = formatGcodeNumber(v);
    EXPECT_EQ(s.find_first_of("eE"), std::string::npos) << s;
    EXPECT_EQ(std::strtod(s.c_str(), nullptr), v) << s;
  }
}

TEST(Flatten, UnrollsSubsLoopsAndConditionsKeepingComments) {
  const std::string src =
      "%\n"
      "(header)\n"
      "#<r> = 5\n"
      "o100 sub (a circle)\n"
      "  G1 X[#1] Y0 F[#2*2] ; start\n"
      "  G3 X[#1] Y0 I[-#1] J0\n"
      "o100 endsub\n"
      "N5 G21 G90\n"
      "/ M8\n"
      "o101 repeat [2]\n"
      "  (pass)\n"
      "  o100 call [#<r>] [300]\n"
      "  #<r> = [#<r> + 0.5]\n"
      "o101 endrepeat\n"
      "o102 if [#<r> GT 5.5]\n"
      "  (big)\n"
      "  G0 Z[#<r> * 2]\n"
      "o102 else\n"
      "  G0 Z0\n"
      "o102 endif\n"
      "M2\n"
      "%\n"
      "ignored after the closing percent\n";
  const FlatProgram f = flattenProgram(src, "t.ngc");
  EXPECT_EQ(f.text,
            "%\n"
            "(header)\n"
            "G21 G90\n"
            "/M8\n"
            "  (pass)\n"
            "G1 X5 Y0 F600 ; start\n"
            "G3 X5 Y0 I-5 J0\n"
            "  (pass)\n"
            "G1 X5.5 Y0 F600 ; start\n"
            "G3 X5.5 Y0 I-5.5 J0\n"
            "  (big)\n"
            "G0 Z12\n"
            "M2\n"
            "%\n");
  EXPECT_EQ(f.blocks, 8u);
  EXPECT_TRUE(f.had_o_words);
  const std::vector<std::size_t> lines{1, 2, 8, 9, 11, 5, 6, 11, 5, 6, 16, 17, 21, 22};
  EXPECT_EQ(f.source_line, lines);
  expectSameMotion(movesOf(src), movesOf(f.text), "inline program");
}

TEST(Flatten, ShippedExamplesAndCorpusMakeTheSameMotions) {
  InterpreterOptions o;
  std::size_t programs = 0;
  // Each folder with its tool table (the corpus's is rs274's sample table in mm: the diameters
  // its cutter-compensation programs were checked with).
  for (const auto& [dir, table] : {std::pair{kRoot / "examples/gcode", "tools.tbl"},
                                   std::pair{kRoot / "tests/cnc/corpus", "tools_mm.tbl"}}) {
    o.tools = ToolTable::load((dir / table).string(), 1.0);
    for (const auto& e : fs::directory_iterator(dir)) {
      const std::string name = e.path().filename().string();
      if (e.path().extension() != ".ngc" || name.rfind("err_", 0) == 0) continue;
      const std::string text = Program::readFile(e.path().string());
      FlatProgram f;
      try {
        f = flattenProgram(text, name, o);
      } catch (const IoError& err) {  // programs that need rs274's inch tool table, and M73
        const std::string what = err.what();
        EXPECT_TRUE(what.find("tool table") != std::string::npos ||
                    what.find("does not support M73") != std::string::npos)
            << what;
        continue;
      }
      ++programs;
      const Program flat = Program::parse(f.text, name);
      for (const Block& b : flat.blocks()) {
        EXPECT_EQ(b.o_kind, OKind::kNone) << name;
        EXPECT_TRUE(b.assignments.empty()) << name << ":" << b.line;
        for (const Word& w : b.words) EXPECT_TRUE(w.value.isConstant()) << name << ":" << b.line;
      }
      expectSameMotion(movesOf(text, o), movesOf(f.text, o), name);
      // Flattening is idempotent on its own output.
      EXPECT_EQ(flattenProgram(f.text, name, o).text, f.text) << name;
    }
  }
  EXPECT_GE(programs, 15u);
}

TEST(Flatten, LinesStayWithinLinuxcncLimit) {
  // Seven words of 1/3 multiples and a 120-character comment: the comment goes on its own line.
  // Built by appending: GCC 12 reports a false -Warray-bounds for literal + string + literal.
  std::string comment(120, 'c');
  comment.front() = '(';
  comment.back() = ')';
  std::string a = "#1 = [1/3]\nG1 X#1 Y[#1*2] Z[#1*4] A[#1*5] B[#1*7] C[#1*8] F[#1*10] ";
  a.append(comment).append("\nM2\n");
  const FlatProgram f = flattenProgram(a, "t.ngc");
  EXPECT_EQ(f.text.rfind(comment + "\nG1 X0.3333333333333333 ", 0), 0u) << f.text;
  expectSameMotion(movesOf(a), movesOf(f.text), "long comment");
  // Eight G codes and ten 25-character values exceed 256 characters: rounded to 9 decimals.
  const std::string b =
      "#2 = [-1/300000]\nG17 G90 G94 G21 G54 G99 G64 P[-#2] Q[-#2] G1 X#2 Y#2 Z#2 A#2 B#2 C#2 "
      "F[-#2] S[-#2]\nM2\n";
  const FlatProgram g = flattenProgram(b, "t.ngc");
  EXPECT_NE(g.text.find(" X-0.000003333 "), std::string::npos) << g.text;
  const MoveCollector mb = movesOf(b), mg = movesOf(g.text);
  ASSERT_EQ(mb.moves.size(), 1u);
  ASSERT_EQ(mg.moves.size(), 1u);
  for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(mg.moves[0].end[k], mb.moves[0].end[k], 1e-9);
  for (const std::string& text : {f.text, g.text})
    for (std::size_t start = 0; start < text.size();) {
      const std::size_t nl = text.find('\n', start);
      EXPECT_LE(nl - start, 256u) << text;
      start = nl + 1;
    }
}

TEST(Flatten, ErrorsNameTheSourceLine) {
  try {
    (void)flattenProgram("o1 sub\nG1 X1\no1 endsub\no1 call\n", "bad.ngc");
    ADD_FAILURE();
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.ngc:2: cannot do G1 with zero feed rate"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
