// Interpreter: each modal code, offsets, arcs and helices, control flow, error paths with line
// numbers. Expected values are hand-computed from LinuxCNC's documented semantics (and were
// cross-checked with rs274, see rs274_compare_test.cpp).
#include "pkm/cnc/interpreter.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <tuple>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace pkm::cnc {
namespace PKM_TEST_NS {

using pkm::test::kTolRoundTrip;
using ::testing::HasSubstr;

std::vector<Move> run(const std::string& text, InterpreterOptions options = {}) {
  Interpreter interp(std::move(options));
  MoveCollector c;
  interp.run(Program::parse(text, "t.ngc"), c);
  return c.moves;
}

std::string errorOf(const std::string& text, InterpreterOptions options = {}) {
  try {
    (void)run(text, std::move(options));
  } catch (const IoError& e) {
    return e.what();
  }
  return "no error";
}

void expectEnd(const Move& m, double x, double y, double z) {
  EXPECT_NEAR(m.end[0], x, kTolRoundTrip);
  EXPECT_NEAR(m.end[1], y, kTolRoundTrip);
  EXPECT_NEAR(m.end[2], z, kTolRoundTrip);
}

TEST(Interpreter, RapidAndFeedWithLineNumbers) {
  const auto m = run("G21 G90\nG0 X1 Y2 Z3\n\nG1 X4 F100\nM2\n");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].kind, MoveKind::kRapid);
  EXPECT_EQ(m[0].line, 2u);
  EXPECT_TRUE(std::isnan(m[0].feed));
  EXPECT_EQ(m[1].kind, MoveKind::kLinear);
  EXPECT_EQ(m[1].line, 4u);
  EXPECT_EQ(m[1].feed, 100.0);
  expectEnd(m[1], 4, 2, 3);
}

TEST(Interpreter, InchAndFeedUnits) {
  // F is converted with the units active when it executes: F comes before G20 in a block.
  const auto m = run("G20\nF10\nG1 X1\nG21 G1 X10\nM2\n");
  ASSERT_EQ(m.size(), 2u);
  EXPECT_NEAR(m[0].end[0], 25.4, kTolRoundTrip);
  EXPECT_NEAR(m[0].feed, 254.0, kTolRoundTrip);
  EXPECT_NEAR(m[1].end[0], 10.0, kTolRoundTrip);
  EXPECT_NEAR(m[1].feed, 254.0, kTolRoundTrip);  // switching units does not rescale F
}

TEST(Interpreter, RotaryOnlyMovesAreFedInDegreesAMinuteWhateverTheLengthUnit) {
  // LinuxCNC: F of a move of X, Y or Z is a length a minute (inch under G20); of a rotary-only
  // move, degrees a minute, unscaled (rs274 prints SET_FEED_RATE(300) either way). A move of
  // XYZ and A together is fed along XYZ.
  const auto m = run("G20\nF300\nG1 A90\nG1 X1 C10\nG1 C40\nG21\nG1 A0\nG1 X0\nM2\n");
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[0].feed, 300.0);                    // deg/min
  EXPECT_NEAR(m[1].feed, 7620.0, kTolRoundTrip);  // mm/min
  EXPECT_EQ(m[2].feed, 300.0);                    // rotary only again
  EXPECT_EQ(m[3].feed, 300.0);                    // G21 rescales neither
  EXPECT_NEAR(m[4].feed, 7620.0, kTolRoundTrip);
  // Inverse time: the rotary-only move's length is its angle either way.
  const auto g93 = run("G20\nG93 G1 A90 F2\nM2\n");
  ASSERT_EQ(g93.size(), 1u);
  EXPECT_NEAR(g93[0].feed, 180.0, kTolRoundTrip);  // 90 deg in 1/2 min
}

TEST(Interpreter, StartupCodeSetsTheModesTheProgramStartsIn) {
  InterpreterOptions o;
  o.startup_code = "G20 G91";
  o.startup_source = "m.ini:7";
  const auto m = run("G1 X1 F10\nG1 X1\nM2\n", o);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_NEAR(m[0].end[0], 25.4, kTolRoundTrip);
  EXPECT_NEAR(m[1].end[0], 50.8, kTolRoundTrip);  // incremental from the start-up code
  o.startup_code = "G0 X1";
  EXPECT_EQ(errorOf("G0 X0\n", o),
            "m.ini:7: RS274NGC_STARTUP_CODE moves the machine; it may set "
            "modes only");
  o.startup_code = "G20 G999";
  EXPECT_THAT(errorOf("G0 X0\n", o), HasSubstr("m.ini:7: RS274NGC_STARTUP_CODE:1: "));
}

