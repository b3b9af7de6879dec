#include "pkm/kinematics/hybrid_chain.hpp"

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/error_motion.hpp"
#include "pkm/geometry/rigid_transform.hpp"

namespace pkm::kinematics {

namespace {
using geometry::errorMotionHtm;
using geometry::errorRotation;
using geometry::errorTranslation;
using geometry::rotationTransform;
using geometry::translationTransform;

void checkCommand(const HybridCommand& c) {
  PKM_CHECK(std::isfinite(c.x2) && std::isfinite(c.y2) && c.pkm.allFinite(),
            "hybrid command is not finite (x2 {}, y2 {}, pkm ({}, {}, {}))",
            c.x2,
            c.y2,
            c.pkm.x(),
            c.pkm.y(),
            c.pkm.z());
}
}  // namespace

HybridChain hybridChain(const HybridMachineModel& model,
                        const HybridErrorValues& values,
                        const HybridCommand& command) {
  checkCommand(command);
  HybridChain c;
  c.F_T_Y2 =
      translationTransform(command.y2 * Eigen::Vector3d::UnitY()) * errorMotionHtm(values.y2);
  c.Y2_T_w = translationTransform(model.Y2_p_work);
  c.F_T_X2 = rotationTransform(squarenessRotationX2(values.squareness)) *
             translationTransform(command.x2 * Eigen::Vector3d::UnitX()) *
             errorMotionHtm(values.x2);
  c.X2_T_P = translationTransform(model.X2_p_P) *
             rotationTransform(squarenessRotationP(values.squareness));
  c.P_T_t = translationTransform(model.P_p_tcp0 + command.pkm) * errorMotionHtm(values.pkm);
  c.w_T_t = (c.F_T_Y2 * c.Y2_T_w).inverse() * c.F_T_X2 * c.X2_T_P * c.P_T_t;
  return c;
}

geometry::RigidTransform hybridNominalPose(const HybridMachineModel& model,
                                           const HybridCommand& command) {
  checkCommand(command);
  return translationTransform(hybridNominalToolPosition(model, command));
}

geometry::RigidTransform hybridActualPose(const HybridMachineModel& model,
                                          const HybridErrorValues& values,
                                          const HybridCommand& command) {
  return hybridChain(model, values, command).w_T_t;
}

geometry::RigidTransform hybridActualPose(const HybridMachineModel& model,
                                          const GeometricErrors& errors,
                                          const HybridCommand& command) {
  return hybridActualPose(model, evaluateHybridErrors(errors, command), command);
}

Eigen::Vector3d hybridVolumetricError(const HybridMachineModel& model,
                                      const HybridErrorValues& values,
                                      const HybridCommand& command) {
  return hybridActualPose(model, values, command).translation() -
         hybridNominalToolPosition(model, command);
}

Eigen::Vector3d hybridVolumetricError(const HybridMachineModel& model,
                                      const GeometricErrors& errors,
                                      const HybridCommand& command) {
  return hybridVolumetricError(model, evaluateHybridErrors(errors, command), command);
}

Eigen::Vector3d hybridVolumetricErrorLinear(const HybridMachineModel& model,
                                            const HybridErrorValues& values,
                                            const HybridCommand& command) {
  checkCommand(command);
  const Eigen::Vector3d q = model.P_p_tcp0 + command.pkm;
  const Eigen::Vector3d r = model.X2_p_P + q;
  const Eigen::Vector3d along_x2 = command.x2 * Eigen::Vector3d::UnitX() + r;
  const Eigen::Vector3d s = along_x2 - command.y2 * Eigen::Vector3d::UnitY();
  const Eigen::Vector3d omega_x2 = squarenessRotationX2(values.squareness);
  const Eigen::Vector3d omega_p = squarenessRotationP(values.squareness);
  return errorTranslation(values.pkm) + omega_p.cross(q)  // PKM and its squareness
         + errorTranslation(values.x2) + errorRotation(values.x2).cross(r)  // X2 PDGE
         + omega_x2.cross(along_x2)                                         // szX2
         - errorTranslation(values.y2) -
         errorRotation(values.y2).cross(s);  // Y2 PDGE (moves the work)
}

Eigen::Vector3d hybridVolumetricErrorLinear(const HybridMachineModel& model,
                                            const GeometricErrors& errors,
                                            const HybridCommand& command) {
  return hybridVolumetricErrorLinear(model, evaluateHybridErrors(errors, command), command);
}

}  // namespace pkm::kinematics
