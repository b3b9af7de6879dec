// The CLI contract of `pkm volumetric`, tested by running the built binary (PKM_BINARY) as a
// subprocess: output header, grid order, the exact and first-order volumetric errors, the sign of
// the X2 squareness, the --commands form, out-of-range policies, and exit code 2 with FILE:LINE
// messages on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/cli_fixture.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using pkm::test::kTolExact;
using ::testing::HasSubstr;
using ::testing::StartsWith;

using pkm::test::CliRun;
using pkm::test::kExitUsage;
using pkm::test::num;
using pkm::test::splitFields;
using pkm::test::splitLines;
constexpr const char* kHeader = "x,y,z,x2,y2,xp,yp,zp,dx,dy,dz,dp,dx_lin,dy_lin,dz_lin,status";
const std::string kSeedErrors = std::string(PKM_SOURCE_DIR) + "/data/errors/mxt700s-seed000.json";
constexpr const char* kGrid = "0:1000:3,0:200:2,-100:100:2";
/// Exact and first-order errors agree within this fraction of |dp|, or kTolLinearAbs (mm).
constexpr double kTolLinearRelative = 0.02;
constexpr double kTolLinearAbs = 0.02;
/// Output columns.
enum Column : std::size_t {
  kX,
  kY,
  kZ,
  kX2,
  kY2,
  kXp,
  kYp,
  kZp,
  kDx,
  kDy,
  kDz,
  kDp,
  kDxLin,
  kDyLin,
  kDzLin,
  kStatus
};

/// The data rows (after the header), split in fields; each must have the header's 16 fields.
std::vector<std::vector<std::string>> rowsOf(const std::string& csv) {
  std::vector<std::vector<std::string>> rows;
  const auto lines = splitLines(csv);
  EXPECT_FALSE(lines.empty());
  if (!lines.empty()) {
    EXPECT_EQ(lines[0], kHeader);
  }
  for (std::size_t k = 1; k < lines.size(); ++k) {
    rows.push_back(splitFields(lines[k]));
    EXPECT_EQ(rows.back().size(), 16u) << lines[k];
  }
  return rows;
}

/// An errors file with only the given squareness (µrad) set.
std::string squarenessOnly(const std::string& entries) {
  return "{\"schema\": \"pkm.errors/1\", \"type\": \"hybrid_geometric_errors\",\n"
         " \"squareness_urad\": {" +
         entries + "}}\n";
}

class VolumetricCli : public pkm::test::CliTest {};

// ---------------------------------------------------------------------------------------------
// Grid form with the seed-000 errors

TEST_F(VolumetricCli, GridOfSeedErrors) {
  const CliRun r = pkm({"volumetric", "--errors", kSeedErrors, "--grid", kGrid});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_EQ(splitLines(r.out).at(0), kHeader);
  const auto rows = rowsOf(r.out);
  ASSERT_EQ(rows.size(), 12u);
  std::size_t k = 0;
  for (double z : {-100.0, 100.0})
    for (double y : {0.0, 200.0})
      for (double x : {0.0, 500.0, 1000.0}) {  // x fastest, then y, then z
        const auto& f = rows[k++];
        SCOPED_TRACE(testing::Message() << "row " << k);
        ASSERT_EQ(f.size(), 16u);
        EXPECT_EQ(num(f[kX]), x);
        EXPECT_EQ(num(f[kY]), y);
        EXPECT_EQ(num(f[kZ]), z);
        // The command puts the tool there nominally: x = x2 + xP, y = yP - y2, z = zP.
        EXPECT_EQ(num(f[kX2]) + num(f[kXp]), x);
        EXPECT_EQ(num(f[kYp]) - num(f[kY2]), y);
        EXPECT_EQ(num(f[kZp]), z);
        EXPECT_EQ(f[kStatus], "ok");
        const Eigen::Vector3d dp(num(f[kDx]), num(f[kDy]), num(f[kDz]));
        const Eigen::Vector3d lin(num(f[kDxLin]), num(f[kDyLin]), num(f[kDzLin]));
        EXPECT_NEAR(num(f[kDp]), dp.norm(), kTolExact * dp.norm());
        EXPECT_LE((dp - lin).norm(), std::max(kTolLinearRelative * dp.norm(), kTolLinearAbs))
            << dp.transpose() << " vs " << lin.transpose();
        // The squareness errors of seed 000 are mrad over hundreds of mm: dp is not negligible.
        EXPECT_GT(dp.norm(), 1.0);
      }
}