TEST(Interpreter, AMotionWordWithoutAxesMovesNowhereAsRs274Does) {
  // rs274: `G1 F150` gives SET_FEED_RATE(150) and STRAIGHT_FEED to the current position; `G0`
  // alone a STRAIGHT_TRAVERSE there; a block with F only (modal G1) no motion.
  const auto m = run("G21 G90\nG0 X1 Y2 Z3\nG1 F150\nF300\nG0\nG1\nX5\nM2\n");
  ASSERT_EQ(m.size(), 5u);
  EXPECT_EQ(m[1].line, 3u);
  EXPECT_EQ(m[1].kind, MoveKind::kLinear);
  EXPECT_EQ(m[1].feed, 150.0);
  expectEnd(m[1], 1, 2, 3);
  EXPECT_EQ(m[2].line, 5u);
  EXPECT_EQ(m[2].kind, MoveKind::kRapid);
  EXPECT_EQ(m[3].line, 6u);
  EXPECT_EQ(m[3].feed, 300.0);
  expectEnd(m[4], 5, 2, 3);
  EXPECT_THAT(errorOf("G1\n"), HasSubstr("zero feed rate"));  // as rs274: G1 needs a feed
}

TEST(Interpreter, IncrementalDistance) {
  const auto m = run("G91 G0 X1 Y1\nX1\nG90 X0\nM2\n");
  expectEnd(m[1], 2, 1, 0);
  expectEnd(m[2], 0, 1, 0);
}

TEST(Interpreter, WorkOffsetsAndG53) {
  const auto m = run(
      "G10 L2 P2 X10 Y20 Z30\nG55 G0 X1 Y1 Z1\nG53 G0 X0\nG10 L20 P2 X5\nG0 X5\nG54 G0 X0\nM2\n");
  expectEnd(m[0], 11, 21, 31);
  expectEnd(m[1], 0, 21, 31);  // G53: machine coordinates
  // L20: current program X (-10) becomes 5 -> origin = -10 + 10 - 5 = -5.
  expectEnd(m[2], 0, 21, 31);
  expectEnd(m[3], 0, 21, 31);
}

TEST(Interpreter, G92Family) {
  const auto m = run("G0 X10\nG92 X0\nG0 X1\nG92.2\nG0 X1\nG92.3\nG0 X1\nG92.1\nG0 X1\nM2\n");
  expectEnd(m[1], 11, 0, 0);
  expectEnd(m[2], 1, 0, 0);
  expectEnd(m[3], 11, 0, 0);
  expectEnd(m[4], 1, 0, 0);
}

TEST(Interpreter, ToolLengthOffsets) {
  InterpreterOptions o;
  o.tools = ToolTable::parse("T1 P1 Z25\nT2 P2 Z10\n", 1.0, "t.tbl");
  const auto m = run("T1 M6\nG43\nG0 Z0\nG43 H2\nG0 Z0\nG43.1 Z-3\nG0 Z0\nG49\nG0 Z0\nM2\n", o);
  expectEnd(m[0], 0, 0, 25);
  expectEnd(m[1], 0, 0, 10);
  expectEnd(m[2], 0, 0, -3);
  expectEnd(m[3], 0, 0, 0);
  EXPECT_THAT(errorOf("G43 H7\n", o), HasSubstr("t.ngc:1: tool 7"));
}

TEST(Interpreter, ArcIjkAndFullCircleHelix) {
  const auto m = run("G0 X10 Y0\nG3 X10 Y0 I-10 J0 Z-4 P2 F50\nG2 X-10 Y0 I-10 J0\nM2\n");
  ASSERT_EQ(m.size(), 3u);
  EXPECT_EQ(m[1].kind, MoveKind::kArc);
  EXPECT_EQ(m[1].turns, 2);
  EXPECT_NEAR(m[1].centre[0], 0.0, kTolRoundTrip);
  EXPECT_NEAR(m[1].centre[1], 0.0, kTolRoundTrip);
  EXPECT_TRUE(std::isnan(m[1].centre[2]));
  expectEnd(m[1], 10, 0, -4);
  EXPECT_EQ(m[2].turns, -1);
  EXPECT_EQ(m[2].plane, Plane::kXY);
}

