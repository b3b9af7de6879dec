// The self-contained HTML campaign report (pkm/io/html_report.hpp, docs/report.md).
#include "pkm/io/html_report.hpp"

#include <fmt/format.h>

#include <string>
#include <utility>
#include <vector>

#include "detail/report_data.hpp"
#include "pkm/core/error.hpp"

namespace pkm::io {
namespace detail {
// Generated at build time from web/report (src/CMakeLists.txt, cmake/PkmEmbed.cmake).
const std::vector<std::pair<std::string_view, std::string_view>>& reportUplotJs();
const std::vector<std::pair<std::string_view, std::string_view>>& reportUplotCss();
const std::vector<std::pair<std::string_view, std::string_view>>& reportRenderJs();
const std::vector<std::pair<std::string_view, std::string_view>>& reportStyleCss();
}  // namespace detail

namespace {

using nlohmann::json;

std::string_view asset(const std::vector<std::pair<std::string_view, std::string_view>>& files,
                       const char* name) {
  if (files.size() != 1)
    throw IoError(
        fmt::format("HTML report asset {} was not embedded (run scripts/setup.sh)", name));
  return files.front().second;
}

/// Text as HTML character data or attribute value.
void appendEscaped(std::string& out, std::string_view text) {
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
}

std::string escaped(std::string_view text) {
  std::string out;
  appendEscaped(out, text);
  return out;
}

/// Inline <script>/<style> content must not contain its own end tag; assets are ours, so a
/// violation is a build problem, reported rather than silently producing a broken page.
std::string_view inlineAsset(std::string_view text, std::string_view end_tag, const char* name) {
  if (text.find(end_tag) != std::string_view::npos)
    throw IoError(fmt::format("HTML report asset {} contains {}", name, end_tag));
  return text;
}

/// A table cell: strings as given, integers exactly, other numbers with up to 6 significant
/// digits, null as an em dash.
std::string cell(const json& v) {
  if (v.is_null()) return "\u2014";
  if (v.is_string()) return escaped(v.get_ref<const std::string&>());
  if (v.is_number_integer()) return v.dump();
  return fmt::format("{:.6g}", v.get<double>());
}

void appendTable(std::string& out, const json& t) {
  out += "<div class=\"table-wrap\"><table>\n<caption>";
  appendEscaped(out, t["title"].get_ref<const std::string&>());
  out += "</caption>\n<thead><tr>";
  for (const json& c : t["columns"])
    out += fmt::format("<th>{}</th>", escaped(c.get<std::string>()));
  out += "</tr></thead>\n<tbody>\n";
  for (const json& row : t["rows"]) {
    out += "<tr>";
    for (const json& c : row)
      out += fmt::format("<td class=\"{}\">{}</td>", c.is_number() ? "num" : "txt", cell(c));
    out += "</tr>\n";
  }
  out += "</tbody></table></div>\n";
}

void appendPlot(std::string& out, const json& p) {
  const std::string id = escaped(p["id"].get<std::string>());
  out += fmt::format(
      "<figure class=\"plot plot-{}\" id=\"plot-{}\" data-plot-id=\"{}\">\n"
      "<figcaption>{}</figcaption>\n<div class=\"chart\"></div>\n"
      "<noscript>This figure needs JavaScript.</noscript>\n</figure>\n",
      escaped(p["kind"].get<std::string>()),
      id,
      id,
      escaped(p["title"].get<std::string>()));
}

void appendSection(std::string& out, const json& s) {
  out += fmt::format("<section id=\"sec-{}\">\n<h2>{}</h2>\n",
                     escaped(s["id"].get<std::string>()),
                     escaped(s["title"].get<std::string>()));
  for (const json& para : s.value("paragraphs", json::array()))
    out += fmt::format("<p>{}</p>\n", escaped(para.get<std::string>()));
  const json plots = s.value("plots", json::array());
  if (!plots.empty()) {
    out += "<div class=\"figures\">\n";
    for (const json& p : plots) appendPlot(out, p);
    out += "</div>\n";
  }
  for (const json& t : s.value("tables", json::array())) appendTable(out, t);
  out += "</section>\n";
}

/// The plots as JSON for render.js, safe inside <script type="application/json">: "</" becomes
/// "<\/" and "<!--" becomes "\u003c!--" (both still the same JSON strings).
std::string plotData(const json& doc) {
  json plots = json::array();
  for (const json& s : doc["sections"])
    for (const json& p : s.value("plots", json::array())) plots.push_back(p);
  const std::string raw =
      json{{"plots", plots}}.dump(-1, ' ', false, json::error_handler_t::replace);
  std::string out;
  out.reserve(raw.size() + 64);
  for (std::size_t i = 0; i < raw.size(); ++i) {
    if (raw.compare(i, 2, "</") == 0) {
      out += "<\\/";
      ++i;
    } else if (raw.compare(i, 4, "<!--") == 0) {
      out += "\\u003c";
    } else {
      out += raw[i];
    }
  }
  return out;
}

}  // namespace

std::string renderHtmlReport(std::string_view json_text, const std::string& source) {
  const json doc = detail::parseReportData(json_text, source);
  const std::string title = escaped(doc["title"].get<std::string>());
  std::string out;
  out.reserve(json_text.size() + 96 * 1024);
  out += fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta name=\"generator\" content=\"pkm report ({})\">\n<title>{}</title>\n",
      kReportSchema,
      title);
  out += "<style>\n";
  out += inlineAsset(asset(detail::reportUplotCss(), "uPlot.min.css"), "</style", "uPlot.min.css");
  out += "\n";
  out += inlineAsset(asset(detail::reportStyleCss(), "style.css"), "</style", "style.css");
  out += "\n</style>\n</head>\n<body>\n<header>\n";
  out += fmt::format("<h1>{}</h1>\n", title);
  if (doc.contains("subtitle"))
    out +=
        fmt::format("<p class=\"subtitle\">{}</p>\n", escaped(doc["subtitle"].get<std::string>()));
  for (const json& note : doc.value("notes", json::array()))
    out += fmt::format("<p class=\"subtitle note\">{}</p>\n", escaped(note.get<std::string>()));
  if (doc.contains("generated"))
    out += fmt::format("<p class=\"generated\">Generated {}</p>\n",
                       escaped(doc["generated"].get<std::string>()));
  out += "</header>\n<main>\n<section id=\"summary\" class=\"summary\">\n";
  appendTable(out, doc["summary"]);
  out += "</section>\n";
  const json& sections = doc["sections"];
  if (!sections.empty()) {
    out += "<nav class=\"toc\">\n<h2>Contents</h2>\n<ol>\n";
    for (const json& s : sections)
      out += fmt::format("<li><a href=\"#sec-{}\">{}</a></li>\n",
                         escaped(s["id"].get<std::string>()),
                         escaped(s["title"].get<std::string>()));
    out += "</ol>\n</nav>\n";
  }
  for (const json& s : sections) appendSection(out, s);
  out += "</main>\n<footer>Plots drawn with uPlot (MIT licence), inlined.</footer>\n";
  out += "<script type=\"application/json\" id=\"pkm-report-data\">";
  out += plotData(doc);
  out += "</script>\n<script>\n";
  out += inlineAsset(asset(detail::reportUplotJs(), "uPlot.iife.min.js"), "</script", "uPlot.js");
  out += "\n</script>\n<script>\n";
  out += inlineAsset(asset(detail::reportRenderJs(), "render.js"), "</script", "render.js");
  out += "\n</script>\n</body>\n</html>\n";
  return out;
}

}  // namespace pkm::io
