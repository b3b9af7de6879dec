// workflow::writeCompensationTable: exact tables from data with exact binary fractions, the
// summary and notices, the refusal to overwrite, and bad requests and data refused.
#include "pkm/workflow/compensation_table.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "pkm/core/error.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path scratch(const std::string& name) { return test::scratchPath("workflow_comp", name); }

using test::slurp;

/// Targets 0, 64, 128; deviations ↑ 2⁻⁷, 2⁻⁸, −2⁻⁹ and ↓ 0, −2⁻⁸, −2⁻⁷, two identical runs.
io::NamedText positioning() {
  std::string text = "target,direction,run,measured\n";
  const double t[3] = {0, 64, 128}, up[3] = {0.0078125, 0.00390625, -0.001953125},
               down[3] = {0, -0.00390625, -0.0078125};
  for (int run = 1; run <= 2; ++run) {
    for (int i = 0; i < 3; ++i) text += fmt::format("{},+,{},{}\n", t[i], run, t[i] + up[i]);
    for (int i = 2; i >= 0; --i) text += fmt::format("{},-,{},{}\n", t[i], run, t[i] + down[i]);
  }
  return {"pos.csv", text};
}

CompensationTableRequest request(const std::string& out) {
  CompensationTableRequest r;
  r.data = {positioning()};
  r.format = "linuxcnc1";
  r.axis = "X";
  r.out = scratch(out).string();
  r.force = true;
  return r;
}

TEST(CompensationTableWorkflow, TheTableIsInTheMachinesUnit) {
  // An INI with LINEAR_UNITS inch: the same table, every length divided by 25.4.
  const fs::path ini = scratch("inch.ini");
  std::ofstream(ini) << "[TRAJ]\nLINEAR_UNITS = inch\n";
  CompensationTableRequest q = request("inch.comp");
  q.ini = ini.string();
  std::vector<std::string> notes;
  RunControl control;
  control.notice = [&](const std::string& n) { notes.push_back(n); };
  const CompensationTableResult r = writeCompensationTable(q, control);
  EXPECT_EQ(r.text,
            fmt::format("0 {} 0\n{} {} {}\n{} {} {}\n",
                        -0.0078125 / 25.4,
                        64 / 25.4,
                        -0.00390625 / 25.4,
                        0.00390625 / 25.4,
                        128 / 25.4,
                        0.001953125 / 25.4,
                        0.0078125 / 25.4));
  EXPECT_EQ(r.summary.unit, "inch");
  EXPECT_EQ(r.summary.last, 128 / 25.4);
  EXPECT_EQ(r.summary.max_correction, 0.0078125 / 25.4);
  // pos.csv states no unit: read as mm, flagged on an inch machine.
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_THAT(notes[0], HasSubstr("pos.csv: its header states no length unit"));
  EXPECT_EQ(writeCompensationTable(request("mm.comp")).summary.unit, "mm");
}

TEST(CompensationTableWorkflow, ALinuxcncTableHoldsTheNegatedMeanDeviations) {
  const CompensationTableResult r = writeCompensationTable(request("x.comp"));
  const std::string expected =
      "0 -0.0078125 0\n"
      "64 -0.00390625 0.00390625\n"
      "128 0.001953125 0.0078125\n";
  EXPECT_EQ(r.text, expected);
  EXPECT_EQ(slurp(r.summary.out), expected);
  EXPECT_EQ(r.summary.rows, 3u);
  EXPECT_EQ(r.summary.input_rows, 3u);
  EXPECT_EQ(r.summary.first, 0.0);
  EXPECT_EQ(r.summary.last, 128.0);
  EXPECT_EQ(r.summary.max_correction, 0.0078125);
  EXPECT_EQ(r.summary.axis, "X");
  ASSERT_TRUE(r.summary.iso.has_value());
  EXPECT_FALSE(r.summary.input_axis.has_value());
}

TEST(CompensationTableWorkflow, AStraightnessTableHasTheLineRemoved) {
  CompensationTableRequest q = request("eyx.csv");
  q.data = {
      {"str.csv", "position,deviation\n0,0.0009765625\n100,-0.001953125\n200,0.0029296875\n"}};
  q.format = "isg";
  q.axis.clear();
  q.input_axis = "X";
  q.output_axis = "Y";
  q.line = "raw";
  const CompensationTableResult r = writeCompensationTable(q);
  EXPECT_EQ(r.summary.rows, 3u);
  EXPECT_EQ(r.summary.axis, "Y");
  EXPECT_EQ(r.summary.input_axis, "X");
  EXPECT_EQ(r.summary.max_correction, 0.0029296875);
  EXPECT_FALSE(r.summary.iso.has_value());
}

TEST(CompensationTableWorkflow, NotesAOneTableFormatGivenBidirectionalData) {
  CompensationTableRequest q = request("x.eec");
  q.format = "siemens-eec";
  std::vector<std::string> notices;
  RunControl control;
  control.notice = [&](const std::string& n) { notices.push_back(n); };
  (void)writeCompensationTable(q, control);
  ASSERT_EQ(notices.size(), 1u);
  EXPECT_THAT(notices[0], HasSubstr("siemens-eec has one table per axis"));
}

TEST(CompensationTableWorkflow, RefusesToOverwriteWithoutForce) {
  CompensationTableRequest q = request("keep.comp");
  std::ofstream(q.out) << "keep me\n";
  q.force = false;
  try {
    (void)writeCompensationTable(q);
    FAIL() << "overwrote";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("exists; refusing to overwrite (use --force)"));
  }
  EXPECT_EQ(slurp(q.out), "keep me\n");
}

TEST(CompensationTableWorkflow, RefusesBadRequestsAndData) {
  CompensationTableRequest q = request("bad.comp");
  q.axis.clear();
  EXPECT_THROW(q.validate(), InvalidArgument);
  q = request("bad.comp");
  q.format = "fanuc";
  EXPECT_THROW(q.validate(), InvalidArgument);
  q = request("bad.comp");
  q.format = "siemens-cec";
  EXPECT_THROW(q.validate(), InvalidArgument);  // needs --input-axis and --output-axis
  q = request("bad.comp");
  q.data = {{"upload.csv", "target,direction,run,measured\n0,+,1,0\n0,+,2,x\n"}};
  try {
    (void)writeCompensationTable(q);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("upload.csv:3:"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
