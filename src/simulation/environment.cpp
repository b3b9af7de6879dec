#include "pkm/simulation/environment.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::simulation {

namespace {

bool fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

/// The air at both ends of a drift (fluctuations aside) must be inside Edlén's range.
bool airInRange(const AirEnvironment& a, std::string* why) {
  for (const double f : {0.0, 1.0}) {
    const AirConditions c{
        a.temperature_c.smooth(f), a.pressure_pa.smooth(f), a.humidity_percent.smooth(f)};
    std::string reason;
    if (!c.isValid(&reason)) return fail(why, fmt::format("air at fraction {}: {}", f, reason));
  }
  return true;
}

/// "realistic": the air of a workshop over one shift, compensated by a typical unit
/// (docs/simulation-errors.md lists the sources of every number).
AirEnvironment realisticAir() {
  AirEnvironment a;
  a.enabled = true;
  a.temperature_c = {20.5, 1.0, 0.1, 900.0};       // +1 K over the shift, 0.1 K HVAC cycling
  a.pressure_pa = {101325.0, -300.0, 5.0, 900.0};  // −3 hPa (weather), 5 Pa fluctuation
  a.humidity_percent = {45.0, 5.0, 1.0, 900.0};
  // Offsets within the compensation unit's specification (±0.2 K, ±1 hPa, ±6 %RH).
  a.temperature_sensor = {0.1, 0.02};
  a.pressure_sensor = {-50.0, 5.0};
  a.humidity_sensor = {3.0, 0.5};
  a.dead_path_mm = 100.0;
  return a;
}

}  // namespace

bool Drift::isValid() const {
  return std::isfinite(start) && std::isfinite(change) && std::isfinite(fluctuation) &&
         fluctuation >= 0.0 && std::isfinite(correlation_s) && correlation_s > 0.0;
}

bool SensorError::isValid() const {
  return std::isfinite(offset) && std::isfinite(noise) && noise >= 0.0;
}

bool AirEnvironment::isValid(std::string* why) const {
  if (!temperature_c.isValid() || !pressure_pa.isValid() || !humidity_percent.isValid())
    return fail(why,
                "an air drift has a non-finite value, a negative fluctuation or a "
                "correlation time <= 0");
  if (!temperature_sensor.isValid() || !pressure_sensor.isValid() || !humidity_sensor.isValid())
    return fail(why, "a sensor has a non-finite offset or a negative noise");
  if (!std::isfinite(dead_path_mm) || dead_path_mm < 0.0)
    return fail(why, fmt::format("dead_path_mm must be >= 0, got {}", dead_path_mm));
  if (!std::isfinite(vacuum_wavelength_um) || vacuum_wavelength_um < 0.3 ||
      vacuum_wavelength_um > 1.7)
    return fail(why, "vacuum_wavelength_um must be in 0.3..1.7");
  return airInRange(*this, why);
}

bool Environment::isValid(std::string* why) const {
  if (!std::isfinite(duration_h) || duration_h <= 0.0)
    return fail(why, fmt::format("duration_h must be > 0, got {}", duration_h));
  return air.isValid(why);
}

std::optional<Environment> environmentPreset(std::string_view name) {
  Environment e;
  if (name == "ideal") return e;
  if (name == "realistic") {
    e.name = "realistic";
    e.air = realisticAir();
    return e;
  }
  return std::nullopt;
}

std::vector<std::string_view> environmentPresetNames() { return {"ideal", "realistic"}; }

}  // namespace pkm::simulation
