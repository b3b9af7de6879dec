/// @file
/// @brief `pkm compensate table` as a workflow (docs/compensation.md): a controller compensation
/// table (LinuxCNC COMP_FILE type 0/1, SINUMERIK 840D EEC and CEC part programs, ISG CSV) from
/// ISO 230-2 positioning files or straightness files, fitted to the controller's limits and
/// written atomically.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "pkm/io/compensation_table_report.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/positioning_files.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A compensation-table request.
struct CompensationTableRequest {
  /// The measurement files (required): ISO 230-2 `target,direction,run,measured` or simulator
  /// linear files for an axis table; `position,deviation` or simulator straightness files for a
  /// straightness (cross-axis) table. Lengths in mm.
  std::vector<io::NamedText> data;
  io::PositioningColumns columns;  ///< axis tables: column assignments and units of the exports
  /// The machine the table is for (a machine file, `.hal` or built-in name; "" : none) or its
  /// LinuxCNC INI ([TRAJ] LINEAR_UNITS): the table is written in the machine's length unit (mm
  /// without either), and positioning files stating no unit on an inch machine are flagged.
  std::string machine;
  std::string ini;          ///< see `machine`
  std::string format;       ///< linuxcnc0, linuxcnc1, siemens-eec, siemens-cec or isg (required)
  std::string axis;         ///< axis tables: the axis as the controller knows it (X, X1, AX1, ...)
  std::string input_axis;   ///< straightness tables: the base axis (argument)
  std::string output_axis;  ///< straightness tables: the compensated axis (isg: chooses them)
  std::string line = "endpoint";  ///< straightness: line removed first: endpoint, lsq or raw
  std::optional<std::size_t> max_points;  ///< most rows (default: the format's); longer: resampled
  int encoder = 0;                        ///< siemens-eec: measuring system 0 or 1
  int table_index = 0;                    ///< siemens-cec: table index t, 0..1000
  std::string out;                        ///< the table file to write (required)
  bool force = false;                     ///< replace an existing file
  /// Throws pkm::InvalidArgument for no data, an unknown format or line, a missing --axis (axis
  /// tables) or --input-axis/--output-axis (straightness tables), or an encoder or table index
  /// out of range; pkm::IoError for no output file.
  void validate() const;
  /// Whether the request makes a straightness (cross-axis) table: siemens-cec, or isg with an
  /// output axis.
  [[nodiscard]] bool crossAxis() const;
};

/// What a compensation table produced.
struct CompensationTableResult {
  io::CompensationTableSummary summary;  ///< io::compensationTableText / compensationTableJson
  std::string text;                      ///< the table, as written
};

/// Builds the table and writes it to request.out (atomically). Notices: a resampling, data in
/// one direction only, a one-table format given bidirectional data. Throws pkm::IoError
/// "NAME:LINE: message" for bad data, "OUT: exists; refusing to overwrite (use --force)",
/// pkm::InvalidArgument for a bad request or a table the format cannot hold.
[[nodiscard]] CompensationTableResult writeCompensationTable(
    const CompensationTableRequest& request, const RunControl& control = {});

}  // namespace pkm::workflow
