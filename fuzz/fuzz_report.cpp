// libFuzzer harness for the report-data reader and the HTML report (io/html_report.hpp,
// docs/report.md, schema pkm.report/1): any input validates and renders or throws pkm::IoError /
// pkm::InvalidArgument. A document that validates renders, and nothing in it can end the page's
// inline scripts: the page has exactly the template's three "</script" end tags (any case) and
// no "<!--" after its first <script>.
#include <algorithm>
#include <cctype>
#include <string>

#include "fuzz_support.hpp"
#include "pkm/io/html_report.hpp"

namespace {

std::size_t count(const std::string& text, std::string_view what) {
  std::size_t n = 0;
  for (std::size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = pkm::fuzz::asText(data, size);
  if (!pkm::fuzz::accepts([&] { pkm::io::validateReportData(text, "fuzz.json"); })) return 0;
  std::string html;
  pkm::fuzz::check(pkm::fuzz::accepts([&] { html = pkm::io::renderHtmlReport(text, "fuzz.json"); }),
                   "a document that validates renders");
  std::string lower = html;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) {
    return static_cast<char>(std::tolower(c));
  });
  pkm::fuzz::check(count(lower, "</script") == 3, "only the template's </script tags");
  const std::size_t scripts = lower.find("<script");
  pkm::fuzz::check(scripts != std::string::npos && lower.find("<!--", scripts) == std::string::npos,
                   "no <!-- inside the scripts");
  return 0;
}