TEST(Interpreter, ArcRadiusSignRule) {
  const auto m = run("G3 X0 Y10 R-7.0710678 F10\nG0 X0 Y0\nG3 X0 Y10 R7.0710678\nM2\n");
  EXPECT_NEAR(m[0].centre[0], 5.0, 1e-6);
  EXPECT_NEAR(m[0].centre[1], 5.0, 1e-6);
  EXPECT_NEAR(m[2].centre[0], -5.0, 1e-6);
}

TEST(Interpreter, ArcsInXzAndYzPlanes) {
  const auto m = run("F1\nG18 G2 X10 Z0 I5 K0 Y3\nG19 G0 X0 Y0 Z0\nG3 Y0 Z10 J0 K5\nM2\n");
  EXPECT_EQ(m[0].plane, Plane::kXZ);
  EXPECT_NEAR(m[0].centre[0], 5.0, kTolRoundTrip);
  EXPECT_NEAR(m[0].centre[2], 0.0, kTolRoundTrip);
  EXPECT_TRUE(std::isnan(m[0].centre[1]));
  EXPECT_NEAR(m[0].end[1], 3.0, kTolRoundTrip);
  EXPECT_EQ(m[2].plane, Plane::kYZ);
  EXPECT_NEAR(m[2].centre[2], 5.0, kTolRoundTrip);
  EXPECT_TRUE(std::isnan(m[2].centre[0]));
}

TEST(Interpreter, AbsoluteArcCentreG901) {
  const auto m = run("G10 L2 P1 X100\nG0 X0 Y0\nG90.1 G2 X10 Y0 I5 J0 F1\nM2\n");
  EXPECT_NEAR(m[1].centre[0], 105.0, kTolRoundTrip);
}

TEST(Interpreter, InverseTimeFeed) {
  const auto m = run("G93 G1 X30 Y40 F2\nM2\n");
  EXPECT_NEAR(m[0].feed, 100.0, kTolRoundTrip);  // 50 mm in 1/2 min
  EXPECT_THAT(errorOf("G93\nG1 X30 F2\nG1 X40\n"), HasSubstr("t.ngc:3: F word missing"));
}

TEST(Interpreter, CannedCycleThroughTheInterpreter) {
  const auto m = run("G0 Z10\nG98 G81 X1 Y1 Z-3 R2 F100\nX2\nG80\nM2\n");
  ASSERT_EQ(m.size(), 9u);
  expectEnd(m[4], 1, 1, 10);
  expectEnd(m[5], 2, 1, 10);
  EXPECT_EQ(m[5].line, 3u);
}

TEST(Interpreter, DwellsReachTheSinkInOrderWithTheMotions) {
  struct Recorder final : MoveSink {
    void onMove(const Move&) override { ++moves; }
    void onDwell(std::size_t line, double seconds) override {
      dwells.push_back({moves, line, seconds});
    }
    std::size_t moves = 0;
    std::vector<std::tuple<std::size_t, std::size_t, double>> dwells;
  } r;
  Interpreter interp;
  interp.run(Program::parse("G4 P0.5\nG0 Z10\nG99 G82 X1 Y1 Z-3 R2 P1.5 F100\nM2\n", "t.ngc"), r);
  // G4 before any motion; G82's dwell after G0, the rapids to the hole and to R and the feed.
  ASSERT_EQ(r.dwells.size(), 2u);
  EXPECT_EQ(r.dwells[0], std::make_tuple(std::size_t{0}, std::size_t{1}, 0.5));
  EXPECT_EQ(r.dwells[1], std::make_tuple(std::size_t{4}, std::size_t{3}, 1.5));
  EXPECT_EQ(r.moves, 5u);
}

