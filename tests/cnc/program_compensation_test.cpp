// Program pre-distortion: IK_nominal(command) == IK_calibrated(desired) at every point to 1e-6
// mm, the written text reads back to the same commands, line structure (N numbers, comments,
// non-motion lines) kept, subdivided motions on inserted lines, O-word programs flattened, offsets
// and units, unsupported constructs rejected with their line; the hybrid machine's X2 term. Home
// returns and canned cycles: program_compensation_cycles_test.cpp.
#include "pkm/cnc/program_compensation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <string>
#include <vector>

#include "cnc/program_compensation_models.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"
#include "support/sample_models.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::test::calibrated;
using pkm::test::kJointMatch;
using pkm::test::kTextDigits;
using pkm::test::kTol;

const char* const kProgram =
    "%\n"
    "(header comment)\n"
    "N10 G21 G90 G17\n"
    "N20 G0 X0 Y0 Z200 (rapid to home)\n"
    "N30 G1 X30 F600 M3 S1000 ; cut\n"
    "#1 = 5\n"
    "N40 G2 X50 Y20 I0 J20\n"
    "N50 G1 Y[#1 * 2] C10\n"
    "M2\n"
    "%\n";

TEST(CompensateProgram, RoundTripThroughBothKinematics) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r = compensateProgram(kProgram, "p.ngc", nominal, cal, o);
  ASSERT_FALSE(r.points.empty());
  EXPECT_GT(r.max_correction, 0.1);  // the errors matter
  HexapodJointConverter n(nominal), c(cal);
  for (const auto& p : r.points) {
    const kin::StrutVector qn = n.solve(p.command), qc = c.solve(p.desired);
    EXPECT_LE((qn - qc).cwiseAbs().maxCoeff(), kJointMatch) << "line " << p.line;
  }
  // The text reads back (rs274 semantics) to the same commands.
  const Program back = Program::parse(r.text, "out.ngc");
  MoveCollector moves;
  Interpreter interp;
  (void)interp.run(back, moves);
  ASSERT_EQ(moves.moves.size(), r.points.size());
  for (std::size_t i = 0; i < moves.moves.size(); ++i) {
    for (std::size_t k = 0; k < 6; ++k)
      EXPECT_NEAR(moves.moves[i].end[k], r.points[i].command[k], kTextDigits);
    EXPECT_NE(moves.moves[i].kind, MoveKind::kArc);
  }
}

TEST(CompensateProgram, KeepsLineStructure) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r = compensateProgram(kProgram, "p.ngc", nominal, cal, o);
  std::vector<std::string> lines;
  for (std::size_t s = 0, e; s < r.text.size(); s = e + 1) {
    e = r.text.find('\n', s);
    lines.push_back(r.text.substr(s, e - s));
  }
  EXPECT_EQ(lines[0], "%");
  EXPECT_EQ(lines[1], "(header comment)");
  EXPECT_EQ(lines[2], "N10 G21 G90 G17");
  EXPECT_EQ(lines[3].rfind("N20 G0 X", 0), 0u) << lines[3];
  EXPECT_NE(lines[3].find("(rapid to home)"), std::string::npos);
  EXPECT_EQ(lines[4].rfind("N30 G1 X", 0), 0u) << lines[4];
  EXPECT_NE(lines[4].find("M3 S1000 ; cut"), std::string::npos);
  EXPECT_EQ(lines[4].find("X30 "), std::string::npos);  // the old axis word is gone
  EXPECT_EQ(r.text.back(), '\n');
  EXPECT_NE(r.text.find("(pkm: line 7 segment 2/"), std::string::npos);
  EXPECT_EQ(r.motion_lines, 4u);
  EXPECT_EQ(lines.size(), 10u + r.added_lines);
  EXPECT_EQ(lines[lines.size() - 2], "M2");
}

