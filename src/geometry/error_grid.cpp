#include "pkm/geometry/error_grid.hpp"

#include <utility>

#include "geometry/detail/interpolation_nodes.hpp"
#include "pkm/core/error.hpp"

namespace pkm::geometry {

namespace {
constexpr std::array<const char*, 3> kAxisNames = {
    "error grid x nodes", "error grid y nodes", "error grid z nodes"};

std::size_t nodeCount(const std::array<std::vector<double>, 3>& axes) {
  return axes[0].size() * axes[1].size() * axes[2].size();
}
}  // namespace

ErrorGrid3d::ErrorGrid3d(std::array<std::vector<double>, 3> axes,
                         Eigen::MatrixXd values,
                         OutOfRange out_of_range)
    : axes_(std::move(axes)), values_(std::move(values)), out_of_range_(out_of_range) {
  for (std::size_t a = 0; a < 3; ++a) detail::validateNodes(axes_[a], kAxisNames[a]);
  PKM_CHECK(values_.rows() == static_cast<Eigen::Index>(nodeCount(axes_)),
            "error grid: {} rows of values for {}x{}x{} nodes",
            values_.rows(),
            axes_[0].size(),
            axes_[1].size(),
            axes_[2].size());
  PKM_CHECK(values_.cols() >= 1, "error grid: no value columns");
  PKM_CHECK(values_.allFinite(), "error grid: values are not all finite");
}

ErrorGrid3d ErrorGrid3d::fromFunction(
    std::array<std::vector<double>, 3> axes,
    const std::function<Eigen::VectorXd(const Eigen::Vector3d&)>& field,
    OutOfRange out_of_range) {
  for (std::size_t a = 0; a < 3; ++a) detail::validateNodes(axes[a], kAxisNames[a]);
  Eigen::MatrixXd values;
  Eigen::Index row = 0;
  for (const double z : axes[2]) {
    for (const double y : axes[1]) {
      for (const double x : axes[0]) {
        const Eigen::VectorXd v = field(Eigen::Vector3d(x, y, z));
        if (row == 0) {
          PKM_CHECK(v.size() >= 1, "error grid: the field returned no values");
          values.resize(static_cast<Eigen::Index>(nodeCount(axes)), v.size());
        }
        PKM_CHECK(v.size() == values.cols(),
                  "error grid: the field returned {} values, then {}",
                  values.cols(),
                  v.size());
        values.row(row++) = v.transpose();
      }
    }
  }
  return ErrorGrid3d(std::move(axes), std::move(values), out_of_range);
}

Eigen::Index ErrorGrid3d::nodeIndex(std::size_t i, std::size_t j, std::size_t k) const {
  return static_cast<Eigen::Index>(i + axes_[0].size() * (j + axes_[1].size() * k));
}

Eigen::Vector3d ErrorGrid3d::nodePoint(std::size_t i, std::size_t j, std::size_t k) const {
  return {axes_[0][i], axes_[1][j], axes_[2][k]};
}

Eigen::VectorXd ErrorGrid3d::evaluate(const Eigen::Vector3d& point) const {
  std::array<detail::Bracket, 3> b;
  for (std::size_t a = 0; a < 3; ++a) {
    b[a] = detail::bracket(
        axes_[a], point[static_cast<Eigen::Index>(a)], out_of_range_, kAxisNames[a]);
  }
  Eigen::VectorXd out = Eigen::VectorXd::Zero(values_.cols());
  // Sum over the 8 cell corners; corner weights are products of (1 − t) and t per axis.
  for (int corner = 0; corner < 8; ++corner) {
    const bool up_x = (corner & 1) != 0, up_y = (corner & 2) != 0, up_z = (corner & 4) != 0;
    const double w = (up_x ? b[0].t : 1.0 - b[0].t) * (up_y ? b[1].t : 1.0 - b[1].t) *
                     (up_z ? b[2].t : 1.0 - b[2].t);
    if (w == 0.0) continue;  // keeps node values exact and skips degenerate (single-node) corners
    const Eigen::Index row =
        nodeIndex(up_x ? b[0].hi : b[0].lo, up_y ? b[1].hi : b[1].lo, up_z ? b[2].hi : b[2].lo);
    out += w * values_.row(row).transpose();
  }
  return out;
}

ErrorMotion ErrorGrid3d::evaluateMotion(const Eigen::Vector3d& point) const {
  PKM_CHECK(components() == 6, "error grid has {} columns, an error motion needs 6", components());
  return evaluate(point);
}

}  // namespace pkm::geometry
