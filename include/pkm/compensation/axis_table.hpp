/// @file
/// @brief Axis error tables for controller compensation: the positioning error of one axis per
/// approach direction (from an ISO 230-2 evaluation), a cross-axis (straightness/sag) error table,
/// the controller formats' sign conventions and point limits, and resampling to those limits
/// (docs/compensation.md; ISO 230-2:2014 for the deviation's sign).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/metrology/iso230_2.hpp"

namespace pkm::compensation {

/// The positioning error of one axis as a table over the commanded (nominal) position. The error is
/// the ISO 230-2 deviation x = actual − commanded (ISO 230-2:2014): positive when the axis
/// travels further than commanded. Linear interpolation between rows, end values held outside.
struct AxisErrorTable {
  std::string axis;                ///< axis name as the controller knows it (e.g. "X", "AX1")
  std::vector<double> nominal;     ///< commanded positions, strictly increasing, mm
  std::vector<double> error_up;    ///< error when approached in + (ISO 230-2 x̄i↑), mm
  std::vector<double> error_down;  ///< error when approached in − (x̄i↓), mm

  /// Number of rows.
  [[nodiscard]] std::size_t size() const { return nominal.size(); }
  /// Throws pkm::InvalidArgument unless there are ≥ 2 rows, the three columns have equal sizes,
  /// every value is finite and `nominal` is strictly increasing.
  void validate() const;
  /// The error at `position` approached in `direction` (+1 or −1), mm: linear interpolation
  /// between the two enclosing rows, the end row's value outside the table. Throws
  /// pkm::InvalidArgument for a non-finite position or a direction other than ±1.
  [[nodiscard]] double errorAt(double position, int direction) const;
  /// The bidirectional mean (error_up + error_down)/2 at row i (ISO 230-2 x̄i).
  [[nodiscard]] double meanError(std::size_t i) const {
    return 0.5 * (error_up[i] + error_down[i]);
  }
  /// max over rows and directions of |error|, mm.
  [[nodiscard]] double maxAbsError() const;
};

/// The table of an ISO 230-2 result: one row per target, error_up = x̄i↑ and error_down = x̄i↓.
/// When only one direction was measured (`result.bidirectional` false), both columns hold that
/// direction's mean. Throws pkm::InvalidArgument for fewer than 2 targets or a non-finite mean.
[[nodiscard]] AxisErrorTable tableFromIso230_2(const metrology::Iso230_2Result& result,
                                               std::string axis);

/// A cross-axis error table (straightness or sag, ISO 230-1 e.g. EYX): the error of the output
/// (compensated) axis, actual − nominal along its + direction, mm, as a function of the commanded
/// position of the input (base) axis, mm. Linear interpolation, end values held outside.
struct CrossAxisTable {
  std::string input_axis;        ///< base axis (argument), e.g. "X"
  std::string output_axis;       ///< compensated axis, e.g. "Y"
  std::vector<double> position;  ///< input-axis positions, strictly increasing, mm
  std::vector<double> error;     ///< output-axis error, mm
  /// Throws pkm::InvalidArgument unless ≥ 2 rows, equal sizes, finite values, strictly increasing
  /// positions and non-empty axis names.
  void validate() const;
};

/// A cross-axis table from measured points (position, deviation) in any order: the deviations at
/// equal positions are averaged, the rows sorted. Throws pkm::InvalidArgument for unequal sizes,
/// non-finite values or fewer than 2 distinct positions.
[[nodiscard]] CrossAxisTable crossTableFromPoints(std::string input_axis,
                                                  std::string output_axis,
                                                  std::span<const double> positions,
                                                  std::span<const double> deviations);

/// The controller table formats pkm writes (docs/compensation.md).
enum class TableFormat {
  kLinuxcnc0,   ///< LinuxCNC COMP_FILE_TYPE 0: nominal, actual moving +, actual moving −
  kLinuxcnc1,   ///< LinuxCNC COMP_FILE_TYPE 1: nominal, trim moving +, trim moving −
  kSiemensEec,  ///< SINUMERIK 840D measuring-system error compensation ($AA_ENC_COMP)
  kSiemensCec,  ///< SINUMERIK 840D sag/cross compensation ($AN_CEC)
  kIsgCsv,      ///< ISG / TwinCAT CNC volumetric compensation "ISG CSV"
};

/// "linuxcnc0", "linuxcnc1", "siemens-eec", "siemens-cec", "isg".
[[nodiscard]] std::string_view toString(TableFormat format);
/// The inverse of toString; throws pkm::InvalidArgument for an unknown name.
[[nodiscard]] TableFormat parseTableFormat(std::string_view name);

/// What a format stores for an axis whose error (actual − commanded) is e at nominal position P
/// (the sign table of docs/compensation.md).
enum class StoredValue {
  kError,           ///< +e (Siemens $AA_ENC_COMP / $AN_CEC, ISG EXX/EYX)
  kCorrection,      ///< −e, added to the command (LinuxCNC type 1 trims)
  kActualPosition,  ///< P + e, the position reached (LinuxCNC type 0)
};

/// The conventions and limits of one format.
struct FormatTraits {
  StoredValue stored = StoredValue::kError;  ///< the sign convention (docs/compensation.md)
  bool bidirectional = false;  ///< separate + and − columns (else the mean x̄i is written)
  bool even_spacing = false;   ///< rows must be equidistant (MIN, MAX, STEP)
  /// Default largest number of rows: LinuxCNC EMCMOT_COMP_SIZE = 256 (a hard limit); Siemens 200
  /// (808D EEC and 828D CEC, the smallest documented; 840D: MD38000 / MD18342); ISG 1500
  /// (P-COMP-00059 default).
  std::size_t default_max_points = 0;
  /// The largest row count the format can take at all (LinuxCNC 256; else unbounded, 0).
  std::size_t hard_max_points = 0;
};

/// The traits of `format`.
[[nodiscard]] FormatTraits traits(TableFormat format);

/// The stored value for error `error` at nominal position `nominal` under `stored`
/// (docs/compensation.md, sign table).
[[nodiscard]] double storedValue(StoredValue stored, double nominal, double error);

/// `table` resampled at `points` equidistant positions from its first to its last nominal
/// position, by linear interpolation of each column between the old rows (exact at the ends; the
/// resampled curve is the chord polygon of the old one at the new nodes). Throws
/// pkm::InvalidArgument for points < 2 or an invalid table.
[[nodiscard]] AxisErrorTable resampleEven(const AxisErrorTable& table, std::size_t points);
/// As above for a cross-axis table.
[[nodiscard]] CrossAxisTable resampleEven(const CrossAxisTable& table, std::size_t points);

/// True when consecutive positions differ by the same step to within 1e-9 of the span.
[[nodiscard]] bool isEvenlySpaced(std::span<const double> positions);

/// The number of rows a table with `positions` gets for a target with `max_points` rows at most:
/// not even spacing required: min(n, max_points); even spacing required: n when already even,
/// else enough points that the step is no larger than the smallest original gap
/// (⌈span/min gap⌉ + 1), in both cases at most max_points. Throws pkm::InvalidArgument for
/// max_points < 2.
[[nodiscard]] std::size_t pointsForTarget(std::span<const double> positions,
                                          bool even_spacing,
                                          std::size_t max_points);

/// `table` fitted to a target: unchanged when it already satisfies it (row count ≤ max_points and,
/// if required, even spacing), else resampleEven to pointsForTarget rows. Throws
/// pkm::InvalidArgument for max_points < 2 or above a hard limit of the format.
[[nodiscard]] AxisErrorTable fitToTarget(const AxisErrorTable& table,
                                         const FormatTraits& target,
                                         std::size_t max_points);
/// As above for a cross-axis table.
[[nodiscard]] CrossAxisTable fitToTarget(const CrossAxisTable& table,
                                         const FormatTraits& target,
                                         std::size_t max_points);

/// Linear interpolation of (x, y) at `at`, end values held outside. Preconditions (unchecked):
/// x strictly increasing, x.size() == y.size() ≥ 1.
[[nodiscard]] double interpolateHeld(std::span<const double> x,
                                     std::span<const double> y,
                                     double at);

}  // namespace pkm::compensation
