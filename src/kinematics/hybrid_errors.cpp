#include "pkm/kinematics/hybrid_errors.hpp"

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::kinematics {

Eigen::Vector3d squarenessRotationX2(const HybridSquareness& s) { return {0.0, 0.0, -s.sz_x2}; }

Eigen::Vector3d squarenessRotationP(const HybridSquareness& s) { return {s.sx_p, -s.sy_p, s.sz_p}; }

void GeometricErrors::validate() const {
  PKM_CHECK(!x2 || x2->components() == 6, "X2 error table has {} columns, not 6", x2->components());
  PKM_CHECK(!y2 || y2->components() == 6, "Y2 error table has {} columns, not 6", y2->components());
  PKM_CHECK(
      !pkm || pkm->components() == 6, "PKM error grid has {} columns, not 6", pkm->components());
  const HybridSquareness& s = squareness;
  PKM_CHECK(std::isfinite(s.sz_x2) && std::isfinite(s.sx_p) && std::isfinite(s.sy_p) &&
                std::isfinite(s.sz_p),
            "squareness errors are not finite");
}

HybridErrorValues scaled(const HybridErrorValues& values, double factor) {
  HybridErrorValues out;
  out.x2 = factor * values.x2;
  out.y2 = factor * values.y2;
  out.pkm = factor * values.pkm;
  out.squareness.sz_x2 = factor * values.squareness.sz_x2;
  out.squareness.sx_p = factor * values.squareness.sx_p;
  out.squareness.sy_p = factor * values.squareness.sy_p;
  out.squareness.sz_p = factor * values.squareness.sz_p;
  return out;
}

HybridErrorValues evaluateHybridErrors(const GeometricErrors& errors,
                                       const HybridCommand& command) {
  HybridErrorValues v;
  if (errors.x2) v.x2 = errors.x2->evaluateMotion(command.x2);
  if (errors.y2) v.y2 = errors.y2->evaluateMotion(command.y2);
  if (errors.pkm) v.pkm = errors.pkm->evaluateMotion(command.pkm);
  v.squareness = errors.squareness;
  return v;
}

}  // namespace pkm::kinematics
