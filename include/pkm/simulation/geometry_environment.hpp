/// @file
/// @brief The "geometry" source of a simulated campaign's environment (docs/simulation-errors.md,
/// "Geometry the kinematic models cannot represent"): the magnitudes of the true machines'
/// geometry beyond their calibration models, from which each machine's own errors are drawn
/// (unmodelled_geometry.hpp): ball-screw lead errors of the hexapod's struts and of the Exechon's
/// legs (ISO 3408-3), and universal joints whose two axes do not intersect.
#pragma once

#include <string>

namespace pkm::simulation {

/// Magnitudes of the unmodelled geometry. Every strut or leg draws its own errors from them
/// (drawHexapodGeometry, drawLegLeadErrors): a progressive lead error uniform in
/// ±lead_progressive, a long-wave travel variation of amplitude lead_wave_mm and a variation per
/// screw revolution of amplitude lead_periodic_mm, each with a uniform random phase, and a U-joint
/// axis offset uniform in ±joint_axis_offset_mm. Lengths in mm.
struct GeometryEnvironment {
  bool enabled = false;  ///< false: the true machines' geometry is what their models describe
  /// Bound of each screw's progressive (linear) lead error, relative (mm per mm of travel; e.g.
  /// 1.0e-4 = 100 µm/m), ≥ 0: ISO 3408-3's representative travel deviation e_p over the travel.
  double lead_progressive = 0.0;
  /// Amplitude of each screw's long-wave travel variation about the representative travel, mm
  /// (≥ 0): ISO 3408-3's variation V_300 is about twice it.
  double lead_wave_mm = 0.0;
  double lead_wave_length_mm = 300.0;  ///< wavelength of that variation, mm (> 0)
  /// Amplitude of the travel variation within one screw revolution, mm (≥ 0): ISO 3408-3's V_2π
  /// (peak to valley) is twice it.
  double lead_periodic_mm = 0.0;
  double screw_lead_mm = 10.0;  ///< the screws' lead (travel per revolution), mm (> 0)
  /// Bound of the offset between the two axes of each hexapod platform U-joint, mm (≥ 0): the
  /// strut's line passes through a point that moves with the strut's direction (UJointOffset).
  double joint_axis_offset_mm = 0.0;
  /// True when every value is finite, the amplitudes and bounds ≥ 0 and the lengths > 0;
  /// otherwise false with the reason in *why.
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// The "realistic" geometry (docs/simulation-errors.md lists the sources): rolled ball screws of
/// accuracy grade C7 (±50 µm per 300 mm) with 10 mm lead, and 20 µm U-joint axis offsets.
[[nodiscard]] GeometryEnvironment realisticGeometry();

}  // namespace pkm::simulation
