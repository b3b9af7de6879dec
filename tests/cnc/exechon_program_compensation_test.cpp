// Exechon program pre-distortion: the nominal machine's readings for the command equal the
// calibrated machine's readings for the desired point (both orientation modes), the text reads
// back to the commands without a B word, equal models change nothing, bad points are refused with
// their line; the virtual head's angles round-trip through the tool direction.
#include "pkm/cnc/exechon_program_compensation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "kinematics/exechon_sample_models.hpp"
#include "pkm/cnc/interpreter.hpp"
#include "pkm/cnc/program.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using namespace pkm::cnc;
namespace kin = pkm::kinematics;
using pkm::test::kSeed;
using pkm::test::kTolRoundTrip;

constexpr double kReadingMatch = 1e-6;  ///< mm: the hexapod pre-distortion's requirement
constexpr double kWristMatch = 1e-8;    ///< rad
constexpr double kTextDigits = 1e-8;    ///< mm/deg: the 9 decimals of the written words
constexpr double kTol = 0.01;           ///< mm, chordal tolerance

/// The sample machine with sub-millimetre geometric errors (the "real" machine).
kin::ExechonModel calibratedModel(const kin::ExechonModel& nominal) {
  kin::ExechonModel m = nominal;
  m.name = nominal.name + "-calibrated";
  m.tripod.dA += 0.3;
  m.tripod.pB -= 0.2;
  m.tripod.hx += 0.15;
  m.tripod.l12A += 0.1;
  m.legs[1].length_offset += 0.05;
  m.wrist.a0 += 0.002;
  m.wrist.tool_length += 0.2;
  return m;
}

const char* const kProgram =
    "G21 G90 G17\n"
    "N10 G0 X0 Y0 Z0 A0 C0 (start)\n"
    "N20 G1 X20 Y-10 Z-15 F600\n"
    "N30 G2 X20 Y10 I0 J10 A5 C30\n"
    "N40 G1 X-10 A8 C60 ; tilt\n"
    "M2\n";

ExechonProgramCompensationOptions optionsFor(const kin::ExechonModel& m, ExechonOrientation o) {
  ExechonProgramCompensationOptions options;
  options.orientation = o;
  options.interpolation = exechonInterpolation(m, kTol);
  return options;
}

class ExechonCompensation : public ::testing::TestWithParam<ExechonOrientation> {};

TEST_P(ExechonCompensation, NominalReadingsOfTheCommandAreTheRealMachinesOfTheDesiredPoint) {
  const kin::ExechonModel nominal = pkm::test::machineModel();
  const kin::ExechonModel real = calibratedModel(nominal);
  const ProgramCompensation r =
      compensateExechonProgram(kProgram, "p.ngc", nominal, real, optionsFor(real, GetParam()));
  ASSERT_GT(r.points.size(), 10u);
  EXPECT_GT(r.max_correction, 0.1);  // the errors matter
  ExechonJointConverter controller(nominal, GetParam()), machine(real, GetParam());
  for (const auto& p : r.points) {
    const ExechonPathSample c = controller.solve(p.command), d = machine.solve(p.desired);
    ASSERT_TRUE(c.ok() && d.ok()) << "line " << p.line;
    EXPECT_LE((c.readings - d.readings).cwiseAbs().maxCoeff(), kReadingMatch) << "line " << p.line;
    EXPECT_NEAR(c.config.c, d.config.c, kWristMatch) << "line " << p.line;
    EXPECT_NEAR(c.config.a, d.config.a, kWristMatch) << "line " << p.line;
    EXPECT_EQ(p.command[4], 0.0);
  }
  // The text reads back to the commands; no B word is written.
  MoveCollector moves;
  Interpreter interp;
  (void)interp.run(Program::parse(r.text, "out.ngc"), moves);
  ASSERT_EQ(moves.moves.size(), r.points.size());
  for (std::size_t i = 0; i < moves.moves.size(); ++i)
    for (std::size_t k = 0; k < 6; ++k)
      EXPECT_NEAR(moves.moves[i].end[k], r.points[i].command[k], kTextDigits);
  EXPECT_EQ(r.text.find(" B"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find(" (start)\n"), std::string::npos) << r.text;
  EXPECT_NE(r.text.find(" ; tilt\n"), std::string::npos) << r.text;
}

TEST_P(ExechonCompensation, EqualModelsChangeNothing) {
  const kin::ExechonModel m = pkm::test::machineModel();
  const ProgramCompensation r =
      compensateExechonProgram(kProgram, "p.ngc", m, m, optionsFor(m, GetParam()));
  for (const auto& p : r.points)
    for (std::size_t k = 0; k < 6; ++k) EXPECT_NEAR(p.command[k], p.desired[k], kReadingMatch);
}

INSTANTIATE_TEST_SUITE_P(Orientation,
                         ExechonCompensation,
                         ::testing::Values(ExechonOrientation::kToolVector,
                                           ExechonOrientation::kWristAxes));

TEST(ExechonProgramCompensation, RefusesPointsItCannotServeWithTheirLine) {
  const kin::ExechonModel nominal = pkm::test::machineModel();
  const kin::ExechonModel real = calibratedModel(nominal);
  const auto options = optionsFor(real, ExechonOrientation::kToolVector);
  for (const char* text : {"G0 X0 Y0 Z0\nG1 B5 F100\n", "G0 X0 Y0 Z0\nG0 X1e5\n"}) {
    try {
      (void)compensateExechonProgram(text, "bad.ngc", nominal, real, options);
      ADD_FAILURE() << text;
    } catch (const pkm::IoError& e) {
      EXPECT_NE(std::string(e.what()).find("bad.ngc:2:"), std::string::npos) << e.what();
    }
  }
  kin::ExechonModel inches = real;
  inches.unit = pkm::LengthUnit::kInch;
  EXPECT_THROW((void)compensateExechonProgram("G0 X0\n", "p.ngc", nominal, inches, options),
               pkm::InvalidArgument);
}

TEST(ToolAnglesFromDirection, InvertsTheVirtualHead) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> a(-89.0, 89.0), c(-179.0, 179.0);
  for (int i = 0; i < 200; ++i) {
    const double ai = a(rng), ci = c(rng);
    const auto back = toolAnglesFromDirection(toolDirectionFromAngles(ai, ci), ai, ci);
    if (std::abs(ai) < 1e-6) continue;  // vertical: C undefined
    EXPECT_NEAR(back[0], ai, kTolRoundTrip);
    EXPECT_NEAR(back[1], ci, kTolRoundTrip);
    // The other solution (−A, C + 180°) when it is the nearer one, in the turn nearest C.
    const auto flip = toolAnglesFromDirection(toolDirectionFromAngles(ai, ci), -ai, ci + 540.0);
    EXPECT_NEAR(flip[0], -ai, kTolRoundTrip);
    EXPECT_NEAR(flip[1], ci + 540.0, kTolRoundTrip);
  }
  // A vertical tool keeps C.
  const auto v = toolAnglesFromDirection(Eigen::Vector3d(0, 0, -2), 0.0, 33.0);
  EXPECT_NEAR(v[0], 0.0, kTolRoundTrip);
  EXPECT_EQ(v[1], 33.0);
  EXPECT_THROW((void)toolAnglesFromDirection(Eigen::Vector3d::Zero(), 0, 0), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
