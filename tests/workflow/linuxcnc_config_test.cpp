// workflow::writeLinuxcncConfig: the folder written (hexapod, calibrated hexapod file, Exechon),
// compensation tables copied and checked, nothing replaced without force, and the sample
// configurations in data/linuxcnc equal to what the writer produces today.
#include "pkm/workflow/linuxcnc_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/hexapod_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "support/scratch_files.hpp"
#include "support/truth_text.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

/// A fresh scratch folder.
fs::path freshDir(const std::string& name) {
  const fs::path dir = test::scratchPath("linuxcnc_config", name);
  fs::remove_all(dir);
  return dir;
}

TEST(LinuxcncConfigWorkflow, WritesTheHexapodFolder) {
  const fs::path dir = freshDir("hexapod");
  LinuxcncConfigRequest r;
  r.machine = "hexapod-default";
  r.out = dir.string();
  const LinuxcncConfigResult res = writeLinuxcncConfig(r);
  EXPECT_EQ(res.kind, "hexapod");
  EXPECT_EQ(res.ini, (dir / "pkm-hx1200.ini").string());
  EXPECT_THAT(res.files,
              ElementsAre((dir / "pkm-hx1200.ini").string(),
                          (dir / "kinematics.hal").string(),
                          (dir / "sim.hal").string(),
                          (dir / "tool.tbl").string(),
                          (dir / "pkm-hx1200.params").string()));
  for (const std::string& f : res.files) EXPECT_TRUE(fs::is_regular_file(f)) << f;
}

TEST(LinuxcncConfigWorkflow, TheSimulatedMachineJoinsTheLoop) {
  const fs::path dir = freshDir("truth");
  fs::create_directories(dir.parent_path());
  const fs::path truth = dir.parent_path() / "truth-in.json";
  std::ofstream(truth) << test::hexapodTruthText();
  LinuxcncConfigRequest r;
  r.machine = "hexapod-default";
  r.out = dir.string();
  r.simulate_truth = truth.string();
  r.truth_program = "/opt/pkm/bin/pkm-truth";
  const LinuxcncConfigResult res = writeLinuxcncConfig(r);
  EXPECT_THAT(res.files, ::testing::Contains((dir / "truth.hal").string()));
  EXPECT_THAT(res.files, ::testing::Contains((dir / "truth.json").string()));
  const std::string hal = test::slurp(dir / "truth.hal");
  EXPECT_THAT(hal,
              HasSubstr("loadusr -Wn pkmtruth /opt/pkm/bin/pkm-truth --truth truth.json --name "
                        "pkmtruth --joint-offset 250.49"));
  EXPECT_THAT(hal, HasSubstr("net j5-pos => pkmtruth.joint-5\n"));
  const std::string ini = test::slurp(res.ini);
  EXPECT_THAT(ini, HasSubstr("HALFILE = sim.hal\nHALFILE = truth.hal\n"));
  EXPECT_EQ(test::slurp(dir / "truth.json"), test::hexapodTruthText());
  // Refused: an Exechon, a machine in inch, a malformed truth.
  r.force = true;
  r.machine = "mxt700s-like";
  EXPECT_THROW((void)writeLinuxcncConfig(r), InvalidArgument);
  r.machine = "hexapod-linuxcnc-sim";
  EXPECT_THROW((void)writeLinuxcncConfig(r), InvalidArgument);
  r.machine = "hexapod-default";
  std::ofstream(truth) << "{";
  EXPECT_THROW((void)writeLinuxcncConfig(r), IoError);
}

TEST(LinuxcncConfigWorkflow, RefusesToReplaceWithoutForce) {
  const fs::path dir = freshDir("refuse");
  fs::create_directories(dir);
  io::writeFileAtomic(dir / "kinematics.hal", "mine\n", io::Overwrite::kAllow);
  io::writeFileAtomic(dir / "notes.txt", "kept\n", io::Overwrite::kAllow);
  LinuxcncConfigRequest r;
  r.machine = "hexapod-default";
  r.out = dir.string();
  try {
    (void)writeLinuxcncConfig(r);
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr((dir / "kinematics.hal").string()));
    EXPECT_THAT(e.what(), HasSubstr("--force"));
  }
  EXPECT_FALSE(fs::exists(dir / "pkm-hx1200.ini"));  // nothing written
  EXPECT_EQ(test::slurp(dir / "kinematics.hal"), "mine\n");
  r.force = true;
  (void)writeLinuxcncConfig(r);
  EXPECT_THAT(test::slurp(dir / "kinematics.hal"), HasSubstr("loadrt [KINS]KINEMATICS"));
  EXPECT_THAT(test::slurp(dir / "pkm-hx1200.params"), HasSubstr("\nbase.0 "));
  EXPECT_EQ(test::slurp(dir / "notes.txt"), "kept\n");  // other files untouched
}

