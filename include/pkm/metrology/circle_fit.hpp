/// @file
/// @brief Least-squares (Gauss) circle: the geometric fit that minimises the sum of squared
/// orthogonal distances, started from the algebraic Kåsa fit (I. Kåsa, IEEE Trans. Instrum.
/// Meas. 25(1), 1976; ISO 4291 / ISO 12181 "LSC"), and the radial deviations and roundness about
/// any centre.
#pragma once

#include <Eigen/Core>
#include <span>
#include <string>
#include <vector>

namespace pkm::metrology {

/// A point in the measurement plane (any length unit; results are in the same unit).
using Point2 = Eigen::Vector2d;

/// A circle: centre and radius (the points' unit).
struct Circle {
  Point2 center = Point2::Zero();  ///< centre
  double radius = 0.0;             ///< radius, > 0
};

/// Kåsa's algebraic fit: minimises Σ((x−a)² + (y−b)² − R²)², a linear least-squares problem in
/// (2a, 2b, R² − a² − b²) (Kåsa 1976), solved on centroid-shifted, scaled data.
/// Biased towards small radii on short arcs; used as the start of fitCircle. Throws
/// pkm::InvalidArgument for fewer than 3 points, non-finite coordinates, or collinear/coincident
/// points.
[[nodiscard]] Circle fitCircleKasa(std::span<const Point2> points);

/// Options of the geometric least-squares fit (Levenberg-Marquardt on orthogonal distances).
/// The fit stops at the first of three reachable criteria (as MINPACK's lmder, which scipy's
/// least_squares(method="lm") runs): a small step, a small relative decrease of the cost, or a
/// cost that no step can lower any more because it is at the rounding floor of its sum.
struct CircleFitOptions {
  int max_iterations = 100;  ///< LM iterations, >= 1
  /// Converged when an undamped step (centre and radius) is below step_tolerance × the radius.
  double step_tolerance = 1e-10;
  /// Converged when an accepted step lowers Σe² by less than cost_tolerance × Σe².
  double cost_tolerance = 1e-12;

  /// True when every field is usable; otherwise false with the reason in *why (if given).
  [[nodiscard]] bool isValid(std::string* why = nullptr) const;
};

/// Result of the least-squares circle (LSC).
struct CircleFit {
  Circle circle;                  ///< LSC centre and radius
  std::vector<double> residuals;  ///< e_k = |p_k − centre| − radius, per point (signed, outward +)
  double roundness = 0.0;         ///< max e_k − min e_k (roundness about the LSC centre, RONt)
  double rms = 0.0;               ///< sqrt(Σ e_k² / N)
  int iterations = 0;             ///< LM iterations done
  bool converged = false;         ///< a convergence criterion was met within max_iterations
};

/// Geometric least-squares circle: minimises Σ(|p_k − c| − R)² (orthogonal distances, ISO 4291 /
/// ISO 12181 LSC) by Levenberg-Marquardt from the Kåsa start (a few iterations on a full circle,
/// noisy or not; `converged` false only when max_iterations ran out). Throws pkm::InvalidArgument
/// like fitCircleKasa or when the options are invalid.
[[nodiscard]] CircleFit fitCircle(std::span<const Point2> points,
                                  const CircleFitOptions& options = {});

/// Distances |p_k − center| (the radial positions about `center`).
[[nodiscard]] std::vector<double> radialDistances(std::span<const Point2> points,
                                                  const Point2& center);

/// Roundness of `points` about `center`: max_k |p_k − c| − min_k |p_k − c| (ISO 12181).
/// Throws pkm::InvalidArgument when `points` is empty.
[[nodiscard]] double roundnessAbout(std::span<const Point2> points, const Point2& center);

/// Throws pkm::InvalidArgument "<what>: ..." unless there are at least `minimum` points and every
/// coordinate is finite.
void requirePoints(std::span<const Point2> points, std::size_t minimum, const char* what);

}  // namespace pkm::metrology
