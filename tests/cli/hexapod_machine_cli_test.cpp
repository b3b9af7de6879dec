// The CLI contract of `pkm hexapod check|linuxcnc-params|hal|describe|machines` and of the inputs
// of every `pkm hexapod` command, tested by running the built binary (PKM_BINARY) as a subprocess:
// limit checks, machine round trips through `hal` and `describe --json`, and exit code 2 with
// FILE:LINE messages on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli/hexapod_cli.hpp"
#include "support/cli_fixture.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

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

// ---------------------------------------------------------------------------------------------
// check, describe, hal, machines

TEST_F(HexapodCli, CheckRuns) {
  const CliRun sim =
      pkm({"hexapod", "check", "-m", "hexapod-linuxcnc-sim", "-p", write("P.csv", kSimPoses)});
  ASSERT_EQ(sim.code, 0) << sim.err;
  auto lines = splitLines(sim.out);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_THAT(lines[0], StartsWith("row,status,min_stroke_margin,stroke_strut,"));
  const std::size_t columns = splitFields(lines[0]).size();
  for (std::size_t k = 1; k < lines.size(); ++k) {
    EXPECT_THAT(lines[k], StartsWith(std::to_string(k - 1) + ",ok,"));
    EXPECT_EQ(splitFields(lines[k]).size(), columns) << lines[k];
  }
  const CliRun def = pkm(
      {"hexapod", "check", "-p", write("D.csv", "x,y,z,a,b,c\n0,0,200,0,0,0\n0,0,-400,0,0,0\n")});
  ASSERT_EQ(def.code, 0) << def.err;
  lines = splitLines(def.out);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_THAT(lines[1], StartsWith("0,ok,"));
  EXPECT_THAT(lines[2], StartsWith("1,stroke,-"));  // negative stroke margin
  EXPECT_THAT(lines[2], HasSubstr("stroke strut 0"));
  EXPECT_EQ(splitFields(lines[2]).size(), columns);
}

// The pkmhexkins parameter file (read by the component at loadrt; its parser's round trip is
// tests/io/linuxcnc_hexapod_params_test.cpp): every strut, the tool and home, the machine's unit.
TEST_F(HexapodCli, LinuxcncParamsWritesTheComponentsFile) {
  const CliRun r = pkm({"hexapod", "linuxcnc-params", "--machine", "hexapod-linuxcnc-sim"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("lengths in inch"));
  EXPECT_THAT(r.out, HasSubstr("\nbase.0 -22.95 13.25 0\n"));
  EXPECT_THAT(r.out, HasSubstr("\nplatform.2 10.459 -4.884 0\n"));
  EXPECT_THAT(r.out, HasSubstr("\nlength-offset.5 "));
  EXPECT_THAT(r.out, HasSubstr("\nhome 0 0 20 0 0 0\n"));
  const CliRun bad = pkm({"hexapod", "linuxcnc-params", "--machine", "no-such-machine"});
  EXPECT_EQ(bad.code, kExitUsage);
  EXPECT_THAT(bad.err, HasSubstr("no-such-machine"));
}

TEST_F(HexapodCli, HalOutputReadBackGivesSameIk) {
  const std::string poses = write("P.csv", kSimPoses);
  const CliRun hal = pkm({"hexapod", "hal", "--machine", "hexapod-linuxcnc-sim"});
  ASSERT_EQ(hal.code, 0) << hal.err;
  EXPECT_THAT(hal.out, HasSubstr("setp genhexkins.platform.2.x 10.459\n"));
  const std::string hal_file = write("kinematics.hal", hal.out);
  // The sim geometry needs its INI (HOME z 20); the setp block lists the values to put there.
  EXPECT_THAT(hal.out, HasSubstr("# [TRAJ] HOME = 0 0 20 0 0 0"));
  const std::string ini = write("sim.ini", "[TRAJ]\nHOME = 0 0 20 0 0 0\nLINEAR_UNITS = inch\n");
  const CliRun builtin =
      pkm({"hexapod", "ik", "--machine", "hexapod-linuxcnc-sim", "--poses", poses});
  const CliRun from_hal =
      pkm({"hexapod", "ik", "--machine", hal_file, "--ini", ini, "--poses", poses});
  ASSERT_EQ(from_hal.code, 0) << from_hal.err;
  EXPECT_EQ(from_hal.out, builtin.out);
  // Notices about ignored lines go to stderr, not into the output.
  EXPECT_THAT(from_hal.out, ::testing::Not(HasSubstr("note")));
}

TEST_F(HexapodCli, HalOfDefaultMachineReadBackGivesSameJointDistances) {
  const CliRun hal = pkm({"hexapod", "hal"});
  ASSERT_EQ(hal.code, 0) << hal.err;
  const std::string hal_file = write("kinematics.hal", hal.out);
  write("machine.ini",
        "[HAL]\nHALFILE = kinematics.hal\n[TRAJ]\nHOME = 0 0 200 0 0 0\nLINEAR_UNITS = mm\n");
  const std::string poses = write("P.csv", kDefaultPoses);
  const CliRun builtin = pkm({"hexapod", "ik", "--poses", poses});
  const CliRun from_hal = pkm({"hexapod", "ik", "--machine", hal_file, "--poses", poses});
  ASSERT_EQ(from_hal.code, 0) << from_hal.err;
  EXPECT_THAT(from_hal.err, HasSubstr("pkm: note: using INI"));
  const auto a = splitLines(builtin.out), b = splitLines(from_hal.out);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 1; k < a.size(); ++k) {
    const auto fa = splitFields(a[k]), fb = splitFields(b[k]);
    // LinuxCNC joint positions are joint-centre distances: the pkm reading plus the 650 length
    // offset.
    for (std::size_t i = 0; i < 6; ++i) EXPECT_NEAR(num(fb[i]), num(fa[i]) + 650.0, kTolRoundTrip);
  }
}

