/// @file
/// @brief 2-D error prediction on the XY plane from extracted error components (Hwang et al.,
/// "Analysis of multi-axis volumetric errors", §3): the tool-position error
/// e(x, y) = (EXX(x) + EXY(y), EYX(x) + EYY(y)) of the additive model (first-order rigid-body
/// model, ISO 230-1 names, z fixed), built from a step-diagonal or shifted-diagonal evaluation, and
/// its comparison with direct measurements along lines in the plane (linear or straightness).
#pragma once

#include <Eigen/Core>
#include <span>
#include <vector>

#include "pkm/metrology/shifted_diagonal.hpp"
#include "pkm/metrology/step_diagonal.hpp"

namespace pkm::metrology {

/// A component error as a function of one axis position: linear interpolation through the nodes,
/// linear extrapolation from the end intervals. Empty: zero.
struct ErrorFunction {
  std::vector<double> positions;  ///< strictly increasing, mm
  std::vector<double> values;     ///< mm
  /// The value at `q` (mm).
  [[nodiscard]] double operator()(double q) const;
};

/// The additive XY error model: error along X = exx(x) + exy(y), along Y = eyx(x) + eyy(y).
struct PlaneErrorModel {
  ErrorFunction exx, exy, eyx, eyy;
  /// The error vector at (x, y), mm.
  [[nodiscard]] Eigen::Vector2d error(double x, double y) const;
};

/// From Wang's extraction: EXX, EYX of the X sub-moves and EXY, EYY of the Y sub-moves.
[[nodiscard]] PlaneErrorModel planeModel(const StepDiagonalResult& step);

/// From the shifted-diagonal components (linear functions through 0, X the reference direction):
/// exx = k_x·x, eyy = k_y·y, exy = −squareness_xy·y, eyx = 0. A rigid rotation of the plane is
/// not observable by lengths, so X is taken as the reference as ISO 230-1 does.
[[nodiscard]] PlaneErrorModel planeModel(const ShiftedDiagonalResult& shifted);

/// The predicted reading of a line measurement in the plane, relative to its start:
/// sensitive·(e(start + s·direction) − e(start)), mm. For a linear (displacement) measurement
/// `sensitive` is the unit `direction`; for straightness the lateral unit direction.
[[nodiscard]] double predictReading(const PlaneErrorModel& model,
                                    const Eigen::Vector2d& start,
                                    const Eigen::Vector2d& direction,
                                    const Eigen::Vector2d& sensitive,
                                    double s);

/// Predicted against measured readings at the same positions.
struct PlaneComparison {
  std::vector<double> positions;  ///< s, mm
  std::vector<double> measured;   ///< mm (after removing the least-squares line when asked)
  std::vector<double> predicted;  ///< mm (likewise)
  double rms = 0.0;               ///< RMS of measured − predicted, mm
  double max_abs = 0.0;           ///< max |measured − predicted|, mm
};

/// Compares `measured` (deviations at `positions` along the line, mm) with predictReading; both
/// series are shifted so that their mean is 0 (a datum offset is not a prediction error). With
/// `remove_line` the least-squares line is removed from both (straightness: the beam misalignment
/// is unknown). Throws pkm::InvalidArgument for sizes that differ, fewer than 2 points or
/// non-finite values.
[[nodiscard]] PlaneComparison comparePlanePrediction(const PlaneErrorModel& model,
                                                     const Eigen::Vector2d& start,
                                                     const Eigen::Vector2d& direction,
                                                     const Eigen::Vector2d& sensitive,
                                                     std::span<const double> positions,
                                                     std::span<const double> measured,
                                                     bool remove_line);

}  // namespace pkm::metrology