TEST(CompensateProgram, AMotionThatGoesNowhereKeepsThePreviousCommand) {
  // `G1 F150` moves to where the machine is (rs274): its line gets the previous point's command
  // and the lines after it keep theirs.
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r =
      compensateProgram("G0 X0 Y0 Z200\nG1 F150\nG1 X10\nG1 F200\nM2\n", "p.ngc", nominal, cal, o);
  std::vector<std::string> axes;  // each line's "X.. Y.. Z.. A.. B.. C.." words
  for (std::size_t s = 0, e; s < r.text.size(); s = e + 1) {
    e = r.text.find('\n', s);
    const std::string line = r.text.substr(s, e - s);
    const std::size_t x = line.find('X'), c = line.find(' ', line.find('C'));
    axes.push_back(x == std::string::npos ? line : line.substr(x, c - x));
  }
  ASSERT_GE(axes.size(), 4u);
  EXPECT_EQ(axes[1], axes[0]);                // G1 F150: where the G0 left the machine
  EXPECT_EQ(axes.end()[-2], axes.end()[-3]);  // G1 F200: where the last segment of X10 ended
  EXPECT_NE(axes[2], axes[1]);
  EXPECT_EQ(r.text.back(), '\n');
}

TEST(CompensateProgram, IdentityForEqualModels) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const ProgramCompensation r = compensateProgram(kProgram, "p.ngc", nominal, nominal);
  for (const auto& p : r.points)
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(p.command[k], p.desired[k], kJointMatch);
}

TEST(CompensateProgram, RejectsUnsupportedWithLine) {
  const kin::HexapodModel m = pkm::test::millingModel();
  for (const char* text : {"G0 X0 Y0 Z200 M3\nG87 X1 Z150 R190 I1 J0 K160 F100\n",
                           "G0 X0 Y0 Z200\nG33 X1 K1\n",
                           "G0 X0 Y0 Z200\nG81 G4 P1 X1 Z150 R190 F100\n",
                           "G0 X0 Y0 Z200\nG93 G1 X1 F10\n",
                           "G0 X0 Y0 Z200\nG92 X[#1]\n",
                           "G0 X0 Y0 Z200\nG10 L20 P1 X[1 + #2]\n",
                           "G0 X0 Y0 Z200\nG88 X1 Z150 R190 P1 F100 S100 M3\n",
                           "G0 X0 Y0 Z200\nG52 X5\n",
                           "G0 X0 Y0 Z200\nG10 L10 P1 Z0\n",
                           "G0 X0 Y0 Z200\nG10 L11 P1 Z0\n",
                           "G0 X0 Y0 Z200\nG0 @10 ^30\n",
                           "G0 X0 Y0 Z200\nG41.1 D2 G91 G1 X10 F100\n",
                           "G10 L2 P1 R30\nG0 X1\n"}) {
    try {
      (void)compensateProgram(text, "bad.ngc", m, m);
      ADD_FAILURE() << text;
    } catch (const pkm::IoError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.ngc:2:"), std::string::npos) << e.what();
    }
  }
}

