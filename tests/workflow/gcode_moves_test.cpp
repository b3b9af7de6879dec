// workflow::runGcodeMoves: the CSV of a short program, errors named after an upload, the output
// file written atomically and never over an existing one without force, cancellation.
#include "pkm/workflow/gcode_moves.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "pkm/cnc/move.hpp"
#include "pkm/core/error.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

using test::slurp;

fs::path scratch(const std::string& name) {
  return test::scratchPath("workflow_gcode_moves", name);
}

GcodeMovesRequest request(std::string text) {
  GcodeMovesRequest r;
  r.program = {"upload.ngc", std::move(text)};
  r.interpreter.require_program_end = false;  // snippets; the CLI tests check the end
  return r;
}

TEST(GcodeMovesWorkflow, OneRowPerMotion) {
  const GcodeMovesResult r =
      runGcodeMoves(request("(part)\nG0 X0 Y0 Z10\nG1 X10 F600\nG1 Y10\nG4 P1\nM2\n"));
  EXPECT_EQ(r.moves, 3u);
  EXPECT_EQ(r.lines, 6u);
  EXPECT_TRUE(r.ended_by_m2);
  EXPECT_THAT(r.csv, StartsWith(std::string(cnc::kMoveCsvHeader) + "\n"));
  EXPECT_EQ(std::count(r.csv.begin(), r.csv.end(), '\n'), 4);
  EXPECT_THAT(r.note, HasSubstr("3 moves"));
  EXPECT_THAT(runGcodeMoves(request("G0 X1\n")).note, HasSubstr("(no M2/M30 at the end)"));
}

TEST(GcodeMovesWorkflow, AnInchProgramIsToldItsCsvIsInMillimetres) {
  // rs274 prints canonical calls in program units; the CSV keeps machine mm (its documented
  // contract, byte for byte for every program), and the note says so for moves under G20.
  const GcodeMovesResult in = runGcodeMoves(request("G20\nG0 X1\nG1 A15 F300\nG21 G0 X0\nM2\n"));
  EXPECT_EQ(in.csv,
            std::string(cnc::kMoveCsvHeader) +
                "\n2,rapid,25.4,0,0,0,0,0,,,,0,XY,\n3,linear,25.4,0,0,15,0,0,,,,0,XY,300\n"
                "4,rapid,0,0,0,15,0,0,,,,0,XY,\n");
  EXPECT_THAT(in.note,
              HasSubstr("3 moves; 2 of them programmed in inches (G20): the CSV is in mm"));
  EXPECT_THAT(runGcodeMoves(request("G21 G0 X1\nM2\n")).note, Not(HasSubstr("inch")));
}

TEST(GcodeMovesWorkflow, ProgramTextHeldElsewhereIsReadInsteadOfTheRequestsText) {
  const std::string text = "G0 X0\nG1 X1 F100\nG33 X1\n";
  GcodeMovesRequest r = request("G0 X5\nM2\n");
  r.program_text = std::string_view(text).substr(0, text.find("G33"));  // the first two lines
  const GcodeMovesResult ok = runGcodeMoves(r);
  EXPECT_EQ(ok.moves, 2u);
  EXPECT_EQ(ok.lines, 2u);
  r.program_text = text;
  try {
    (void)runGcodeMoves(r);
    FAIL() << "accepted G33";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:3:"));
  }
}

TEST(GcodeMovesWorkflow, TheOutputCallbackGetsTheCsv) {
  std::string seen;
  const GcodeMovesResult r =
      runGcodeMoves(request("G0 X0\nG1 X1 F100\n"), {}, [&](std::string_view t) { seen += t; });
  EXPECT_TRUE(r.csv.empty());
  EXPECT_THAT(seen, StartsWith(cnc::kMoveCsvHeader));
  EXPECT_EQ(std::count(seen.begin(), seen.end(), '\n'), 3);
}

TEST(GcodeMovesWorkflow, ErrorsNameTheUploadAndItsLine) {
  for (const char* text : {"G0 X0\nG33 X1\n", "o1 sub\nG0 X0\no1 endsub\nG33 X1\n"}) {
    try {
      (void)runGcodeMoves(request(text));
      FAIL() << "accepted " << text;
    } catch (const IoError& e) {
      EXPECT_THAT(e.what(), StartsWith("upload.ngc:")) << text;
      EXPECT_THAT(e.what(), HasSubstr("G33"));
    }
  }
}

TEST(GcodeMovesWorkflow, WritesTheFileAndRefusesToOverwriteIt) {
  GcodeMovesRequest r = request("G0 X0\nG1 X1 F100\nM2\n");
  r.out = scratch("moves.csv").string();
  fs::remove(r.out);
  const GcodeMovesResult first = runGcodeMoves(r);
  EXPECT_TRUE(first.csv.empty());
  EXPECT_THAT(slurp(r.out), StartsWith(cnc::kMoveCsvHeader));
  std::ofstream(r.out) << "the user's file";
  EXPECT_THROW((void)runGcodeMoves(r), IoError);
  EXPECT_EQ(slurp(r.out), "the user's file");
  // A failing program leaves the existing file alone even with force.
  r.force = true;
  r.program.text = "G0 X0\nG33 X1\n";
  EXPECT_THROW((void)runGcodeMoves(r), IoError);
  EXPECT_EQ(slurp(r.out), "the user's file");
  EXPECT_FALSE(fs::exists(r.out + ".tmp"));
}

TEST(GcodeMovesWorkflow, RejectsBadSettings) {
  GcodeMovesRequest r = request("G0 X0\n");
  r.interpreter.tool_units = "cm";
  EXPECT_THROW(r.validate(), InvalidArgument);
  EXPECT_THROW((void)runGcodeMoves(r), InvalidArgument);
  r.interpreter.tool_units = "inch";
  r.interpreter.max_iterations = 0;
  EXPECT_THROW((void)runGcodeMoves(r), InvalidArgument);
}

TEST(GcodeMovesWorkflow, CancellationStopsALongProgram) {
  // 40000 motions: a progress report every kGcodeProgressInterval of them.
  GcodeMovesRequest r = request("o1 repeat [20000]\nG1 X1 F6000\nG1 X0\no1 endrepeat\nM2\n");
  r.out = scratch("long.csv").string();
  fs::remove(r.out);
  CancellationToken token;
  std::vector<std::string> messages;
  RunControl control;
  control.cancel = &token;
  control.progress = [&](const ProgressEvent& e) {
    messages.push_back(e.message);
    if (messages.size() == 2) token.cancel();
  };
  EXPECT_THROW((void)runGcodeMoves(r, control), Cancelled);
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0], "interpreting: 10000 motions");
  EXPECT_FALSE(fs::exists(r.out));
  EXPECT_FALSE(fs::exists(r.out + ".tmp"));
  // Uncancelled, the same request runs to the end.
  token.reset();
  messages.clear();
  control.progress = [&](const ProgressEvent& e) { messages.push_back(e.message); };
  EXPECT_EQ(runGcodeMoves(r, control).moves, 40000u);
  EXPECT_EQ(messages.size(), 4u);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
