#include "pkm/simulation/environment.hpp"

#include <fmt/format.h>

#include <cmath>

namespace pkm::simulation {

namespace {

bool fail(std::string* why, const std::string& message) {
  if (why != nullptr) *why = message;
  return false;
}

/// The air at both ends of a pass (fluctuations aside) must be inside Edlén's range; `last` is the
/// pass's end as a fraction of the duration.
bool airInRange(const AirEnvironment& a, double last, std::string* why) {
  for (const double f : {0.0, last}) {
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

/// "realistic": a machine that warms up over the shift (docs/simulation-errors.md).
ThermalEnvironment realisticThermal() {
  ThermalEnvironment t;
  t.enabled = true;
  t.material_temperature_c = {20.5, 1.0, 0.02, 3600.0};  // follows the air, slowly
  t.material_sensor = {0.05, 0.01};                      // within ±0.1 K
  t.machine_cte_per_k = 11.0e-6;  // steel screws in a cast-iron and steel structure
  t.assumed_cte_per_k = 11.5e-6;  // the operator enters steel
  t.warmup_drift_mm = {0.005, 0.008, -0.030};
  t.warmup_tilt_rad = {50e-6, 0.0, 30e-6};  // a PKM head tilting by tens of µrad as it warms
  t.warmup_time_constant_h = 1.0;
  t.strut_warmup_k = 2.0;
  t.strut_cte_per_k = 11.5e-6;
  return t;
}

/// "realistic": an operator's careful set-up (docs/simulation-errors.md).
SetupEnvironment realisticSetup() {
  SetupEnvironment s;
  s.enabled = true;
  s.beam_misalignment_rad = 200e-6;  // aligned to 0.2 mm over 1 m
  s.reflector_offset_mm = 5.0;       // the reflector a few mm off the tool point
  s.probe_lobing_mm = 0.25e-3;       // strain-gauge probe, 2D form ±0.25 µm
  s.probe_lobes = 3;
  return s;
}

/// "realistic": a structure that does not return to the same point to better than about a
/// micrometre (docs/simulation-errors.md).
StructureEnvironment realisticStructure() {
  StructureEnvironment s;
  s.enabled = true;
  s.correlated_sigma_mm = 1.0e-3;
  s.correlation_s = 600.0;
  s.white_sigma_mm = 0.2e-3;
  return s;
}

/// "realistic": a machine that sags under its own weight and whose joints have a little play
/// (docs/simulation-errors.md, "Structure: compliance (gravity sag) and joint clearance").
ComplianceEnvironment realisticCompliance() {
  ComplianceEnvironment c;
  c.enabled = true;
  c.hexapod.platform_mass_kg = 150.0;  // platform and motor spindle
  c.hexapod.platform_com_mm = {0.0, 0.0, -100.0};
  c.hexapod.strut_mass_kg = 20.0;
  c.hexapod.strut_com_fraction = 0.5;
  c.hexapod.strut_stiffness_n_per_um = 50.0;  // screw, nut, bearings and joints in series
  c.hexapod.joint_clearance_mm = 4e-3;        // 2 µm in each of the two joints
  c.exechon.head_mass_kg = 250.0;
  c.exechon.head_com_mm = {0.0, 0.0, 200.0};  // on the tool axis, 200 mm back from the tool point
  c.exechon.leg_stiffness_n_per_um = 50.0;
  c.exechon.joint_clearance_mm = 4e-3;
  // The Cartesian machine's Y slide carries the spindle head on a ram 300..700 mm out.
  c.cartesian[1] = {AxisSag::Kind::kCantilever, 25e-3, 1000.0, 300.0, 1.0};
  c.x2 = {AxisSag::Kind::kSpan, 10e-3, 4000.0, 0.0, 1.0};        // the PKM's weight on the X2 bed
  c.y2 = {AxisSag::Kind::kCantilever, 5e-3, 600.0, 150.0, 1.0};  // the table running off Y2
  return c;
}

bool finiteNonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

bool AxisSag::isValid(std::string* why) const {
  if (!finiteNonNegative(sag_mm)) return fail(why, "sag_mm must be finite and >= 0");
  if (!std::isfinite(length_mm) || length_mm <= 0.0)
    return fail(why, fmt::format("sag length_mm must be > 0, got {}", length_mm));
  if (!std::isfinite(zero_mm)) return fail(why, "sag zero_mm must be finite");
  if (sense != 1.0 && sense != -1.0)
    return fail(why, fmt::format("sag sense must be 1 or -1, got {}", sense));
  return true;
}

bool HexapodCompliance::isValid(std::string* why) const {
  if (!finiteNonNegative(platform_mass_kg) || !finiteNonNegative(strut_mass_kg) ||
      !finiteNonNegative(joint_clearance_mm) || !platform_com_mm.allFinite())
    return fail(why, "hexapod masses and clearance must be finite and >= 0");
  if (!std::isfinite(strut_com_fraction) || strut_com_fraction < 0.0 || strut_com_fraction > 1.0)
    return fail(why,
                fmt::format("strut_com_fraction must be in [0, 1], got {}", strut_com_fraction));
  if (!std::isfinite(strut_stiffness_n_per_um) || strut_stiffness_n_per_um <= 0.0)
    return fail(why, "strut_stiffness_n_per_um must be > 0");
  return true;
}

bool ExechonCompliance::isValid(std::string* why) const {
  if (!finiteNonNegative(head_mass_kg) || !finiteNonNegative(joint_clearance_mm) ||
      !head_com_mm.allFinite())
    return fail(why, "Exechon head mass and clearance must be finite and >= 0");
  if (!std::isfinite(leg_stiffness_n_per_um) || leg_stiffness_n_per_um <= 0.0)
    return fail(why, "leg_stiffness_n_per_um must be > 0");
  return true;
}

bool ComplianceEnvironment::isValid(std::string* why) const {
  if (!hexapod.isValid(why) || !exechon.isValid(why)) return false;
  for (const AxisSag& s : cartesian)
    if (!s.isValid(why)) return false;
  return x2.isValid(why) && y2.isValid(why);
}

bool StructureEnvironment::isValid(std::string* why) const {
  if (!std::isfinite(correlated_sigma_mm) || correlated_sigma_mm < 0.0 ||
      !std::isfinite(white_sigma_mm) || white_sigma_mm < 0.0)
    return fail(why, "structure sigmas must be finite and >= 0");
  if (!std::isfinite(correlation_s) || correlation_s <= 0.0)
    return fail(why, fmt::format("structure correlation_s must be > 0, got {}", correlation_s));
  return true;
}

bool SetupEnvironment::isValid(std::string* why) const {
  for (const double v : {beam_misalignment_rad, reflector_offset_mm, probe_lobing_mm})
    if (!std::isfinite(v) || v < 0.0) return fail(why, "set-up errors must be finite and >= 0");
  if (probe_lobes < 1)
    return fail(why, fmt::format("probe_lobes must be >= 1, got {}", probe_lobes));
  return true;
}

std::optional<double> expansionCoefficient(std::string_view material) {
  if (material == "steel") return 11.5e-6;
  if (material == "cast_iron") return 10.5e-6;
  if (material == "aluminium") return 23.1e-6;
  if (material == "granite") return 7.0e-6;
  if (material == "invar") return 1.2e-6;
  return std::nullopt;
}

bool ThermalEnvironment::isValid(std::string* why) const {
  if (!material_temperature_c.isValid() || !material_sensor.isValid())
    return fail(why, "the material temperature drift or its sensor is invalid");
  if (!std::isfinite(machine_cte_per_k) || !std::isfinite(assumed_cte_per_k) ||
      !std::isfinite(strut_cte_per_k) || !std::isfinite(strut_warmup_k) ||
      !warmup_drift_mm.allFinite() || !warmup_tilt_rad.allFinite())
    return fail(why, "thermal values must be finite");
  if (!std::isfinite(warmup_time_constant_h) || warmup_time_constant_h <= 0.0)
    return fail(why,
                fmt::format("warmup_time_constant_h must be > 0, got {}", warmup_time_constant_h));
  return true;
}

double Environment::warmup(double time_s) const {
  if (!thermal.enabled) return 0.0;
  return 1.0 - std::exp(-time_s / (thermal.warmup_time_constant_h * 3600.0));
}

Eigen::Vector3d Environment::pkmTilt(double time_s) const {
  return thermal.enabled ? Eigen::Vector3d(thermal.warmup_tilt_rad * warmup(time_s))
                         : Eigen::Vector3d::Zero();
}

double Environment::strutGrowth(double time_s) const {
  return thermal.enabled ? thermal.strut_cte_per_k * thermal.strut_warmup_k * warmup(time_s) : 0.0;
}

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
  return true;
}

bool Environment::isValid(std::string* why) const {
  if (!std::isfinite(duration_h) || duration_h <= 0.0)
    return fail(why, fmt::format("duration_h must be > 0, got {}", duration_h));
  if (!std::isfinite(elapsed_h) || elapsed_h < 0.0)
    return fail(why, fmt::format("elapsed_h must be >= 0, got {}", elapsed_h));
  return air.isValid(why) && airInRange(air, 1.0 + elapsed_h / duration_h, why) &&
         thermal.isValid(why) && setup.isValid(why) && structure.isValid(why) &&
         compliance.isValid(why) && geometry.isValid(why);
}

std::optional<Environment> environmentPreset(std::string_view name) {
  Environment e;
  if (name == "ideal") return e;
  if (name == "realistic") {
    e.name = "realistic";
    e.air = realisticAir();
    e.thermal = realisticThermal();
    e.setup = realisticSetup();
    e.structure = realisticStructure();
    e.compliance = realisticCompliance();
    e.geometry = realisticGeometry();
    return e;
  }
  return std::nullopt;
}

std::vector<std::string_view> environmentPresetNames() { return {"ideal", "realistic"}; }

}  // namespace pkm::simulation
