#include "pkm/kinematics/hexapod_model.hpp"

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::kinematics {

double HexapodModel::characteristicLength() const {
  double sum = 0.0;
  for (const Strut& s : struts) sum += s.platform_p_joint.norm();
  const double mean = sum / kStruts;
  return mean > 0.0 ? mean : 1.0;
}

namespace {
bool finite(const Eigen::Vector3d& v) { return v.allFinite(); }

void validateCone(const JointCone& cone, int i, const char* which) {
  PKM_CHECK(finite(cone.axis) && std::isfinite(cone.max_angle),
            "strut {}: {} joint cone is not finite",
            i,
            which);
  PKM_CHECK(cone.axis.norm() > 1e-12, "strut {}: {} joint cone axis has zero length", i, which);
}
}  // namespace

void HexapodModel::validate() const {
  PKM_CHECK(
      finite(tool_offset) && std::isfinite(spindle_offset) && std::isfinite(linuxcnc_tool_offset),
      "tool or spindle offset is not finite");
  PKM_CHECK(std::isfinite(strut_diameter) && strut_diameter >= 0.0,
            "strut diameter must be finite and >= 0 (got {})",
            strut_diameter);
  PKM_CHECK(max_condition > 1.0, "max_condition must be > 1 (got {})", max_condition);
  PKM_CHECK(finite(home.position) && finite(home.rpy), "home pose is not finite");
  double scale = 0.0;
  for (const Strut& s : struts)
    scale = std::max({scale, s.world_p_base.norm(), s.platform_p_joint.norm()});
  PKM_CHECK(scale > 0.0, "all joint centres are at the origin");
  const double tiny = 1e-9 * scale;
  for (int i = 0; i < kStruts; ++i) {
    const Strut& s = struts[static_cast<std::size_t>(i)];
    PKM_CHECK(finite(s.world_p_base) && finite(s.platform_p_joint),
              "strut {}: joint centre is not finite",
              i);
    PKM_CHECK(std::isfinite(s.length_offset), "strut {}: length offset is not finite", i);
    PKM_CHECK(
        !std::isnan(s.min_reading) && !std::isnan(s.max_reading) && s.min_reading <= s.max_reading,
        "strut {}: stroke [{}, {}] is empty",
        i,
        s.min_reading,
        s.max_reading);
    validateCone(s.base_cone, i, "base");
    validateCone(s.platform_cone, i, "platform");
    for (int j = 0; j < i; ++j) {
      const Strut& o = struts[static_cast<std::size_t>(j)];
      PKM_CHECK((s.world_p_base - o.world_p_base).norm() > tiny ||
                    (s.platform_p_joint - o.platform_p_joint).norm() > tiny,
                "struts {} and {} have coincident base and platform joints (the same leg twice)",
                j,
                i);
    }
  }
  // Coincident platform joints of all struts, or all base joints, make the platform unconstrained.
  HexapodData data(*this);
  inverseKinematics(*this, data, home);
  for (int i = 0; i < kStruts; ++i) {
    PKM_CHECK(data.joint_distance[i] > tiny, "strut {} has zero length at the home pose", i);
  }
  computeStrutJacobian(*this, data);
  const double cond = scaledConditionNumber(*this, data);
  PKM_CHECK(std::isfinite(cond) && cond < 1e12,
            "the geometry is singular at the home pose (scaled Jacobian condition number {:.3g}); "
            "check for coincident or collinear joints",
            cond);
}

}  // namespace pkm::kinematics
