// workflow::flattenGcode: loops unrolled, errors named after an upload, the output file written
// and never over an existing one without force.
#include "pkm/workflow/gcode_flatten.hpp"

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
using ::testing::StartsWith;

using test::slurp;

GcodeFlattenRequest request(std::string text) {
  GcodeFlattenRequest r;
  r.program = {"upload.ngc", std::move(text)};
  r.interpreter.require_program_end = false;  // snippets; the CLI tests check the end
  return r;
}

constexpr const char* kLoop = "#1=2\no100 repeat [3]\nG1 X#1 F100\n#1=[#1+1]\no100 endrepeat\nM2\n";

TEST(GcodeFlattenWorkflow, UnrollsALoop) {
  const GcodeFlattenResult r = flattenGcode(request(kLoop));
  EXPECT_TRUE(r.flat.had_o_words);
  EXPECT_THAT(r.flat.text, HasSubstr("G1 X2 F100\nG1 X3 F100\nG1 X4 F100\n"));
  EXPECT_EQ(r.flat.text.find("o100"), std::string::npos);
  EXPECT_THAT(r.note, StartsWith(std::to_string(r.flat.blocks) + " executed blocks written"));
  EXPECT_THAT(flattenGcode(request("G0 X1\n")).note, HasSubstr("(the program has no O-words)"));
}

TEST(GcodeFlattenWorkflow, ErrorsNameTheUploadAndItsLine) {
  try {
    (void)flattenGcode(request("G0 X0\no1 endwhile\n"));
    FAIL() << "accepted a stray endwhile";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith("upload.ngc:2:"));
  }
}

TEST(GcodeFlattenWorkflow, WritesTheFileAndRefusesToOverwriteIt) {
  const fs::path dir =
      fs::temp_directory_path() / ("pkm_workflow_gcode_flatten_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  GcodeFlattenRequest r = request(kLoop);
  r.out = (dir / "flat.ngc").string();
  fs::remove(r.out);
  const GcodeFlattenResult first = flattenGcode(r);
  EXPECT_EQ(slurp(r.out), first.flat.text);
  std::ofstream(r.out) << "keep";
  EXPECT_THROW((void)flattenGcode(r), IoError);
  EXPECT_EQ(slurp(r.out), "keep");
  r.force = true;
  (void)flattenGcode(r);
  EXPECT_EQ(slurp(r.out), first.flat.text);
  fs::remove_all(dir);
}

TEST(GcodeFlattenWorkflow, RejectsBadSettings) {
  GcodeFlattenRequest r = request(kLoop);
  r.interpreter.max_iterations = 0;
  EXPECT_THROW((void)flattenGcode(r), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