TEST(LinuxcncConfigWorkflow, CalibratedMachineFileAndCompensationTables) {
  const fs::path dir = freshDir("calibrated");
  fs::create_directories(dir);
  io::HexapodMachine cal = io::loadHexapodMachine("hexapod-default");
  cal.model.name = "pkm-hx1200-calibrated";
  cal.model.struts[2].length_offset += 0.0625;
  io::writeFileAtomic(dir / "cal.json", io::writeHexapodJson(cal), io::Overwrite::kAllow);
  io::writeFileAtomic(
      dir / "s2.txt", "0 -0.01 0.002\n250 0.004 0.003\n500 0 0\n", io::Overwrite::kAllow);
  LinuxcncConfigRequest r;
  r.machine = (dir / "cal.json").string();
  r.out = (dir / "cfg").string();
  r.comp_files = {{2, (dir / "s2.txt").string()}};
  r.comp_file_type = 1;
  r.display = "linuxcncrsh";
  const LinuxcncConfigResult res = writeLinuxcncConfig(r);
  EXPECT_EQ(res.ini, (dir / "cfg/pkm-hx1200-calibrated.ini").string());
  EXPECT_EQ(res.files.back(), (dir / "cfg/joint2.comp").string());
  EXPECT_EQ(test::slurp(dir / "cfg/joint2.comp"), test::slurp(dir / "s2.txt"));
  const std::string ini = test::slurp(res.ini);
  EXPECT_THAT(ini, HasSubstr("[JOINT_2]\n"));
  EXPECT_THAT(ini, HasSubstr("COMP_FILE = joint2.comp\nCOMP_FILE_TYPE = 1\n"));
  EXPECT_THAT(ini, HasSubstr("DISPLAY = linuxcncrsh\n"));
  EXPECT_THAT(test::slurp(dir / "cfg/pkm-hx1200-calibrated.params"),
              HasSubstr("\nlength-offset.2 650.0625\n"));
}

TEST(LinuxcncConfigWorkflow, BadTablesAndRequests) {
  const fs::path dir = freshDir("bad");
  fs::create_directories(dir);
  io::writeFileAtomic(dir / "bad.txt", "0 1 2\n5 1\n", io::Overwrite::kAllow);
  LinuxcncConfigRequest r;
  r.out = (dir / "cfg").string();
  r.comp_files = {{0, (dir / "bad.txt").string()}};
  EXPECT_THROW((void)writeLinuxcncConfig(r), InvalidArgument);  // no type
  r.comp_file_type = 1;
  try {
    (void)writeLinuxcncConfig(r);
    FAIL() << "no exception";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("bad.txt:2"));
  }
  r.comp_files = {{6, (dir / "bad.txt").string()}};
  io::writeFileAtomic(dir / "bad.txt", "0 1 2\n", io::Overwrite::kAllow);
  EXPECT_THROW((void)writeLinuxcncConfig(r), InvalidArgument);  // joint 6 of a hexapod
  EXPECT_FALSE(fs::exists(dir / "cfg"));
  LinuxcncConfigRequest empty;
  EXPECT_THROW(empty.validate(), InvalidArgument);  // no --out
}

/// A request for hexapod-default with one type-`type` table of joint 0 holding `rows`.
LinuxcncConfigRequest tableRequest(const fs::path& dir, const std::string& rows, int type) {
  fs::create_directories(dir);
  io::writeFileAtomic(dir / "t.comp", rows, io::Overwrite::kAllow);
  LinuxcncConfigRequest r;
  r.machine = "hexapod-default";
  r.out = (dir / "cfg").string();
  r.comp_files = {{0, (dir / "t.comp").string()}};
  r.comp_file_type = type;
  return r;
}

