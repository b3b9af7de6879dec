// `pkm report render` (report_render.hpp).
#include "pkm/workflow/report_render.hpp"

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::workflow {
namespace {

io::Overwrite overwriteOf(const ReportRenderRequest& request) {
  return request.force ? io::Overwrite::kAllow : io::Overwrite::kRefuse;
}

}  // namespace

void ReportRenderRequest::validate() const {
  if (out.empty()) throw IoError("give --out FILE");
  io::checkOverwrite(out, overwriteOf(*this));
}

ReportRenderResult renderReport(const ReportRenderRequest& request) {
  request.validate();
  const std::string html = io::renderHtmlReport(request.data.text, request.data.name);
  io::writeFileAtomic(request.out, html, overwriteOf(request));
  return {request.out, html.size()};
}

}  // namespace pkm::workflow
