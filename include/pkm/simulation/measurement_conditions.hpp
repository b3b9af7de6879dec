/// @file
/// @brief The environment's state during one measurement of a campaign (environment.hpp): the
/// campaign clock at each reading, the true air and what the compensation unit's sensors read,
/// and the laser displacement reading that results.
#pragma once

#include <cstdint>

#include "pkm/core/air_refractive_index.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/simulation/environment.hpp"
#include "pkm/simulation/random.hpp"

namespace pkm::simulation {

/// The conditions of one measurement. The drifts' fraction τ/T is not clamped: a later pass
/// (Environment::elapsed_h) continues them. The measurement occupies the campaign time [start_s,
/// start_s + window_s): the instrument is zeroed at start_s and its `readings` readings follow
/// at equal steps window_s/readings (the last at the window's end). The fluctuations and the
/// sensor noise draw from the measurement's own stream, nothing when they are zero.
class MeasurementConditions {
 public:
  /// Keeps a reference to `environment` (must outlive this). Throws pkm::InvalidArgument for an
  /// invalid environment, a negative start, a window ≤ 0 or readings < 1.
  MeasurementConditions(const Environment& environment,
                        double start_s,
                        double window_s,
                        int readings,
                        std::uint64_t seed);
  /// A temporary environment would dangle: refused at compile time.
  MeasurementConditions(Environment&&, double, double, int, std::uint64_t) = delete;

  /// The instrument is zeroed: the clock at start_s, the fluctuations drawn from their
  /// stationary distribution, n_true(τ₀) kept for the dead path.
  void zero();
  /// The next reading: the clock advances one step, the fluctuations one AR(1) step, the sensors
  /// draw their noise.
  void next();

  /// Campaign time of the current reading, s.
  [[nodiscard]] double timeS() const { return time_s_; }
  /// The true air now (°C, Pa, %).
  [[nodiscard]] AirConditions trueAir() const;
  /// What the compensation unit's sensors read now.
  [[nodiscard]] AirConditions sensedAir() const { return sensed_; }
  /// The refractive index of the true air now and at the zeroing.
  [[nodiscard]] double trueIndex() const;
  [[nodiscard]] double datumIndex() const { return n_datum_; }

  /// The laser's reading of a true displacement `displacement_mm` along the beam since the datum
  /// (mm): [n_t·(L_dp + Δ) − n_t(τ₀)·L_dp]/n_s = Δ + Δ·(n_t − n_s)/n_s + L_dp·(n_t − n_t(τ₀))/n_s,
  /// n_t the true index, n_s the index of the sensed air (ISO 230-2:2014 Annex A); with the thermal
  /// source on, then normalised to 20 °C: divided by 1 + α_assumed·(T_m,sensed − 20). Δ itself
  /// when both sources are off.
  [[nodiscard]] double laserDisplacement(double displacement_mm) const;

  /// The beam the laser reads along for the nominal beam direction `beam` (unit): tilted by the
  /// set-up's misalignment θ towards the direction drawn for this measurement; `beam` itself
  /// without the set-up source.
  [[nodiscard]] Eigen::Vector3d laserBeam(const Eigen::Vector3d& beam) const;
  /// The reflector's offset from the tool point drawn for this measurement (tool frame, mm);
  /// zero without the set-up source.
  [[nodiscard]] const Eigen::Vector3d& reflectorOffset() const { return reflector_offset_; }

  /// The true material (machine) temperature now and what the laser's material sensor reads, °C.
  [[nodiscard]] double materialTemperature() const;
  [[nodiscard]] double sensedMaterialTemperature() const { return sensed_material_; }
  /// The machine's actual pose now for the pose `pose` it would have at 20 °C and cold (work
  /// frame, mm): translation p → p·(1 + α_machine·(T_m − 20)) + d∞·(1 − exp(−τ/τ_w)) (thermal)
  /// + the structure's non-repeatable error now (AR(1) + white, drawn at zero() and next()).
  /// `pose` itself when both sources are off.
  [[nodiscard]] geometry::RigidTransform actualPose(const geometry::RigidTransform& pose) const;

 private:
  [[nodiscard]] double fraction() const;
  void advanceAir();
  void advanceStructure(bool first);

  const Environment& env_;
  double start_s_ = 0.0;
  double step_s_ = 0.0;
  double time_s_ = 0.0;
  RandomStream rng_;
  double x_t_ = 0.0, x_p_ = 0.0, x_h_ = 0.0;  // fluctuations of t, p and RH
  double x_m_ = 0.0;                          // fluctuation of the material temperature
  double sensed_material_ = 20.0;
  double tilt_azimuth_ = 0.0;  // direction of the beam's tilt around the line, rad
  Eigen::Vector3d reflector_offset_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d wander_ = Eigen::Vector3d::Zero();  // AR(1) part of the structure's error
  Eigen::Vector3d white_ = Eigen::Vector3d::Zero();   // white part at the current reading
  AirConditions sensed_;
  double n_datum_ = 1.0;
};

}  // namespace pkm::simulation
