/// @file
/// @brief Straightness of a line of motion (ISO 230-1; HP 5528A User's Guide §21): the
/// end-point, least-squares and minimum-zone reference lines and the straightness deviation about
/// them.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

namespace pkm::metrology {

/// Which reference line a straightness evaluation uses.
enum class StraightnessReference {
  kEndpoint,      ///< through the (mean) deviations at the first and last position
  kLeastSquares,  ///< least-squares line, residuals in the deviation direction
  kMinimumZone,   ///< the line minimising the peak-to-valley of the residuals (Chebyshev line)
};

/// "endpoint", "lsq", "minzone".
[[nodiscard]] std::string_view toString(StraightnessReference reference);
/// Parses "endpoint", "lsq" (or "least-squares") and "minzone" (or "minimum-zone"). Throws
/// pkm::InvalidArgument for another name.
[[nodiscard]] StraightnessReference parseStraightnessReference(std::string_view name);

/// A reference line deviation = intercept + slope · position.
struct ReferenceLine {
  double slope = 0.0;      ///< deviation unit per position unit (mm/mm = rad for small slopes)
  double intercept = 0.0;  ///< deviation at position 0
  /// The line's value at `position`.
  [[nodiscard]] double at(double position) const { return intercept + slope * position; }
};

/// A straightness evaluation.
struct StraightnessResult {
  StraightnessReference reference = StraightnessReference::kLeastSquares;
  ReferenceLine line;             ///< the reference line
  double straightness = 0.0;      ///< max residual - min residual (peak to valley), >= 0
  std::vector<double> residuals;  ///< deviation - line(position), in input order
  /// Minimum zone only: indices (input order) of the three points on the two zone lines that
  /// certify optimality, sorted by position: two on one line and the middle one on the other
  /// (Chebyshev alternation). Empty for the other references.
  std::vector<std::size_t> contact_points;
};

/// End-point line through the mean deviation at the smallest and at the largest position
/// (ISO 230-1, HP 5528A User's Guide §21). Throws pkm::InvalidArgument (see evaluateStraightness).
[[nodiscard]] ReferenceLine endpointLine(std::span<const double> positions,
                                         std::span<const double> deviations);

/// Least-squares line (ISO 230-1), computed about the centroid for accuracy.
/// Throws pkm::InvalidArgument (see evaluateStraightness).
[[nodiscard]] ReferenceLine leastSquaresLine(std::span<const double> positions,
                                             std::span<const double> deviations);

/// Exact minimum-zone (Chebyshev) line: minimises max_k r_k - min_k r_k, r_k = d_k - line(x_k).
/// The zone width as a function of the slope is convex and piecewise linear with breakpoints at
/// the slopes of the convex hull's edges, so the optimum lies on a hull edge; found by monotone
/// chain hull (O(n log n)) and a binary search over the edge slopes (O(h log h)).
/// `contacts` (optional) receives the three certifying points (see StraightnessResult).
/// Throws pkm::InvalidArgument (see evaluateStraightness).
[[nodiscard]] ReferenceLine minimumZoneLine(std::span<const double> positions,
                                            std::span<const double> deviations,
                                            std::array<std::size_t, 3>* contacts = nullptr);

/// Evaluates the straightness of deviations d_k (perpendicular to the motion, any length unit)
/// measured at positions x_k about the chosen reference line. Positions need not be sorted and
/// may repeat (several runs). Minimum zone <= least squares and <= end point always.
/// @throws pkm::InvalidArgument for sizes that differ, non-finite values, or fewer than 2
/// distinct positions.
[[nodiscard]] StraightnessResult evaluateStraightness(std::span<const double> positions,
                                                      std::span<const double> deviations,
                                                      StraightnessReference reference);

}  // namespace pkm::metrology
