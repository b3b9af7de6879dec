/// @file
/// @brief Readers of positioning and straightness measurement files, from memory (io::NamedText),
/// shared by `pkm analyze` and `pkm compensate` (docs/analysis.md, "ISO 230-2 positioning" and
/// "Straightness"; docs/formats.md, "Measurement files"). Errors name the input and the line,
/// "NAME:LINE: message", whether it came from a file or an upload.
#pragma once

#include <span>
#include <vector>

#include "pkm/io/export_columns.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/io/text_table.hpp"
#include "pkm/metrology/iso230_2.hpp"

namespace pkm::io {

/// True for a simulator measurement file (docs/formats.md "Measurement files"): it has the
/// columns target_mm and reading_mm.
[[nodiscard]] bool isMeasurementFile(const TextTable& t);

/// Points (position, value) along a line, e.g. per-target means; both in the file's length unit.
struct Profile {
  std::vector<double> position, value;
};

/// Per-target mean of the readings of simulator measurement files (over runs and directions;
/// rows with a sub_step other than 0 left out; metrology::perTargetMeans), sorted by target;
/// `minus_target` subtracts the target (the positioning deviation). Throws pkm::IoError
/// "NAME:LINE: message" for a missing column or a bad field.
[[nodiscard]] Profile meanProfile(std::span<const TextTable> tables, bool minus_target);

/// Every straightness reading of the inputs (position, deviation), in input order, in mm: plain
/// tables whose columns are recognised by name with their units (position: `position`,
/// `target`, `nominal`; deviation: `deviation`, `error`, `straightness`; mm when the header
/// states none) and simulator straightness files (`target_mm`, `reading_mm`; sub-step rows left
/// out). Throws pkm::IoError "NAME:LINE: message" (missing columns listed with the columns found).
[[nodiscard]] Profile readStraightnessPoints(std::span<const NamedText> inputs);

/// The per-position mean of `points` (metrology::perTargetMeans), sorted by position.
[[nodiscard]] Profile perTargetMean(const Profile& points);

/// The straightness profile of the inputs: the per-target mean over runs of
/// readStraightnessPoints (metrology::perTargetMeans), sorted by position — whatever the column
/// names, as ISO 230-1 evaluates a line. Throws as readStraightnessPoints.
[[nodiscard]] Profile readStraightness(std::span<const NamedText> inputs);

/// How to read positioning exports whose header does not say everything (the `--columns`,
/// `--unit` and `--error-unit` options of `pkm analyze iso230-2` and `pkm compensate`).
struct PositioningColumns {
  ColumnAssignments columns;  ///< explicit role=COLUMN assignments
  std::string unit;           ///< unit of target and measured columns that state none ("" : mm)
  std::string error_unit;     ///< unit of an error column that states none (required then)
};

/// ISO 230-2 samples (ISO 230-2:2014 §2), in mm, from the inputs concatenated. Each input is a
/// table whose columns are recognised by name (io::ExportColumns; docs/formats.md, "Instrument
/// exports"): target (`target`, `nominal`, `position`, …), run, direction (`+`/`-`,
/// `Forward`/`Reverse`, `F`/`R`, `Up`/`Down`, `1`/`-1`) and either the measured position
/// (`measured`, `actual`, `reading`) or the deviation (`error`, `deviation`: measured = target +
/// deviation), each with the unit its header states (`Target (mm)`, `Error [µm]`, `reading_mm`)
/// or the one `how` gives; or a Renishaw LaserXL `.rtl` text file (io::isRenishawRtl). Throws
/// pkm::IoError "NAME:LINE: message" for missing columns (listing the names accepted and the
/// columns found), an unstated error unit, a bad field, a run < 1 or a repeated (target,
/// direction, run) ("... (first at NAME:LINE)"). When `unstated` is given, the names of the
/// inputs whose target positions were read as mm for want of a unit (none in the header, no
/// how.unit) are appended to it.
[[nodiscard]] std::vector<metrology::PositioningSample> readPositioningSamples(
    std::span<const NamedText> inputs,
    const PositioningColumns& how = {},
    std::vector<std::string>* unstated = nullptr);

}  // namespace pkm::io
