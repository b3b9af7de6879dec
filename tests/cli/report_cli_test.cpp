// `pkm report render DATA.json --out report.html [--force]` (docs/report.md).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "support/cli_fixture.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::string fixture() {
  return (std::filesystem::path(PKM_SOURCE_DIR) / "tests/data/report/example.json").string();
}

TEST_F(CliTest, RendersTheFixture) {
  const CliRun r = pkm({"report", "render", fixture(), "--out", path("report.html")});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("report.html"));
  const std::string html = slurp(path("report.html"));
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_THAT(html, HasSubstr("data-plot-id=\"roundness\""));
  EXPECT_THAT(html, HasSubstr("</html>\n"));
  EXPECT_FALSE(std::filesystem::exists(path("report.html.tmp")));
}

TEST_F(CliTest, NeverOverwritesWithoutForce) {
  write("report.html", "mine");
  expectUsageError(pkm({"report", "render", fixture(), "--out", path("report.html")}),
                   "exists; pass --force");
  EXPECT_EQ(slurp(path("report.html")), "mine");
  ASSERT_EQ(pkm({"report", "render", fixture(), "--out", path("report.html"), "--force"}).code, 0);
  EXPECT_EQ(slurp(path("report.html")).rfind("<!DOCTYPE html>", 0), 0u);
}

TEST_F(CliTest, InvalidDataIsAnInputErrorAndWritesNothing) {
  const std::string data = write("bad.json",
                                 R"({"schema": "pkm.report/1", "title": "t", "summary":
      {"title": "s", "columns": ["a"], "rows": [[1]]},
      "sections": [{"id": "a", "title": "A", "plots": [{"id": "p", "title": "P",
        "kind": "line", "series": [{"label": "l", "x": [1, 2], "y": [1]}]}]}]})");
  expectUsageError(pkm({"report", "render", data, "--out", path("r.html")}),
                   "sections[0].plots[0].series[0]: x has 2 values but y has 1");
  EXPECT_FALSE(std::filesystem::exists(path("r.html")));
  const std::string broken = write("broken.json", "{\n\"schema\": ,\n}");
  expectUsageError(pkm({"report", "render", broken, "--out", path("r.html")}), "broken.json:2:");
  EXPECT_FALSE(std::filesystem::exists(path("r.html")));
}

TEST_F(CliTest, UsageErrors) {
  expectUsageError(pkm({"report", "render", path("missing.json"), "--out", path("r.html")}),
                   "missing.json");
  expectUsageError(pkm({"report", "render", fixture()}), "--out");
  EXPECT_EQ(pkm({"report"}).code, kExitUsage);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
