// `pkm report render DATA.json --out report.html [--force]`: the self-contained HTML campaign
// report from a report-data document, schema pkm.report/1 (pkm/io/html_report.hpp,
// docs/report.md).
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::cli {
namespace {

struct ReportArgs {
  std::string data;
  std::string out;
  bool force = false;
};

void runRender(const ReportArgs& args) {
  const io::Overwrite overwrite = args.force ? io::Overwrite::kAllow : io::Overwrite::kRefuse;
  io::checkOverwrite(args.out, overwrite);
  const std::string html = io::renderHtmlReport(io::readFileText(args.data), args.data);
  io::writeFileAtomic(args.out, html, overwrite);
  fmt::print("pkm: wrote {} ({} bytes)\n", args.out, html.size());
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
  render->add_option("--out,-o", args->out, "the HTML file to write")->required();
  render->add_flag("--force", args->force, "overwrite an existing --out file");
  render->callback([args] { runRender(*args); });
}

const CommandRegistration kRegisterReport{900, &addReport};

}  // namespace
}  // namespace pkm::cli
