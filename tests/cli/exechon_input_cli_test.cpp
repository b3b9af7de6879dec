// The CLI contract of `pkm exechon describe` and of the inputs of every `pkm exechon` command,
// tested by running the built binary (PKM_BINARY) as a subprocess: `describe` round trips, and exit
// code 2 with FILE:LINE messages on bad input (CSV files, machine names and files).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include "cli/exechon_cli.hpp"
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
using pkm::test::splitLines;

// ---------------------------------------------------------------------------------------------
// describe

TEST_F(ExechonCli, DescribeReadBackGivesIdenticalIk) {
  const CliRun json = pkm({"exechon", "describe", "-m", "exechon-zoppi2010"});
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_THAT(json.out, StartsWith("{"));
  EXPECT_THAT(json.out, HasSubstr("\"type\": \"exechon\""));
  const std::string file = write("m.json", json.out);
  EXPECT_EQ(pkm({"exechon", "describe", "-m", file}).out, json.out);  // a fixed point
  const std::string wrist = write("W.csv", "sx,sy,sz\n20,700,1020\n40,650,1000\n0,0,0\n");
  const CliRun a = pkm({"exechon", "ik", "-m", "exechon-zoppi2010", "--wrist", wrist});
  const CliRun b = pkm({"exechon", "ik", "-m", file, "--wrist", wrist});
  ASSERT_EQ(b.code, 0) << b.err;
  EXPECT_EQ(b.out, a.out);
  const std::string poses =
      write("P.csv", "x,y,z,i,j,k\n20,700,1020,0,0,1\n40,650,1000,0.2,0.1,1\n0,0,0,0,0,1\n");
  const CliRun c = pkm({"exechon", "ik", "-m", "exechon-zoppi2010", "--poses", poses});
  const CliRun d = pkm({"exechon", "ik", "-m", file, "--poses", poses});
  ASSERT_EQ(d.code, 0) << d.err;
  EXPECT_EQ(d.out, c.out);
  EXPECT_EQ(pkm({"exechon", "check", "-m", file, "--poses", poses}).out,
            pkm({"exechon", "check", "-m", "exechon-zoppi2010", "--poses", poses}).out);
}

