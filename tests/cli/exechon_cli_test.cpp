// The CLI contract of `pkm exechon ik|fk|check|drm`, tested by running the built binary
// (PKM_BINARY) as a subprocess: output headers, the paper's numeric example, hybrid splits, IK ->
// FK round trips, limit checks and the DRM table. Machine descriptions and bad input:
// exechon_input_cli_test.cpp.
#include "cli/exechon_cli.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "support/cli_fixture.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::test::kTolRoundTrip;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using pkm::test::CliRun;
using pkm::test::ExechonCli;
using pkm::test::kExitUsage;
using pkm::test::kHybridPoses;
using pkm::test::kZoppiWrist;
using pkm::test::num;
using pkm::test::rowsOf;
using pkm::test::splitFields;
using pkm::test::splitLines;
/// Zoppi et al. 2010 print lengths (mm here) with 4 decimals and angles (deg) with 5.
constexpr double kTolPaperLength = 1e-3;
constexpr double kTolPaperAngleDeg = 1e-5;
constexpr double kTolPaperH = 1e-4;

/// The paper's results for the first point of kZoppiWrist: q, alpha, beta (deg), h (mm) for
/// branch (+,+,+,+).
const double kZoppiQ[3] = {1633.1243, 1491.8367, 912.2380};
constexpr double kZoppiAlphaDeg = 75.03004;
constexpr double kZoppiBetaDeg = -33.20611;
constexpr double kZoppiH = 1403.5096;

// ---------------------------------------------------------------------------------------------
// ik --wrist: the paper's numeric example

TEST_F(ExechonCli, IkWristReproducesThePaper) {
  const CliRun r =
      pkm({"exechon", "ik", "-m", "exechon-zoppi2010", "--wrist", write("W.csv", kZoppiWrist)});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_EQ(lines[0], "q1,q2,q3,alpha,beta,h,status");
  const auto f = splitFields(lines[1]);
  ASSERT_EQ(f.size(), 7u) << lines[1];
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(num(f[i]), kZoppiQ[i], kTolPaperLength) << i;
  EXPECT_NEAR(num(f[3]), kZoppiAlphaDeg, kTolPaperAngleDeg);
  EXPECT_NEAR(num(f[4]), kZoppiBetaDeg, kTolPaperAngleDeg);
  EXPECT_NEAR(num(f[5]), kZoppiH, kTolPaperH);
  EXPECT_EQ(f[6], "ok");
  // S at the base axis: closer to it than hx = 282.8, no real solution. A result, not an error.
  EXPECT_EQ(lines[2], ",,,,,,unreachable");
}