TEST_F(VolumetricCli, BuiltinErrorSetByName) {
  const CliRun by_path = pkm({"volumetric", "--errors", kSeedErrors, "--grid", kGrid});
  const CliRun by_name = pkm({"volumetric", "-e", "mxt700s-seed000", "--grid", kGrid});
  ASSERT_EQ(by_name.code, 0) << by_name.err;
  EXPECT_EQ(by_name.out, by_path.out);
  expectUsageError(pkm({"volumetric", "-e", "no-such-errors", "--grid", kGrid}), "no-such-errors");
}

// ---------------------------------------------------------------------------------------------
// The sign of szX2: moving X2 alone by x moves the tool by (x·cos szX2, −x·sin szX2, 0)

TEST_F(VolumetricCli, SquarenessSzX2MovesTheToolAlongMinusY) {
  constexpr double kSzX2 = 100e-6;  // rad; 100 µrad in the file
  const std::string errors = write("E.json", squarenessOnly("\"szX2\": 100"));
  const CliRun r = pkm({"volumetric",
                        "-e",
                        errors,
                        "--commands",
                        write("C.csv",
                              "x2,y2,xp,yp,zp\n"
                              "0,0,0,0,0\n"
                              "1000,0,0,0,0\n"
                              "4000,0,0,0,0\n"
                              "2000,100,10,-200,50\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = rowsOf(r.out);
  ASSERT_EQ(rows.size(), 4u);
  const double c = std::cos(kSzX2), s = std::sin(kSzX2);
  for (const auto& f : rows) {
    SCOPED_TRACE(f[kX2]);
    // Exact: szX2 turns X2 and everything it carries about F's z by -szX2; x = x2 + xP, yP.
    const double x = num(f[kX2]) + num(f[kXp]), yp = num(f[kYp]);
    EXPECT_NEAR(num(f[kDx]), (c - 1) * x + s * yp, kTolExact * (1 + x));
    EXPECT_NEAR(num(f[kDy]), -s * x + (c - 1) * yp, kTolExact * (1 + x));
    EXPECT_EQ(num(f[kDz]), 0.0);
    // To first order dy = -szX2·x, dx = szX2·yP; the linear model is exactly that.
    EXPECT_NEAR(num(f[kDy]), -kSzX2 * x, kSzX2 * kSzX2 * (x + std::abs(yp)));
    EXPECT_NEAR(num(f[kDyLin]), -kSzX2 * x, kTolExact * (1 + x));
    EXPECT_NEAR(num(f[kDxLin]), kSzX2 * yp, kTolExact * (1 + x));
    EXPECT_EQ(num(f[kDzLin]), 0.0);
    EXPECT_EQ(f[kStatus], "ok");
  }
  EXPECT_EQ(rows[0][kDp], "0");
  EXPECT_NEAR(num(rows[2][kDy]), -0.4, kSzX2 * kSzX2 * 4000);  // 100 µrad over 4 m
  EXPECT_LT(num(rows[2][kDy]), 0.0);
  // The grid form with X2 and Y2 given: the tool at x = 1000 with X2 at 1000 and the PKM at 0.
  const CliRun g = pkm({"volumetric",
                        "-e",
                        errors,
                        "--grid",
                        "1000:1000:1,0:0:1,0:0:1",
                        "--x2",
                        "1000",
                        "--y2",
                        "0"});
  ASSERT_EQ(g.code, 0) << g.err;
  const auto grow = rowsOf(g.out);
  ASSERT_EQ(grow.size(), 1u);
  EXPECT_EQ(grow[0][kXp], "0");
  EXPECT_NEAR(num(grow[0][kDy]), -s * 1000, kTolExact * 1000);
  EXPECT_NEAR(num(grow[0][kDy]), -kSzX2 * 1000, kSzX2 * kSzX2 * 1000);
}

// ---------------------------------------------------------------------------------------------
// --commands

TEST_F(VolumetricCli, CommandsForm) {
  const CliRun r = pkm({"volumetric",
                        "-e",
                        kSeedErrors,
                        "--commands",
                        write("C.csv",
                              "# X2, Y2 and the PKM command\n"
                              "x2,y2,xp,yp,zp,note\n"
                              "500,0,0,0,-100,1\n"
                              "500,100,10,20,30,2\n"
                              "5000,0,0,0,0,3\n")});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto rows = rowsOf(r.out);
  ASSERT_EQ(rows.size(), 3u);
  // The command is echoed, and x, y, z is its nominal tool position.
  EXPECT_EQ(rows[1][kX2], "500");
  EXPECT_EQ(rows[1][kY2], "100");
  EXPECT_EQ(rows[1][kXp], "10");
  EXPECT_EQ(rows[1][kYp], "20");
  EXPECT_EQ(rows[1][kZp], "30");
  EXPECT_EQ(num(rows[1][kX]), 510.0);
  EXPECT_EQ(num(rows[1][kY]), -80.0);
  EXPECT_EQ(num(rows[1][kZ]), 30.0);
  EXPECT_EQ(rows[0][kStatus], "ok");
  EXPECT_EQ(rows[1][kStatus], "ok");
  EXPECT_EQ(rows[2][kStatus], "axis_limit");  // X2 beyond its 4000 mm stroke; still evaluated
  EXPECT_NE(rows[2][kDp], "");
  // The first row is the grid's (500, 0, -100) point with its centred command: same numbers.
  const CliRun g = pkm({"volumetric", "-e", kSeedErrors, "--grid", "500:500:1,0:0:1,-100:-100:1"});
  ASSERT_EQ(g.code, 0) << g.err;
  const auto grow = rowsOf(g.out);
  ASSERT_EQ(grow.size(), 1u);
  EXPECT_EQ(grow[0], rows[0]);
}

// ---------------------------------------------------------------------------------------------
// Zero errors and out-of-range policies

TEST_F(VolumetricCli, ZeroErrorsGiveExactlyZero) {
  const std::string empty = write("E.json", "{\"type\": \"hybrid_geometric_errors\"}\n");
  const std::string zeros =
      write("Z.json",
            "{\"type\": \"hybrid_geometric_errors\",\n"
            " \"squareness_urad\": {\"szX2\": 0, \"sxP\": 0, \"syP\": 0, \"szP\": 0},\n"
            " \"x2\": {\"positions\": [0, 4000], \"dx\": [0, 0], \"ez_urad\": [0, 0]},\n"
            " \"y2\": {\"positions\": [0], \"dy\": [0]},\n"
            " \"pkm\": {\"x\": [0], \"y\": [0], \"z\": [-350, 350], \"ex_urad\": [0, 0]}}\n");
  for (const std::string& errors : {empty, zeros}) {
    SCOPED_TRACE(errors);
    const CliRun r = pkm({"volumetric", "-e", errors, "--grid", kGrid});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto rows = rowsOf(r.out);
    ASSERT_EQ(rows.size(), 12u);
    for (const auto& f : rows)
      for (std::size_t i = kDx; i <= kDzLin; ++i) EXPECT_EQ(f[i], "0") << i;
  }
}

TEST_F(VolumetricCli, ErrorPolicyOutsideTheTable) {
  // An X2 table over 0..875 with "error": x = 1000 is outside it; "clamp" holds the end value.
  const auto errors = [&](const char* policy) {
    return write(std::string(policy) + ".json",
                 std::string("{\"type\": \"hybrid_geometric_errors\",\n"
                             " \"x2\": {\"out_of_range\": \"") +
                     policy + "\", \"positions\": [0, 875], \"dx\": [0, -0.078]}}\n");
  };
  const CliRun r = pkm({"volumetric", "-e", errors("error"), "--grid", "0:1000:3,0:0:1,0:0:1"});
  ASSERT_EQ(r.code, 0) << r.err;  // an uncovered command is a result, not an input error
  const auto rows = rowsOf(r.out);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0][kStatus], "ok");
  EXPECT_EQ(rows[1][kStatus], "ok");
  // dx = (x2 + dx) - x2: exact up to the rounding of a sum with x2 (kTolExact per mm of x2).
  EXPECT_NEAR(num(rows[1][kDx]), -0.078 * 500 / 875, kTolExact * 500);
  EXPECT_EQ(rows[2][kStatus], "outside_table");
  EXPECT_EQ(rows[2][kX], "1000");
  for (std::size_t i = kDx; i <= kDzLin; ++i) EXPECT_EQ(rows[2][i], "") << i;
  const CliRun c = pkm({"volumetric", "-e", errors("clamp"), "--grid", "0:1000:3,0:0:1,0:0:1"});
  ASSERT_EQ(c.code, 0) << c.err;
  const auto crows = rowsOf(c.out);
  ASSERT_EQ(crows.size(), 3u);
  EXPECT_EQ(crows[2][kStatus], "ok");
  EXPECT_NEAR(num(crows[2][kDx]), -0.078, kTolExact * 1000);
}

// ---------------------------------------------------------------------------------------------
// Bad input: exit code 2, a message naming the file and line, and no output

TEST_F(VolumetricCli, MissingErrors) {
  const CliRun r = pkm({"volumetric", "--grid", kGrid});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("--errors"));
  EXPECT_EQ(r.out, "");
}

