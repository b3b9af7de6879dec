// `pkm report render DATA.json --out report.html [--force]`: the self-contained HTML campaign
// report from a report-data document, schema pkm.report/1 (pkm/io/html_report.hpp,
// docs/report.md).
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>

#include "cli_common.hpp"
#include "pkm/core/error.hpp"
#include "pkm/io/html_report.hpp"

namespace pkm::cli {
namespace {

struct ReportArgs {
  std::string data;
  std::string out;
  bool force = false;
};

std::string readText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(fmt::format("{}: cannot open for reading", path));
  std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw IoError(fmt::format("{}: read error", path));
  return text;
}

void runRender(const ReportArgs& args) {
  std::error_code ec;
  if (!args.force && std::filesystem::exists(args.out, ec))
    throw IoError(fmt::format("{} exists; pass --force to overwrite it", args.out));
  const std::string html = io::renderHtmlReport(readText(args.data), args.data);
  // Written next to the target first, so that a failed write never leaves half a report.
  const std::string tmp = args.out + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw IoError(fmt::format("{}: cannot open for writing", tmp));
    out.write(html.data(), static_cast<std::streamsize>(html.size()));
    out.close();
    if (!out) throw IoError(fmt::format("{}: write error", tmp));
  }
  std::filesystem::rename(tmp, args.out, ec);
  if (ec) {
    std::filesystem::remove(tmp, ec);
    throw IoError(fmt::format("{}: cannot write the report", args.out));
  }
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