TEST(Interpreter, BoringCyclesTrackTheSpindle) {
  // G88 stops for a manual retraction: no motion, but a following G91 move starts from R.
  const auto m = run("S500 M3 F100\nG0 Z10\nG99 G88 X1 Y1 Z-3 R2 P1\nG91 G0 Z5\nM2\n");
  ASSERT_EQ(m.size(), 5u);
  expectEnd(m[3], 1, 1, -3);
  expectEnd(m[4], 1, 1, 7);
  EXPECT_THAT(errorOf("F100\nG0 Z10\nG86 X1 Z-3 R2 P1\n"),
              HasSubstr("t.ngc:3: spindle not turning in G86"));
  EXPECT_THAT(errorOf("F100 M3\nM5\nG84 X1 Z-3 R2\n"), HasSubstr("t.ngc:3: spindle not turning"));
  EXPECT_THAT(errorOf("F100 M4\nG84 X1 Z-3 R2\n"), HasSubstr("t.ngc:2: spindle turning counter"));
  EXPECT_THAT(errorOf("F100 M3\nG87 X1 Z-3 R2 I1 K-1\n"), HasSubstr("t.ngc:2: J word missing"));
  EXPECT_THAT(errorOf("F100 M3\nG88 X1 Z-3 R2\n"), HasSubstr("t.ngc:2: dwell time P word missing"));
  EXPECT_THAT(errorOf("F100 M3\nG86 X1 Z-3 R2 P-1\n"), HasSubstr("t.ngc:2: negative dwell"));
}

TEST(Interpreter, HomeReturnsG28AndG30) {
  // G28.1 stores the machine position (offsets included); G28 Z goes up to the intermediate
  // point and then homes Z only; G30 without words homes every axis to #5181.. (0 here).
  const auto m = run("G10 L2 P1 X10\nG0 X1 Y2 Z3\nG28.1\nG0 X5 Z7\nG91 G28 Z2\nG90 G30\nM2\n");
  ASSERT_EQ(m.size(), 6u);
  expectEnd(m[2], 15, 2, 9);  // intermediate: Z + 2
  expectEnd(m[3], 15, 2, 3);  // home Z only
  expectEnd(m[4], 15, 2, 3);  // G30 without words: the intermediate rapid goes nowhere
  expectEnd(m[5], 0, 0, 0);   // then all axes to the G30 position
  EXPECT_EQ(m[5].kind, MoveKind::kRapid);
  EXPECT_THAT(errorOf("G1 G28 X1 F100\n"), HasSubstr("t.ngc:1: cannot use two G codes"));
  EXPECT_THAT(errorOf("G28 G92 X1\n"), HasSubstr("t.ngc:1: two G codes from the same modal"));
}

TEST(Interpreter, ControlFlow) {
  const auto m =
      run("#1 = 0\no1 while [#1 LT 3]\nG0 X#1\n#1 = [#1 + 1]\no1 endwhile\n"
          "o2 repeat [2]\nG0 Y1\no2 endrepeat\n"
          "#2 = 5\no3 if [#2 LT 3]\nG0 Z1\no3 elseif [#2 LT 6]\nG0 Z2\no3 else\nG0 Z3\no3 endif\n"
          "o4 do\nG0 A1\no4 while [0]\n"
          "#3 = 0\no5 while [1]\n#3 = [#3 + 1]\no6 if [#3 EQ 2]\no5 continue\no6 endif\n"
          "o7 if [#3 GT 3]\no5 break\no7 endif\nG0 B#3\no5 endwhile\nM2\n");
  ASSERT_EQ(m.size(), 9u);
  EXPECT_EQ(m[2].end[0], 2.0);
  EXPECT_EQ(m[4].end[1], 1.0);
  EXPECT_EQ(m[5].end[2], 2.0);
  EXPECT_EQ(m[6].end[3], 1.0);
  EXPECT_EQ(m[7].end[4], 1.0);
  EXPECT_EQ(m[8].end[4], 3.0);
}

TEST(Interpreter, SubroutinesWithArgumentsAndReturnValues) {
  const auto m =
      run("o<twice> sub\no<twice> return [#1 * 2]\no<twice> endsub\n"
          "o<go> sub\nG0 X#1 Y#2\no<twice> call [#1]\nG0 Z#<_value>\no<go> endsub\n"
          "#1 = 9\no<go> call [3] [4]\nG0 A#1\nM2\n");
  ASSERT_EQ(m.size(), 3u);
  expectEnd(m[0], 3, 4, 0);
  EXPECT_EQ(m[1].end[2], 6.0);
  EXPECT_EQ(m[2].end[3], 9.0);  // #1 restored after the call
}

