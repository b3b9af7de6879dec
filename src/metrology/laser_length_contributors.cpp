// The laser's length contributors of a positioning budget (metrology/positioning_uncertainty.hpp):
// ISO/TR 230-9 §6 and ISO 230-2:2014 Annex A.
#include <cmath>
#include <string>

#include "metrology/detail/length_contributor.hpp"
#include "pkm/core/error.hpp"
#include "pkm/metrology/positioning_uncertainty.hpp"
#include "pkm/metrology/recorded_conditions.hpp"

namespace pkm::metrology {

namespace {
constexpr double kPpm = 1e-6;
}  // namespace

void addLaserLengthContributors(UncertaintyBudget& b,
                                double length_mm,
                                const UncertaintySources& src) {
  std::string why;
  PKM_CHECK(src.isValid(&why), "uncertainty sources: {}", why);
  PKM_CHECK(std::isfinite(length_mm) && length_mm >= 0.0,
            "uncertainty: measured length must be >= 0, got {}",
            length_mm);
  const LaserInterferometer& laser = src.laser;
  const MeasurementEnvironment& env = src.environment;
  const double L = length_mm;
  const AirIndexSensitivity dn = edlenSensitivity(env.air, laser.vacuum_wavelength_um);
  addContributor(b,
                 detail::boundedContributor("laser wavelength (vacuum)",
                                            laser.wavelength_accuracy_ppm,
                                            "ppm",
                                            L * kPpm,
                                            "instrument"));
  addContributor(b,
                 detail::boundedContributor("air temperature sensor",
                                            laser.air_temperature_accuracy_k,
                                            "K",
                                            L * dn.per_kelvin,
                                            "instrument; Edlen sensitivity"));
  addContributor(b,
                 detail::boundedContributor("air pressure sensor",
                                            laser.air_pressure_accuracy_pa,
                                            "Pa",
                                            L * dn.per_pascal,
                                            "instrument; Edlen sensitivity"));
  addContributor(b,
                 detail::boundedContributor("air humidity sensor",
                                            laser.air_humidity_accuracy_percent,
                                            "%RH",
                                            L * dn.per_percent_rh,
                                            "instrument; Edlen sensitivity"));
  addContributor(b,
                 detail::boundedContributor("material temperature sensor",
                                            laser.material_temperature_accuracy_k,
                                            "K",
                                            L * env.expansion_coefficient_per_k,
                                            "instrument"));
  addContributor(b,
                 detail::boundedContributor("expansion coefficient",
                                            env.expansion_coefficient_accuracy_per_k,
                                            "1/K",
                                            L * std::abs(env.material_temperature_c - 20.0),
                                            "environment"));
  addContributor(b,
                 detail::boundedContributor("dead path (air change during the test)",
                                            env.air_temperature_variation_k,
                                            "K",
                                            env.dead_path_mm * dn.per_kelvin,
                                            "environment; Edlen sensitivity"));
  addContributor(b,
                 detail::boundedContributor("cosine error (beam misalignment)",
                                            L * env.misalignment_rad * env.misalignment_rad / 2.0,
                                            "mm",
                                            1.0,
                                            "set-up"));
  addContributor(b,
                 detail::boundedContributor("Abbe error",
                                            env.abbe_offset_mm * env.angular_error_range_rad / 2.0,
                                            "mm",
                                            1.0,
                                            "set-up"));
  addContributor(b,
                 detail::lengthContributor("set-up repeatability",
                                           env.setup_repeatability_mm,
                                           Distribution::kNormal,
                                           1.0,
                                           "set-up"));
  addContributor(b,
                 detail::boundedContributor("environmental variation error E_VE",
                                            env.environmental_variation_mm / 2.0,
                                            "mm",
                                            1.0,
                                            "drift test (ISO 230-2 Annex A)"));
  b.conditions = laserConditions(src);
}

}  // namespace pkm::metrology
