// The CLI contract of `pkm hexapod ik|fk` and `pkm demo`, tested by running the built binary
// (PKM_BINARY) as a subprocess: output headers, values against the LinuxCNC reference, FK failure
// rows and long paths. Checks, machine files and bad input: hexapod_machine_cli_test.cpp.
#include "cli/hexapod_cli.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "support/cli_fixture.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::test::kTolLinuxcnc;
using pkm::test::kTolRoundTrip;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using pkm::test::CliRun;
using pkm::test::HexapodCli;
using pkm::test::kDefaultPoses;
using pkm::test::kExitUsage;
using pkm::test::kSimPoses;
using pkm::test::num;
using pkm::test::splitFields;
using pkm::test::splitLines;

/// Reference strut lengths of the LinuxCNC hexapod-sim (genhexkins), inch, 6 decimals.
struct Reference {
  double pose[6];
  double lengths[6];
};
const Reference kReference[] = {
    {{0, 0, 20, 0, 0, 0}, {29.746680, 29.746680, 29.746715, 29.746363, 29.746363, 29.746715}},
    {{2, -1, 22, 3, -4, 10}, {31.597194, 31.713899, 29.975223, 32.850082, 27.921167, 33.441616}},
    {{-3, 2, 18, 10, 10, -15}, {30.022945, 29.402324, 29.682443, 25.351693, 33.820068, 24.667812}},
};

// ---------------------------------------------------------------------------------------------
// ik / fk

TEST_F(HexapodCli, IkMatchesLinuxcncReference) {
  const CliRun r = pkm(
      {"hexapod", "ik", "--machine", "hexapod-linuxcnc-sim", "--poses", write("P.csv", kSimPoses)});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 4u) << r.out;
  EXPECT_EQ(lines[0], "l0,l1,l2,l3,l4,l5,status");
  for (std::size_t k = 0; k < 3; ++k) {
    const auto f = splitFields(lines[k + 1]);
    ASSERT_EQ(f.size(), 7u) << lines[k + 1];
    for (std::size_t i = 0; i < 6; ++i)
      EXPECT_NEAR(num(f[i]), kReference[k].lengths[i], kTolLinuxcnc)
          << "row " << k << " strut " << i;
    EXPECT_EQ(f[6], "ok");
  }
}

TEST_F(HexapodCli, IkReadsStandardInput) {
  const std::string poses = write("P.csv", kSimPoses);
  const CliRun from_file = pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "-p", poses});
  const CliRun from_stdin =
      pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "--poses", "-"}, poses);
  ASSERT_EQ(from_stdin.code, 0) << from_stdin.err;
  EXPECT_EQ(from_stdin.out, from_file.out);
}