TEST_F(VolumetricCli, MalformedGrid) {
  for (const std::string grid : {"0:1:2,0:1:2",
                                 "0:1:2,0:1:2,0:1:2,0:1:2",
                                 "0:1,0:1:2,0:1:2",
                                 "0:1:2:3,0:1:2,0:1:2",
                                 "a:1:2,0:1:2,0:1:2",
                                 "0:1:0,0:1:2,0:1:2",
                                 "0:1:2.5,0:1:2,0:1:2",
                                 "0:1:-1,0:1:2,0:1:2",
                                 "0:inf:2,0:1:2,0:1:2",
                                 ""}) {
    SCOPED_TRACE(grid);
    expectUsageError(pkm({"volumetric", "-e", kSeedErrors, "--grid", grid}), "--grid");
  }
}

TEST_F(VolumetricCli, X2WithoutY2) {
  expectUsageError(pkm({"volumetric", "-e", kSeedErrors, "--grid", kGrid, "--x2", "100"}),
                   "give both --x2 and --y2");
  expectUsageError(pkm({"volumetric", "-e", kSeedErrors, "--grid", kGrid, "--y2", "100"}),
                   "give both --x2 and --y2");
}

TEST_F(VolumetricCli, MachineWithoutHybridSection) {
  const std::string err = expectUsageError(
      pkm({"volumetric", "-m", "exechon-zoppi2010", "-e", kSeedErrors, "--grid", kGrid}),
      "builtin:exechon-zoppi2010: ");
  EXPECT_THAT(err, HasSubstr("no \"hybrid\" section"));
  expectUsageError(pkm({"volumetric", "-m", "hexapod-default", "-e", kSeedErrors, "--grid", kGrid}),
                   "not a built-in exechon machine");
}

