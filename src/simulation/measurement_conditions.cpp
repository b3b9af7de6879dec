#include "pkm/simulation/measurement_conditions.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "pkm/core/error.hpp"

namespace pkm::simulation {

namespace {

constexpr double kSecondsPerHour = 3600.0;
constexpr double kReferenceC = 20.0;  // ISO 1: the reference temperature of lengths

/// One AR(1) step of a fluctuation of standard deviation `sigma` over `dt` seconds.
double ar1(double x, const Drift& d, double dt, RandomStream& rng) {
  if (d.fluctuation == 0.0) return 0.0;
  const double phi = std::exp(-dt / d.correlation_s);
  return phi * x + rng.normal(std::sqrt(1.0 - phi * phi) * d.fluctuation);
}

double sense(double truth, const SensorError& s, RandomStream& rng) {
  return truth + s.offset + rng.normal(s.noise);
}

}  // namespace

MeasurementConditions::MeasurementConditions(const Environment& environment,
                                             double start_s,
                                             double window_s,
                                             int readings,
                                             std::uint64_t seed)
    : env_(environment), start_s_(start_s), time_s_(start_s), rng_(seed) {
  std::string why;
  PKM_CHECK(environment.isValid(&why), "environment '{}': {}", environment.name, why);
  PKM_CHECK(
      std::isfinite(start_s) && start_s >= 0.0, "measurement start {} s must be >= 0", start_s);
  PKM_CHECK(
      std::isfinite(window_s) && window_s > 0.0, "measurement window {} s must be > 0", window_s);
  PKM_CHECK(readings >= 1, "a measurement needs at least one reading, got {}", readings);
  step_s_ = window_s / readings;
  const SetupEnvironment& set = environment.setup;
  if (set.enabled) {  // drawn once per measurement, before anything else
    tilt_azimuth_ = rng_.uniform(0.0, 2.0 * std::numbers::pi);
    for (Eigen::Index k = 0; k < 3; ++k)
      reflector_offset_[k] = rng_.normal(set.reflector_offset_mm);
    if (environment.perfect_instrument) reflector_offset_.setZero();  // drawn, not applied
  }
}

Eigen::Vector3d MeasurementConditions::laserBeam(const Eigen::Vector3d& beam) const {
  const SetupEnvironment& set = env_.setup;
  if (!set.enabled || set.beam_misalignment_rad == 0.0 || env_.perfect_instrument) return beam;
  // Two unit vectors across the beam, then the tilt towards the drawn azimuth.
  const Eigen::Vector3d helper =
      std::abs(beam.z()) < 0.9 ? Eigen::Vector3d::UnitZ() : Eigen::Vector3d::UnitX();
  const Eigen::Vector3d e1 = beam.cross(helper).normalized();
  const Eigen::Vector3d e2 = beam.cross(e1);
  const Eigen::Vector3d across = std::cos(tilt_azimuth_) * e1 + std::sin(tilt_azimuth_) * e2;
  const double theta = set.beam_misalignment_rad;
  return std::cos(theta) * beam + std::sin(theta) * across;
}

double MeasurementConditions::fraction() const {
  return time_s_ / (env_.duration_h * kSecondsPerHour);
}

AirConditions MeasurementConditions::trueAir() const {
  const AirEnvironment& a = env_.air;
  const double f = fraction();
  const double rh = a.humidity_percent.smooth(f) + x_h_;
  return {a.temperature_c.smooth(f) + x_t_,
          a.pressure_pa.smooth(f) + x_p_,
          std::fmin(100.0, std::fmax(0.0, rh))};
}

double MeasurementConditions::trueIndex() const {
  return refractiveIndexEdlen(trueAir(), env_.air.vacuum_wavelength_um);
}

double MeasurementConditions::materialTemperature() const {
  return env_.thermal.material_temperature_c.smooth(fraction()) + x_m_;
}

void MeasurementConditions::zero() {
  time_s_ = start_s_;
  const AirEnvironment& a = env_.air;
  if (a.enabled) {
    x_t_ = rng_.normal(a.temperature_c.fluctuation);
    x_p_ = rng_.normal(a.pressure_pa.fluctuation);
    x_h_ = rng_.normal(a.humidity_percent.fluctuation);
    n_datum_ = trueIndex();
    sensed_ = trueAir();
  }
  if (env_.thermal.enabled) {
    x_m_ = rng_.normal(env_.thermal.material_temperature_c.fluctuation);
    sensed_material_ = materialTemperature();
  }
  advanceStructure(true);
}

void MeasurementConditions::advanceStructure(bool first) {
  const StructureEnvironment& st = env_.structure;
  if (!st.enabled) return;
  const double phi = first ? 0.0 : std::exp(-step_s_ / st.correlation_s);
  const double innovation = std::sqrt(1.0 - phi * phi) * st.correlated_sigma_mm;
  for (Eigen::Index k = 0; k < 3; ++k) {
    wander_[k] = phi * wander_[k] + rng_.normal(innovation);
    white_[k] = rng_.normal(st.white_sigma_mm);
  }
}

void MeasurementConditions::next() {
  time_s_ += step_s_;
  advanceAir();
  const ThermalEnvironment& t = env_.thermal;
  if (t.enabled) {
    x_m_ = ar1(x_m_, t.material_temperature_c, step_s_, rng_);
    sensed_material_ = sense(materialTemperature(), t.material_sensor, rng_);
    if (env_.perfect_instrument) sensed_material_ = materialTemperature();
  }
  advanceStructure(false);
}

void MeasurementConditions::advanceAir() {
  const AirEnvironment& a = env_.air;
  if (!a.enabled) return;
  x_t_ = ar1(x_t_, a.temperature_c, step_s_, rng_);
  x_p_ = ar1(x_p_, a.pressure_pa, step_s_, rng_);
  x_h_ = ar1(x_h_, a.humidity_percent, step_s_, rng_);
  const AirConditions t = trueAir();
  sensed_ = {sense(t.temperature_c, a.temperature_sensor, rng_),
             sense(t.pressure_pa, a.pressure_sensor, rng_),
             sense(t.relative_humidity, a.humidity_sensor, rng_)};
  // A sensor cannot read outside its range: a humidity sensor reads 0..100 %.
  sensed_.relative_humidity = std::fmin(100.0, std::fmax(0.0, sensed_.relative_humidity));
  if (env_.perfect_instrument) sensed_ = t;  // drawn above, so later draws stay aligned
}

double MeasurementConditions::laserDisplacement(double displacement_mm) const {
  const AirEnvironment& a = env_.air;
  double reading = displacement_mm;
  const ThermalEnvironment& t = env_.thermal;
  if (env_.perfect_instrument) {
    // Compensated with the true index (no dead-path error) and normalised to 20 °C with the
    // machine's true expansion at its true temperature.
    if (t.enabled) reading /= 1.0 + t.machine_cte_per_k * (materialTemperature() - kReferenceC);
    return reading;
  }
  if (a.enabled) {
    const double n_t = trueIndex();
    const double n_s = refractiveIndexEdlen(sensed_, a.vacuum_wavelength_um);
    reading = (n_t * (a.dead_path_mm + displacement_mm) - n_datum_ * a.dead_path_mm) / n_s;
  }
  if (t.enabled) reading /= 1.0 + t.assumed_cte_per_k * (sensed_material_ - kReferenceC);
  return reading;
}

geometry::RigidTransform MeasurementConditions::actualPose(
    const geometry::RigidTransform& pose) const {
  const ThermalEnvironment& t = env_.thermal;
  geometry::RigidTransform out = pose;
  if (t.enabled) {
    const double scale = 1.0 + t.machine_cte_per_k * (materialTemperature() - kReferenceC);
    out.translation() = scale * pose.translation() + env_.warmup(time_s_) * t.warmup_drift_mm;
  }
  if (env_.structure.enabled) out.translation() += wander_ + white_;
  return out;
}

}  // namespace pkm::simulation
