// `pkm linuxcnc install`: the differences shown and nothing written without --force (exit 2),
// the files patched with --force (exit 0), on a copy of LinuxCNC's hexapod-sim configuration.
// `pkm linuxcnc config`: the folder written, refused without --force, bad --comp-file values;
// `pkm hexapod hal --kins pkmhexkins`.
#include <filesystem>
#include <string>

#include "support/cli_fixture.hpp"
#include "support/linuxcnc_sample.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

TEST_F(CliTest, LinuxcncInstallShowsThenPatches) {
  const fs::path sample = pkm::test::linuxcncHexapodSim();
  if (!fs::is_directory(sample))
    GTEST_SKIP() << sample << " not found (run scripts/fetch-linuxcnc.sh)";
  fs::copy(sample, path("cfg"), fs::copy_options::recursive);
  // A calibration of the sim hexapod: its machine file with one joint moved.
  std::string cal = slurp(fs::path(PKM_SOURCE_DIR) / "data/machines/hexapod-linuxcnc-sim.json");
  cal.replace(cal.find("\"base\": [-22.95, 13.25, 0]"), 26, "\"base\": [-22.95, 13.3, 0]");
  const std::string cal_path = write("cal.json", cal);
  const std::vector<std::string> args{
      "linuxcnc", "install", "--calibration", cal_path, "--ini", path("cfg/hexapod.ini")};
  const CliRun preview = pkm(args);
  EXPECT_EQ(preview.code, 2);
  EXPECT_THAT(preview.out,
              HasSubstr("-setp genhexkins.base.0.y  13.250\n+setp genhexkins.base.0.y  13.3\n"));
  EXPECT_THAT(preview.err, HasSubstr("nothing written"));
  // Round joint limits stay round (no -999.9999999999973 from stroke + length offset).
  EXPECT_THAT(preview.out, ::testing::Not(HasSubstr("99999999")));
  EXPECT_THAT(preview.out, ::testing::Not(HasSubstr("00000000")));
  EXPECT_FALSE(fs::exists(path("cfg/kinematics.hal.pkm-backup")));
  std::vector<std::string> forced = args;
  forced.push_back("--force");
  const CliRun done = pkm(forced);
  EXPECT_EQ(done.code, 0) << done.err;
  EXPECT_THAT(done.out, HasSubstr("backups: "));
  EXPECT_THAT(slurp(path("cfg/kinematics.hal")), HasSubstr("setp genhexkins.base.0.y  13.3\n"));
  EXPECT_EQ(pkm(args).code, 0);  // nothing left to change
}

TEST_F(CliTest, LinuxcncConfigWritesRefusesAndForces) {
  const std::vector<std::string> args{
      "linuxcnc", "config", "--machine", "hexapod-default", "--out", path("cfg")};
  const CliRun first = pkm(args);
  ASSERT_EQ(first.code, 0) << first.err;
  EXPECT_THAT(first.out, HasSubstr("linuxcnc " + path("cfg/pkm-hx1200.ini")));
  EXPECT_TRUE(fs::is_regular_file(path("cfg/kinematics.hal")));
  const CliRun again = pkm(args);
  EXPECT_EQ(again.code, 2);
  EXPECT_THAT(again.err, HasSubstr("--force"));
  std::vector<std::string> forced = args;
  forced.push_back("--force");
  EXPECT_EQ(pkm(forced).code, 0);
}

