// workflow::renderReport: a report-data document from memory rendered into one HTML file, the
// refusal to overwrite, and a bad document named in the error with nothing written.
#include "pkm/workflow/report_render.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"
#include "support/scratch_files.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

fs::path scratch(const std::string& name) { return test::scratchPath("workflow_report", name); }

TEST(ReportRenderWorkflow, WritesTheHtmlOnce) {
  ReportRenderRequest q;
  q.data = io::readNamedText(std::string(PKM_SOURCE_DIR) + "/tests/data/report/example.json");
  q.out = scratch("report.html").string();
  fs::remove(q.out);
  const ReportRenderResult r = renderReport(q);
  EXPECT_EQ(r.out, q.out);
  EXPECT_EQ(fs::file_size(q.out), r.bytes);
  EXPECT_GT(r.bytes, 1000u);
  EXPECT_THROW((void)renderReport(q), IoError);  // exists, no force
  q.force = true;
  EXPECT_EQ(renderReport(q).bytes, r.bytes);
}

TEST(ReportRenderWorkflow, ABadDocumentIsNamedAndNothingIsWritten) {
  ReportRenderRequest q;
  q.data = {"upload.json", "{\"schema\": \n"};  // cut short
  q.out = scratch("bad.html").string();
  fs::remove(q.out);
  try {
    (void)renderReport(q);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("upload.json"));
  }
  q.data = {"upload.json", "{\"schema\": \"something else\"}"};
  EXPECT_THROW((void)renderReport(q), InvalidArgument);
  EXPECT_FALSE(fs::exists(q.out));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
