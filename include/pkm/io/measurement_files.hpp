/// @file
/// @brief Measurement files (docs/formats.md, "Measurement files"): one CSV per run of a
/// line measurement, with "# key: value" metadata lines, a header row
/// `target_mm,run,direction,reading_mm` (or `reading_urad` for angular readings) and one row per
/// reading, direction "+" or "-". The reader also takes a generic laser-interferometer export with
/// the same four columns and no metadata.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pkm/io/text_table.hpp"
#include "pkm/simulation/dial_gauges.hpp"
#include "pkm/simulation/line_measurement.hpp"

namespace pkm::io {

/// The CSV text of one run: `metadata` as "# key: value" lines, the header, the readings. The
/// reading column is reading_mm for kLinear and kStraightness and reading_urad (the reading × 1e6)
/// for kAngular; a step-diagonal run (a reading with sub_step ≠ 0) adds the column sub_step, a
/// run whose readings recorded their conditions (LineReading::sensed) the columns
/// air_temperature_c, air_pressure_pa, air_humidity_rh and material_temperature_c.
/// Numbers in shortest round-trip form.
[[nodiscard]] std::string lineRunCsv(simulation::LineQuantity quantity,
                                     const Metadata& metadata,
                                     const simulation::LineRun& run);

/// The CSV text of a constrained-motion (dial gauge) measurement: `metadata` as "# key: value"
/// lines, then the header
/// `station,x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,l0_mm,...,l5_mm,g0_mm,g1_mm,g2_mm,iterations,converged`
/// and one row per station (0 = the reference where the gauges were zeroed): the final command,
/// the commanded strut readings, the final gauge readings, the readings taken, and converged 1 or
/// 0. All columns are numbers, so io::CsvReader reads the file.
[[nodiscard]] std::string dialGaugeCsv(const Metadata& metadata,
                                       const std::vector<simulation::DialGaugeStation>& stations);

/// A measurement file as read.
struct LineRunFile {
  Metadata metadata;                              ///< the "# key: value" lines
  std::string reading_unit;                       ///< "mm" or "urad" (from the header)
  std::vector<int> runs;                          ///< run number of each reading
  std::vector<simulation::LineReading> readings;  ///< in file order, in the file's units
};

/// Parses a measurement CSV: '#' lines (metadata when of the form "key: value"), blank lines,
/// a header with target_mm, run, direction and reading_mm or reading_urad (any order, other
/// columns ignored; an optional sub_step column, an integer ≥ 0, is read into LineReading::
/// sub_step), then rows; direction is "+", "-", "+1", "1" or "-1". Throws pkm::IoError
/// "SOURCE:LINE: message" for a missing column, a bad number or direction, or a wrong field count.
[[nodiscard]] LineRunFile parseLineRunCsv(const std::string& text, const std::string& source);
/// Reads a measurement file (parseLineRunCsv). Throws pkm::IoError.
[[nodiscard]] LineRunFile readLineRunCsv(const std::string& path);

}  // namespace pkm::io
