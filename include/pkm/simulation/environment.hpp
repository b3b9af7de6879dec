/// @file
/// @brief The environment of a simulated campaign (docs/simulation-errors.md): error sources a real
/// workshop adds to every measurement and that pkm's analyses do not model. Each is off in the
/// default ("ideal") environment, which reproduces the simulator's behaviour without them.
/// - Air: the air's temperature, pressure and humidity drift over the campaign (a linear drift
///   plus an AR(1) fluctuation); a laser interferometer counts fringes of the wavelength in the
///   TRUE air (modified Edlén, pkm/core/air_refractive_index.hpp) while its environmental
///   compensation unit converts them with the index of the air its own sensors read (with their
///   offsets and noise), so a displacement Δ reads Δ·n_true/n_sensed, plus the dead-path error
///   L_dp·(n_true(τ) − n_true(τ₀))/n_sensed (ISO 230-2:2014 Annex A; ISO/TR 230-9 §6).
/// - Thermal: the machine's structure and scales expand with the material temperature (positions
///   scale by 1 + α_machine·(T_m − 20 °C) about the work frame's origin) while the laser
///   normalises its reading to 20 °C with the CTE the operator entered and its material sensor's
///   reading; a warm-up drift of the tool point d∞·(1 − exp(−τ/τ_w)); the hexapod's struts grow by
///   α_strut·ΔT_strut(τ)·L with the same warm-up law (ISO 230-3; Mayr et al., CIRP Annals 61(2),
///   2012).
/// - Set-up: laser beam misalignment (cosine error), the reflector's unknown offset from the tool
///   point (Abbe: the machine's angular errors times it), a touch probe's pre-travel lobing.
/// - Structure: non-repeatable errors of the tool point with a spectrum (AR(1) plus white).
/// - Compliance: gravity self-weight deflection that changes with the pose (a hexapod's and an
///   Exechon's legs under the platform's weight, f = J⁻ᵀ·w, shortening by f/k; the sag of
///   extending axes) and passive-joint clearance taking up in the direction of each leg's force.
/// - Geometry (geometry_environment.hpp): the true machines' geometry beyond their kinematic
///   models, which no calibration of those models absorbs: ball-screw lead errors of the struts
///   and legs, U-joints whose axes do not intersect.
#pragma once

#include <Eigen/Core>
#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pkm/core/air_refractive_index.hpp"
#include "pkm/simulation/geometry_environment.hpp"