/// A program with a subroutine called in a loop is flattened, then rewritten: the output has no
/// O-word, reads back to the commands, and an unsupported code inside the subroutine is reported
/// on its source line.
TEST(CompensateProgram, OWordProgramsAreFlattenedFirst) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  const char* const program =
      "G21 G90 G17\n"
      "o<square> sub (side #1 at height #2)\n"
      "  G1 X[-#1] Y[-#1] Z#2 F600\n"
      "  G1 X#1\n"
      "  G2 Y#1 I0 J#1 (a half circle)\n"
      "  G1 X[-#1] Y[-#1]\n"
      "o<square> endsub\n"
      "G0 X0 Y0 Z200\n"
      "#<k> = 0\n"
      "o1 while [#<k> LT 3]\n"
      "  o<square> call [10 + 5 * #<k>] [190 - #<k>]\n"
      "  #<k> = [#<k> + 1]\n"
      "o1 endwhile\n"
      "M2\n";
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r = compensateProgram(program, "p.ngc", nominal, cal, o);
  EXPECT_EQ(r.flattened_blocks, 15u);  // G21, G0, M2 and 3 passes of 4 motions
  EXPECT_GT(r.max_correction, 0.1);
  const Program out = Program::parse(r.text, "out.ngc");
  for (const Block& b : out.blocks()) EXPECT_EQ(b.o_kind, OKind::kNone) << r.text;
  MoveCollector back;
  Interpreter i;
  (void)i.run(out, back);
  ASSERT_EQ(back.moves.size(), r.points.size()) << r.text;
  for (std::size_t k = 0; k < back.moves.size(); ++k)
    for (std::size_t a = 0; a < 6; ++a)
      EXPECT_NEAR(back.moves[k].end[a], r.points[k].command[a], kTextDigits) << k;
  HexapodJointConverter n(nominal), c(cal);
  for (const auto& p : r.points) {
    const kin::StrutVector qn = n.solve(p.command), qc = c.solve(p.desired);
    EXPECT_LE((qn - qc).cwiseAbs().maxCoeff(), kJointMatch);
  }
  EXPECT_NE(r.text.find("(a half circle)"), std::string::npos) << r.text;
  try {
    (void)compensateProgram(
        "G0 X0 Y0 Z200 S100 M3\no1 sub\n  G1 Z190 F100\n  G88 X1 Z150 R190 P1\no1 endsub\no1 "
        "call\n",
        "bad.ngc",
        nominal,
        nominal);
    ADD_FAILURE();
  } catch (const pkm::IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.ngc:4: G88 is not supported"), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("(line 3 of the flattened program)"), std::string::npos)
        << e.what();
  }
}

