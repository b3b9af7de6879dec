/// @file
/// @brief The report of `pkm demo`: an IK/FK round trip of a hexapod along a 5-axis path and,
/// on the default machines, the Exechon part (tool path round trip, dependent rotational motion
/// along a ring gauge (Lee et al. 2019), volumetric error map of the MXT700S parallelism paper's
/// errors), as text.
#pragma once

#include <map>
#include <optional>
#include <string>

#include "pkm/core/units.hpp"

namespace pkm::io {

/// The hexapod part of the demo.
struct HexapodDemoReport {
  std::string description;  ///< describeHexapodMachine of the machine
  LengthUnit unit = LengthUnit::kMillimetre;
  int points = 0;       ///< path poses
  double radius = 0.0;  ///< path circle radius, machine unit
  double tilt = 0.0;    ///< largest tilt amplitude of a and b, rad (the text shows 2 × tilt)
  std::map<std::string, int> statuses;              ///< checkPose status → poses
  double min_condition = 0.0, max_condition = 0.0;  ///< scaled condition numbers along the path
  double condition_limit = 0.0;                     ///< the machine's max_condition
  double min_stroke_margin = 0.0;                   ///< machine unit
  double min_angle_margin = 0.0;                    ///< joint cone margin, rad
  int converged = 0;                                ///< FK solves that converged
  std::map<int, int> iterations;                    ///< FK iterations → solves
  double max_position_error = 0.0;                  ///< |p_FK − p|, machine unit
  double max_rotation_error = 0.0;                  ///< rad
  double max_residual = 0.0;                        ///< strut residual, machine unit
  double seconds = 0.0;                             ///< time of the FK solves
  bool pass = false;  ///< every FK converged within the machine's tolerance
};

/// The Exechon part of the demo (on the built-in hybrid machine).
struct ExechonDemoReport {
  std::string machine, source;  ///< name and source of the machine
  double x2_min = 0.0, x2_max = 0.0, y2_min = 0.0, y2_max = 0.0;  ///< axis strokes, mm
  bool path_solved = false;  ///< every tool pose had an IK solution (else no path figures)
  int points = 0, violations = 0, converged = 0, max_iterations = 0;
  double us_per_solve = 0.0;           ///< µs per tool FK solve
  double max_position_error = 0.0;     ///< |p_FK − p|, mm
  double max_direction_error = 0.0;    ///< |u_FK − u|
  std::string drm_status = "ok";       ///< sampleDrmCircle status on the 40 mm ring
  double drm_max_phi = 0.0;            ///< max |φ_DRM|, rad
  double drm_max_fit_deviation = 0.0;  ///< of the 5th-order fit (Lee et al. 2019, eq. 10), rad
  int volumetric_points = 0;
  double max_dp = 0.0;          ///< largest |Δp| over the map, mm
  double max_dp_linear = 0.0;   ///< largest |Δp − Δp_linear|, mm
  double parallelism_dz = 0.0;  ///< z deviation of the PKM's Y over 600 mm, mm
  double sx_p = 0.0;            ///< the squareness sxP of the errors, rad
  bool pass = false;            ///< the tool path round trip returned every pose
};

/// The hexapod part as text: the description, the path and the summary lines.
[[nodiscard]] std::string hexapodDemoText(const HexapodDemoReport& report);

/// The Exechon part as text, starting with an empty line.
[[nodiscard]] std::string exechonDemoText(const ExechonDemoReport& report);

}  // namespace pkm::io