TEST_F(HexapodCli, IkOnDefaultMachineReportsStroke) {
  const CliRun r = pkm(
      {"hexapod", "ik", "--poses", write("P.csv", "x,y,z,a,b,c\n0,0,200,0,0,0\n0,0,-400,0,0,0\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(splitFields(lines[1]).back(), "ok");
  EXPECT_EQ(splitFields(lines[2]).back(), "stroke");  // readings are printed all the same
  EXPECT_GT(num(splitFields(lines[2])[0]), 500.0);
}

TEST_F(HexapodCli, FkHeaderAndRoundTripOfIkOutput) {
  const CliRun ik = pkm(
      {"hexapod", "ik", "--machine", "hexapod-linuxcnc-sim", "--poses", write("P.csv", kSimPoses)});
  ASSERT_EQ(ik.code, 0) << ik.err;
  // The ik output (with its status column) is a valid fk input: extra columns are ignored.
  const CliRun fk = pkm(
      {"hexapod", "fk", "--machine", "hexapod-linuxcnc-sim", "--lengths", write("L.csv", ik.out)});
  ASSERT_EQ(fk.code, 0) << fk.err;
  const auto lines = splitLines(fk.out);
  ASSERT_EQ(lines.size(), 4u) << fk.out;
  EXPECT_EQ(lines[0], "x,y,z,a,b,c,iterations,status");
  for (std::size_t k = 0; k < 3; ++k) {
    const auto f = splitFields(lines[k + 1]);
    ASSERT_EQ(f.size(), 8u) << lines[k + 1];
    for (std::size_t i = 0; i < 6; ++i)
      EXPECT_NEAR(num(f[i]), kReference[k].pose[i], kTolRoundTrip) << "row " << k << " field " << i;
    EXPECT_GE(num(f[6]), 0.0);
    EXPECT_EQ(f[7], "ok");
  }
}

TEST_F(HexapodCli, FkRoundTripOnDefaultMachine) {
  const CliRun ik = pkm({"hexapod", "ik", "--poses", write("P.csv", kDefaultPoses)});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const CliRun fk = pkm({"hexapod", "fk", "--lengths", write("L.csv", ik.out)});
  ASSERT_EQ(fk.code, 0) << fk.err;
  const auto want = splitLines(kDefaultPoses);
  const auto got = splitLines(fk.out);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 1; k < got.size(); ++k) {
    const auto f = splitFields(got[k]);
    const auto w = splitFields(want[k]);
    ASSERT_EQ(f.size(), 8u);
    for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(num(f[i]), num(w[i]), kTolRoundTrip) << got[k];
    EXPECT_EQ(f[7], "ok");
  }
}

TEST_F(HexapodCli, FkSeedOption) {
  const CliRun ik = pkm({"hexapod",
                         "ik",
                         "-m",
                         "hexapod-linuxcnc-sim",
                         "-p",
                         write("P.csv", "x,y,z,a,b,c\n2,-1,22,3,-4,10\n")});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const std::string lengths = write("L.csv", ik.out);
  const CliRun from_home = pkm({"hexapod", "fk", "-m", "hexapod-linuxcnc-sim", "-l", lengths});
  const CliRun seeded = pkm(
      {"hexapod", "fk", "-m", "hexapod-linuxcnc-sim", "-l", lengths, "--seed", "2,-1,22,3,-4,10"});
  ASSERT_EQ(from_home.code, 0) << from_home.err;
  ASSERT_EQ(seeded.code, 0) << seeded.err;
  const auto a = splitFields(splitLines(from_home.out).at(1));
  const auto b = splitFields(splitLines(seeded.out).at(1));
  ASSERT_EQ(a.size(), 8u);
  ASSERT_EQ(b.size(), 8u);
  EXPECT_EQ(a[7], "ok");
  EXPECT_EQ(b[7], "ok");
  for (std::size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(num(b[i]), kReference[1].pose[i], kTolRoundTrip);
    EXPECT_NEAR(num(a[i]), num(b[i]), kTolRoundTrip);
  }
  // Seeded at the answer, the solve needs fewer Newton steps than from home.
  EXPECT_LT(num(b[6]), num(a[6]));
  EXPECT_LE(num(b[6]), 1.0);
}

TEST_F(HexapodCli, FkBadSeedIsUsageError) {
  const std::string lengths = write("L.csv", "l0,l1,l2,l3,l4,l5\n30,30,30,30,30,30\n");
  for (const std::string seed : {"1,2,3", "0,0,20,0,0,x", "0,0,20,0,0,0,0", "0,0,nan,0,0,0"}) {
    SCOPED_TRACE(seed);
    const CliRun r =
        pkm({"hexapod", "fk", "-m", "hexapod-linuxcnc-sim", "-l", lengths, "--seed", seed});
    expectUsageError(r, "--seed");
  }
}

TEST_F(HexapodCli, FkImpossibleRowGivesEmptyPoseAndNextRowReseedsFromHome) {
  // Struts 0 and 1 share no base joint; their base joints are 45.9 apart, their platform joints 2:
  // lengths of 1 cannot close the loop.
  const std::string good =
      "31.597194336721323,31.713899300748924,29.975222906668,32.85008205799862,"
      "27.921166698780066,33.44161557269717";
  const CliRun alone = pkm({"hexapod",
                            "fk",
                            "-m",
                            "hexapod-linuxcnc-sim",
                            "-l",
                            write("good.csv", "l0,l1,l2,l3,l4,l5\n" + good + "\n")});
  const CliRun r = pkm({"hexapod",
                        "fk",
                        "-m",
                        "hexapod-linuxcnc-sim",
                        "-l",
                        write("L.csv", "l0,l1,l2,l3,l4,l5\n1,1,30,30,30,30\n" + good + "\n")});
  ASSERT_EQ(alone.code, 0) << alone.err;
  ASSERT_EQ(r.code, 0) << r.err;  // a failed row is a result, not an input error
  const auto lines = splitLines(r.out);
  ASSERT_EQ(lines.size(), 3u) << r.out;
  const auto bad = splitFields(lines[1]);
  ASSERT_EQ(bad.size(), 8u) << lines[1];
  for (std::size_t i = 0; i < 6; ++i) EXPECT_EQ(bad[i], "") << lines[1];
  EXPECT_GT(num(bad[6]), 0.0);
  EXPECT_NE(bad[7], "ok");
  EXPECT_THAT(bad[7], ::testing::AnyOf("no_convergence", "singular"));
  // The next row solves, exactly as it does from home on its own (same pose and iteration count).
  EXPECT_EQ(lines[2], splitLines(alone.out).at(1));
  const auto next = splitFields(lines[2]);
  EXPECT_EQ(next[7], "ok");
  for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(num(next[i]), kReference[1].pose[i], 1e-6);
}

// A path long enough for several input chunks and printed pieces (the two-thread pipeline): every
// row in order, each the path's pose; a bad line far down still prints every row before it.
TEST_F(HexapodCli, FkLongPathKeepsOrderAndReportsLateBadLine) {
  constexpr int kRows = 20000;
  std::string poses = "x,y,z,a,b,c\n";
  for (int k = 0; k < kRows; ++k) {
    const double t = 2.0 * 3.141592653589793 * k / kRows;
    poses += std::to_string(3 * std::sin(t)) + "," + std::to_string(3 * (1 - std::cos(t))) + "," +
             std::to_string(20 + std::sin(2 * t)) + "," + std::to_string(8 * std::sin(t)) + "," +
             std::to_string(6 * std::sin(3 * t)) + "," + std::to_string(11 * std::sin(t)) + "\n";
  }
  const CliRun ik =
      pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "-p", write("P.csv", poses)});
  ASSERT_EQ(ik.code, 0) << ik.err;
  const CliRun fk = pkm({"hexapod",
                         "fk",
                         "-m",
                         "hexapod-linuxcnc-sim",
                         "-l",
                         write("L.csv", ik.out),
                         "--seed",
                         "0,0,20,0,0,0"});
  ASSERT_EQ(fk.code, 0) << fk.err;
  const auto want = splitLines(poses);
  const auto got = splitLines(fk.out);
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t k = 1; k < got.size(); ++k) {
    const auto g = splitFields(got[k]);
    const auto w = splitFields(want[k]);
    ASSERT_EQ(g.size(), 8u) << got[k];
    ASSERT_EQ(g[7], "ok") << "row " << k;
    for (std::size_t i = 0; i < 6; ++i)
      ASSERT_NEAR(num(g[i]), num(w[i]), kTolRoundTrip) << "row " << k << " column " << i;
  }
  // Line 15002 of the file (row 15001) is bad: 15000 rows, then FILE:LINE and exit 2.
  auto lines = splitLines(ik.out);
  lines[15001] = "1,2,x,4,5,6";
  std::string bad;
  for (const auto& l : lines) bad += l + "\n";
  const std::string file = write("B.csv", bad);
  const CliRun r =
      pkm({"hexapod", "fk", "-m", "hexapod-linuxcnc-sim", "-l", file, "--seed", "0,0,20,0,0,0"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr(file + ":15002:"));
  const auto printed = splitLines(r.out);
  ASSERT_EQ(printed.size(), 15001u);
  EXPECT_EQ(printed.back(), got[15000]);
}

// ---------------------------------------------------------------------------------------------
// demo

TEST_F(HexapodCli, DemoPasses) {
  const CliRun r = pkm({"demo", "--points", "200"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("PASS"));
  EXPECT_THAT(r.out, HasSubstr("200 of 200 converged"));
}

TEST_F(HexapodCli, VersionAndHelpExitZero) {
  const CliRun v = pkm({"--version"});
  EXPECT_EQ(v.code, 0);
  EXPECT_THAT(v.out, HasSubstr("pkm"));
  const CliRun h = pkm({"hexapod", "ik", "--help"});
  EXPECT_EQ(h.code, 0);
  EXPECT_THAT(h.out, HasSubstr("--poses"));
}

}  // namespace PKM_TEST_NS