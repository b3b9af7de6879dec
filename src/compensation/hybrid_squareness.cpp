#include "pkm/compensation/hybrid_squareness.hpp"

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::compensation {

HybridSquarenessCompensation hybridSquarenessCompensation(
    const kinematics::HybridMachineModel& model, const kinematics::HybridSquareness& s) {
  PKM_CHECK(std::isfinite(s.sz_x2) && std::isfinite(s.sx_p) && std::isfinite(s.sy_p) &&
                std::isfinite(s.sz_p),
            "squareness compensation: a squareness is not finite");
  model.validate();
  const Eigen::Matrix3d R_X2 = geometry::so3Exp(kinematics::squarenessRotationX2(s));
  const Eigen::Matrix3d R_P = geometry::so3Exp(kinematics::squarenessRotationP(s));
  HybridSquarenessCompensation c;
  c.base_rotation = R_P.transpose() * R_X2.transpose();
  c.base_rpy = geometry::rpyFromRotation(c.base_rotation);
  const Eigen::Matrix3d D = R_P.transpose() * (R_X2.transpose() - Eigen::Matrix3d::Identity());
  c.base_offset = c.base_rotation * model.P_p_tcp0 - model.P_p_tcp0 + D * model.X2_p_P;
  c.per_x2 = D * Eigen::Vector3d::UnitX();
  return c;
}

kinematics::HybridCommand compensatedCommand(const HybridSquarenessCompensation& c,
                                             const kinematics::HybridCommand& command) {
  kinematics::HybridCommand out = command;
  out.pkm = c.base_rotation * command.pkm + c.base_offset + command.x2 * c.per_x2;
  return out;
}

}  // namespace pkm::compensation