TEST(Interpreter, RunawayLoopIsRejected) {
  InterpreterOptions o;
  o.max_loop_iterations = 1000;
  EXPECT_THAT(errorOf("G0 X1\no1 while [1]\no1 endwhile\n", o),
              HasSubstr("t.ngc:3: loop o1 exceeded 1000 iterations"));
  EXPECT_THAT(errorOf("o1 do\no1 while [1]\n", o), HasSubstr("exceeded"));
  EXPECT_THAT(errorOf("o<r> sub\no<r> call\no<r> endsub\no<r> call\n"), HasSubstr("nested deeper"));
  // A loop within the iteration guard whose motions exceed the run's budget: refused at the
  // motion past it, before the moves pile up.
  o.max_moves = 10;
  EXPECT_THAT(errorOf("#1=0\no1 while [#1 LT 100]\nG1 X#1 F9\n#1=[#1+1]\no1 endwhile\n", o),
              HasSubstr("t.ngc:3: the program makes more than 10 motions"));
}

TEST(Interpreter, ErrorsNameTheLine) {
  EXPECT_THAT(errorOf("G0 X1\nG5.1 X2\n"), HasSubstr("t.ngc:2: unsupported G code G5.1"));
  EXPECT_THAT(errorOf("G0 X1\nM62\n"), HasSubstr("t.ngc:2: M62 needs a P word"));
  EXPECT_THAT(errorOf("G0 X1\nM120\n"), HasSubstr("t.ngc:2: user M code M120"));
  EXPECT_THAT(errorOf("G1 X1 D1 F1\n"), HasSubstr("t.ngc:1: D word with no G41"));
  EXPECT_THAT(errorOf("G0 X1\nG1 X[1/0] F1\n"), HasSubstr("t.ngc:2: attempt to divide by zero"));
  EXPECT_THAT(errorOf("G0 X1\no<nope> call\n"), HasSubstr("t.ngc:2: call to undefined subroutine"));
  EXPECT_THAT(errorOf("G0 G1 X1\n"), HasSubstr("t.ngc:1: two G codes from the same modal group"));
  EXPECT_THAT(errorOf("G17 G18\n"), HasSubstr("same modal group"));
  EXPECT_THAT(errorOf("M3 M4\n"), HasSubstr("same modal group"));
  EXPECT_THAT(errorOf("X1\n"), HasSubstr("without a G code"));
  EXPECT_THAT(errorOf("G80 X1\n"), HasSubstr("G80"));
  EXPECT_THAT(errorOf("G1 X1\n"), HasSubstr("zero feed rate"));
  EXPECT_THAT(errorOf("G2 X1 F1\n"), HasSubstr("needs R or at least one of I and J"));
  EXPECT_THAT(errorOf("G2 X1 I1 K1 F1\n"), HasSubstr("K word given for an arc in the XY plane"));
  EXPECT_THAT(errorOf("G4\n"), HasSubstr("G4 needs a P word"));
  EXPECT_THAT(errorOf("G10 L1 P1 Z1\n"),
              HasSubstr("t.ngc:1: G10 L1: tool 1 is not in the tool table"));
  EXPECT_THAT(errorOf("G10 L3 P1 Z1\n"), HasSubstr("t.ngc:1: G10 L3 is not supported"));
  EXPECT_THAT(errorOf("G92\n"), HasSubstr("G92 needs"));
  EXPECT_THAT(errorOf("G92 X1 G1 Y1\n"), HasSubstr("both use axis values"));
  EXPECT_THAT(errorOf("G81 X1 R2 F1\n"), HasSubstr("Z missing"));
  EXPECT_THAT(errorOf("G83 X1 Z-1 R2 F1\n"), HasSubstr("Q word missing"));
  EXPECT_THAT(errorOf("G18 G81 X1 Z-1 R2 F1\n"),
              HasSubstr("t.ngc:1: Y missing in the first block of a canned cycle"));
  EXPECT_THAT(errorOf("G91 G53 G0 X1\n"), HasSubstr("G53"));
  EXPECT_THAT(errorOf("G0 U1\n"), HasSubstr("u axis"));
  EXPECT_THAT(errorOf("G1 X1 F1\nI5\n"), HasSubstr("t.ngc:2:"));
  EXPECT_THAT(errorOf("#<x> = #<y>\n"), HasSubstr("#<y> not defined"));
  EXPECT_THAT(errorOf("G2 X1 Y1 P1.5 I1 F1\n"), HasSubstr("positive integer"));
}

