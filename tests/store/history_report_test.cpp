// store::historyText / historyJson: the aligned table and the JSON rows.
#include "pkm/store/history_report.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

namespace pkm::store {
namespace PKM_TEST_NS {

std::vector<HistoryRow> rows() {
  HistoryRow r;
  r.campaign = 7;
  r.time = "2026-11-22T08:30:00Z";
  r.campaign_name = "calibrate hexapod";
  r.quantity = "holdout.rms";
  r.stage = "after";
  r.value = 0.00123456789;
  r.unit = "mm";
  HistoryRow with_u = r;
  with_u.stage = "before";
  with_u.value = 13.6;
  with_u.U = 0.042;
  return {r, with_u};
}

TEST(HistoryReport, Text) {
  const std::string t = historyText(rows());
  const std::size_t nl = t.find('\n');
  EXPECT_EQ(t.substr(0, 8), "campaign");
  EXPECT_EQ(t.substr(nl + 1, 8), "       7");
  EXPECT_NE(t.find("              0.00123457  mm\n"), std::string::npos);  // no U: the value
  EXPECT_NE(t.find("           13.6 ± 0.042  mm\n"), std::string::npos);   // value ± U
  EXPECT_NE(t.find("value ± U (k = 2)  unit\n"), std::string::npos);
  EXPECT_EQ(historyText({}).find('\n'), t.find('\n'));  // header only
}

TEST(HistoryReport, Json) {
  const nlohmann::json j = nlohmann::json::parse(historyJson("hx1", "pkm.db", rows()));
  EXPECT_EQ(j["machine"], "hx1");
  EXPECT_EQ(j["db"], "pkm.db");
  ASSERT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][0]["campaign"], 7);
  EXPECT_EQ(j["rows"][0]["value"], 0.00123456789);
  EXPECT_TRUE(j["rows"][0]["U"].is_null());
  EXPECT_EQ(j["rows"][1]["U"], 0.042);
  EXPECT_TRUE(nlohmann::json::parse(historyJson("x", "d", {}))["rows"].empty());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::store
