// `pkm history` and the result store written by `pkm calibrate --db`, with concurrent writers.
#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "pkm/store/result_store.hpp"
#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

constexpr int kConcurrentRuns = 3;

TEST_F(CliTest, CalibrationsRunAtOnceAllLandInTheHistory) {
  ASSERT_EQ(pkm({"simulate", "seed004-hexapod-calibration", "--out", path("sim")}).code, 0);
  // Three calibrations write the same store at the same time, as separate processes.
  std::string script = "(";
  for (int k = 0; k < kConcurrentRuns; ++k)
    script += fmt::format(
        "{} calibrate hexapod --machine hexapod-default --data {} --holdout {} --out {} --db {} "
        "> /dev/null 2>&1 & ",
        PKM_BINARY,
        path("sim/tracker-pose.csv"),
        path("sim/tracker-holdout.csv"),
        path(fmt::format("cal{}.json", k)),
        path("pkm.db"));
  script += "wait)";
  ASSERT_EQ(std::system(script.c_str()), 0);
  const CliRun r = pkm({"history",
                        "--machine",
                        "pkm-hx1200",
                        "--db",
                        path("pkm.db"),
                        "--quantity",
                        "holdout.rms",
                        "--json"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 2u * kConcurrentRuns);  // before and after of each
  for (const auto& row : j["rows"]) {
    EXPECT_EQ(row["campaign_name"], "calibrate hexapod");
    if (row["stage"] == "after") {
      EXPECT_LT(row["value"].get<double>(), 0.015);
    }
  }
  store::ResultStore results(path("pkm.db"));
  EXPECT_TRUE(results.integrityOk());
  // The readable table lists every stored quantity of the machine.
  const CliRun table = pkm({"history", "--machine", "pkm-hx1200", "--db", path("pkm.db")});
  ASSERT_EQ(table.code, 0) << table.err;
  EXPECT_THAT(table.out, HasSubstr("residuals.rms"));
  EXPECT_THAT(table.out, HasSubstr("tcp_error_map.mean"));
}

TEST_F(CliTest, HistoryNeverCreatesAStoreAndNamesTheMachinesItHas) {
  expectUsageError(pkm({"history", "--machine", "x", "--db", path("none.db")}), "no result store");
  EXPECT_FALSE(std::filesystem::exists(path("none.db")));
  {
    store::ResultStore results(path("pkm.db"));
    store::CampaignRecord c;
    c.machine = "alpha";
    c.machine_type = "hexapod";
    c.name = "test";
    c.results.push_back({"q", "after", 1.5, "mm"});
    (void)results.store(c);
  }
  expectUsageError(pkm({"history", "--machine", "beta", "--db", path("pkm.db")}), "alpha");
  const std::string notes = write("notes.txt", "my notes\n");
  expectUsageError(pkm({"history", "--machine", "x", "--db", notes}), "notes.txt");
  EXPECT_EQ(slurp(notes), "my notes\n");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
