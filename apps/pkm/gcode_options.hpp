/// @file
/// @brief The interpreter options the `pkm gcode` commands share: tool table, block delete, loop
/// guard.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <string>

#include "pkm/cnc/interpreter.hpp"

namespace pkm::cli {

/// --tool-table, --tool-units, --block-delete and --max-iterations.
struct InterpreterArgs {
  std::string tool_table;
  std::string tool_units = "mm";
  bool block_delete = false;
  std::uint64_t max_iterations = 10'000'000;
  /// Adds the options to `cmd` (all four, or the tool table's two only).
  void add(CLI::App& cmd, bool all = true);
  /// The interpreter options. Throws pkm::InvalidArgument for a bad unit or a zero iteration
  /// cap, pkm::IoError when the tool table cannot be read.
  [[nodiscard]] cnc::InterpreterOptions options() const;
};

}  // namespace pkm::cli
