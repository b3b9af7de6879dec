// Program pre-distortion of the expanded constructs: G28/G30 home returns, drilling cycles (with
// their dwells) and tapping and boring cycles (with their spindle and override codes) become
// motions each pre-distorted (IK_nominal(command) == IK_calibrated(desired) to 1e-6 mm), dwells
// and M codes in the order the cycles make them; the text reads back to the commands.
#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "cnc/program_compensation_models.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/joint_path.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/cnc/program_compensation.hpp"
#include "support/sample_models.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::test::calibrated;
using pkm::test::kJointMatch;
using pkm::test::kTextDigits;
using pkm::test::kTol;

/// G28/G30 are expanded into their two rapids (intermediate point, stored position), each
/// pre-distorted; G28.1 stays.
TEST(CompensateProgram, HomeReturnsAreExpanded) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  const char* const program =
      "G21 G90\n"
      "G0 X0 Y0 Z200\n"
      "G1 X10 Y5 Z190 F600\n"
      "G28.1\n"
      "G0 X30 Z195\n"
      "G91 G28 Z2 (up 2 mm, then home in Z)\n"
      "G90 G30 X5\n"
      "M2\n";
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r = compensateProgram(program, "p.ngc", nominal, cal, o);
  MoveCollector source;
  Interpreter a;
  (void)a.run(Program::parse(program, "p.ngc"), source);
  ASSERT_EQ(source.moves.size(), 7u);
  EXPECT_EQ(source.moves[4].end[2], 190.0);  // G28 Z: the Z stored by G28.1
  EXPECT_EQ(source.moves[6].end[0], 0.0);    // G30 X: #5181 = 0
  (void)pkm::test::expectReadsBackToCommands(r, kTextDigits);
  HexapodJointConverter n(nominal), c(cal);
  for (const auto& p : r.points) {
    const kin::StrutVector qn = n.solve(p.command), qc = c.solve(p.desired);
    EXPECT_LE((qn - qc).cwiseAbs().maxCoeff(), kJointMatch);
  }
  EXPECT_EQ(r.text.find("G28 "), std::string::npos) << r.text;
  EXPECT_EQ(r.text.find("G30"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\nG28.1\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("(up 2 mm, then home in Z)"), std::string::npos) << r.text;
}

/// Records the dwells of a program with the number of motions before each.
struct DwellSink final : MoveSink {
  void onMove(const Move&) override { ++moves; }
  void onDwell(std::size_t, double seconds) override { dwells.emplace_back(moves, seconds); }
  std::size_t moves = 0;
  std::vector<std::pair<std::size_t, double>> dwells;
};

