// Instrument and environment descriptions (metrology/uncertainty_sources.hpp): checks.
#include "pkm/metrology/uncertainty_sources.hpp"

#include <fmt/format.h>

#include <cmath>
#include <initializer_list>
#include <utility>

namespace pkm::metrology {

const char* toString(ConditionOrigin origin) {
  switch (origin) {
    case ConditionOrigin::kStated:
      return "stated";
    case ConditionOrigin::kRecorded:
      return "recorded";
    case ConditionOrigin::kDefault:
      break;
  }
  return "default";
}

namespace {

/// The weights' statements: masses and clearances >= 0, centres finite, stiffness > 0, the
/// strut share in 0..1; otherwise false with the reason.
bool weightsValid(const HexapodPlatform& pl, const ExechonHead& h, std::string& reason) {
  const auto fail = [&](std::string why) {
    reason = std::move(why);
    return false;
  };
  const std::initializer_list<std::pair<const char*, double>> non_negative{
      {"hexapod_platform mass_kg", pl.mass_kg},
      {"hexapod_platform strut_mass_kg", pl.strut_mass_kg},
      {"hexapod_platform joint_clearance_mm", pl.joint_clearance_mm},
      {"exechon_head mass_kg", h.mass_kg},
      {"exechon_head joint_clearance_mm", h.joint_clearance_mm}};
  for (const auto& [name, v] : non_negative)
    if (!(std::isfinite(v) && v >= 0.0))
      return fail(fmt::format("{} must be >= 0, got {}", name, v));
  if (!(std::isfinite(pl.com_x_mm) && std::isfinite(pl.com_y_mm) && std::isfinite(pl.com_z_mm)))
    return fail("hexapod_platform com_x_mm, com_y_mm and com_z_mm must be finite");
  if (!(pl.strut_com_fraction >= 0.0 && pl.strut_com_fraction <= 1.0))
    return fail(fmt::format("hexapod_platform strut_com_fraction must be in 0..1, got {}",
                            pl.strut_com_fraction));
  if (!(std::isfinite(pl.strut_stiffness_n_per_um) && pl.strut_stiffness_n_per_um > 0.0))
    return fail(fmt::format("hexapod_platform strut_stiffness_n_per_um must be > 0, got {}",
                            pl.strut_stiffness_n_per_um));
  if (!(std::isfinite(h.com_x_mm) && std::isfinite(h.com_y_mm) && std::isfinite(h.com_z_mm)))
    return fail("exechon_head com_x_mm, com_y_mm and com_z_mm must be finite");
  if (!(std::isfinite(h.leg_stiffness_n_per_um) && h.leg_stiffness_n_per_um > 0.0))
    return fail(fmt::format("exechon_head leg_stiffness_n_per_um must be > 0, got {}",
                            h.leg_stiffness_n_per_um));
  return true;
}

}  // namespace

bool UncertaintySources::isValid(std::string* why) const {
  const auto fail = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  const MeasurementEnvironment& e = environment;
  const std::initializer_list<std::pair<const char*, double>> non_negative{
      {"laser wavelength_accuracy_ppm", laser.wavelength_accuracy_ppm},
      {"laser resolution_mm", laser.resolution_mm},
      {"laser reading_noise_mm", laser.reading_noise_mm},
      {"laser air_temperature_accuracy_k", laser.air_temperature_accuracy_k},
      {"laser air_pressure_accuracy_pa", laser.air_pressure_accuracy_pa},
      {"laser air_humidity_accuracy_percent", laser.air_humidity_accuracy_percent},
      {"laser material_temperature_accuracy_k", laser.material_temperature_accuracy_k},
      {"laser straightness_accuracy_mm", laser.straightness_accuracy_mm},
      {"laser straightness_relative", laser.straightness_relative},
      {"laser straightness_length_mm_per_m2", laser.straightness_length_mm_per_m2},
      {"laser angular_accuracy_rad", laser.angular_accuracy_rad},
      {"laser angular_accuracy_rad_per_m", laser.angular_accuracy_rad_per_m},
      {"probe repeatability_2sigma_mm", probe.repeatability_2sigma_mm},
      {"probe form_2d_mm", probe.form_2d_mm},
      {"probe stylus_radius_uncertainty_mm", probe.stylus_radius_uncertainty_mm},
      {"probe ring_diameter_uncertainty_mm", probe.ring_diameter_uncertainty_mm},
      {"probe ring_form_mm", probe.ring_form_mm},
      {"dial_gauge accuracy_mm", dial_gauge.accuracy_mm},
      {"dial_gauge resolution_mm", dial_gauge.resolution_mm},
      {"tracker accuracy_mm", tracker.accuracy_mm},
      {"tracker accuracy_mm_per_m", tracker.accuracy_mm_per_m},
      {"tracker range_mm", tracker.range_mm},
      {"tracker orientation_accuracy_rad", tracker.orientation_accuracy_rad},
      {"actuators resolution_mm", actuators.resolution_mm},
      {"actuators repeatability_mm", actuators.repeatability_mm},
      {"actuators backlash_mm", actuators.backlash_mm},
      {"actuators lead_error_mm_per_m", actuators.lead_error_mm_per_m},
      {"actuators lead_wave_mm", actuators.lead_wave_mm},
      {"actuators lead_periodic_mm", actuators.lead_periodic_mm},
      {"ballbar sensor_accuracy_mm", ballbar.sensor_accuracy_mm},
      {"ballbar resolution_mm", ballbar.resolution_mm},
      {"ballbar length_uncertainty_mm", ballbar.length_uncertainty_mm},
      {"environment expansion_coefficient_accuracy_per_k", e.expansion_coefficient_accuracy_per_k},
      {"environment air_temperature_variation_k", e.air_temperature_variation_k},
      {"environment dead_path_mm", e.dead_path_mm},
      {"environment misalignment_rad", e.misalignment_rad},
      {"environment abbe_offset_mm", e.abbe_offset_mm},
      {"environment angular_error_range_rad", e.angular_error_range_rad},
      {"environment setup_repeatability_mm", e.setup_repeatability_mm},
      {"environment environmental_variation_mm", e.environmental_variation_mm}};
  for (const auto& [name, v] : non_negative) {
    if (!(std::isfinite(v) && v >= 0.0))
      return fail(fmt::format("{} must be >= 0, got {}", name, v));
  }
  if (!(std::isfinite(laser.vacuum_wavelength_um) && laser.vacuum_wavelength_um >= 0.3 &&
        laser.vacuum_wavelength_um <= 1.7))
    return fail(fmt::format("laser vacuum_wavelength_um must be in 0.3..1.7, got {}",
                            laser.vacuum_wavelength_um));
  if (!(std::isfinite(e.material_temperature_c) &&
        std::abs(e.material_temperature_c - 20.0) <= 30.0))
    return fail(fmt::format("environment material_temperature_c must be in -10..50, got {}",
                            e.material_temperature_c));
  if (!std::isfinite(e.expansion_coefficient_per_k))
    return fail("environment expansion_coefficient_per_k must be finite");
  if (!(std::isfinite(actuators.lead_wave_length_mm) && actuators.lead_wave_length_mm > 0.0))
    return fail(fmt::format("actuators lead_wave_length_mm must be > 0, got {}",
                            actuators.lead_wave_length_mm));
  if (std::string reason; !weightsValid(hexapod_platform, exechon_head, reason))
    return fail(reason);
  std::string air_why;
  if (!e.air.isValid(&air_why)) return fail("environment air: " + air_why);
  if (!(std::isfinite(coverage_factor) && coverage_factor > 0.0))
    return fail(fmt::format("coverage_factor must be > 0, got {}", coverage_factor));
  return true;
}

}  // namespace pkm::metrology
