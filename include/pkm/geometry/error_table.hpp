/// @file
/// @brief ErrorTable1d: values given at strictly increasing positions along one axis (for example
/// the six position-dependent geometric errors of a linear axis), linearly interpolated.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "pkm/geometry/error_motion.hpp"

namespace pkm::geometry {

/// What an interpolating table does with a query position outside its node range.
enum class OutOfRange {
  kClamp,  ///< hold the value of the nearest end node (constant extrapolation)
  kThrow,  ///< throw pkm::InvalidArgument
};

/// A table of `components()` values at each of `positions()`; between nodes the values are
/// interpolated linearly, and they are exact at the nodes. Positions are in the unit of the axis
/// (model length unit for a linear axis); the values' units are those of the columns (for a PDGE
/// table of six columns: ErrorMotion order [dx, dy, dz, ex, ey, ez], length unit and radians).
/// Immutable after construction, so it can be shared between threads.
class ErrorTable1d {
 public:
  /// `positions`: n ≥ 1 finite, strictly increasing positions. `values`: n rows (one per position)
  /// of m ≥ 1 finite columns. A single node gives a constant table. Throws pkm::InvalidArgument
  /// when a precondition is violated (empty, non-increasing or non-finite positions, a row count
  /// that is not n, no columns, non-finite values).
  ErrorTable1d(std::vector<double> positions,
               Eigen::MatrixXd values,
               OutOfRange out_of_range = OutOfRange::kClamp);

  /// A table of six columns (an ErrorMotion per position, in ErrorMotion order). Same
  /// preconditions and throws as the constructor; `motions.size()` must equal `positions.size()`.
  [[nodiscard]] static ErrorTable1d fromErrorMotions(std::vector<double> positions,
                                                     const std::vector<ErrorMotion>& motions,
                                                     OutOfRange out_of_range = OutOfRange::kClamp);

  /// The node positions (strictly increasing).
  [[nodiscard]] const std::vector<double>& positions() const { return positions_; }
  /// The node values: row i holds the values at positions()[i].
  [[nodiscard]] const Eigen::MatrixXd& values() const { return values_; }
  /// Number of columns m.
  [[nodiscard]] Eigen::Index components() const { return values_.cols(); }
  /// The out-of-range policy.
  [[nodiscard]] OutOfRange outOfRange() const { return out_of_range_; }

  /// The m values at `position`: linear interpolation between the two enclosing nodes, exact at
  /// nodes. Outside [positions().front(), positions().back()] the policy applies (kClamp: the end
  /// node's values; kThrow: pkm::InvalidArgument). Throws pkm::InvalidArgument for a NaN position.
  [[nodiscard]] Eigen::VectorXd evaluate(double position) const;

  /// As evaluate(position), as an ErrorMotion. Throws pkm::InvalidArgument unless components()
  /// == 6.
  [[nodiscard]] ErrorMotion evaluateMotion(double position) const;

 private:
  std::vector<double> positions_;
  Eigen::MatrixXd values_;
  OutOfRange out_of_range_;
};

}  // namespace pkm::geometry
