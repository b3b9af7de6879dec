// The self-contained HTML report (pkm/io/html_report.hpp): structure, escaping, embedded data
// round trip, self-containment and schema validation messages naming the JSON path.
#include "pkm/io/html_report.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <fstream>
#include <functional>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using nlohmann::json;
using ::testing::HasSubstr;
using ::testing::Not;

/// Upper size of a rendered report of the fixture (the size budget for a typical campaign).
constexpr std::size_t kMaxReportBytes = 600 * 1024;

std::string fixtureText() {
  std::ifstream in(std::string(PKM_SOURCE_DIR) + "/tests/data/report/example.json");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

json minimal() {
  return json::parse(R"({"schema": "pkm.report/1", "title": "T",
    "summary": {"title": "S", "columns": ["a", "b"], "rows": [["x", 1.5]]},
    "sections": [{"id": "s1", "title": "One", "paragraphs": ["p"],
      "plots": [{"id": "p1", "title": "P", "kind": "line", "x_label": "x", "y_label": "y",
                 "series": [{"label": "before", "x": [0, 1, 2], "y": [1, 2, 3]},
                            {"label": "after", "x": [0, 2], "y": [0.5, 0.25]}]}]}]})");
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

/// The JSON embedded for render.js.
std::string embeddedData(const std::string& html) {
  const std::string open = R"(<script type="application/json" id="pkm-report-data">)";
  const std::size_t a = html.find(open);
  EXPECT_NE(a, std::string::npos);
  const std::size_t b = html.find("</script>", a);
  return html.substr(a + open.size(), b - a - open.size());
}

TEST(HtmlReport, FixtureHasEveryPlotSectionAndTable) {
  const std::string text = fixtureText();
  ASSERT_FALSE(text.empty());
  const json doc = json::parse(text);
  const std::string html = renderHtmlReport(text, "example.json");
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_LT(html.size(), kMaxReportBytes);
  std::size_t plots = 0, tables = 1;  // the summary table
  for (const json& s : doc["sections"]) {
    const std::string sid = s["id"].get<std::string>();
    EXPECT_THAT(html, HasSubstr("<section id=\"sec-" + sid + "\">"));
    EXPECT_THAT(html, HasSubstr("<a href=\"#sec-" + sid + "\">"));
    for (const json& p : s.value("plots", json::array())) {
      ++plots;
      EXPECT_EQ(count(html, "data-plot-id=\"" + p["id"].get<std::string>() + "\""), 1u);
    }
    tables += s.value("tables", json::array()).size();
  }
  EXPECT_EQ(plots, 5u);
  EXPECT_EQ(count(html, "<figure class=\"plot"), plots);
  EXPECT_EQ(count(html, "<table>"), tables);
  // Every plot kind of the schema appears in the fixture.
  for (const char* kind : {"line", "scatter", "polar", "bar"})
    EXPECT_THAT(html, HasSubstr(std::string("class=\"plot plot-") + kind + "\""));
}

TEST(HtmlReport, IsSelfContained) {
  const std::string html = renderHtmlReport(fixtureText());
  EXPECT_THAT(html, Not(HasSubstr("src=\"http")));
  EXPECT_THAT(html, Not(HasSubstr("href=\"http")));
  EXPECT_THAT(html, Not(HasSubstr("<link")));
  EXPECT_THAT(html, Not(HasSubstr("<script src")));
  // The plotting library, our client code and style are inlined.
  EXPECT_THAT(html, HasSubstr("uPlot"));
  EXPECT_THAT(html, HasSubstr("pkm-report-data"));
  EXPECT_THAT(html, HasSubstr(".u-legend"));
  EXPECT_THAT(html, HasSubstr("figure.plot"));
}

TEST(HtmlReport, EscapesAllText) {
  json doc = minimal();
  doc["title"] = "<script>alert(\"x\")</script> & 'q'";
  doc["summary"]["rows"][0][0] = "<b>cell</b>";
  doc["sections"][0]["paragraphs"][0] = "a < b > c";
  doc["sections"][0]["title"] = "<i>sec</i>";
  const std::string html = renderHtmlReport(doc.dump());
  EXPECT_THAT(html,
              HasSubstr("&lt;script&gt;alert(&quot;x&quot;)&lt;/script&gt; &amp; &#39;q&#39;"));
  EXPECT_THAT(html, HasSubstr("<td class=\"txt\">&lt;b&gt;cell&lt;/b&gt;</td>"));
  EXPECT_THAT(html, HasSubstr("<p>a &lt; b &gt; c</p>"));
  EXPECT_THAT(html, HasSubstr("&lt;i&gt;sec&lt;/i&gt;"));
  EXPECT_THAT(html, Not(HasSubstr("<script>alert")));
  EXPECT_THAT(html, Not(HasSubstr("<b>cell")));
}

TEST(HtmlReport, EmbeddedDataCannotCloseItsScriptAndRoundTrips) {
  json doc = minimal();
  doc["sections"][0]["plots"][0]["title"] = "</script><script>alert(1)</script><!-- x";
  doc["sections"][0]["plots"][0]["series"][0]["label"] = "</SCRIPT> before \u00b5m";
  const std::string html = renderHtmlReport(doc.dump());
  const std::string data = embeddedData(html);
  EXPECT_THAT(data, Not(HasSubstr("</")));
  EXPECT_THAT(data, Not(HasSubstr("<!--")));
  EXPECT_THAT(data, HasSubstr("<\\/script>"));
  // The escaped text is still the same JSON: the plots come back unchanged.
  const json parsed = json::parse(data);
  ASSERT_EQ(parsed["plots"].size(), 1u);
  EXPECT_EQ(parsed["plots"][0], doc["sections"][0]["plots"][0]);
}

TEST(HtmlReport, FormatsCells) {
  json doc = minimal();
  doc["summary"]["columns"] = {"a", "b", "c", "d", "e"};
  doc["summary"]["rows"] =
      json::array({json::array({0.00812345678, 120, nullptr, 1234567.0, -0.5})});
  const std::string html = renderHtmlReport(doc.dump());
  EXPECT_THAT(html, HasSubstr("<td class=\"num\">0.00812346</td>"));
  EXPECT_THAT(html, HasSubstr("<td class=\"num\">120</td>"));
  EXPECT_THAT(html, HasSubstr("<td class=\"txt\">\u2014</td>"));
  EXPECT_THAT(html, HasSubstr("<td class=\"num\">1.23457e+06</td>"));
  EXPECT_THAT(html, HasSubstr("<td class=\"num\">-0.5</td>"));
}

TEST(HtmlReport, OptionalPartsMayBeAbsent) {
  json doc = minimal();
  doc["sections"] = json::array();
  const std::string html = renderHtmlReport(doc.dump());
  EXPECT_THAT(html, Not(HasSubstr("<nav")));
  EXPECT_THAT(embeddedData(html), HasSubstr("\"plots\":[]"));
  doc = minimal();
  doc["sections"][0].erase("paragraphs");
  doc["subtitle"] = "sub";
  EXPECT_THAT(renderHtmlReport(doc.dump()), HasSubstr("<p class=\"subtitle\">sub</p>"));
}

TEST(HtmlReport, HeaderNotesAndBandsAreRendered) {
  json doc = minimal();
  doc["notes"] = {"Environment: <realistic>", "Seed 7"};
  json& series = doc["sections"][0]["plots"][0]["series"][0];
  series["lower"] = {0.9, 1.8, 2.7};
  series["upper"] = {1.1, 2.2, 3.3};
  const std::string html = renderHtmlReport(doc.dump());
  const std::size_t header_end = html.find("</header>");
  EXPECT_LT(html.find("<p class=\"subtitle note\">Environment: &lt;realistic&gt;</p>"), header_end);
  EXPECT_LT(html.find("<p class=\"subtitle note\">Seed 7</p>"), header_end);
  // The band goes to render.js with its series.
  const json embedded = json::parse(embeddedData(html));
  EXPECT_EQ(embedded["plots"][0]["series"][0]["upper"], series["upper"]);
  EXPECT_THAT(html, HasSubstr("bands.push("));  // render.js draws it
}

struct BadCase {
  const char* name;
  std::function<void(json&)> mutate;
  const char* message;  ///< expected in the error: the JSON path and the reason
};

/// Invalid documents: the root, the summary, the sections, their tables and the notes.
std::vector<BadCase> badDocumentCases() {
  return {
      {"no schema", [](json& d) { d.erase("schema"); }, "(root): missing key 'schema'"},
      {"other schema", [](json& d) { d["schema"] = "pkm.report/2"; }, "schema: expected"},
      {"title type", [](json& d) { d["title"] = 3; }, "title: expected a string"},
      {"no summary", [](json& d) { d.erase("summary"); }, "missing key 'summary'"},
      {"short row",
       [](json& d) { d["summary"]["rows"][0] = {"x"}; },
       "summary.rows[0]: has 1 cells for 2 columns"},
      {"bool cell", [](json& d) { d["summary"]["rows"][0][1] = true; }, "summary.rows[0][1]"},
      {"sections type", [](json& d) { d["sections"] = json::object(); }, "sections: expected"},
      {"section id", [](json& d) { d["sections"][0]["id"] = "a b"; }, "sections[0].id"},
      {"paragraph",
       [](json& d) { d["sections"][0]["paragraphs"][0] = 1; },
       "sections[0].paragraphs[0]"},
      {"duplicate section",
       [](json& d) {
         json s = d["sections"][0];
         s.erase("plots");
         d["sections"].push_back(s);
       },
       "sections[1].id: duplicate section id 's1'"},
      {"notes",
       [](json& d) {
         d["notes"] = {"a", 1};
       },
       "notes[1]: expected a string"},
      {"table",
       [](json& d) {
         d["sections"][0]["tables"] = {{{"title", "t"}}};
       },
       "sections[0].tables[0]: missing key 'columns'"},
  };
}

/// Invalid plots: the kind, the series (lengths, values, x order, bands, bars) and the plot ids.
std::vector<BadCase> badPlotCases() {
  return {
      {"kind",
       [](json& d) { d["sections"][0]["plots"][0]["kind"] = "pie"; },
       "sections[0].plots[0].kind: unknown kind 'pie'"},
      {"length",
       [](json& d) { d["sections"][0]["plots"][0]["series"][1]["y"] = {1.0}; },
       "sections[0].plots[0].series[1]: x has 2 values but y has 1"},
      {"number",
       [](json& d) { d["sections"][0]["plots"][0]["series"][0]["y"][2] = "3"; },
       "sections[0].plots[0].series[0].y[2]: expected a number"},
      {"ascending",
       [](json& d) {
         d["sections"][0]["plots"][0]["series"][0]["x"] = {0, 2, 1};
       },
       "sections[0].plots[0].series[0].x[2]: x of a line plot must be ascending"},
      {"no series",
       [](json& d) { d["sections"][0]["plots"][0]["series"] = json::array(); },
       "sections[0].plots[0].series: expected a non-empty array"},
      {"duplicate plot",
       [](json& d) {
         json s = d["sections"][0];
         s["id"] = "s2";
         d["sections"].push_back(s);
       },
       "sections[1].plots[0].id: duplicate plot id 'p1'"},
      {"bar categories",
       [](json& d) { d["sections"][0]["plots"][0]["kind"] = "bar"; },
       "sections[0].plots[0].series[0]: a bar series needs 'categories'"},
      {"bar length",
       [](json& d) {
         d["sections"][0]["plots"][0]["kind"] = "bar";
         d["sections"][0]["plots"][0]["categories"] = {"a", "b"};
       },
       "sections[0].plots[0].series[0]: 2 categories but 3 y values"},
      {"value length",
       [](json& d) {
         d["sections"][0]["plots"][0]["kind"] = "scatter";
         d["sections"][0]["plots"][0]["series"][0]["value"] = {1.0};
       },
       "sections[0].plots[0].series[0]: value has 1 entries but x has 3"},
      {"band length",
       [](json& d) {
         json& s = d["sections"][0]["plots"][0]["series"][0];
         s["lower"] = {0.0, 1.0, 2.0};
         s["upper"] = {1.0, 2.0};
       },
       "sections[0].plots[0].series[0]: upper has 2 values but y has 3"},
      {"band half",
       [](json& d) {
         d["sections"][0]["plots"][0]["series"][0]["lower"] = {0.0, 1.0, 2.0};
       },
       "sections[0].plots[0].series[0]: missing key 'upper'"},
      {"band kind",
       [](json& d) {
         d["sections"][0]["plots"][0]["kind"] = "scatter";
         d["sections"][0]["plots"][0]["series"][0]["lower"] = {0.0, 1.0, 2.0};
         d["sections"][0]["plots"][0]["series"][0]["upper"] = {0.0, 1.0, 2.0};
       },
       "'lower' and 'upper' (a band) belong to line plots only"},
  };
}

TEST(HtmlReport, InvalidDocumentsNameTheJsonPath) {
  std::vector<BadCase> cases = badDocumentCases();
  const std::vector<BadCase> plot_cases = badPlotCases();
  cases.insert(cases.end(), plot_cases.begin(), plot_cases.end());
  for (const BadCase& c : cases) {
    json doc = minimal();
    c.mutate(doc);
    try {
      (void)renderHtmlReport(doc.dump());
      ADD_FAILURE() << c.name << ": no error";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr(c.message)) << c.name;
    }
    EXPECT_THROW(validateReportData(doc.dump()), InvalidArgument) << c.name;
  }
  EXPECT_NO_THROW(validateReportData(minimal().dump()));
}

TEST(HtmlReport, SyntaxErrorNamesSourceAndLine) {
  try {
    (void)renderHtmlReport("{\n  \"schema\": \"pkm.report/1\",\n  \"title\": }\n", "data.json");
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("data.json:3: invalid JSON"));
  }
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