TEST_F(HexapodCli, HalOutputLoadsOnItsOwn) {
  const CliRun hal = pkm({"hexapod", "hal", "--machine", "hexapod-linuxcnc-sim"});
  ASSERT_EQ(hal.code, 0) << hal.err;
  const std::string poses = write("P.csv", kSimPoses);
  const CliRun from_hal =
      pkm({"hexapod", "ik", "--machine", write("alone.hal", hal.out), "--poses", poses});
  ASSERT_EQ(from_hal.code, 0) << from_hal.err;
  EXPECT_EQ(from_hal.out,
            pkm({"hexapod", "ik", "--machine", "hexapod-linuxcnc-sim", "--poses", poses}).out);
}

TEST_F(HexapodCli, HalWithoutIniExplainsWhy) {
  const CliRun hal = pkm({"hexapod", "hal", "--machine", "hexapod-linuxcnc-sim"});
  std::string without_home;  // the setp block without its "# pkm:" lines, as a hand-written file
  std::istringstream in(hal.out);
  for (std::string line; std::getline(in, line);)
    if (line.rfind("# pkm:", 0) != 0) without_home += line + "\n";
  const std::string hal_file = write("lonely.hal", without_home);
  const CliRun r =
      pkm({"hexapod", "ik", "--machine", hal_file, "--poses", write("P.csv", kSimPoses)});
  expectUsageError(r, hal_file + ": ");
  EXPECT_THAT(r.err, HasSubstr("--ini"));
}

TEST_F(HexapodCli, DescribeJsonReadBackGivesSameIk) {
  for (const auto& [machine, poses_text] : {std::pair{"hexapod-default", kDefaultPoses},
                                            std::pair{"hexapod-linuxcnc-sim", kSimPoses}}) {
    SCOPED_TRACE(machine);
    const CliRun json = pkm({"hexapod", "describe", "--json", "--machine", machine});
    ASSERT_EQ(json.code, 0) << json.err;
    EXPECT_THAT(json.out, StartsWith("{"));
    const std::string file = write("m.json", json.out);
    const std::string poses = write("P.csv", poses_text);
    const CliRun builtin = pkm({"hexapod", "ik", "--machine", machine, "--poses", poses});
    const CliRun from_json = pkm({"hexapod", "ik", "--machine", file, "--poses", poses});
    ASSERT_EQ(from_json.code, 0) << from_json.err;
    EXPECT_EQ(from_json.out, builtin.out);
    const CliRun check_a = pkm({"hexapod", "check", "--machine", machine, "--poses", poses});
    const CliRun check_b = pkm({"hexapod", "check", "--machine", file, "--poses", poses});
    EXPECT_EQ(check_a.out, check_b.out);  // limits, cones and diameters survive too
  }
}

TEST_F(HexapodCli, DescribeText) {
  const CliRun r = pkm({"hexapod", "describe"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("pkm-hx1200"));
  EXPECT_THAT(r.out, HasSubstr("builtin:hexapod-default"));
  EXPECT_THAT(r.out, HasSubstr("at home      status ok"));
}

TEST_F(HexapodCli, MachinesListsBuiltins) {
  const CliRun r = pkm({"hexapod", "machines"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(splitLines(r.out),
              ::testing::IsSupersetOf({"hexapod-default", "hexapod-linuxcnc-sim"}));
}

// ---------------------------------------------------------------------------------------------
// Bad input: exit code 2 and a message naming the file and line

TEST_F(HexapodCli, MissingColumn) {
  const std::string p = write("P.csv", "x,y,z,a,b\n0,0,20,0,0\n");
  const std::string err =
      expectUsageError(pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "-p", p}), p + ":1: ");
  EXPECT_THAT(err, HasSubstr("missing column"));
  EXPECT_THAT(err, StartsWith("pkm: error: "));
}

TEST_F(HexapodCli, NonNumber) {
  const std::string p = write("P.csv", "x,y,z,a,b,c\n0,0,20,0,0,0\n0,0,20,zero,0,0\n");
  const std::string err =
      expectUsageError(pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "-p", p}), p + ":3: ");
  EXPECT_THAT(err, HasSubstr("'zero'"));
}

