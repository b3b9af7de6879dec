// `pkm analyze`: the registry of analysis kinds (analyze_common.hpp).
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <utility>

#include "analyze_common.hpp"
#include "cli_common.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/uncertainty_sources.hpp"

namespace pkm::cli {
namespace {

struct Entry {
  int order;
  AnalyzeAdder add;
};

std::vector<Entry>& registry() {
  static std::vector<Entry> entries;
  return entries;
}

}  // namespace

AnalyzeRegistration::AnalyzeRegistration(int order, AnalyzeAdder add) {
  registry().push_back({order, add});
}

void AnalyzeIo::add(CLI::App& cmd, std::size_t min_files, std::size_t max_files) {
  auto* opt = cmd.add_option("--data", data, "input file(s), CSV with a header row")
                  ->required()
                  ->check(CLI::ExistingFile);
  if (max_files == 0)
    opt->expected(static_cast<int>(min_files), CLI::detail::expected_max_vector_size);
  else
    opt->expected(static_cast<int>(min_files), static_cast<int>(max_files));
  cmd.add_flag("--json", json, "print one JSON object instead of a table");
}

void UncertaintyArgs::add(CLI::App& cmd) {
  cmd.add_option("--uncertainty",
                 file,
                 "instruments and environment of the uncertainty budgets (JSON; default: "
                 "typical datasheet values, docs/formats.md \"Uncertainty sources\")")
      ->check(CLI::ExistingFile);
}

metrology::UncertaintySources UncertaintyArgs::parsed() const {
  return file.empty() ? metrology::UncertaintySources{}
                      : io::readUncertaintySources(io::readNamedText(file));
}

void PositioningColumnArgs::add(CLI::App& cmd) {
  cmd.add_option("--columns",
                 columns,
                 "assign columns the header does not name: ROLE=COLUMN,... with roles target, "
                 "run, direction, measured, error (e.g. error=Dev)");
  cmd.add_option("--unit",
                 unit,
                 "unit of target/measured columns whose header states none: mm "
                 "(default), um, in, m")
      ->check(CLI::IsMember({"mm", "um", "µm", "nm", "m", "in"}));
  cmd.add_option("--error-unit",
                 error_unit,
                 "unit of an error/deviation column whose header states none: um, mm, in")
      ->check(CLI::IsMember({"mm", "um", "µm", "nm", "m", "in"}));
  cmd.add_option("--machine",
                 machine,
                 "the machine the axis belongs to (JSON, LinuxCNC .hal or built-in name): its "
                 "length unit; files stating none on an inch machine are flagged");
  cmd.add_option(
      "--ini", ini, "the machine's LinuxCNC INI: its [TRAJ] LINEAR_UNITS is the machine's unit");
}

io::PositioningColumns PositioningColumnArgs::parsed() const {
  return {columns.empty() ? io::ColumnAssignments{} : io::parseColumnAssignments(columns),
          unit,
          error_unit};
}

void printText(const std::string& text) {
  std::fwrite(text.data(), 1, text.size(), stdout);
  std::fflush(stdout);
}

void addAnalyzeCommand(CLI::App& app) {
  CLI::App* analyze = app.add_subcommand(
      "analyze",
      "evaluate measurement files: ISO 230 statistics, straightness, squareness, "
      "diagonals, circles (docs/analysis.md)");
  analyze->require_subcommand(1);
  std::vector<Entry> entries = registry();
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.order < b.order;
  });
  for (const Entry& e : entries) e.add(*analyze);
}

}  // namespace pkm::cli