TEST_F(ExechonCli, DescribeReadBackOfHybridMachine) {
  // world_T_zoppi is written as rpy in degrees, which round-trips to within an ulp, not exactly:
  // the ik output agrees to the round-trip tolerance, and the text is a fixed point after one
  // round.
  const CliRun json = pkm({"exechon", "describe", "-m", "mxt700s-like"});
  ASSERT_EQ(json.code, 0) << json.err;
  EXPECT_THAT(json.out,
              HasSubstr("\"hybrid\": {\"x2_stroke\": [0, 4000], \"y2_stroke\": [0, 450]"));
  const std::string file = write("m.json", json.out);
  EXPECT_EQ(pkm({"exechon", "describe", "-m", file}).out, json.out);
  const std::string poses = write("P.csv", kHybridPoses);
  const CliRun a = pkm({"exechon", "ik", "-m", "mxt700s-like", "--poses", poses});
  const CliRun b = pkm({"exechon", "ik", "-m", file, "--poses", poses});
  ASSERT_EQ(b.code, 0) << b.err;
  const auto ra = rowsOf(a.out), rb = rowsOf(b.out);
  ASSERT_EQ(ra.size(), rb.size());
  EXPECT_EQ(splitLines(a.out)[0], splitLines(b.out)[0]);
  for (std::size_t k = 0; k < ra.size(); ++k) {
    ASSERT_EQ(ra[k].size(), rb[k].size());
    for (std::size_t i = 0; i < ra[k].size(); ++i) {
      if (i == 6)
        EXPECT_EQ(ra[k][i], rb[k][i]);
      else
        EXPECT_NEAR(num(ra[k][i]), num(rb[k][i]), kTolRoundTrip) << "row " << k << " field " << i;
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Bad input: exit code 2 and a message naming the file and line

TEST_F(ExechonCli, MissingColumn) {
  const std::string p = write("P.csv", "x,y,z,i,j\n0,0,0,0,0\n");
  const std::string err = expectUsageError(pkm({"exechon", "ik", "-p", p}), p + ":1: ");
  EXPECT_THAT(err, StartsWith("pkm: error: "));
  EXPECT_THAT(err, HasSubstr("missing column"));
  const std::string w = write("W.csv", "sx,sz\n0,0\n");
  expectUsageError(pkm({"exechon", "ik", "-w", w}), w + ":1: ");
  const std::string j = write("J.csv", "q1,q2,q3,c\n1,2,3,4\n");
  expectUsageError(pkm({"exechon", "fk", "-j", j}), j + ":1: ");
  const CliRun r = pkm({"exechon", "check", "-p", p});
  expectUsageError(r, p + ":1: ");
  EXPECT_EQ(r.out, "");
}

TEST_F(ExechonCli, NonNumber) {
  const std::string p = write("P.csv", "x,y,z,i,j,k\n0,0,0,0,0,-1\n\n0,0,zero,0,0,-1\n");
  const std::string err = expectUsageError(pkm({"exechon", "ik", "-p", p}), p + ":4: ");
  EXPECT_THAT(err, HasSubstr("column 'z'"));
  EXPECT_THAT(err, HasSubstr("'zero'"));
  const std::string w = write("W.csv", "sx,sy,sz\n20,700,nan\n");
  expectUsageError(pkm({"exechon", "ik", "-m", "exechon-zoppi2010", "-w", w}), w + ":2: ");
  // In an optional column too.
  const std::string q = write("Q.csv", "x,y,z,i,j,k,x2,y2\n0,0,0,0,0,-1,0,far\n");
  expectUsageError(pkm({"exechon", "ik", "-p", q}), q + ":2: column 'y2'");
}

TEST_F(ExechonCli, OnlyX2WithoutY2) {
  const std::string p = write("P.csv", "x,y,z,i,j,k,x2\n0,0,0,0,0,-1,0\n");
  const CliRun r = pkm({"exechon", "ik", "-p", p});
  const std::string err = expectUsageError(r, p + ":1: ");
  EXPECT_THAT(err, HasSubstr("give both x2 and y2"));
  EXPECT_EQ(r.out, "");
  const std::string q = write("Q.csv", "x,y,z,i,j,k,y2\n0,0,0,0,0,-1,0\n");
  expectUsageError(pkm({"exechon", "check", "-p", q}), q + ":1: ");
  const std::string j = write("J.csv", "q1,q2,q3,c,a,x2\n350,350,350,0,-20,0\n");
  expectUsageError(pkm({"exechon", "fk", "-j", j}), j + ":1: ");
}

TEST_F(ExechonCli, X2Y2ColumnsNeedAHybridMachine) {
  const std::string p = write("P.csv", "x,y,z,i,j,k,x2,y2\n20,700,1020,0,0,1,0,0\n");
  const CliRun r = pkm({"exechon", "ik", "-m", "exechon-zoppi2010", "-p", p});
  const std::string err = expectUsageError(r, p + ":1: ");
  EXPECT_THAT(err, HasSubstr("\"hybrid\""));
  EXPECT_EQ(r.out, "");
  expectUsageError(pkm({"exechon", "check", "-m", "exechon-zoppi2010", "-p", p}), p + ":1: ");
  const std::string j = write("J.csv", "q1,q2,q3,c,a,x2,y2\n1633,1491,912,0,0,0,0\n");
  expectUsageError(pkm({"exechon", "fk", "-m", "exechon-zoppi2010", "-j", j}), j + ":1: ");
}

TEST_F(ExechonCli, WristAndPosesTogetherOrNeither) {
  const std::string w = write("W.csv", kZoppiWrist);
  const std::string p = write("P.csv", kHybridPoses);
  const CliRun both = pkm({"exechon", "ik", "--wrist", w, "--poses", p});
  EXPECT_EQ(both.code, kExitUsage);
  EXPECT_THAT(both.err, HasSubstr("--wrist"));
  EXPECT_THAT(both.err, HasSubstr("--poses"));
  EXPECT_EQ(both.out, "");
  const CliRun neither = pkm({"exechon", "ik"});
  EXPECT_EQ(neither.code, kExitUsage);
  EXPECT_THAT(neither.err, HasSubstr("--wrist or --poses"));
  EXPECT_EQ(neither.out, "");
}

TEST_F(ExechonCli, RequiredInputsAndSubcommands) {
  EXPECT_THAT(pkm({"exechon", "fk"}).err, HasSubstr("--joints"));
  EXPECT_EQ(pkm({"exechon", "fk"}).code, kExitUsage);
  EXPECT_EQ(pkm({"exechon", "check"}).code, kExitUsage);
  EXPECT_EQ(pkm({"exechon"}).code, kExitUsage);
  EXPECT_EQ(pkm({"exechon", "frobnicate"}).code, kExitUsage);
}

TEST_F(ExechonCli, UnknownMachineListsExechonBuiltins) {
  const std::string err = expectUsageError(pkm({"exechon", "describe", "-m", "hexapod-default"}),
                                           "not a built-in exechon machine");
  EXPECT_THAT(err, HasSubstr("exechon-zoppi2010"));
  EXPECT_THAT(err, HasSubstr("mxt700s-like"));
}

TEST_F(ExechonCli, MalformedMachineFileNamesLine) {
  const CliRun json = pkm({"exechon", "describe", "-m", "exechon-zoppi2010"});
  std::string text = json.out;
  const auto pos = text.find("\"delta2B\": 1");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 12, "\"delta2B\": 2");
  const std::size_t line =
      1 + static_cast<std::size_t>(
              std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  const std::string m = write("m.json", text);
  expectUsageError(pkm({"exechon", "ik", "-m", m, "-w", write("W.csv", kZoppiWrist)}),
                   m + ":" + std::to_string(line) + ": /tripod/branch/delta2B: ");
}

}  // namespace PKM_TEST_NS