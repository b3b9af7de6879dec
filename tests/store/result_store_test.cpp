#include "pkm/store/result_store.hpp"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

#include "pkm/core/error.hpp"

namespace pkm::store {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

class ResultStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           fmt::format("pkm_result_store_{}",
                       ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string db() const { return (dir_ / "pkm.db").string(); }
  std::filesystem::path dir_;
};

CampaignRecord campaign(const std::string& machine, double before, double after) {
  CampaignRecord c;
  c.machine = machine;
  c.machine_type = "hexapod";
  c.name = "calibrate hexapod";
  c.source = "sim/tracker-pose.csv";
  c.measurements.push_back({"tracker-pose", "tracker-pose", "sim/tracker-pose.csv", 200});
  c.results.push_back({"holdout.rms", "before", before, "mm"});
  c.results.push_back({"holdout.rms", "after", after, "mm"});
  c.results.push_back({"residual.rms", "after", after / 2, "mm"});
  c.compensations.push_back({"linuxcnc-hal", "cal.hal", "setp genhexkins.base.0.x 1\n"});
  return c;
}

TEST_F(ResultStoreTest, StoresAndFollowsAMachineAcrossCampaigns) {
  {
    ResultStore store(db());
    EXPECT_EQ(store.store(campaign("hx", 13.6, 0.0094)), 1);
    EXPECT_EQ(store.store(campaign("other", 1.0, 0.5)), 2);
  }
  ResultStore store(db());  // reopened: the data persisted
  EXPECT_EQ(store.store(campaign("hx", 0.02, 0.008)), 3);
  EXPECT_THAT(store.machines(), ::testing::ElementsAre("hx", "other"));
  const auto all = store.history("hx");
  ASSERT_EQ(all.size(), 6u);
  EXPECT_EQ(all[0].campaign, 1);
  EXPECT_EQ(all[0].quantity, "holdout.rms");
  EXPECT_EQ(all[0].stage, "before");
  EXPECT_EQ(all[0].value, 13.6);
  EXPECT_EQ(all[0].unit, "mm");
  EXPECT_EQ(all[0].campaign_name, "calibrate hexapod");
  EXPECT_EQ(all[0].time.size(), 20u);  // 2026-11-22T08:30:00Z
  EXPECT_EQ(all[5].campaign, 3);
  const auto one = store.history("hx", std::string("residual.rms"));
  ASSERT_EQ(one.size(), 2u);
  EXPECT_EQ(one[1].value, 0.004);
  EXPECT_TRUE(store.history("nobody").empty());
  EXPECT_TRUE(store.integrityOk());
}

TEST_F(ResultStoreTest, ABadCampaignStoresNothing) {
  ResultStore store(db());
  CampaignRecord bad = campaign("hx", 1.0, 0.5);
  bad.results.push_back({"x", "after", std::nan(""), "mm"});
  EXPECT_THROW((void)store.store(bad), InvalidArgument);
  CampaignRecord unnamed = campaign("", 1.0, 0.5);
  EXPECT_THROW((void)store.store(unnamed), InvalidArgument);
  EXPECT_TRUE(store.machines().empty());
  EXPECT_EQ(store.store(campaign("hx", 1.0, 0.5)), 1);
}

/// Several connections (as several processes would) write at once: every campaign arrives whole.
TEST_F(ResultStoreTest, ConcurrentWritersDoNotCorruptTheStore) {
  constexpr int kWriters = 4;
  constexpr int kCampaigns = 25;
  std::vector<std::thread> threads;  // they also create the store together
  for (int w = 0; w < kWriters; ++w)
    threads.emplace_back([this, w] {
      ResultStore store(db());
      for (int k = 0; k < kCampaigns; ++k) (void)store.store(campaign(fmt::format("m{}", w), k, k));
    });
  for (std::thread& t : threads) t.join();
  ResultStore store(db());
  EXPECT_TRUE(store.integrityOk());
  ASSERT_EQ(store.machines().size(), static_cast<std::size_t>(kWriters));
  for (int w = 0; w < kWriters; ++w) {
    const auto rows = store.history(fmt::format("m{}", w), std::string("holdout.rms"));
    ASSERT_EQ(rows.size(), 2u * kCampaigns);
    for (int k = 0; k < kCampaigns; ++k) EXPECT_EQ(rows[2 * static_cast<std::size_t>(k)].value, k);
  }
}

TEST_F(ResultStoreTest, AFileThatIsNotADatabaseIsAnError) {
  const std::string path = (dir_ / "notes.txt").string();
  std::ofstream(path) << "these are my notes, not a database\n" << std::string(200, 'x');
  try {
    ResultStore store(path);
    FAIL() << "expected an error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("notes.txt"));
  }
  // The user's file is untouched.
  std::ifstream in(path);
  std::string first;
  std::getline(in, first);
  EXPECT_EQ(first, "these are my notes, not a database");
}

TEST_F(ResultStoreTest, StoresTheExpandedUncertaintyOrNull) {
  ResultStore store(db());
  CampaignRecord c = campaign("hx", 13.6, 0.0094);
  c.results[0].U = 0.04;  // before ± 0.04 mm; the other two have none (NaN -> NULL)
  (void)store.store(c);
  const auto rows = store.history("hx");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(rows[0].U, 0.04);
  EXPECT_TRUE(std::isnan(rows[1].U));
  EXPECT_TRUE(std::isnan(rows[2].U));
  CampaignRecord bad = campaign("hx", 1.0, 0.5);
  bad.results[1].U = -1e-3;
  EXPECT_THROW((void)store.store(bad), InvalidArgument);
  bad.results[1].U = std::numeric_limits<double>::infinity();
  EXPECT_THROW((void)store.store(bad), InvalidArgument);
  EXPECT_EQ(store.history("hx").size(), 3u);  // nothing of the bad campaigns stored
}

/// A store written by the pkm of schema 1 (tests/data/store/README.md): opening it migrates it in
/// place; its results keep their values with no U, new campaigns store U beside them.
TEST_F(ResultStoreTest, AStoreOfSchemaOneIsMigrated) {
  const std::filesystem::path old = dir_ / "old.db";
  std::filesystem::copy_file(std::filesystem::path(PKM_SOURCE_DIR) / "tests/data/store/schema1.db",
                             old);
  {
    ResultStore store(old.string());
    EXPECT_TRUE(store.integrityOk());
    const auto rows = store.history("pkm-hx1200");
    ASSERT_EQ(rows.size(), 17u);
    EXPECT_EQ(rows[0].quantity, "residuals.rms");
    EXPECT_EQ(rows[0].stage, "before");
    EXPECT_NEAR(rows[0].value, 29.918307848938056, 1e-12);
    for (const HistoryRow& r : rows) EXPECT_TRUE(std::isnan(r.U)) << r.quantity;
    CampaignRecord c = campaign("pkm-hx1200", 0.02, 0.008);
    c.results[1].U = 0.003;
    EXPECT_EQ(store.store(c), 2);
  }
  ResultStore again(old.string());  // already migrated: opens as it is
  const auto rows = again.history("pkm-hx1200", std::string("holdout.rms"));
  ASSERT_GE(rows.size(), 2u);
  EXPECT_EQ(rows.back().value, 0.008);
  EXPECT_EQ(rows.back().U, 0.003);
  EXPECT_TRUE(again.integrityOk());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::store
