/// @file
/// @brief `pkm analyze <kind>`: the registry of analysis kinds and the options and output helpers
/// they share (docs/analysis.md). Each kind lives in its own apps/pkm/analyze_*.cpp, registers
/// itself with a static AnalyzeRegistration, turns its options into a workflow request
/// (pkm/workflow/analyze_*.hpp) and prints the report.
#pragma once

#include <CLI/CLI.hpp>
#include <cstddef>
#include <string>
#include <vector>

#include "pkm/io/analysis_report.hpp"
#include "pkm/io/analysis_text.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::cli {

/// Adds one kind (a subcommand with its options and callback) to the `analyze` command.
using AnalyzeAdder = void (*)(CLI::App& analyze);

/// Registers a kind at static-initialisation time; kinds are added to `pkm analyze` in ascending
/// `order` (ties: registration order). Use only for namespace-scope constants.
struct AnalyzeRegistration {
  AnalyzeRegistration(int order, AnalyzeAdder add);
};

/// The input files and output switch every kind shares.
struct AnalyzeIo {
  std::vector<std::string> data;  ///< the --data files, in the order given
  bool json = false;              ///< --json: one JSON object on stdout instead of the table
  /// Adds `--data FILE...` (required; `min_files` to `max_files` files, each must exist; 0 for
  /// max_files means no limit) and `--json` to `cmd`.
  void add(CLI::App& cmd, std::size_t min_files = 1, std::size_t max_files = 0);
};

/// The options that say how to read a positioning export whose header does not say everything:
/// `--columns ROLE=COLUMN,...`, `--unit U`, `--error-unit U` (io::PositioningColumns).
struct PositioningColumnArgs {
  std::string columns, unit, error_unit;
  std::string machine, ini;  ///< --machine / --ini: the machine's length unit
  void add(CLI::App& cmd);
  /// The parsed options. Throws pkm::InvalidArgument for a bad --columns item.
  [[nodiscard]] io::PositioningColumns parsed() const;
};

/// `--uncertainty FILE`: the instruments and environment of the uncertainty budgets
/// (io::readUncertaintySources; docs/formats.md, "Uncertainty sources").
struct UncertaintyArgs {
  std::string file;  ///< "" : the built-in typical values
  void add(CLI::App& cmd);
  /// The sources read from `file`, or the defaults. Throws pkm::IoError "FILE:LINE: ...".
  [[nodiscard]] metrology::UncertaintySources parsed() const;
};

/// Writes `text` to stdout as it is.
void printText(const std::string& text);

/// Prints an analysis report: its JSON document (io::analysisJson) with --json, else its table
/// (io::analysisText).
template <class Report>
void printReport(const AnalyzeIo& io, const Report& report) {
  printText(io.json ? io::analysisJson(report) : io::analysisText(report));
}

/// Adds `pkm analyze` with every registered kind to `app`.
void addAnalyzeCommand(CLI::App& app);

}  // namespace pkm::cli