/// Work offsets (G54..G59.3 set by G10 L2, G92.1), tool length offsets (G43.1), inches (G20),
/// incremental distance (G91) and G53: the written words, read back by the interpreter with the
/// same offsets and modes, command exactly the compensated machine positions.
TEST(CompensateProgram, OffsetsUnitsAndIncrementalReadBackToTheCommands) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  const char* const program =
      "G21 G90 G17\n"
      "G10 L2 P2 X5 Y-3 Z150 C2\n"
      "G55\n"
      "G0 X0 Y0 Z50\n"
      "G1 X20 F600\n"
      "G10 L2 P1 X-2 Y1\n"
      "G1 X10 Y10\n"
      "G43.1 Z-20\n"
      "G1 Z60\n"
      "G91 G1 X5 Y-5 C3\n"
      "G2 X10 Y0 I5 J0\n"
      "G90 G20 G1 X0.5 Y0.25\n"
      "G21 G53 G0 X0 Y0 Z200\n"
      "G92.1 G49 G54 G1 X-10 Y5 Z190 C0\n"
      "N150 G92 X0 Y0 C5 (here is zero)\n"
      "G1 X4 Y-3 C8\n"
      "G10 L20 P3 Z10 B1\n"
      "G56 G1 Z12 B2\n"
      "G20 G92 X1\n"
      "G1 X1.5\n"
      "M2\n";
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r = compensateProgram(program, "p.ngc", nominal, cal, o);
  EXPECT_GT(r.max_correction, 0.1);
  // Every desired point is where the source program goes (the moves of the source program).
  MoveCollector source;
  Interpreter a;
  (void)a.run(Program::parse(program, "p.ngc"), source);
  EXPECT_EQ(r.motion_lines, source.moves.size());
  (void)pkm::test::expectReadsBackToCommands(r, kTextDigits * 25.4);
  // The modes stay on their lines (after the new motion words); G53 is repeated on the inserted
  // segment lines of its motion; no trailing blanks appear.
  EXPECT_NE(r.text.find(" G91\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find(" G21 G53\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\nG53 G0 X"), std::string::npos) << r.text;
  // G92 / G10 L20 keep their place and words; the values are shifted by the correction there.
  EXPECT_EQ(r.offset_lines, 3u);
  EXPECT_NE(r.text.find("\nN150 G92 X"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find(" (here is zero)\n"), std::string::npos) << r.text;
  EXPECT_EQ(r.text.find("G92 X0 Y0 C5 "), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\nG10 L20 P3 Z"), std::string::npos) << r.text;
  EXPECT_EQ(r.text.find(" \n"), std::string::npos) << r.text;
}

TEST(CompensateHybridProgram, AddsTheX2TermAndOptionallyTheBaseFrame) {
  // b₁ = (1e-6, -4e-5, 2e-6) per mm of X2, a 3 mrad base rotation about z and a 0.1 mm offset.
  pkm::compensation::HybridSquarenessCompensation c;
  c.per_x2 = Eigen::Vector3d(1e-6, -4e-5, 2e-6);
  c.base_rpy = Eigen::Vector3d(0.0, 0.0, 3e-3);
  c.base_rotation = Eigen::AngleAxisd(3e-3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  c.base_offset = Eigen::Vector3d(0.1, 0.0, 0.0);
  const std::string text = "G21 G90\nG0 X0 Y0 Z10\nG1 X100 Y50 Z-2 F600 (cut)\nM2\n";
  const double x2 = 2000.0;
  const ProgramCompensation in_controller = compensateHybridProgram(text, "h.ngc", c, x2, true);
  const ProgramCompensation full = compensateHybridProgram(text, "h.ngc", c, x2, false);
  ASSERT_EQ(in_controller.points.size(), full.points.size());
  for (std::size_t i = 0; i < full.points.size(); ++i) {
    const Axes& d = full.points[i].desired;
    const Eigen::Vector3d p(d[0], d[1], d[2]);
    const Eigen::Vector3d shifted = p + x2 * c.per_x2;
    const Eigen::Vector3d rotated = c.base_rotation * p + c.base_offset + x2 * c.per_x2;
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(in_controller.points[i].command[static_cast<std::size_t>(k)], shifted[k], 1e-12);
      EXPECT_NEAR(full.points[i].command[static_cast<std::size_t>(k)], rotated[k], 1e-12);
    }
  }
  EXPECT_NE(in_controller.text.find("(cut)"), std::string::npos);  // comments kept
  EXPECT_THROW((void)compensateHybridProgram(text, "h.ngc", c, std::nan(""), true),
               pkm::InvalidArgument);
}

/// A cutter-compensated program is written as its compensated tool path: the G41/G42 and D
/// words go (the controller must not offset the corrected path again), and the text reads back,
/// without compensation, to the commands, which follow the compensated path of the source.
TEST(CompensateProgram, CutterCompensationIsWrittenIntoThePath) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const char* const program =
      "G21 G90 G17 F600\n"
      "G0 X-20 Y-20 Z200\n"
      "G41.1 D6 G1 X0 Y0 (entry)\n"
      "G1 X30\n"
      "G3 X40 Y10 R10\n"
      "G1 Y30 ; concave next\n"
      "G1 X0 Y20\n"
      "G40 G1 X-20 Y-20\n"
      "M2\n";
  const ProgramCompensation r = compensateProgram(program, "p.ngc", nominal, nominal);
  EXPECT_EQ(r.text.find("G41"), std::string::npos) << r.text;
  EXPECT_EQ(r.text.find("D6"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("(entry) (pkm: cutter compensation is in the path)"), std::string::npos)
      << r.text;
  const std::vector<Move> back = pkm::test::expectReadsBackToCommands(r, kTextDigits);
  // The written path ends each source move where the compensated source move ends.
  for (const Move& m : pkm::test::movesOf(program, "p.ngc")) {
    bool found = false;
    for (const Move& w : back)
      found = found || (std::abs(w.end[0] - m.end[0]) < kTextDigits &&
                        std::abs(w.end[1] - m.end[1]) < kTextDigits && w.end[2] == m.end[2]);
    EXPECT_TRUE(found) << "line " << m.line << "\n" << r.text;
  }
}

}  // namespace PKM_TEST_NS