TEST_F(ExechonCli, IkWristReportsStrokeOnALimitedMachine) {
  // mxt700s-like (the default machine): its home (alpha 90°, beta 0, h 1000) puts S at
  // (0, 0, h + hz) in the Zoppi frame with every leg at mid-stroke; 2.75 m further out is beyond
  // the 700 mm stroke.
  const CliRun r =
      pkm({"exechon", "ik", "--wrist", write("W.csv", "sx,sy,sz\n0,0,1250\n0,300,4000\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = rowsOf(r.out);
  ASSERT_EQ(rows.size(), 2u);
  ASSERT_EQ(rows[0].size(), 7u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(num(rows[0][i]), 350.0, kTolPaperLength) << i;
  EXPECT_NEAR(num(rows[0][3]), 90.0, kTolRoundTrip);
  EXPECT_NEAR(num(rows[0][4]), 0.0, kTolRoundTrip);
  EXPECT_NEAR(num(rows[0][5]), 1000.0, kTolRoundTrip);
  EXPECT_EQ(rows[0][6], "ok");
  EXPECT_EQ(rows[1][6], "stroke");
  EXPECT_GT(num(rows[1][0]), 700.0);  // readings are printed all the same
}

// ---------------------------------------------------------------------------------------------
// ik --poses on the hybrid machine

TEST_F(ExechonCli, IkPosesHybridCentredSplit) {
  const CliRun r =
      pkm({"exechon", "ik", "-m", "mxt700s-like", "--poses", write("P.csv", kHybridPoses)});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 5u) << r.out;
  EXPECT_EQ(lines[0], "q1,q2,q3,c,a,drm,status,x2,y2");
  const auto poses = rowsOf(kHybridPoses);
  const auto rows = rowsOf(r.out);
  for (std::size_t k = 0; k < rows.size(); ++k) {
    SCOPED_TRACE(lines[k + 1]);
    ASSERT_EQ(rows[k].size(), 9u);
    EXPECT_EQ(rows[k][6], "ok");
    for (std::size_t i = 0; i < 3; ++i) {  // within the 0..700 stroke
      EXPECT_GE(num(rows[k][i]), 0.0);
      EXPECT_LE(num(rows[k][i]), 700.0);
    }
    // Centred split: the PKM's xP = yP = 0 where the strokes allow (X2 0..4000, Y2 0..450):
    // x2 = x, y2 = -y (y = yP - y2), each clamped to its stroke.
    const double x = num(poses[k][0]), y = num(poses[k][1]);
    EXPECT_EQ(num(rows[k][7]), std::clamp(x, 0.0, 4000.0));
    EXPECT_EQ(num(rows[k][8]), std::clamp(-y, 0.0, 450.0));
  }
  // The first solved row is the DRM reference.
  EXPECT_EQ(rows[0][5], "0");
  // The home tool is vertical with A about -20° (the tripod axis is tilted 20°).
  EXPECT_NEAR(num(rows[0][4]), -20.0, 1e-3);
}

TEST_F(ExechonCli, IkPosesHybridWithGivenX2Y2) {
  // With x2, y2 given, the PKM takes the rest: pkm = (x - x2, y + y2, z). Row 1 puts the PKM at
  // (50, 30, -50), as row 2 does with X2 and Y2 at zero, so both have the same joints.
  const CliRun r = pkm({"exechon",
                        "ik",
                        "-m",
                        "mxt700s-like",
                        "--poses",
                        write("P.csv",
                              "x,y,z,i,j,k,x2,y2\n"
                              "500,20,-50,0,0,-1,450,10\n"
                              "50,30,-50,0,0,-1,0,0\n"
                              "4050,30,-50,0,0,-1,4000,0\n"
                              "5050,30,-50,0,0,-1,5000,0\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 5u) << r.out;
  EXPECT_EQ(lines[0], "q1,q2,q3,c,a,drm,status,x2,y2");
  const auto rows = rowsOf(r.out);
  EXPECT_EQ(rows[0][5], "0");
  for (std::size_t k = 1; k < rows.size(); ++k)
    for (std::size_t i = 0; i < 5; ++i)
      EXPECT_NEAR(num(rows[k][i]), num(rows[0][i]), kTolRoundTrip) << "row " << k << " field " << i;
  EXPECT_EQ(rows[0][7], "450");
  EXPECT_EQ(rows[0][8], "10");
  EXPECT_EQ(rows[1][7], "0");
  EXPECT_EQ(rows[0][6], "ok");
  EXPECT_EQ(rows[2][6], "ok");          // X2 at the end of its stroke
  EXPECT_EQ(rows[3][6], "axis_limit");  // X2 beyond it: the joints are printed all the same
  EXPECT_EQ(rows[3][7], "5000");
}

TEST_F(ExechonCli, IkPosesOnStandAloneTripod) {
  // exechon-zoppi2010: no hybrid section, no x2,y2 columns; the tool point is S (no tool length).
  const CliRun r = pkm({"exechon",
                        "ik",
                        "-m",
                        "exechon-zoppi2010",
                        "--poses",
                        write("P.csv", "x,y,z,i,j,k\n20,700,1020,0,0,1\n0,0,0,0,0,1\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_EQ(lines[0], "q1,q2,q3,c,a,drm,status");
  const auto f = splitFields(lines[1]);
  ASSERT_EQ(f.size(), 7u);
  for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(num(f[i]), kZoppiQ[i], kTolPaperLength) << i;
  EXPECT_EQ(f[5], "0");
  EXPECT_EQ(f[6], "ok");
  EXPECT_EQ(lines[2], ",,,,,,unreachable");
}

// ---------------------------------------------------------------------------------------------
// fk: the ik output read back

/// Expects fk output `fk` to give back the tool points and unit directions of `poses`.
void expectPosesBack(const std::string& fk, const char* poses) {
  const auto lines = splitLines(fk);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "x,y,z,i,j,k,iterations,status");
  const auto want = rowsOf(poses);
  const auto got = rowsOf(fk);
  ASSERT_EQ(got.size(), want.size()) << fk;
  for (std::size_t k = 0; k < got.size(); ++k) {
    SCOPED_TRACE(lines[k + 1]);
    ASSERT_EQ(got[k].size(), 8u);
    EXPECT_EQ(got[k][7], "ok");
    EXPECT_GE(num(got[k][6]), 0.0);
    for (std::size_t i = 0; i < 3; ++i) EXPECT_NEAR(num(got[k][i]), num(want[k][i]), kTolRoundTrip);
    const double n = std::hypot(num(want[k][3]), num(want[k][4]), num(want[k][5]));
    for (std::size_t i = 3; i < 6; ++i)
      EXPECT_NEAR(num(got[k][i]), num(want[k][i]) / n, kTolRoundTrip);
  }
}

TEST_F(ExechonCli, FkOfIkOutputOnHybridMachine) {
  const CliRun ik = pkm({"exechon", "ik", "--poses", write("P.csv", kHybridPoses)});
  ASSERT_EQ(ik.code, 0) << ik.err;
  // The ik output (q1,q2,q3,c,a plus drm, status, x2, y2) is a valid fk input; with x2, y2 the
  // tool point comes back in the work frame.
  const CliRun fk = pkm({"exechon", "fk", "--joints", write("J.csv", ik.out)});
  ASSERT_EQ(fk.code, 0) << fk.err;
  expectPosesBack(fk.out, kHybridPoses);
}

TEST_F(ExechonCli, FkOfIkOutputWithGivenX2Y2) {
  constexpr const char* poses =
      "x,y,z,i,j,k,x2,y2\n500,20,-50,0,0,-1,450,10\n2200,-300,80,0.1,-0.1,-1,2000,100\n";
  const CliRun ik = pkm({"exechon", "ik", "-m", "mxt700s-like", "--poses", write("P.csv", poses)});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const CliRun fk =
      pkm({"exechon", "fk", "-m", "mxt700s-like", "--joints", write("J.csv", ik.out)});
  ASSERT_EQ(fk.code, 0) << fk.err;
  expectPosesBack(fk.out, poses);
}

TEST_F(ExechonCli, FkWithoutX2Y2GivesThePkmFramePoint) {
  // Without x2, y2 columns fk reports the tool in the PKM frame: the work point minus the split.
  const CliRun ik = pkm({"exechon",
                         "ik",
                         "--poses",
                         write("P.csv", "x,y,z,i,j,k,x2,y2\n500,20,-50,0,0,-1,450,10\n")});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const auto f = rowsOf(ik.out).at(0);
  const std::string joints =
      "q1,q2,q3,c,a\n" + f[0] + "," + f[1] + "," + f[2] + "," + f[3] + "," + f[4] + "\n";
  const CliRun fk = pkm({"exechon", "fk", "--joints", write("J.csv", joints)});
  ASSERT_EQ(fk.code, 0) << fk.err;
  expectPosesBack(fk.out, "x,y,z,i,j,k\n50,30,-50,0,0,-1\n");
}

TEST_F(ExechonCli, FkOfIkOutputOnStandAloneTripod) {
  constexpr const char* poses = "x,y,z,i,j,k\n20,700,1020,0,0,1\n40,650,1000,0.2,0.1,1\n";
  const CliRun ik =
      pkm({"exechon", "ik", "-m", "exechon-zoppi2010", "--poses", write("P.csv", poses)});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const CliRun fk =
      pkm({"exechon", "fk", "-m", "exechon-zoppi2010", "--joints", write("J.csv", ik.out)});
  ASSERT_EQ(fk.code, 0) << fk.err;
  expectPosesBack(fk.out, poses);
}

// ---------------------------------------------------------------------------------------------
// check

TEST_F(ExechonCli, CheckReportsStroke) {
  const CliRun r = pkm({"exechon",
                        "check",
                        "--poses",
                        write("P.csv", "x,y,z,i,j,k\n0,0,0,0,0,-1\n0,0,-1000,0,0,-1\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  EXPECT_THAT(lines[0], StartsWith("row,status,min_stroke_margin,stroke_leg,"));
  const std::size_t columns = splitFields(lines[0]).size();
  EXPECT_THAT(lines[1], StartsWith("0,ok,"));
  EXPECT_EQ(splitFields(lines[1]).size(), columns);
  EXPECT_THAT(lines[2], StartsWith("1,stroke,-"));  // negative stroke margin
  EXPECT_THAT(lines[2], HasSubstr("stroke leg A value="));
  EXPECT_EQ(splitFields(lines[2]).size(), columns);
  // At home every leg is at mid-stroke: the margin is half the 700 stroke.
  EXPECT_NEAR(num(splitFields(lines[1])[2]), 350.0, kTolPaperLength);
}

// ---------------------------------------------------------------------------------------------
// drm

TEST_F(ExechonCli, DrmCircleTable) {
  const CliRun r = pkm({"exechon", "drm", "--circle", "0,0,-100,25", "--step", "10"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_FALSE(lines.empty());
  EXPECT_EQ(lines[0], "theta_deg,phi_drm_deg,fit_deg,residual_deg");
  const auto rows = rowsOf(r.out);
  ASSERT_EQ(rows.size(), 37u);  // 0, 10, ..., 360
  for (std::size_t k = 0; k < rows.size(); ++k) {
    ASSERT_EQ(rows[k].size(), 4u);
    EXPECT_NEAR(num(rows[k][0]), 10.0 * static_cast<double>(k), kTolRoundTrip);
    EXPECT_NEAR(num(rows[k][3]), num(rows[k][1]) - num(rows[k][2]), kTolRoundTrip);
  }
  EXPECT_EQ(rows[0][0], "0");
  // The circle closes: the same tool pose at 0° and 360°.
  EXPECT_NEAR(num(rows.back()[1]), num(rows[0][1]), kTolRoundTrip);
  EXPECT_THAT(r.out, HasSubstr("# status ok\n"));
  EXPECT_THAT(r.out, HasSubstr("\n# c5 "));
  EXPECT_THAT(r.out, HasSubstr("\n# max |phi_drm| "));
  ASSERT_THAT(r.out, HasSubstr("\n# max fit deviation "));
  double max_residual = 0;
  for (const auto& row : rows) max_residual = std::max(max_residual, std::abs(num(row[3])));
  const std::string tail = r.out.substr(r.out.find("# max fit deviation ") + 20);
  EXPECT_NEAR(num(tail.substr(0, tail.find(" deg"))), max_residual, kTolRoundTrip);
}

TEST_F(ExechonCli, DrmIsZeroAtTheCentreAndMatchesIk) {
  // The DRM reference is the tool at the circle's centre (exechon_drm.hpp): ik --poses, whose drm
  // column is relative to its first row, gives the same angle for the centre then the point at
  // theta = 0 (centre + r·x). X2 and Y2 at zero put the PKM frame on the work frame.
  const CliRun drm = pkm({"exechon", "drm", "--circle", "0,0,-100,25", "--step", "10"});
  ASSERT_EQ(drm.code, 0) << drm.err;
  const CliRun ik = pkm({"exechon",
                         "ik",
                         "--poses",
                         write("P.csv",
                               "x,y,z,i,j,k,x2,y2\n0,0,-100,0,0,-1,0,0\n25,0,-100,0,0,-1,0,0\n"
                               "0,25,-100,0,0,-1,0,0\n")});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const auto d = rowsOf(drm.out);
  const auto q = rowsOf(ik.out);
  ASSERT_EQ(q.size(), 3u);
  EXPECT_EQ(q[0][5], "0");                                    // the centre
  EXPECT_NEAR(num(q[1][5]), num(d.at(0)[1]), kTolRoundTrip);  // theta = 0
  EXPECT_NEAR(num(q[2][5]), num(d.at(9)[1]), kTolRoundTrip);  // theta = 90
}

TEST_F(ExechonCli, DrmOfAShrinkingCircleVanishes) {
  // phi(theta) -> 0 with the radius: 1 µm from the centre it is below a milli-degree (25 mm: 3°).
  const CliRun r = pkm({"exechon", "drm", "--circle", "0,0,-100,0.001", "--step", "45"});
  ASSERT_EQ(r.code, 0) << r.err;
  for (const auto& row : rowsOf(r.out)) EXPECT_LT(std::abs(num(row[1])), 1e-3) << row[0];
}

TEST_F(ExechonCli, DrmCircleLeavingTheWorkspace) {
  // Zoppi's tripod cannot reach points within hx = 282.8 mm of its base axis; this circle (in the
  // xz plane) comes within 100 mm of it.
  const CliRun r = pkm({"exechon",
                        "drm",
                        "-m",
                        "exechon-zoppi2010",
                        "--circle",
                        "0,700,400,300",
                        "--direction",
                        "0,1,0",
                        "--step",
                        "30"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("pkm: error: the circle leaves the workspace at point"));
  EXPECT_THAT(r.err, HasSubstr("unreachable"));
  EXPECT_THAT(r.out, StartsWith("theta_deg,phi_drm_deg,fit_deg,residual_deg\n"));
  EXPECT_THAT(r.out, HasSubstr("# status unreachable\n"));
  EXPECT_THAT(r.out, ::testing::Not(HasSubstr("# max fit deviation")));
}

TEST_F(ExechonCli, BadCircleText) {
  for (const std::string circle :
       {"0,0,-100", "0,0,-100,25,1", "0,0,-100,abc", "0,0,,25", "0;0;-100;25", ""}) {
    SCOPED_TRACE(circle);
    const CliRun r = pkm({"exechon", "drm", "--circle", circle});
    EXPECT_EQ(r.code, kExitUsage) << r.err;
    EXPECT_THAT(r.err, HasSubstr("--circle"));
    EXPECT_EQ(r.out, "");
  }
  for (const std::string radius : {"0", "-5"}) {
    const CliRun r = pkm({"exechon", "drm", "--circle", "0,0,-100," + radius});
    expectUsageError(r, "invalid circle");
    EXPECT_EQ(r.out, "");
  }
  expectUsageError(pkm({"exechon", "drm", "--circle", "0,0,-100,25", "--direction", "0,0"}),
                   "--direction");
  EXPECT_EQ(pkm({"exechon", "drm"}).code, kExitUsage);  // --circle is required
}

}  // namespace PKM_TEST_NS