/// Drilling cycles (G81, G82 with a dwell, G83, G73 under G91 with L2, G85, G89 with a dwell, and
/// a line that repeats G81) are expanded: the output reads back to the commands, has no cycle left,
/// and dwells where the source did, at the bottom of the hole.
TEST(CompensateProgram, DrillingCyclesAreExpanded) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  const char* const program =
      "G21 G90 G17\n"
      "G0 X0 Y0 Z200\n"
      "N30 G98 G81 X10 Y5 Z150 R190 F300 (first hole)\n"
      "X20\n"
      "G99 G82 X30 Y-5 Z155 R185 P0.5\n"
      "G83 X0 Y-10 Z160 R190 Q10\n"
      "G91 G73 X5 Y0 Z-20 R-5 Q8 L2\n"
      "G90 G85 X-10 Y0 Z170 R190\n"
      "G89 X-20 Z170 R190 P1.25\n"
      "G80 G0 Z200\n"
      "M2\n";
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  o.interpolation.max_step = 5.0;  // the feeds into the holes get several segments
  const ProgramCompensation r = compensateProgram(program, "p.ngc", nominal, cal, o);
  EXPECT_GT(r.max_correction, 0.1);
  HexapodJointConverter n(nominal), c(cal);
  for (const auto& p : r.points) {
    const kin::StrutVector qn = n.solve(p.command), qc = c.solve(p.desired);
    EXPECT_LE((qn - qc).cwiseAbs().maxCoeff(), kJointMatch) << "line " << p.line;
  }
  DwellSink out;
  Interpreter b;
  (void)b.run(Program::parse(r.text, "out.ngc"), out);
  MoveCollector back;
  Interpreter b2;
  (void)b2.run(Program::parse(r.text, "out.ngc"), back);
  ASSERT_EQ(back.moves.size(), r.points.size()) << r.text;
  for (std::size_t i = 0; i < back.moves.size(); ++i)
    for (std::size_t k = 0; k < 6; ++k)
      EXPECT_NEAR(back.moves[i].end[k], r.points[i].command[k], kTextDigits) << i << "\n" << r.text;
  // The source's dwells, in order, after the motion that reaches the bottom of their hole.
  DwellSink source;
  Interpreter a;
  (void)a.run(Program::parse(program, "p.ngc"), source);
  ASSERT_EQ(source.dwells.size(), 2u);
  ASSERT_EQ(out.dwells.size(), 2u) << r.text;
  const double bottoms[] = {155.0, 170.0};
  for (std::size_t d = 0; d < 2; ++d) {
    EXPECT_EQ(out.dwells[d].second, source.dwells[d].second);
    ASSERT_GT(out.dwells[d].first, 0u);
    EXPECT_NEAR(r.points[out.dwells[d].first - 1].desired[2], bottoms[d], 1e-9);
  }
  // No cycle is left; N numbers, comments and the other words stay.
  for (const char* cycle : {"G81", "G82", "G83", "G73", "G85", "G89", " R", " Q", " L2"})
    EXPECT_EQ(r.text.find(cycle), std::string::npos) << cycle << "\n" << r.text;
  EXPECT_NE(r.text.find("\nN30 G0 X"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find(" G98 F300 (first hole)\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\nG4 P0.5 (pkm: line 5 dwell)\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\nG4 P1.25 (pkm: line 9 dwell)\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find(" G80\n"), std::string::npos) << r.text;  // after the new words
  EXPECT_EQ(r.motion_lines, 9u);
}

/// Records the spindle, override and dwell events of a program as (motions before, code): the
/// source's from the cycles (onCycleAction, onDwell), the output's from its M-code and G4 blocks.
struct EventSink final : MoveSink {
  [[nodiscard]] bool wantsBlocks() const override { return reportBlocks; }
  void onMove(const Move&) override { ++moves; }
  void onDwell(std::size_t, double seconds) override { events.emplace_back(moves, 4.0 + seconds); }
  void onCycleAction(std::size_t, CycleAction a) override {
    static constexpr double kCode[] = {5, 3, 4, 19, 49, 48, 0};
    events.emplace_back(moves, 100.0 + kCode[static_cast<int>(a)]);
  }
  void onBlock(const Block&, std::size_t, const std::vector<EvaluatedWord>& words) override {
    for (const EvaluatedWord& w : words)
      if (w.letter == 'm' && w.value != 2.0) events.emplace_back(moves, 100.0 + w.value);
  }
  bool reportBlocks = false;
  std::size_t moves = 0;
  std::vector<std::pair<std::size_t, double>> events;
};

/// G84 (with its override switches), G74 and G86 are expanded into motions, dwells and M codes
/// in the order the cycles make them, each at the same desired position.
TEST(CompensateProgram, TappingAndBoringCyclesAreExpanded) {
  const kin::HexapodModel nominal = pkm::test::millingModel();
  const kin::HexapodModel cal = calibrated(nominal);
  const char* const program =
      "G21 G90 G17 S500\n"
      "G0 X0 Y0 Z200\n"
      "M3\n"
      "N30 G98 G84 X10 Y5 Z170 R190 F300 P0.3 (tap)\n"
      "G99 G86 X20 Z175 R185 P0.5\n"
      "M4\n"
      "G74 X-10 Z170 R190\n"
      "G80 G0 Z200\n"
      "M2\n";
  ProgramCompensationOptions o;
  o.interpolation = jointSpaceInterpolation(cal, kTol);
  const ProgramCompensation r = compensateProgram(program, "p.ngc", nominal, cal, o);
  EXPECT_GT(r.max_correction, 0.1);
  HexapodJointConverter n(nominal), c(cal);
  for (const auto& p : r.points) {
    const kin::StrutVector qn = n.solve(p.command), qc = c.solve(p.desired);
    EXPECT_LE((qn - qc).cwiseAbs().maxCoeff(), kJointMatch);
  }
  EventSink source;
  MoveCollector source_moves;
  {
    Interpreter a;
    (void)a.run(Program::parse(program, "p.ngc"), source);
    Interpreter a2;
    (void)a2.run(Program::parse(program, "p.ngc"), source_moves);
  }
  EventSink out;
  out.reportBlocks = true;
  Interpreter b;
  (void)b.run(Program::parse(r.text, "out.ngc"), out);
  EXPECT_EQ(out.moves, r.points.size());
  // The output's events: the source's M3/M4 lines, then the cycles' events.
  std::vector<std::pair<std::size_t, double>> got;
  for (const auto& e : out.events)
    if (e.first > 1) got.push_back(e);  // drop M3 before the first cycle
  std::vector<std::pair<std::size_t, double>> want;
  for (const auto& e : source.events) want.push_back(e);
  // The M4 block of line 6 is in the output's list only: it is skipped below.
  ASSERT_EQ(got.size(), want.size() + 1) << r.text;
  std::size_t j = 0;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if (got[i].second == 104.0 && (j >= want.size() || want[j].second != 104.0)) continue;  // M4
    ASSERT_LT(j, want.size());
    EXPECT_EQ(got[i].second, want[j].second) << i;
    // The same desired position: the end of the source motion before the event.
    const auto& d = r.points[got[i].first - 1].desired;
    const auto& e = source_moves.moves[want[j].first - 1].end;
    for (std::size_t k = 0; k < 3; ++k) EXPECT_NEAR(d[k], e[k], 1e-9) << i;
    ++j;
  }
  EXPECT_EQ(j, want.size());
  for (const char* cycle : {"G84", "G74", "G86", " R1", " P0.3 (tap)"})
    EXPECT_EQ(r.text.find(cycle), std::string::npos) << cycle << "\n" << r.text;
  EXPECT_NE(r.text.find("\nM49 (pkm: line 4 overrides off)\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find("\nM48 (pkm: line 4 overrides on)\n"), std::string::npos) << r.text;
}

}  // namespace PKM_TEST_NS
