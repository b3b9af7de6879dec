// `pkm report render DATA.json --out report.html [--force]`: the self-contained HTML campaign
// report from a report-data document, schema pkm.report/1 (pkm/io/html_report.hpp,
// docs/report.md).
#include <fmt/format.h>

#include <memory>
#include <string>

#include "cli_common.hpp"
#include "pkm/workflow/report_render.hpp"

namespace pkm::cli {
namespace {

struct ReportArgs {
  workflow::ReportRenderRequest request;
  std::string data;
};

void runRender(ReportArgs& args) {
  args.request.data = io::readNamedText(args.data);
  const workflow::ReportRenderResult r = workflow::renderReport(args.request);
  fmt::print("pkm: wrote {} ({} bytes)\n", r.out, r.bytes);
}

void addReport(CLI::App& app) {
  CLI::App* report = app.add_subcommand("report", "the HTML campaign report (docs/report.md)");
  report->require_subcommand(1);
  auto args = std::make_shared<ReportArgs>();
  CLI::App* render = report->add_subcommand(
      "render", "render report-data JSON (pkm.report/1) into one self-contained HTML file");
  render->add_option("data", args->data, "report-data JSON file")
      ->required()
      ->check(CLI::ExistingFile);
  render->add_option("--out,-o", args->request.out, "the HTML file to write")->required();
  render->add_flag("--force", args->request.force, "overwrite an existing --out file");
  render->callback([args] { runRender(*args); });
}

const CommandRegistration kRegisterReport{900, "report", &addReport};

}  // namespace
}  // namespace pkm::cli
