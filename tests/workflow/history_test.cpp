// workflow::queryHistory: a machine's rows from a store, one quantity, the refusal without a store
// and, when rows are required, for a machine the store does not have.
#include "pkm/workflow/history.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "pkm/core/error.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

std::string storeWithTwoResults() {
  const fs::path db =
      fs::temp_directory_path() / ("pkm_workflow_history_" + std::to_string(::getpid()) + ".db");
  fs::remove(db);
  store::ResultStore results(db.string());
  store::CampaignRecord c;
  c.machine = "hx1";
  c.machine_type = "hexapod";
  c.name = "calibrate hexapod";
  c.results = {{"holdout.rms", "before", 0.25, "mm"},
               {"holdout.rms", "after", 0.002, "mm"},
               {"parallelism", "estimate", 1e-5, "rad"}};
  (void)results.store(c);
  return db.string();
}

TEST(HistoryWorkflow, ReadsAMachinesRows) {
  HistoryRequest q;
  q.machine = "hx1";
  q.db = storeWithTwoResults();
  const HistoryResult r = queryHistory(q);
  EXPECT_EQ(r.machine, "hx1");
  ASSERT_EQ(r.rows.size(), 3u);
  EXPECT_EQ(r.rows[1].stage, "after");
  EXPECT_EQ(r.rows[1].value, 0.002);
  q.quantity = "parallelism";
  EXPECT_EQ(queryHistory(q).rows.size(), 1u);
}

TEST(HistoryWorkflow, RefusesAMissingStoreAndAnUnknownMachine) {
  HistoryRequest q;
  q.machine = "hx1";
  q.db = (fs::temp_directory_path() / "pkm_workflow_history_none.db").string();
  EXPECT_THROW((void)queryHistory(q), IoError);
  EXPECT_FALSE(fs::exists(q.db));  // reading never creates a store
  q.db = storeWithTwoResults();
  q.machine = "other";
  EXPECT_TRUE(queryHistory(q).rows.empty());
  q.require_rows = true;
  try {
    (void)queryHistory(q);
    FAIL();
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("no results for machine 'other' (machines in the store: hx1)"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