TEST_F(VolumetricCli, ErrorsFileWithABadColumn) {
  const std::string e = write("E.json",
                              "{\n"
                              "  \"type\": \"hybrid_geometric_errors\",\n"
                              "  \"x2\": {\"positions\": [0, 100, 200],\n"
                              "         \"dx\": [0, 0.01]}\n"
                              "}\n");
  const std::string err =
      expectUsageError(pkm({"volumetric", "-e", e, "--grid", kGrid}), e + ":4: /x2/dx: ");
  EXPECT_THAT(err, StartsWith("pkm: error: "));
  EXPECT_THAT(err, HasSubstr("expected 3 values, found 2"));
  const std::string u =
      write("U.json", "{\n  \"type\": \"hybrid_geometric_errors\",\n  \"x3\": {}\n}\n");
  expectUsageError(pkm({"volumetric", "-e", u, "--grid", kGrid}), u + ":3: /x3: unknown key");
}

TEST_F(VolumetricCli, GridAndCommandsTogetherOrNeither) {
  const std::string c = write("C.csv", "x2,y2,xp,yp,zp\n0,0,0,0,0\n");
  const CliRun both = pkm({"volumetric", "-e", kSeedErrors, "--grid", kGrid, "--commands", c});
  EXPECT_EQ(both.code, kExitUsage);
  EXPECT_EQ(both.out, "");
  const CliRun neither = pkm({"volumetric", "-e", kSeedErrors});
  EXPECT_EQ(neither.code, kExitUsage);
  EXPECT_THAT(neither.err, HasSubstr("--grid or --commands"));
  EXPECT_EQ(neither.out, "");
}

TEST_F(VolumetricCli, BadCommandsFile) {
  const std::string missing = write("M.csv", "x2,y2,xp,yp\n0,0,0,0\n");
  const std::string err = expectUsageError(
      pkm({"volumetric", "-e", kSeedErrors, "--commands", missing}), missing + ":1: ");
  EXPECT_THAT(err, HasSubstr("missing column"));
  const std::string bad = write("B.csv", "x2,y2,xp,yp,zp\n0,0,0,0,0\n0,0,0,zero,0\n");
  const CliRun r = pkm({"volumetric", "-e", kSeedErrors, "--commands", bad});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr(bad + ":3: column 'yp'"));
}

}  // namespace PKM_TEST_NS
