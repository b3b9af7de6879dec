// workflow::computeVolumetricErrors: rows of a grid in x-fastest order, commands from memory with
// NAME:LINE errors, the first-order model close to the exact one, and bad requests refused.
#include "pkm/workflow/volumetric.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::vector<io::VolumetricRow> rowsOf(const VolumetricRequest& request, bool* begun = nullptr) {
  std::vector<io::VolumetricRow> rows;
  VolumetricSink sink;
  sink.begin = [&] {
    if (begun != nullptr) *begun = rows.empty();
  };
  sink.row = [&](const io::VolumetricRow& r) { rows.push_back(r); };
  const std::size_t count = computeVolumetricErrors(request, sink);
  EXPECT_EQ(count, rows.size());
  return rows;
}

TEST(VolumetricWorkflow, AGridGivesOneRowPerPointXFastest) {
  VolumetricRequest q;
  q.errors = "mxt700s-seed000";
  q.grid = "0:1000:3,-100:100:2,0:0:1";
  bool begun = false;
  const std::vector<io::VolumetricRow> rows = rowsOf(q, &begun);
  EXPECT_TRUE(begun);
  ASSERT_EQ(rows.size(), 6u);
  EXPECT_NEAR(rows[1].tool.x(), 500.0, 1e-9);
  EXPECT_NEAR(rows[1].tool.y(), -100.0, 1e-9);
  EXPECT_NEAR(rows[3].tool.y(), 100.0, 1e-9);
  for (const io::VolumetricRow& r : rows) {
    EXPECT_EQ(r.status, io::VolumetricRow::Status::kOk);
    EXPECT_GT(r.dp.norm(), 0.0);  // seed 000's errors move the tool
    // The first-order model is close to the exact one (within 0.05 mm of a few mm here).
    EXPECT_LT((r.dp - r.dp_linear).norm(), 0.05);
  }
}

TEST(VolumetricWorkflow, CommandsAreReadFromMemory) {
  VolumetricRequest q;
  q.errors = "mxt700s-seed000";
  q.commands = io::NamedText{"upload.csv", "x2,y2,xp,yp,zp\n100,50,0,0,0\n5000,0,0,0,0\n"};
  const std::vector<io::VolumetricRow> rows = rowsOf(q);
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].command.x2, 100.0);
  EXPECT_EQ(rows[0].command.y2, 50.0);
  EXPECT_EQ(rows[0].status, io::VolumetricRow::Status::kOk);
  EXPECT_EQ(rows[1].status, io::VolumetricRow::Status::kAxisLimit);  // X2 stroke is 0..4000
  q.commands = io::NamedText{"upload.csv", "x2,y2,xp,yp,zp\n100,50,0,0,0\n1,2,3,x,5\n"};
  try {
    (void)rowsOf(q);
    FAIL();
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("upload.csv:3:"));
  }
}

TEST(VolumetricWorkflow, RefusesBadRequests) {
  VolumetricRequest q;
  q.errors = "mxt700s-seed000";
  EXPECT_THROW(q.validate(), IoError);  // neither a grid nor commands
  q.grid = "0:1:2,0:1:2";
  EXPECT_THROW(q.validate(), IoError);
  q.grid = "0:1:2,0:1:2,0:1:0";
  EXPECT_THROW(q.validate(), IoError);
  q.grid = "0:1:2,0:1:2,0:1:2";
  q.x2 = 10.0;
  EXPECT_THROW(q.validate(), IoError);  // x2 without y2
  q.y2 = 10.0;
  EXPECT_NO_THROW(q.validate());
  q.machine = "hexapod-default";  // not an Exechon with a hybrid section
  EXPECT_THROW((void)rowsOf(q), IoError);
}

TEST(VolumetricWorkflow, ParsesAGrid) {
  const auto axes = parseVolumetricGrid("0:10:3,5:5:1,-1:1:2");
  EXPECT_EQ(axes[0], (std::vector<double>{0.0, 5.0, 10.0}));
  EXPECT_EQ(axes[1], (std::vector<double>{5.0}));
  EXPECT_EQ(axes[2], (std::vector<double>{-1.0, 1.0}));
  EXPECT_THROW((void)parseVolumetricGrid("0:10:20000,0:1:1,0:1:1"), IoError);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