TEST_F(HexapodCli, NanIsRejected) {
  const std::string p = write("P.csv", "x,y,z,a,b,c\nnan,0,20,0,0,0\n");
  expectUsageError(pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "-p", p}), p + ":2: ");
}

TEST_F(HexapodCli, InfIsRejected) {
  const std::string p =
      write("L.csv", "l0,l1,l2,l3,l4,l5\n30,30,30,30,30,30\n\n30,30,30,inf,30,30\n");
  expectUsageError(pkm({"hexapod", "fk", "-m", "hexapod-linuxcnc-sim", "-l", p}), p + ":4: ");
}

TEST_F(HexapodCli, WrongFieldCount) {
  const std::string p = write("P.csv", "x,y,z,a,b,c\n0,0,20,0,0\n");
  const std::string err =
      expectUsageError(pkm({"hexapod", "ik", "-m", "hexapod-linuxcnc-sim", "-p", p}), p + ":2: ");
  EXPECT_THAT(err, HasSubstr("expected 6 fields, found 5"));
  const std::string q = write("Q.csv", "x,y,z,a,b,c\n0,0,20,0,0,0,7\n");
  expectUsageError(pkm({"hexapod", "check", "-m", "hexapod-linuxcnc-sim", "-p", q}), q + ":2: ");
}

TEST_F(HexapodCli, EmptyFile) {
  const std::string p = write("P.csv", "");
  const std::string err = expectUsageError(pkm({"hexapod", "ik", "-p", p}), p);
  EXPECT_THAT(err, HasSubstr("empty file"));
}

TEST_F(HexapodCli, NonexistentFile) {
  const std::string p = path("no-such-poses.csv");
  const std::string err = expectUsageError(pkm({"hexapod", "ik", "-p", p}), p);
  EXPECT_THAT(err, HasSubstr("cannot open"));
}

TEST_F(HexapodCli, MalformedMachineJson) {
  const std::string m = write("m.json", "{\n  \"units\": \"mm\",\n  \"struts\": [1, 2,, 3]\n}\n");
  const std::string err = expectUsageError(
      pkm({"hexapod", "ik", "--machine", m, "-p", write("P.csv", kSimPoses)}), m + ":3: ");
  EXPECT_THAT(err, HasSubstr("invalid JSON"));
}

TEST_F(HexapodCli, InvalidMachineGeometryNamesLine) {
  const CliRun json = pkm({"hexapod", "describe", "--json", "--machine", "hexapod-linuxcnc-sim"});
  std::string text = json.out;
  const auto pos = text.find("\"units\": \"inch\"");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 15, "\"units\": \"feet\"");
  const std::size_t line =
      1 + static_cast<std::size_t>(
              std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(pos), '\n'));
  const std::string m = write("m.json", text);
  expectUsageError(pkm({"hexapod", "describe", "--machine", m}),
                   m + ":" + std::to_string(line) + ": /units: ");
}

TEST_F(HexapodCli, UnknownMachineName) {
  const std::string err = expectUsageError(
      pkm({"hexapod", "describe", "--machine", "no-such-machine"}), "no-such-machine");
  EXPECT_THAT(err, HasSubstr("hexapod-linuxcnc-sim"));
}

TEST_F(HexapodCli, UnknownOption) {
  const CliRun r = pkm({"hexapod", "ik", "-p", write("P.csv", kSimPoses), "--bogus"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("--bogus"));
  EXPECT_EQ(r.out, "");
}

TEST_F(HexapodCli, UnknownSubcommandAndMissingSubcommand) {
  EXPECT_EQ(pkm({"hexapod", "frobnicate"}).code, kExitUsage);
  EXPECT_EQ(pkm({"hexapod"}).code, kExitUsage);
  EXPECT_EQ(pkm({}).code, kExitUsage);
}

TEST_F(HexapodCli, MissingPoses) {
  const CliRun r = pkm({"hexapod", "ik", "--machine", "hexapod-linuxcnc-sim"});
  EXPECT_EQ(r.code, kExitUsage);
  EXPECT_THAT(r.err, HasSubstr("--poses"));
  const CliRun f = pkm({"hexapod", "fk"});
  EXPECT_EQ(f.code, kExitUsage);
  EXPECT_THAT(f.err, HasSubstr("--lengths"));
}

}  // namespace PKM_TEST_NS
