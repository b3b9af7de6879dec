/// @file
/// @brief ISG / Beckhoff TwinCAT CNC volumetric compensation (TF5280) tables in the "ISG CSV"
/// format (ISG kernel documentation, page 296429067 "ISG CSV"; docs/compensation.md).
///
/// Format: whitespace-separated columns named in a header line; `//` starts a comment; a line `#`
/// starts a new block (with its own header). The first column is the argument (the commanded axis
/// position X, Y or Z in mm), the others ISO 230-1 component errors named E<error direction><axis>
/// (EXX positioning of X, EYX straightness of X in Y, ...) in mm. The values are errors
/// (actual − nominal), which the controller subtracts (+e for an axis that overshoots by e; the
/// sign table of docs/compensation.md).
#pragma once

#include <span>
#include <string>
#include <vector>

#include "pkm/compensation/axis_table.hpp"

namespace pkm::compensation {

/// One named column of an ISG CSV block.
struct IsgColumn {
  std::string name;            ///< e.g. "EXX"
  std::vector<double> values;  ///< one per row, mm
};

/// One block: comment, argument column and parameter columns.
struct IsgBlock {
  std::string comment;             ///< written as "// comment" before the header (may be empty)
  std::string argument;            ///< argument column name: X, Y or Z
  std::vector<double> positions;   ///< argument values, strictly increasing, mm
  std::vector<IsgColumn> columns;  ///< parameter columns
  /// Throws pkm::InvalidArgument unless the argument is X/Y/Z, there are ≥ 2 strictly increasing
  /// finite positions, ≥ 1 column, every column named [A-Z0-9]+ with one finite value per row,
  /// and the comment is a single line.
  void validate() const;
};

/// The positioning block of `table`: argument = the axis name (X, Y or Z, case-insensitive),
/// column E<axis><axis> = the bidirectional mean error x̄i (ISG CSV has no approach direction).
/// Throws pkm::InvalidArgument for an invalid table or another axis name.
[[nodiscard]] IsgBlock isgBlockFromTable(const AxisErrorTable& table);
/// The straightness block of a cross-axis table: argument = input axis, column
/// E<output><input> = the output axis' error. Throws as above.
[[nodiscard]] IsgBlock isgBlockFromTable(const CrossAxisTable& table);

/// The ISG CSV text of `blocks` (separated by "#" lines): per block "// comment", the header,
/// one row per position; numbers fixed-point with at most 9 decimals, single spaces. Throws
/// pkm::InvalidArgument for no blocks or an invalid block.
[[nodiscard]] std::string writeIsgCsv(std::span<const IsgBlock> blocks);

}  // namespace pkm::compensation
