#include "pkm/geometry/error_table.hpp"

#include <utility>

#include "geometry/detail/interpolation_nodes.hpp"
#include "pkm/core/error.hpp"

namespace pkm::geometry {

ErrorTable1d::ErrorTable1d(std::vector<double> positions,
                           Eigen::MatrixXd values,
                           OutOfRange out_of_range)
    : positions_(std::move(positions)), values_(std::move(values)), out_of_range_(out_of_range) {
  detail::validateNodes(positions_, "error table positions");
  PKM_CHECK(values_.rows() == static_cast<Eigen::Index>(positions_.size()),
            "error table: {} rows of values for {} positions",
            values_.rows(),
            positions_.size());
  PKM_CHECK(values_.cols() >= 1, "error table: no value columns");
  PKM_CHECK(values_.allFinite(), "error table: values are not all finite");
}

ErrorTable1d ErrorTable1d::fromErrorMotions(std::vector<double> positions,
                                            const std::vector<ErrorMotion>& motions,
                                            OutOfRange out_of_range) {
  PKM_CHECK(motions.size() == positions.size(),
            "error table: {} error motions for {} positions",
            motions.size(),
            positions.size());
  Eigen::MatrixXd values(static_cast<Eigen::Index>(motions.size()), 6);
  for (std::size_t i = 0; i < motions.size(); ++i) {
    values.row(static_cast<Eigen::Index>(i)) = motions[i].transpose();
  }
  return ErrorTable1d(std::move(positions), std::move(values), out_of_range);
}

Eigen::VectorXd ErrorTable1d::evaluate(double position) const {
  const detail::Bracket b = detail::bracket(positions_, position, out_of_range_, "error table");
  const auto lo = static_cast<Eigen::Index>(b.lo), hi = static_cast<Eigen::Index>(b.hi);
  return ((1.0 - b.t) * values_.row(lo) + b.t * values_.row(hi)).transpose();
}

ErrorMotion ErrorTable1d::evaluateMotion(double position) const {
  PKM_CHECK(components() == 6, "error table has {} columns, an error motion needs 6", components());
  return evaluate(position);
}

}  // namespace pkm::geometry
