// io::historyText / historyJson: the aligned table and the JSON rows.
#include "pkm/io/history_report.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace pkm::io {
namespace {

std::vector<HistoryRow> rows() {
  HistoryRow r;
  r.campaign = 7;
  r.time = "2026-11-22T08:30:00Z";
  r.campaign_name = "calibrate hexapod";
  r.quantity = "holdout.rms";
  r.stage = "after";
  r.value = 0.00123456789;
  r.unit = "mm";
  return {r};
}

TEST(HistoryReport, Text) {
  const std::string t = historyText(rows());
  const std::size_t nl = t.find('\n');
  EXPECT_EQ(t.substr(0, 8), "campaign");
  EXPECT_EQ(t.substr(nl + 1, 8), "       7");
  EXPECT_NE(t.find("      0.00123457  mm\n"), std::string::npos);
  EXPECT_EQ(historyText({}).find('\n'), t.find('\n'));  // header only
}

TEST(HistoryReport, Json) {
  const nlohmann::json j = nlohmann::json::parse(historyJson("hx1", "pkm.db", rows()));
  EXPECT_EQ(j["machine"], "hx1");
  EXPECT_EQ(j["db"], "pkm.db");
  ASSERT_EQ(j["rows"].size(), 1u);
  EXPECT_EQ(j["rows"][0]["campaign"], 7);
  EXPECT_EQ(j["rows"][0]["value"], 0.00123456789);
  EXPECT_TRUE(nlohmann::json::parse(historyJson("x", "d", {}))["rows"].empty());
}

}  // namespace
}  // namespace pkm::io
