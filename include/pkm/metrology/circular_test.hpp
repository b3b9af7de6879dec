/// @file
/// @brief ISO 230-4 circular tests (ballbar or any bidirectional circular path): circular
/// deviation G per direction, bidirectional circular deviation G(b), circular hysteresis H and the
/// radial deviations F (ISO 230-4:2005 clauses 3.1-3.4).
#pragma once

#include <optional>
#include <span>

#include "pkm/metrology/circle_fit.hpp"

namespace pkm::metrology {

/// Which centre the deviations are referred to (ISO 230-4 leaves it to the report; pkm's default
/// is the LSC).
enum class CircularCentre {
  kLeastSquares,  ///< least-squares circle of the data (fitCircle)
  kMinimumZone,   ///< minimum-zone circle of the data (fitMinimumZoneCircle)
  kNominal,       ///< the nominal centre given in the options (e.g. the ballbar pivot)
};

/// Options of evaluateCircularTest.
struct CircularTestOptions {
  CircularCentre centre = CircularCentre::kLeastSquares;  ///< centre of G, G(b) and H
  std::optional<Point2> nominal_center;  ///< required for kNominal; also the centre of F
  std::optional<double> nominal_radius;  ///< R0 (> 0): enables the radial deviations F
};

/// Results of one direction (one run).
struct CircularRun {
  Point2 center = Point2::Zero();  ///< the centre used for G of this run
  double radius = 0.0;             ///< mean radius about it
  double circular_deviation = 0.0;  ///< G: max − min radial distance about `center` (ISO 230-4 3.2)
  /// F (ISO 230-4 3.4): radial distance about the nominal (or LSC) centre minus R0; only with a
  /// nominal radius.
  std::optional<double> radial_deviation_max;
  std::optional<double> radial_deviation_min;   ///< see radial_deviation_max
  std::optional<double> mean_radial_deviation;  ///< mean of F over the run
};

/// Results of a bidirectional circular test.
struct CircularTestResult {
  CircularRun cw;                         ///< clockwise run
  CircularRun ccw;                        ///< counter-clockwise run
  Point2 common_center = Point2::Zero();  ///< centre of the combined data (for G(b) and H)
  double bidirectional_deviation = 0.0;   ///< G(b): radial range of both runs about common_center
  /// H (ISO 230-4 3.3): max over angles of |r_cw(θ) − r_ccw(θ)| about common_center, the other
  /// run's radius linearly interpolated in angle (only where that run has data).
  double hysteresis = 0.0;
  double hysteresis_angle = 0.0;  ///< θ of the maximum, rad, about common_center, in [0, 2π)
  CircularCentre centre = CircularCentre::kLeastSquares;  ///< the centre choice used
};

/// Evaluates a bidirectional circular test from the measured path points of the clockwise and the
/// counter-clockwise run (same unit, the plane of the test). Throws pkm::InvalidArgument for fewer
/// than 4 points per run (non-finite or collinear points), kNominal without nominal_center, or a
/// nominal radius <= 0.
[[nodiscard]] CircularTestResult evaluateCircularTest(std::span<const Point2> cw,
                                                      std::span<const Point2> ccw,
                                                      const CircularTestOptions& options = {});

/// Maximum |r_a(θ) − r_b(θ)| about `center`, evaluated at every sample of each run against the
/// other run's radius linearly interpolated in angle (a gap wider than 5 median spacings is not
/// bridged). Returns {H, θ of the maximum}; {0, 0} when the runs do not overlap in angle.
[[nodiscard]] std::pair<double, double> circularHysteresis(std::span<const Point2> a,
                                                           std::span<const Point2> b,
                                                           const Point2& center);

}  // namespace pkm::metrology
