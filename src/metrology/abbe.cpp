#include "pkm/metrology/abbe.hpp"

#include <Eigen/Geometry>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/metrology/checks.hpp"

namespace pkm::metrology {

double abbeError(const Eigen::Vector3d& rotation,
                 const Eigen::Vector3d& offset,
                 const Eigen::Vector3d& direction) {
  PKM_CHECK(rotation.allFinite() && offset.allFinite() && direction.allFinite(),
            "Abbe error: non-finite input");
  PKM_CHECK(direction.norm() > 0.0, "Abbe error: zero reading direction");
  // Small rotation ε of the moving part moves a point at offset r by ε × r (first order).
  return direction.normalized().dot(rotation.cross(offset));
}

std::vector<double> removeAbbeError(std::span<const double> positions,
                                    std::span<const double> readings,
                                    std::span<const AngularProfile> angles,
                                    const Eigen::Vector3d& offset,
                                    const Eigen::Vector3d& direction,
                                    double datum) {
  PKM_CHECK(positions.size() == readings.size(),
            "Abbe error: {} positions but {} readings",
            positions.size(),
            readings.size());
  requireFinite(positions, "Abbe error positions");
  requireFinite(readings, "Abbe error readings");
  PKM_CHECK(std::isfinite(datum), "Abbe error: datum is not finite");
  for (const AngularProfile& a : angles) {
    PKM_CHECK(a.axis.allFinite() && a.axis.norm() > 0.0, "Abbe error: zero rotation axis");
    PKM_CHECK(a.table.components() == 1,
              "Abbe error: an angle table needs 1 column, got {}",
              a.table.components());
  }
  const auto rotationAt = [&](double x) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (const AngularProfile& a : angles) r += a.table.evaluate(x)(0) * a.axis.normalized();
    return r;
  };
  const Eigen::Vector3d r0 = rotationAt(datum);
  std::vector<double> out(readings.size());
  for (std::size_t k = 0; k < readings.size(); ++k) {
    out[k] = readings[k] - abbeError(rotationAt(positions[k]) - r0, offset, direction);
  }
  return out;
}

}  // namespace pkm::metrology
