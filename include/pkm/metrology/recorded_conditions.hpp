/// @file
/// @brief The conditions a measurement recorded (air temperature, pressure and humidity,
/// material temperature per reading, as a laser's environmental compensation unit logs them; the
/// set-up's dead path and beam alignment) and the budgets' sources evaluated at them
/// (ISO 230-2:2014 Annex A; ISO/TR 230-9:2005 §6). docs/analysis.md, "Measurement conditions";
/// docs/formats.md, "Environment records".
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "pkm/metrology/uncertainty_budget.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::metrology {

/// A recorded quantity over a measurement: how many values, their mean and range, in the
/// quantity's unit.
struct RecordedSeries {
  std::size_t count = 0;
  double mean = 0.0;
  double min = 0.0;
  double max = 0.0;

  /// Adds one value (finite).
  void add(double value);
  /// Adds every value of `other`.
  void merge(const RecordedSeries& other);
};

/// What the files of one measurement recorded; a member is empty when nothing recorded it.
struct RecordedConditions {
  std::optional<RecordedSeries> air_temperature_c;       ///< °C
  std::optional<RecordedSeries> air_pressure_pa;         ///< Pa
  std::optional<RecordedSeries> air_humidity_rh;         ///< %RH
  std::optional<RecordedSeries> material_temperature_c;  ///< °C (mean of a reading's sensors)
  std::optional<double> dead_path_mm;       ///< the set-up's dead path, mm (largest recorded)
  std::optional<double> misalignment_rad;   ///< the set-up's beam alignment bound, rad (largest)
  std::optional<double> abbe_offset_mm;     ///< bound of the reflector's offset, mm (largest)
  std::optional<double> angular_range_rad;  ///< range of the angular error along the line, rad

  /// True when nothing is recorded.
  [[nodiscard]] bool empty() const;
  /// Adds the records of another file of the same measurement.
  void merge(const RecordedConditions& other);
};

/// `sources` with the recorded conditions in place of its own, each marked
/// ConditionOrigin::kRecorded with a note:
/// - the air state: the mean of the recorded temperature, pressure and humidity (the budgets'
///   Edlén sensitivities are evaluated there);
/// - the material temperature: the recorded value farthest from 20 °C (the expansion
///   coefficient's uncertainty acts on |T − 20 °C|, so its largest value bounds every reading);
/// - the air temperature variation: the recorded range max − min (the dead path's index change
///   since zeroing is within it), when more than one air temperature is recorded;
/// - dead path and alignment as recorded.
/// Unrecorded conditions keep their value and origin. Throws pkm::InvalidArgument when a recorded
/// air state lies outside the Edlén equation's range.
[[nodiscard]] UncertaintySources withRecordedConditions(const UncertaintySources& sources,
                                                        const RecordedConditions& recorded);

/// The conditions a laser length budget depends on, as evaluated from `sources`: air temperature,
/// pressure and humidity, material temperature, air temperature variation, dead path and beam
/// alignment, each with its value, unit and origin.
[[nodiscard]] std::vector<BudgetCondition> laserConditions(const UncertaintySources& sources);

}  // namespace pkm::metrology