TEST(Interpreter, BlockDeleteSwitch) {
  InterpreterOptions o;
  o.block_delete = true;
  EXPECT_EQ(run("G0 X1\n/G0 X2\nM2\n", o).size(), 1u);
  EXPECT_EQ(run("G0 X1\n/G0 X2\nM2\n").size(), 2u);
}

TEST(Interpreter, ProgramEndStopsAndStateIsKept) {
  Interpreter interp;
  MoveCollector c;
  const RunSummary s = interp.run(Program::parse("G20 G0 X1\nM30\nG0 X2\n"), c);
  EXPECT_TRUE(s.ended_by_m2);
  EXPECT_EQ(s.moves, 1u);
  EXPECT_TRUE(interp.state().inch);
  EXPECT_NEAR(interp.state().machine[0], 25.4, kTolRoundTrip);
}

TEST(Interpreter, PositionParameters) {
  const auto m = run("G20 G10 L2 P1 X1\nG0 X2\nG0 Y#5420 Z#5221\nM2\n");
  EXPECT_NEAR(m[1].end[1], 2 * 25.4, kTolRoundTrip);
  EXPECT_NEAR(m[1].end[2], 25.4, kTolRoundTrip);
}

/// The moves of `text` run while it is read.
std::vector<Move> runStreamed(const std::string& text, InterpreterOptions options = {}) {
  Interpreter interp(std::move(options));
  MoveCollector c;
  LineReader reader(text, "t.ngc");
  interp.runStream(reader, c);
  return c.moves;
}

/// Streaming gives the moves of the whole-program run on every corpus program without O-words.
TEST(InterpreterStream, SameMovesAsTheWholeProgramOnTheCorpus) {
  const std::filesystem::path dir = std::filesystem::path(PKM_SOURCE_DIR) / "tests/cnc/corpus";
  const ToolTable tools = ToolTable::load((dir / "tools_mm.tbl").string(), 1.0);
  int compared = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".ngc" || entry.path().stem().string().starts_with("err_"))
      continue;
    const std::string text = Program::readFile(entry.path().string());
    if (LineReader::mayHaveOWords(text)) continue;
    InterpreterOptions options;
    options.tools = tools;
    const std::vector<Move> whole = run(text, options), streamed = runStreamed(text, options);
    ASSERT_EQ(whole.size(), streamed.size()) << entry.path();
    for (std::size_t i = 0; i < whole.size(); ++i) {
      EXPECT_EQ(whole[i].line, streamed[i].line);
      EXPECT_EQ(whole[i].end, streamed[i].end) << entry.path() << " move " << i;
      EXPECT_EQ(whole[i].turns, streamed[i].turns);
    }
    ++compared;
  }
  EXPECT_GE(compared, 8);
}

TEST(InterpreterStream, ErrorsAndTheEndOfTheProgram) {
  std::string err;
  try {
    (void)runStreamed("G0 X1\no100 sub\no100 endsub\n");
  } catch (const IoError& e) {
    err = e.what();
  }
  EXPECT_THAT(err, HasSubstr("t.ngc:2: o100 statement: O-words need the whole program"));
  // After M2 nothing is run, and a malformed line there is not an error: LinuxCNC stops reading.
  EXPECT_EQ(runStreamed("G0 X1\nM2\nG0 X5\n").size(), 1u);
  EXPECT_EQ(runStreamed("G0 X1\nM2\nG0 X5 (unclosed\n").size(), 1u);
  // Execution errors carry their line as in run().
  try {
    (void)runStreamed("G0 X1\nG1 X2\n");
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("t.ngc:2:"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::cnc
