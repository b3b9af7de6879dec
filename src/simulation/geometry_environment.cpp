#include "pkm/simulation/geometry_environment.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::simulation {

namespace {

bool refuse(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

}  // namespace

bool GeometryEnvironment::isValid(std::string* why) const {
  for (const double v : {lead_progressive, lead_wave_mm, lead_periodic_mm, joint_axis_offset_mm})
    if (!std::isfinite(v) || v < 0.0)
      return refuse(why, "geometry amplitudes and bounds must be finite and >= 0");
  if (!std::isfinite(lead_wave_length_mm) || lead_wave_length_mm <= 0.0 ||
      !std::isfinite(screw_lead_mm) || screw_lead_mm <= 0.0)
    return refuse(
        why,
        fmt::format("geometry lead_wave_length_mm ({}) and screw_lead_mm ({}) must be > 0",
                    lead_wave_length_mm,
                    screw_lead_mm));
  return true;
}

GeometryEnvironment realisticGeometry() {
  GeometryEnvironment g;
  g.enabled = true;
  // Rolled ball screws, accuracy grade C7 (ISO 3408-3 / JIS B 1192: ±50 µm per 300 mm):
  // ±100 µm/m progressive, 10 µm long-wave variation, 4 µm per revolution (V_2π 8 µm).
  g.lead_progressive = 100e-6;
  g.lead_wave_mm = 0.010;
  g.lead_wave_length_mm = 300.0;
  g.lead_periodic_mm = 0.004;
  g.screw_lead_mm = 10.0;
  g.joint_axis_offset_mm = 0.020;  // the U-joint cross's bores within ±20 µm
  return g;
}

}  // namespace pkm::simulation