namespace pkm::simulation {

/// A quantity over the campaign: value(τ) = start + change·τ/T + x(τ), T the campaign's duration
/// and x an AR(1) (Ornstein–Uhlenbeck) fluctuation with standard deviation `fluctuation` and
/// correlation time `correlation_s`, sampled at the readings (x_{j+1} = φ·x_j +
/// √(1 − φ²)·fluctuation·ε, φ = exp(−Δτ/correlation_s), x at a measurement's start drawn from
/// N(0, fluctuation²)). Units: those of the quantity (°C, Pa, %).
struct Drift {
  double start = 0.0;            ///< value at the campaign's start
  double change = 0.0;           ///< change over the whole campaign (linear)
  double fluctuation = 0.0;      ///< standard deviation of the fluctuation, ≥ 0
  double correlation_s = 600.0;  ///< correlation time of the fluctuation, s, > 0
  /// The smooth part start + change·fraction (fraction = τ/T in [0, 1]).
  [[nodiscard]] double smooth(double fraction) const { return start + change * fraction; }
  /// True when every field is finite, fluctuation ≥ 0 and correlation_s > 0.
  [[nodiscard]] bool isValid() const;
};

/// One sensor of a compensation unit: reading = true value + offset + N(0, noise²) per reading
/// (units of the quantity).
struct SensorError {
  double offset = 0.0;  ///< fixed calibration error of the sensor
  double noise = 0.0;   ///< standard deviation per reading, ≥ 0
  /// True when both are finite and noise ≥ 0.
  [[nodiscard]] bool isValid() const;
};

/// The air along the laser beam and the laser's compensation of it.
struct AirEnvironment {
  bool enabled = false;  ///< false: the ideal laser (no refractive-index error)
  Drift temperature_c{20.0, 0.0, 0.0, 600.0};     ///< air temperature, °C
  Drift pressure_pa{101325.0, 0.0, 0.0, 600.0};   ///< absolute pressure, Pa
  Drift humidity_percent{50.0, 0.0, 0.0, 600.0};  ///< relative humidity, %
  SensorError temperature_sensor;  ///< the compensation unit's air-temperature sensor, °C
  SensorError pressure_sensor;     ///< its pressure sensor, Pa
  SensorError humidity_sensor;     ///< its humidity sensor, %
  /// Dead path: beam length from the laser head to the reflector at the datum, mm (≥ 0), over
  /// which the index change since zeroing is not compensated.
  double dead_path_mm = 0.0;
  double vacuum_wavelength_um = kHeNeVacuumWavelengthUm;  ///< laser vacuum wavelength, µm
  /// True when every part is valid (Environment::isValid checks the drift against Edlén's range).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// The linear expansion coefficient of a named material, 1/K: "steel" 11.5e-6, "cast_iron"
/// 10.5e-6, "aluminium" 23.1e-6, "granite" 7.0e-6, "invar" 1.2e-6 (handbook values at 20 °C;
/// docs/simulation-errors.md). std::nullopt for another name.
[[nodiscard]] std::optional<double> expansionCoefficient(std::string_view material);

/// The machine's temperature and its effects.
struct ThermalEnvironment {
  bool enabled = false;  ///< false: the machine at 20 °C, no warm-up
  /// Temperature of the machine structure and scales, °C (a slow drift; the reference is 20 °C).
  Drift material_temperature_c{20.0, 0.0, 0.0, 3600.0};
  SensorError material_sensor;         ///< the laser's material-temperature sensor, °C
  double machine_cte_per_k = 11.5e-6;  ///< true α of the structure and scales, 1/K
  /// α the operator entered in the laser software for its normalisation to 20 °C, 1/K.
  double assumed_cte_per_k = 11.5e-6;
  /// Warm-up: the tool point's displacement in the work frame after a long run, mm; reached as
  /// d∞·(1 − exp(−τ/τ_w)) from the campaign's start (the machine switched on at τ = 0).
  Eigen::Vector3d warmup_drift_mm = Eigen::Vector3d::Zero();
  double warmup_time_constant_h = 1.0;  ///< τ_w, h, > 0
  /// Hexapod struts: temperature rise after a long run, K (same time constant), and their α.
  /// The PKM's tilt relative to its extending axes after a long run (a hybrid machine's head
  /// turning as its structure warms unevenly), rotation vector in the work frame, rad; reached
  /// with the warm-up law (HybridVirtualMachine::setPkmTilt).
  Eigen::Vector3d warmup_tilt_rad = Eigen::Vector3d::Zero();
  double strut_warmup_k = 0.0;
  double strut_cte_per_k = 11.5e-6;
  /// True when every value is finite and the time constant > 0.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// How the instruments are set up (the operator's part).
struct SetupEnvironment {
  bool enabled = false;  ///< false: every instrument set up perfectly
  /// Angle between the laser beam and the line of motion, rad (≥ 0): the laser reads the
  /// displacement along its own beam, Δ·cos θ for a motion along the line (cosine error), plus
  /// sin θ times the motion across the line. The tilt's direction around the line is drawn per
  /// measurement.
  double beam_misalignment_rad = 0.0;
  /// Standard deviation of each component of the reflector's unknown offset from the tool point,
  /// mm (≥ 0), drawn per measurement: the machine's angular errors times it show in the reading
  /// (Abbe), on top of the set-up's own reflector_offset.
  double reflector_offset_mm = 0.0;
  /// A touch probe's pre-travel variation with direction (lobing): amplitude, mm (≥ 0); the
  /// probe triggers a·cos(n·ψ) later along the approach, ψ the approach direction in the probe's
  /// frame, n = probe_lobes (3 for a kinematic probe's three seats).
  double probe_lobing_mm = 0.0;
  int probe_lobes = 3;  ///< ≥ 1
  /// True when every value is finite and ≥ 0 and probe_lobes ≥ 1.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// The structure's non-repeatable errors: the tool point wanders by an AR(1) (Ornstein–Uhlenbeck)
/// process, correlated over `correlation_s` (a red, 1/f²-like spectrum below 1/(2π·τ_c)), plus
/// white noise, each component independent, work frame.
struct StructureEnvironment {
  bool enabled = false;              ///< false: no non-repeatable errors beyond the machine's own
  double correlated_sigma_mm = 0.0;  ///< σ of the AR(1) part per component, mm (≥ 0)
  double correlation_s = 600.0;      ///< its correlation time, s (> 0)
  double white_sigma_mm = 0.0;       ///< σ of the white part per component and reading, mm (≥ 0)
  /// True when every value is finite, the sigmas ≥ 0 and correlation_s > 0.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// How a linear axis's structure sags under gravity (compliance.hpp evaluates it). Gravity is −z of
/// the work frame; only the part of it across the axis bends the structure.
/// - kCantilever: an overhang (a ram, a table running off its saddle) of length
///   L(q) = zero_mm + sense·q that sags at its tip by δ(L) = sag_mm·(L/length_mm)³ with the slope
///   θ(L) = 1.5·δ(L)/L (a cantilever with an end load W: δ = W·L³/(3EI), θ = W·L²/(2EI)).
/// - kSpan: a carriage of weight W at a = zero_mm + sense·q on a span of length_mm between two
///   supports (a bed or track): the span sags under it by δ(a) = sag_mm·16·a²·b²/L⁴ (b = L − a;
///   the simply supported beam's W·a²·b²/(3EIL), sag_mm its value at mid-span W·L³/(48EI)) with
///   the slope θ(a) = sag_mm·16·a·b·(b − a)/L⁴ under the load; 0 outside the span.
struct AxisSag {
  enum class Kind { kNone, kCantilever, kSpan };
  Kind kind = Kind::kNone;  ///< kNone: the axis does not sag
  double sag_mm = 0.0;  ///< tip sag at length_mm (cantilever) or mid-span sag (span), mm (≥ 0)
  double length_mm = 1000.0;  ///< the reference overhang or the span, mm (> 0)
  double zero_mm = 0.0;       ///< overhang or load position at command 0, mm
  double sense = 1.0;  ///< +1: the overhang or position grows with the command; −1: shrinks
  /// True when the values are finite, sag_mm ≥ 0, length_mm > 0 and sense is ±1.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// A hexapod's gravity load and the compliance of its struts.
struct HexapodCompliance {
  double platform_mass_kg = 0.0;  ///< platform, spindle and payload, kg (≥ 0)
  /// Their centre of mass in the platform frame (the frame of the platform joints), mm.
  Eigen::Vector3d platform_com_mm = Eigen::Vector3d::Zero();
  double strut_mass_kg = 0.0;  ///< one strut's mass, kg (≥ 0)
  /// The share η of a strut's weight carried by its platform joint (its centre of mass at η of
  /// the joint distance from the base joint), in [0, 1].
  double strut_com_fraction = 0.5;
  double strut_stiffness_n_per_um = 50.0;  ///< a strut's axial stiffness k, N/µm (> 0)
  /// The radial clearance of a strut's two passive joints together, mm (≥ 0): it takes up in the
  /// direction of the strut's force, so the joint distance is c shorter under compression and c
  /// longer under tension.
  double joint_clearance_mm = 0.0;
  /// True when every value is finite and in range.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// An Exechon's gravity load (the platform, wrist and spindle head) and the compliance of its
/// three actuated legs.
struct ExechonCompliance {
  double head_mass_kg = 0.0;  ///< platform, wrist and spindle head, kg (≥ 0)
  /// Their centre of mass in the tool frame (platform_R_tool axes, origin at the tool point), mm.
  Eigen::Vector3d head_com_mm = Eigen::Vector3d::Zero();
  double leg_stiffness_n_per_um = 50.0;  ///< a leg's axial stiffness, N/µm (> 0)
  double joint_clearance_mm = 0.0;       ///< a leg's joint clearance, mm (≥ 0), as the hexapod's
  /// True when every value is finite and in range.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// Pose-dependent compliance (gravity self-weight deflection) and passive-joint clearance: the
/// machine sags by a different amount at every pose, which no constant parameter absorbs
/// (docs/simulation-errors.md, "Structure: compliance (gravity sag) and joint clearance").
struct ComplianceEnvironment {
  bool enabled = false;              ///< false: a rigid machine without joint clearance
  HexapodCompliance hexapod;         ///< the hexapod's struts
  ExechonCompliance exechon;         ///< an Exechon tripod's legs (a hybrid machine with a tripod)
  std::array<AxisSag, 3> cartesian;  ///< the Cartesian machine's X, Y and Z axes
  AxisSag x2;                        ///< the hybrid machine's X2 (carries the tool)
  AxisSag y2;                        ///< the hybrid machine's Y2 (carries the work table)
  /// True when every part is valid.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// The environment of a campaign. Default: ideal (every source off).
struct Environment {
  std::string name = "ideal";  ///< the preset it came from, or "custom"
  double duration_h = 8.0;     ///< campaign duration T over which the drifts run, h, > 0
  /// Hours since the machine was switched on (and the drifts began) when this pass of the
  /// measurements starts, ≥ 0: 0 for the first pass; a campaign's re-measurement after
  /// compensation runs one duration later (the drifts go on linearly, the warm-up nearly done).
  double elapsed_h = 0.0;
  AirEnvironment air;                ///< the air and the laser's compensation
  ThermalEnvironment thermal;        ///< the machine's temperature, warm-up, struts
  SetupEnvironment setup;            ///< the instruments' set-up errors
  StructureEnvironment structure;    ///< the structure's non-repeatable errors
  ComplianceEnvironment compliance;  ///< gravity deflection and joint clearance
  /// The true machines' geometry beyond their kinematic models (applyGeometryEnvironment puts
  /// it into a campaign's machine).
  GeometryEnvironment geometry;
  /// The truth runs of `pkm validate coverage` (workflow/coverage.hpp): every source draws as
  /// usual, so the machine's thermal and structural state is the measured run's, but the
  /// instrument is perfect — its air and material sensors read the truth, the laser's
  /// compensation uses the true refractive index (no dead-path error) and the machine's true
  /// expansion coefficient, and the set-up errors (beam misalignment, reflector offsets) are
  /// zero. Not a setting of environment files.
  bool perfect_instrument = false;
  /// True when any source is on.
  [[nodiscard]] bool active() const {
    return air.enabled || thermal.enabled || setup.enabled || structure.enabled ||
           compliance.enabled || geometry.enabled;
  }
  /// The warm-up fraction 1 − exp(−τ/τ_w) at campaign time `time_s` (0 when thermal is off).
  [[nodiscard]] double warmup(double time_s) const;
  /// The PKM's thermal tilt warmup_tilt_rad·warmup(τ) at campaign time `time_s` (zero when
  /// thermal is off), rad.
  [[nodiscard]] Eigen::Vector3d pkmTilt(double time_s) const;
  /// The struts' relative thermal growth α_strut·ΔT_strut(τ) at campaign time `time_s`.
  [[nodiscard]] double strutGrowth(double time_s) const;
  /// True when every part is valid and the air stays inside Edlén's range over the pass;
  /// otherwise false with the reason in *why.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// A named environment (docs/simulation-errors.md): "ideal" (every source off) or "realistic"
/// (every finished source on at magnitudes from the literature). std::nullopt for another name.
[[nodiscard]] std::optional<Environment> environmentPreset(std::string_view name);
/// The names environmentPreset knows.
[[nodiscard]] std::vector<std::string_view> environmentPresetNames();

}  // namespace pkm::simulation