TEST_F(CliTest, LinuxcncConfigExechonWithCompensationTable) {
  const std::string table = write("legB.txt", "0 0.001 0.002\n700 699.999 700\n");
  const CliRun r = pkm({"linuxcnc",
                        "config",
                        "--machine",
                        "mxt700s-like",
                        "--out",
                        path("ex"),
                        "--comp-file",
                        "1=" + table,
                        "--comp-file-type",
                        "0",
                        "--display",
                        "linuxcncrsh"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("exechon"));
  EXPECT_THAT(slurp(path("ex/mxt700s-like.ini")),
              HasSubstr("COMP_FILE = joint1.comp\nCOMP_FILE_TYPE = 0\n"));
  EXPECT_EQ(slurp(path("ex/joint1.comp")), slurp(table));
}

TEST_F(CliTest, LinuxcncConfigBadCompFile) {
  const std::string table = write("t.txt", "0 0 0\n");
  for (const std::string& spec : {"x=" + table, "7=" + table, "=" + table, std::string("1=")}) {
    const CliRun r = pkm(
        {"linuxcnc", "config", "--out", path("bad"), "--comp-file", spec, "--comp-file-type", "1"});
    EXPECT_EQ(r.code, 2) << spec;
  }
  const CliRun untyped =
      pkm({"linuxcnc", "config", "--out", path("bad"), "--comp-file", "1=" + table});
  EXPECT_EQ(untyped.code, 2);
  EXPECT_THAT(untyped.err, HasSubstr("--comp-file-type"));
  EXPECT_FALSE(fs::exists(path("bad")));
}

TEST_F(CliTest, LinuxcncConfigRefusesWrongTypeAndFlippedTables) {
  // Joint 2 of hexapod-default: a type 0 table (actual positions) declared as type 1 would add
  // 300 mm corrections; a type 1 table with the errors' sign would double them.
  const std::string type0 = write("t0.comp", "100 100.02 100.01\n300 299.99 300\n");
  const std::vector<std::string> base{
      "linuxcnc", "config", "--machine", "hexapod-default", "--comp-file-type", "1"};
  auto with = [&](std::vector<std::string> extra) {
    std::vector<std::string> a = base;
    a.insert(a.end(), extra.begin(), extra.end());
    return pkm(a);
  };
  const CliRun wrong = with({"--out", path("w"), "--comp-file", "2=" + type0});
  EXPECT_EQ(wrong.code, 2);
  EXPECT_THAT(wrong.err, HasSubstr("t0.comp:1: joint 2's correction at 100 would be 100.02"));
  EXPECT_THAT(wrong.err, HasSubstr("give --comp-file-type 0"));
  EXPECT_FALSE(fs::exists(path("w")));
  const std::string data = write("strut2.csv",
                                 "target,direction,run,measured\n100,+,1,100.02\n100,-,1,100.01\n"
                                 "300,+,1,299.99\n300,-,1,300\n");
  const std::string flipped = write("t1.comp", "100 0.02 0.01\n300 -0.01 0\n");
  const CliRun flip =
      with({"--out", path("f"), "--comp-file", "2=" + flipped, "--comp-data", "2=" + data});
  EXPECT_EQ(flip.code, 2);
  EXPECT_THAT(flip.err, HasSubstr("t1.comp:1: joint 2's corrections have the sign of the errors"));
  EXPECT_FALSE(fs::exists(path("f")));
  const std::string good = write("t1good.comp", "100 -0.02 -0.01\n300 0.01 0\n");
  const CliRun ok =
      with({"--out", path("g"), "--comp-file", "2=" + good, "--comp-data", "2=" + data});
  EXPECT_EQ(ok.code, 0) << ok.err;
  const CliRun forced = with({"--out", path("o"), "--comp-file", "2=" + type0, "--no-comp-check"});
  EXPECT_EQ(forced.code, 0) << forced.err;
  EXPECT_THAT(forced.err, HasSubstr("--no-comp-check"));
}

TEST_F(CliTest, ParamsFileAsMachineSaysWhatItIs) {
  const std::string params =
      write("m.params",
            slurp(fs::path(PKM_SOURCE_DIR) / "data/linuxcnc/hexapod-default/pkm-hx1200.params"));
  const CliRun r = pkm({"linuxcnc", "config", "--machine", params, "--out", path("p")});
  EXPECT_EQ(r.code, 2);
  EXPECT_THAT(r.err, HasSubstr("a LinuxCNC kinematics parameter file"));
  EXPECT_THAT(r.err, HasSubstr("pass the machine it was written from"));
  EXPECT_THAT(r.err, ::testing::Not(HasSubstr("JSON:")));
}

TEST_F(CliTest, LinuxcncConfigOfAHalMachineIsNamedAfterItsFolder) {
  const fs::path sample = pkm::test::linuxcncHexapodSim();
  if (!fs::is_directory(sample))
    GTEST_SKIP() << sample << " not found (run scripts/fetch-linuxcnc.sh)";
  fs::copy(sample, path("hexapod-sim"), fs::copy_options::recursive);
  const CliRun r = pkm({"linuxcnc",
                        "config",
                        "--machine",
                        path("hexapod-sim/kinematics.hal"),
                        "--ini",
                        path("hexapod-sim/hexapod.ini"),
                        "--out",
                        path("out")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(path("out/hexapod-sim.ini")));
  EXPECT_TRUE(fs::is_regular_file(path("out/hexapod-sim.params")));
  EXPECT_FALSE(fs::exists(path("out/kinematics.ini")));
}

TEST_F(CliTest, HexapodHalWritesEitherBlock) {
  const CliRun gen = pkm({"hexapod", "hal", "--machine", "hexapod-default"});
  ASSERT_EQ(gen.code, 0) << gen.err;
  EXPECT_THAT(gen.out, HasSubstr("setp genhexkins.base.0.x"));
  const CliRun pkmkins =
      pkm({"hexapod", "hal", "--machine", "hexapod-default", "--kins", "pkmhexkins"});
  ASSERT_EQ(pkmkins.code, 0) << pkmkins.err;
  EXPECT_THAT(pkmkins.out, HasSubstr("setp pkmhexkins.length-offset.0 650\n"));
  EXPECT_THAT(pkmkins.out, ::testing::Not(HasSubstr("genhexkins")));
  EXPECT_EQ(pkm({"hexapod", "hal", "--kins", "trivkins"}).code, 2);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
