/// @file
/// @brief ErrorGrid3d: values on a rectilinear 3-D grid (for example the six error components of a
/// PKM over its Cartesian working volume), trilinearly interpolated.
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <vector>

#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/error_table.hpp"

namespace pkm::geometry {

/// A rectilinear grid: node coordinates along x, y and z (each strictly increasing, independent
/// spacing) and `components()` values at each of the nx·ny·nz nodes. Between nodes the values are
/// interpolated trilinearly (exact at nodes, and exact for any field that is affine, or more
/// generally multilinear, in (x, y, z)). An axis with one node makes the field constant along it.
/// Coordinates are in the model length unit; value units are those of the columns (six columns:
/// ErrorMotion order). Immutable after construction, so it can be shared between threads.
class ErrorGrid3d {
 public:
  /// `axes`: the node coordinates along x, y, z, each n_a ≥ 1 finite and strictly increasing.
  /// `values`: nx·ny·nz rows of m ≥ 1 finite columns; node (i, j, k) is row nodeIndex(i, j, k) =
  /// i + nx·(j + ny·k) (x fastest). The policy applies to each coordinate separately. Throws
  /// pkm::InvalidArgument when a precondition is violated.
  ErrorGrid3d(std::array<std::vector<double>, 3> axes,
              Eigen::MatrixXd values,
              OutOfRange out_of_range = OutOfRange::kClamp);

  /// A grid whose node values are `field(node point)` (each call must return the same number m ≥ 1
  /// of finite values). Same preconditions and throws as the constructor.
  [[nodiscard]] static ErrorGrid3d fromFunction(
      std::array<std::vector<double>, 3> axes,
      const std::function<Eigen::VectorXd(const Eigen::Vector3d&)>& field,
      OutOfRange out_of_range = OutOfRange::kClamp);

  /// Node coordinates along axis a (0 = x, 1 = y, 2 = z).
  [[nodiscard]] const std::vector<double>& axis(int a) const {
    return axes_[static_cast<std::size_t>(a)];
  }
  /// The node values, one row per node (row nodeIndex(i, j, k)).
  [[nodiscard]] const Eigen::MatrixXd& values() const { return values_; }
  /// Number of columns m.
  [[nodiscard]] Eigen::Index components() const { return values_.cols(); }
  /// The out-of-range policy.
  [[nodiscard]] OutOfRange outOfRange() const { return out_of_range_; }
  /// Row of node (i, j, k) in values(): i + nx·(j + ny·k). Indices are not checked.
  [[nodiscard]] Eigen::Index nodeIndex(std::size_t i, std::size_t j, std::size_t k) const;
  /// The coordinates of node (i, j, k). Indices are not checked.
  [[nodiscard]] Eigen::Vector3d nodePoint(std::size_t i, std::size_t j, std::size_t k) const;

  /// The m values at `point`: trilinear interpolation in the enclosing cell. A coordinate outside
  /// its axis range is clamped to the range (kClamp) or throws pkm::InvalidArgument (kThrow).
  /// Throws pkm::InvalidArgument for a non-finite point.
  [[nodiscard]] Eigen::VectorXd evaluate(const Eigen::Vector3d& point) const;

  /// As evaluate(point), as an ErrorMotion. Throws pkm::InvalidArgument unless components() == 6.
  [[nodiscard]] ErrorMotion evaluateMotion(const Eigen::Vector3d& point) const;

 private:
  std::array<std::vector<double>, 3> axes_;
  Eigen::MatrixXd values_;
  OutOfRange out_of_range_;
};

}  // namespace pkm::geometry
