// Recorded measurement conditions and the budgets' sources at them
// (metrology/recorded_conditions.hpp).
#include "pkm/metrology/recorded_conditions.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

constexpr double kReferenceC = 20.0;  ///< ISO 1 reference temperature, °C

/// "mean of N readings, LO..HI UNIT" (or "1 reading").
std::string seriesNote(const RecordedSeries& s, const char* unit) {
  if (s.count == 1) return "1 reading";
  return fmt::format("mean of {} readings, {:.6g}..{:.6g} {}", s.count, s.min, s.max, unit);
}

void mergeOptional(std::optional<RecordedSeries>& into, const std::optional<RecordedSeries>& x) {
  if (!x) return;
  if (!into)
    into = x;
  else
    into->merge(*x);
}

void mergeLargest(std::optional<double>& into, const std::optional<double>& x) {
  if (x) into = into ? std::max(*into, *x) : *x;
}

}  // namespace

void RecordedSeries::add(double value) {
  PKM_CHECK(std::isfinite(value), "recorded condition: {} is not finite", value);
  if (count == 0) {
    min = max = value;
  } else {
    min = std::min(min, value);
    max = std::max(max, value);
  }
  mean += (value - mean) / static_cast<double>(count + 1);
  ++count;
}

void RecordedSeries::merge(const RecordedSeries& other) {
  if (other.count == 0) return;
  if (count == 0) {
    *this = other;
    return;
  }
  const double n = static_cast<double>(count + other.count);
  mean = (mean * static_cast<double>(count) + other.mean * static_cast<double>(other.count)) / n;
  min = std::min(min, other.min);
  max = std::max(max, other.max);
  count += other.count;
}

bool RecordedConditions::empty() const {
  return !air_temperature_c && !air_pressure_pa && !air_humidity_rh && !material_temperature_c &&
         !dead_path_mm && !misalignment_rad && !abbe_offset_mm && !angular_range_rad;
}

void RecordedConditions::merge(const RecordedConditions& other) {
  mergeOptional(air_temperature_c, other.air_temperature_c);
  mergeOptional(air_pressure_pa, other.air_pressure_pa);
  mergeOptional(air_humidity_rh, other.air_humidity_rh);
  mergeOptional(material_temperature_c, other.material_temperature_c);
  mergeLargest(dead_path_mm, other.dead_path_mm);
  mergeLargest(misalignment_rad, other.misalignment_rad);
  mergeLargest(abbe_offset_mm, other.abbe_offset_mm);
  mergeLargest(angular_range_rad, other.angular_range_rad);
}

UncertaintySources withRecordedConditions(const UncertaintySources& sources,
                                          const RecordedConditions& recorded) {
  UncertaintySources out = sources;
  MeasurementEnvironment& e = out.environment;
  ConditionOrigins& o = e.origin;
  constexpr ConditionOrigin kRec = ConditionOrigin::kRecorded;
  if (const auto& t = recorded.air_temperature_c) {
    e.air.temperature_c = t->mean;
    o.air_temperature = kRec;
    o.air_temperature_note = seriesNote(*t, "degC");
    if (t->count > 1) {
      e.air_temperature_variation_k = t->max - t->min;
      o.air_temperature_variation = kRec;
      o.air_temperature_variation_note = "range of the recorded air temperature";
    }
  }
  if (const auto& p = recorded.air_pressure_pa) {
    e.air.pressure_pa = p->mean;
    o.air_pressure = kRec;
    o.air_pressure_note = seriesNote(*p, "Pa");
  }
  if (const auto& h = recorded.air_humidity_rh) {
    e.air.relative_humidity = h->mean;
    o.air_humidity = kRec;
    o.air_humidity_note = seriesNote(*h, "%RH");
  }
  if (const auto& m = recorded.material_temperature_c) {
    const bool low = std::abs(m->min - kReferenceC) > std::abs(m->max - kReferenceC);
    e.material_temperature_c = low ? m->min : m->max;
    o.material_temperature = kRec;
    o.material_temperature_note =
        m->count == 1 ? std::string("1 reading")
                      : fmt::format("farthest from 20 degC of {} readings ({:.6g}..{:.6g} degC)",
                                    m->count,
                                    m->min,
                                    m->max);
  }
  if (recorded.dead_path_mm) {
    e.dead_path_mm = *recorded.dead_path_mm;
    o.dead_path = kRec;
    o.dead_path_note = "the set-up's record";
  }
  if (recorded.misalignment_rad) {
    e.misalignment_rad = *recorded.misalignment_rad;
    o.misalignment = kRec;
    o.misalignment_note = "the set-up's record";
  }
  if (recorded.abbe_offset_mm && recorded.angular_range_rad) {  // the Abbe term needs both
    e.abbe_offset_mm = *recorded.abbe_offset_mm;
    e.angular_error_range_rad = *recorded.angular_range_rad;
    o.abbe = kRec;
    o.abbe_note = "the set-up's record";
  }
  std::string why;
  PKM_CHECK(e.air.isValid(&why), "recorded air: {}", why);
  return out;
}

std::vector<BudgetCondition> laserConditions(const UncertaintySources& sources) {
  const MeasurementEnvironment& e = sources.environment;
  const ConditionOrigins& o = e.origin;
  return {
      {"air temperature",
       e.air.temperature_c,
       "degC",
       toString(o.air_temperature),
       o.air_temperature_note},
      {"air pressure", e.air.pressure_pa, "Pa", toString(o.air_pressure), o.air_pressure_note},
      {"air humidity",
       e.air.relative_humidity,
       "%RH",
       toString(o.air_humidity),
       o.air_humidity_note},
      {"material temperature",
       e.material_temperature_c,
       "degC",
       toString(o.material_temperature),
       o.material_temperature_note},
      {"air temperature variation",
       e.air_temperature_variation_k,
       "K",
       toString(o.air_temperature_variation),
       o.air_temperature_variation_note},
      {"dead path", e.dead_path_mm, "mm", toString(o.dead_path), o.dead_path_note},
      {"beam alignment", e.misalignment_rad, "rad", toString(o.misalignment), o.misalignment_note},
      {"Abbe offset", e.abbe_offset_mm, "mm", toString(o.abbe), o.abbe_note},
      {"angular error range", e.angular_error_range_rad, "rad", toString(o.abbe), o.abbe_note},
  };
}

}  // namespace pkm::metrology
