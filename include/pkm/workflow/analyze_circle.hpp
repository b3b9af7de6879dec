/// @file
/// @brief `pkm analyze circle | circular | probe-offset` as workflows (docs/analysis.md,
/// "Circles"): least-squares and minimum-zone circles with roundness, the ISO 230-4 circular
/// deviation and hysteresis, and the touch-probe stylus offset from master-ring touches with
/// spindle reversal (Lee et al. 2019). Inputs come from memory (io::NamedText); every input error
/// is pkm::IoError "NAME:LINE: message".
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include "pkm/io/analysis_report.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/metrology/uncertainty_sources.hpp"

namespace pkm::workflow {

/// Circle fits of `x,y` points (x_mm, y_mm accepted).
struct CircleRequest {
  std::vector<io::NamedText> data;  ///< `x,y` tables, concatenated (these, files or `points`)
  /// `x,y` table files ("-": standard input) read by the call itself after `data`, mapped rather
  /// than copied (io::NumberTable::read): the fastest way to read a large file.
  std::vector<std::string> data_files{};
  /// The probe and environment of the budgets (metrology::circleUncertainty).
  metrology::UncertaintySources uncertainty{};
  /// Which circles: "lsc" (least squares alone), "mzc" (the minimum zone alone; the least-squares
  /// centre it starts from is not reported) or "both".
  std::string fit = "both";
  /// The budgets of what is fitted (metrology::circleUncertainty); false: none.
  bool budget = true;
  /// Points held by the caller instead of `data` (e.g. a numpy array, read where it is, not
  /// copied): x, y in the data's length unit, named `points_name` in the report (row r as line
  /// r + 1). Must outlive the call.
  std::span<const metrology::Point2> points{};
  std::string points_name = "data";
  /// Throws pkm::IoError without data and points or with both, pkm::InvalidArgument for another
  /// `fit`.
  void validate() const;
};

/// Least-squares circle (metrology::fitCircle) and minimum-zone circle started from its centre
/// (metrology::fitMinimumZoneCircle), as `fit` asks, with their budgets. Throws as validate(),
/// pkm::IoError for a bad input, pkm::InvalidArgument for too few or degenerate points.
[[nodiscard]] io::CircleReport analyzeCircle(CircleRequest request);

/// ISO 230-4:2005 circular test.
struct CircularRequest {
  /// One `x,y,direction` table (cw/CW/- or ccw/CCW/+), or two `x,y` tables: CW then CCW.
  std::vector<io::NamedText> data;
  metrology::CircularCentre centre = metrology::CircularCentre::kLeastSquares;  ///< of G and H
  std::optional<metrology::Point2> nominal_center;  ///< for kNominal and the radial deviations F
  std::optional<double> nominal_radius;             ///< R0 > 0: enables F
  /// The ballbar and environment of the budgets (metrology::circularTestUncertainty).
  metrology::UncertaintySources uncertainty{};
  /// Throws pkm::IoError without data or with more than two inputs, pkm::InvalidArgument for a
  /// nominal radius not > 0.
  void validate() const;
};

/// Validates, reads the runs and evaluates them (metrology::evaluateCircularTest) with their
/// budgets (metrology::circularTestUncertainty). Throws as
/// validate(), pkm::IoError for a bad input or an unlabelled single input.
[[nodiscard]] io::CircularReport analyzeCircular(const CircularRequest& request);

/// Touch-probe stylus offset (Lee et al. 2019).
struct ProbeOffsetRequest {
  /// `spindle_deg,x,y[,drm_deg,touch,run]` tables (required); `touch` labels +x, -x, +y, -y.
  std::vector<io::NamedText> data;
  std::optional<double> ring_diameter;    ///< certified ring diameter, mm (> 0)
  std::optional<double> stylus_diameter;  ///< ball diameter for eqs. 8-9 (> 0; default effective)
  bool tool_plus_z = false;  ///< tool direction +z (angles clockwise seen from above) or −z
  /// The probe of the budgets (metrology::probeOffsetUncertainty; none below 6 touches).
  metrology::UncertaintySources uncertainty{};
  /// Throws pkm::IoError without data, pkm::InvalidArgument for a diameter not > 0.
  void validate() const;
};

/// The least-squares offset (metrology::fitProbeOffset) and, with a ring diameter, the effective
/// stylus radius and Lee et al. (2019), eqs. 8-9 averaged over the runs that have the six labelled
/// touches (+x, -x, +y, -y at turn 0°; +x, +y at 180°, ±10°). Throws as validate(), pkm::IoError
/// for a bad input or label, pkm::InvalidArgument for too few touches.
[[nodiscard]] io::ProbeOffsetReport analyzeProbeOffset(const ProbeOffsetRequest& request);

}  // namespace pkm::workflow