/// The message of the InvalidArgument `r` throws ("" when none).
std::string refusal(const LinuxcncConfigRequest& r) {
  try {
    (void)writeLinuxcncConfig(r);
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

// A type 0 table (nominal, actual positions; errors of a few µm over 500 mm) and the type 1 table
// of the same errors (nominal, trims = -error).
constexpr const char* kType0 = "0 0.01 0.012\n250 250.004 250.003\n500 500 500.001\n";
constexpr const char* kType1 = "0 -0.01 -0.012\n250 -0.004 -0.003\n500 0 -0.001\n";

TEST(LinuxcncConfigWorkflow, CompTablesOfTheirDeclaredTypePass) {
  EXPECT_EQ(refusal(tableRequest(freshDir("type0"), kType0, 0)), "");
  EXPECT_EQ(refusal(tableRequest(freshDir("type1"), kType1, 1)), "");
}

TEST(LinuxcncConfigWorkflow, CompTableOfTheOtherTypeIsRefused) {
  // Type 0 read as type 1: corrections of 250 mm (the positions), 1 % of 500 mm allowed.
  const std::string as1 = refusal(tableRequest(freshDir("0as1"), kType0, 1));
  EXPECT_THAT(as1, HasSubstr("t.comp:2: joint 0's correction at 250 would be 250.004"));
  EXPECT_THAT(as1, HasSubstr("more than 1 % of the joint's travel (500, 0 to 500)"));
  EXPECT_THAT(as1, HasSubstr("looks like a type 0 table"));
  EXPECT_THAT(as1, HasSubstr("--no-comp-check"));
  const std::string as0 = refusal(tableRequest(freshDir("1as0"), kType1, 0));
  EXPECT_THAT(as0, HasSubstr("t.comp:2:"));
  EXPECT_THAT(as0, HasSubstr("looks like a type 1 table"));
  EXPECT_FALSE(fs::exists(freshDir("1as0") / "cfg"));
}

TEST(LinuxcncConfigWorkflow, CompTableTooLargeForTheTravel) {
  // 6 mm over 500 mm: more than 1 %, and implausible as type 0 too (no hint then).
  const std::string big = refusal(tableRequest(freshDir("big"), "0 6 6\n500 0 0\n", 1));
  EXPECT_THAT(big, HasSubstr("t.comp:1: joint 0's correction at 0 would be 6"));
  EXPECT_THAT(big, ::testing::Not(HasSubstr("looks like")));
  EXPECT_EQ(refusal(tableRequest(freshDir("fine"), "0 4.9 4.9\n500 0 0\n", 1)), "");
}

TEST(LinuxcncConfigWorkflow, NoCompCheckOverridesWithANotice) {
  LinuxcncConfigRequest r = tableRequest(freshDir("override"), kType0, 1);
  r.check_comp_files = false;
  const LinuxcncConfigResult res = writeLinuxcncConfig(r);
  EXPECT_THAT(res.notices, ::testing::Contains(HasSubstr("--no-comp-check")));
}

TEST(LinuxcncConfigWorkflow, FlippedCompTableIsRefusedAgainstItsData) {
  const fs::path dir = freshDir("flipped");
  fs::create_directories(dir);
  // The errors kType1 cancels: measured − target = +0.01 at 0 (+), ... (mm).
  io::writeFileAtomic(dir / "strut0.csv",
                      "target,direction,run,measured\n0,+,1,0.01\n0,-,1,0.012\n250,+,1,250.004\n"
                      "250,-,1,250.003\n500,+,1,500\n500,-,1,500.001\n",
                      io::Overwrite::kAllow);
  LinuxcncConfigRequest good = tableRequest(dir / "good", kType1, 1);
  good.comp_data = {{0, (dir / "strut0.csv").string()}};
  EXPECT_EQ(refusal(good), "");
  LinuxcncConfigRequest flipped =
      tableRequest(dir / "bad", "0 0.01 0.012\n250 0.004 0.003\n500 0 0.001\n", 1);
  flipped.comp_data = good.comp_data;
  const std::string why = refusal(flipped);
  EXPECT_THAT(why, HasSubstr("t.comp:1: joint 0's corrections have the sign of the errors"));
  EXPECT_THAT(why, HasSubstr("strut0.csv"));
  EXPECT_FALSE(fs::exists(dir / "bad/cfg"));
  // Data for a joint without a table is a usage error.
  LinuxcncConfigRequest stray = good;
  stray.comp_data = {{3, (dir / "strut0.csv").string()}};
  EXPECT_THAT(refusal(stray), HasSubstr("--comp-data 3="));
}

TEST(LinuxcncConfigWorkflow, Exechon) {
  const fs::path dir = freshDir("exechon");
  LinuxcncConfigRequest r;
  r.machine = "mxt700s-like";
  r.out = dir.string();
  const LinuxcncConfigResult res = writeLinuxcncConfig(r);
  EXPECT_EQ(res.kind, "exechon");
  EXPECT_TRUE(fs::is_regular_file(dir / "mxt700s-like.params"));
  EXPECT_THAT(res.notices, ::testing::Contains(HasSubstr("X2/Y2")));
}

// data/linuxcnc/<sample> must hold exactly what `pkm linuxcnc config --machine <machine>` writes
// today. When this fails after a change to the writer or a built-in machine, regenerate:
//   build/bin/pkm linuxcnc config --machine <machine> --out data/linuxcnc/<sample> --force
TEST(LinuxcncConfigWorkflow, SamplesAreWhatTheWriterProduces) {
  const std::pair<const char*, const char*> samples[] = {
      {"hexapod-default", "hexapod-default"},
      {"hexapod-linuxcnc-sim", "hexapod-linuxcnc-sim"},
      {"mxt700s-like", "exechon-mxt700s"}};
  for (const auto& [machine, sample] : samples) {
    const fs::path dir = fs::path(PKM_SOURCE_DIR) / "data/linuxcnc" / sample;
    LinuxcncConfigRequest r;
    r.machine = machine;
    r.out = dir.string();
    std::vector<std::string> notices;
    std::set<std::string> names;
    for (const io::NamedText& f : linuxcncConfigFiles(r, notices)) {
      names.insert(f.name);
      EXPECT_EQ(test::slurp(dir / f.name), f.text)
          << (dir / f.name) << " is stale: build/bin/pkm linuxcnc config --machine " << machine
          << " --out data/linuxcnc/" << sample << " --force";
    }
    for (const auto& entry : fs::directory_iterator(dir)) {
      const std::string name = entry.path().filename().string();
      if (name.starts_with("linuxcnc.var")) continue;  // LinuxCNC's own, after a run in place
      EXPECT_TRUE(names.count(name)) << entry.path() << " is not written by pkm linuxcnc config";
    }
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
