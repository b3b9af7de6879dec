/// @file
/// @brief The instruments and the environment of a measurement as data: what an uncertainty
/// budget needs to know about them (ISO/TR 230-9:2005 §6, ISO 230-2:2014 Annex A). The defaults
/// are typical values of current laser calibration systems with environmental compensation,
/// strain-gauge touch probes, dial gauges and laser trackers as manufacturers' datasheets state
/// them (docs/analysis.md, "Instrument and environment defaults", lists the sources); every
/// ± figure of a datasheet is taken as the half-width of a rectangular distribution unless a
/// field says otherwise. Read and written as JSON by io/uncertainty_sources.hpp.
#pragma once

#include <string>

#include "pkm/metrology/air_refractive_index.hpp"

namespace pkm::metrology {

/// A laser interferometer with its environmental compensation unit (air and material sensors).
struct LaserInterferometer {
  std::string name = "typical HeNe laser calibration system with environmental compensation";
  double vacuum_wavelength_um = kHeNeVacuumWavelengthUm;  ///< λ_vac, µm
  double wavelength_accuracy_ppm = 0.05;  ///< vacuum wavelength (frequency) accuracy, ± ppm
  double resolution_mm = 1e-6;            ///< display resolution, mm (quantisation ±res/2)
  /// Reading noise (short-term repeatability of one reading, standard deviation), mm: it raises
  /// the ISO 230-2 reversal and repeatability statistics of a machine that repeats better.
  double reading_noise_mm = 1e-5;
  double air_temperature_accuracy_k = 0.2;       ///< air temperature sensor, ± K
  double air_pressure_accuracy_pa = 100.0;       ///< air pressure sensor, ± Pa (±1 hPa)
  double air_humidity_accuracy_percent = 6.0;    ///< humidity sensor, ± %RH
  double material_temperature_accuracy_k = 0.1;  ///< material temperature sensor, ± K
  /// Straightness optics (short range): accuracy ±(a + b·|reading| + c·L²) with the reading in
  /// µm and the measured length L in m; here a in mm, b relative, c in mm/m².
  double straightness_accuracy_mm = 0.5e-3;
  double straightness_relative = 0.005;
  double straightness_length_mm_per_m2 = 0.15e-3;
  /// Angular optics accuracy of a slope measured over the beam, ± (a + b·L) rad with L in m.
  double angular_accuracy_rad = 0.2e-6;
  double angular_accuracy_rad_per_m = 0.05e-6;
};

/// A touch probe on the machine (on-machine measurement, Lee et al. 2019).
struct TouchProbe {
  std::string name = "typical strain-gauge touch probe";
  double repeatability_2sigma_mm = 0.25e-3;  ///< unidirectional repeatability, 2σ, mm
  double form_2d_mm = 0.25e-3;               ///< 2D (XY) form deviation (lobing), ± mm
  /// Expanded uncertainty (k = 2) of the effective stylus radius from its ring-gauge calibration.
  double stylus_radius_uncertainty_mm = 0.5e-3;
  /// Expanded uncertainty (k = 2) of the master ring's certified diameter, mm.
  double ring_diameter_uncertainty_mm = 1.0e-3;
  /// The master ring's certified roundness (peak to valley), mm: it adds to or hides a measured
  /// roundness by up to itself. Typical of a certified 40 mm setting ring; Lee et al. (2019) list
  /// 2 µm for their ring (Table 4).
  double ring_form_mm = 0.5e-3;
};

/// A dial gauge or digital indicator (constrained-motion calibration, Lee et al., "Development of a
/// Parallel-Typed CNC Machine").
struct DialGauge {
  std::string name = "typical digital indicator, 1 um resolution";
  double accuracy_mm = 3e-3;    ///< maximum permissible error over the used range, ± mm
  double resolution_mm = 1e-3;  ///< display resolution, mm
};

/// The machine's own actuator readings, which a kinematic calibration takes as the joint values
/// of each observation (hexapod strut lengths, Exechon leg lengths): the encoder's quantisation,
/// the actuator's repeatability and its lost motion at a reversal. Lee et al., "Development of a
/// Parallel-Typed CNC Machine", report 2 µm repeatability and a hysteresis at direction reversal;
/// the defaults are of that order. Each reading's errors are independent (the direction a joint
/// last moved in is generally not recorded).
struct ActuatorReadings {
  std::string name = "actuator readings (the machine's encoders)";
  double resolution_mm = 1e-3;     ///< encoder resolution (one count), mm: ± half of it
  double repeatability_mm = 2e-3;  ///< positioning repeatability, one standard deviation, mm
  double backlash_mm = 5e-3;       ///< lost motion at a reversal, mm: ± half of it, U-shaped
  /// The ball screws' progressive lead error (ISO 3408-3 e_p over the used travel): bound of each
  /// screw's travel deviation per travel from its reference, ± mm per m (e.g. 0.1 for rolled
  /// screws of grade C7). One unknown slope per screw, rectangular: the deviation grows with the
  /// reading's distance from where the encoder is referenced (a hexapod's home strut lengths, an
  /// Exechon leg's mid-stroke). 0: not stated.
  double lead_error_mm_per_m = 0.0;
  /// Amplitude of each screw's long-wave travel variation about that line, ± mm (ISO 3408-3's
  /// V_300p is about twice it): a sinusoid of the reading of wavelength lead_wave_length_mm and
  /// unknown phase, so its sine and cosine parts are two errors per screw (U-shaped, ± the
  /// amplitude each), shared by the screw's readings. 0: not stated.
  double lead_wave_mm = 0.0;
  double lead_wave_length_mm = 300.0;  ///< wavelength of that variation, mm (> 0)
  /// Amplitude of the travel variation within one screw revolution, ± mm (ISO 3408-3's V_2πp is
  /// about twice it): independent per reading (U-shaped). 0: not stated.
  double lead_periodic_mm = 0.0;
};

/// The weight of a hexapod's platform (with spindle and payload) and of its struts on the struts:
/// they shorten or lengthen by a different amount at every pose (axial stiffness, joint clearance
/// taken up), which the 42-parameter model does not represent. Stated (platform mass > 0), the
/// deflection the statics predict at every observation enters the hexapod calibration's budgets
/// as an uncorrected systematic effect (GUM JCGM 100:2008 F.2.4.5). Machines in mm only.
/// Default: not stated.
struct HexapodPlatform {
  std::string name = "the hexapod platform's weight on its struts";
  double mass_kg = 0.0;  ///< platform, spindle and payload, kg (0: not stated)
  /// Their centre of mass in the platform frame (the frame of the platform joints), mm.
  double com_x_mm = 0.0, com_y_mm = 0.0, com_z_mm = 0.0;
  double strut_mass_kg = 0.0;       ///< one strut's mass, kg
  double strut_com_fraction = 0.5;  ///< share of a strut's weight on its platform joint, 0..1
  double strut_stiffness_n_per_um = 50.0;  ///< a strut's axial stiffness, N/µm (> 0)
  double joint_clearance_mm = 0.0;         ///< a strut's two joints' clearance together, mm
};

/// The weight of an Exechon's head (platform, wrist and spindle) on its three legs: the legs
/// shorten by a different amount at every pose (axial stiffness, joint clearance taken up), which
/// the tripod's kinematic model does not represent, so its calibration absorbs the deflection
/// into the parameters. Stated (mass > 0), the deflection the statics predict at every
/// observation enters the Exechon calibration's budgets as an uncorrected systematic effect
/// (GUM JCGM 100:2008 F.2.4.5). Machines in mm only. Default: not stated.
struct ExechonHead {
  std::string name = "the Exechon head's weight on its legs";
  double mass_kg = 0.0;  ///< platform, wrist and spindle, kg (0: not stated)
  /// Their centre of mass in the tool frame (origin at the tool point), mm.
  double com_x_mm = 0.0, com_y_mm = 0.0, com_z_mm = 0.0;
  double leg_stiffness_n_per_um = 50.0;  ///< a leg's axial stiffness, N/µm (> 0)
  double joint_clearance_mm = 0.0;       ///< a leg's joint clearance, both ends together, mm
};

/// A laser tracker (hexapod and Exechon calibration).
struct LaserTrackerSpec {
  std::string name = "typical laser tracker (interferometer mode)";
  double accuracy_mm = 15e-3;       ///< maximum permissible error a of ±(a + b·L), mm
  double accuracy_mm_per_m = 6e-3;  ///< b, mm per m of range
  /// The tracker-to-target range L used in a + b·L when the readings are already in the
  /// machine frame (the tracker's position unknown), mm.
  double range_mm = 3000.0;
  /// Orientation accuracy of a 6-DOF probe (T-Probe/T-Mac class: ±0.01°), ± rad per axis.
  double orientation_accuracy_rad = 1.75e-4;
};

/// A telescoping ballbar (ISO 230-4 circular tests): a length sensor between two precision balls,
/// one at the table's pivot, one at the tool. Typical figures of current ballbar datasheets
/// (e.g. a Renishaw QC20-W: sensor accuracy ±0.5 µm at 20 °C, resolution 0.1 µm).
struct Ballbar {
  std::string name = "typical telescoping ballbar";
  double sensor_accuracy_mm = 0.5e-3;  ///< the length sensor's accuracy over its range, ± mm
  double resolution_mm = 0.1e-3;       ///< the sensor's resolution, mm (quantisation ±res/2)
  /// Expanded uncertainty (k = 2) of the bar's absolute length from its calibrator, mm: acts on
  /// the radius and on the radial deviations F from a nominal radius, not on G or H.
  double length_uncertainty_mm = 1.0e-3;
};

/// Where a condition of a budget came from (docs/analysis.md, "Measurement conditions"):
/// pkm's typical value, a value the user stated (`--uncertainty FILE`), or the measurement's own
/// records (the readings' environment columns or its set-up metadata).
enum class ConditionOrigin { kDefault, kStated, kRecorded };

/// "default", "stated" or "recorded".
[[nodiscard]] const char* toString(ConditionOrigin origin);

/// The origin of each condition of MeasurementEnvironment that a laser budget depends on, with a
/// note on how a recorded value was formed (e.g. "mean of 66 readings, 20.41..20.62 °C").
struct ConditionOrigins {
  ConditionOrigin air_temperature = ConditionOrigin::kDefault;
  ConditionOrigin air_pressure = ConditionOrigin::kDefault;
  ConditionOrigin air_humidity = ConditionOrigin::kDefault;
  ConditionOrigin material_temperature = ConditionOrigin::kDefault;
  ConditionOrigin air_temperature_variation = ConditionOrigin::kDefault;
  ConditionOrigin dead_path = ConditionOrigin::kDefault;
  ConditionOrigin misalignment = ConditionOrigin::kDefault;
  ConditionOrigin abbe = ConditionOrigin::kDefault;  ///< Abbe offset and angular error range
  std::string air_temperature_note, air_pressure_note, air_humidity_note, material_temperature_note,
      air_temperature_variation_note, dead_path_note, misalignment_note, abbe_note;
};

/// The environment of a test and the artefact/machine material.
struct MeasurementEnvironment {
  AirConditions air;                     ///< mean air state in the beam path during the test
  double material_temperature_c = 20.0;  ///< the machine scale's (or workpiece's) temperature, °C
  double expansion_coefficient_per_k = 11.5e-6;          ///< α of the scale material (steel), 1/K
  double expansion_coefficient_accuracy_per_k = 1.0e-6;  ///< ± uncertainty of α, 1/K
  /// Air temperature change during the test, ± K: acts on the dead path (the beam between the
  /// interferometer and the zero position, not compensated after the laser is zeroed).
  double air_temperature_variation_k = 0.5;
  double dead_path_mm = 0.0;        ///< dead path length, mm
  double misalignment_rad = 50e-6;  ///< beam-to-axis misalignment bound θ, rad (cosine error)
  /// Abbe offset between the measuring line and the functional point, mm, and the range of the
  /// axis's angular error (pitch or yaw) over the travel, rad: Abbe error ± offset × range / 2.
  double abbe_offset_mm = 0.0;
  double angular_error_range_rad = 0.0;
  /// Set-up repeatability: standard uncertainty of re-setting the optics and the axis, mm
  /// (ISO/TR 230-9 u_SETUP).
  double setup_repeatability_mm = 0.0;
  /// Environmental variation error E_VE of a drift test (ISO 230-2:2014 Annex A), mm: the range
  /// of the reading of a stationary axis over the test duration.
  double environmental_variation_mm = 0.0;
  /// Where the air state, material temperature, air temperature variation, dead path and
  /// misalignment above came from (all defaults unless a reader or the records say otherwise).
  ConditionOrigins origin;
};

/// Everything an uncertainty budget of `pkm analyze` reads: instruments and environment.
struct UncertaintySources {
  LaserInterferometer laser;
  TouchProbe probe;
  DialGauge dial_gauge;
  LaserTrackerSpec tracker;
  ActuatorReadings actuators;
  HexapodPlatform hexapod_platform;
  ExechonHead exechon_head;
  Ballbar ballbar;
  MeasurementEnvironment environment;
  double coverage_factor = 2.0;  ///< k of every expanded uncertainty (ISO/TR 230-9: 2)

  /// True when every number is finite, every accuracy >= 0, the air state valid (AirConditions)
  /// and k > 0; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

}  // namespace pkm::metrology
