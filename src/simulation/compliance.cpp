#include "pkm/simulation/compliance.hpp"

#include <Eigen/LU>
#include <cmath>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"

namespace pkm::simulation {

namespace {

constexpr double kSingular = 1e-12;  // |det J| below which the statics have no solution
constexpr double kLegStepMm = 0.01;  // central-difference step of a leg reading

/// Height of the head's centre of mass at the tool FK for `joints`, mm.
double comHeight(const kinematics::ExechonModel& model,
                 kinematics::ExechonData& data,
                 const kinematics::ExechonJoints& joints,
                 const kinematics::ExechonConfiguration& seed,
                 const kinematics::FkOptions& fk,
                 const Eigen::Vector3d& com) {
  const kinematics::FkSummary s = kinematics::toolForwardKinematics(model, data, joints, seed, fk);
  PKM_CHECK(s.ok(),
            "Exechon compliance: the tool FK does not converge ({})",
            kinematics::toString(s.status));
  return (data.world_p_tool + data.world_R_tool * com).z();
}

/// The sag motion S (work frame): rotation φ about `pivot`, then the drop.
geometry::RigidTransform sagMotion(const AxisDeflection& d,
                                   const Eigen::Vector3d& direction,
                                   const Eigen::Vector3d& pivot) {
  const Eigen::Vector3d across = Eigen::Vector3d::UnitZ().cross(direction.normalized());
  const geometry::RigidTransform turn = geometry::translationTransform(pivot) *
                                        geometry::rotationTransform(d.slope_rad * across) *
                                        geometry::translationTransform(-pivot);
  return geometry::translationTransform(-d.sag_mm * across.norm() * Eigen::Vector3d::UnitZ()) *
         turn;
}

}  // namespace

AxisDeflection axisDeflection(const AxisSag& sag, double command_mm) {
  std::string why;
  PKM_CHECK(sag.isValid(&why), "axis sag: {}", why);
  PKM_CHECK(std::isfinite(command_mm), "axis command {} is not finite", command_mm);
  const double x = sag.zero_mm + sag.sense * command_mm;  // overhang or load position
  const double L = sag.length_mm;
  switch (sag.kind) {
    case AxisSag::Kind::kNone:
      return {};
    case AxisSag::Kind::kCantilever: {
      if (x <= 0.0) return {};
      const double delta = sag.sag_mm * std::pow(x / L, 3);
      return {delta, 1.5 * delta / x};
    }
    case AxisSag::Kind::kSpan: {
      if (x <= 0.0 || x >= L) return {};
      const double b = L - x;
      const double L4 = L * L * L * L;
      return {sag.sag_mm * 16.0 * x * x * b * b / L4, sag.sag_mm * 16.0 * x * b * (b - x) / L4};
    }
  }
  return {};
}

geometry::RigidTransform sagCarryingTool(const geometry::RigidTransform& pose,
                                         const AxisDeflection& d,
                                         const Eigen::Vector3d& direction,
                                         const Eigen::Vector3d& pivot) {
  if (d.sag_mm == 0.0 && d.slope_rad == 0.0) return pose;
  return sagMotion(d, direction, pivot) * pose;
}

geometry::RigidTransform sagCarryingWork(const geometry::RigidTransform& pose,
                                         const AxisDeflection& d,
                                         const Eigen::Vector3d& direction,
                                         const Eigen::Vector3d& pivot) {
  if (d.sag_mm == 0.0 && d.slope_rad == 0.0) return pose;
  return sagMotion(d, direction, pivot).inverse() * pose;
}

kinematics::StrutVector hexapodStrutLoads(const kinematics::HexapodModel& model,
                                          const kinematics::HexapodData& data,
                                          const HexapodCompliance& compliance) {
  std::string why;
  PKM_CHECK(compliance.isValid(&why), "hexapod compliance: {}", why);
  const Eigen::Vector3d g(0.0, 0.0, -kStandardGravity);  // m/s², world −z
  const Eigen::Vector3d share = compliance.strut_com_fraction * compliance.strut_mass_kg * g;
  // The centre of mass relative to the TCP, as effectivePlatform places the joints.
  Eigen::Vector3d com = compliance.platform_com_mm - model.tool_offset;
  com.z() += model.spindle_offset;
  const Eigen::Vector3d weight = compliance.platform_mass_kg * g;
  Eigen::Vector3d force = weight;
  Eigen::Vector3d moment = (data.world_R_platform * com).cross(weight) * 1e-3;  // N·m
  kinematics::Matrix6d A;
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Eigen::Vector3d& u = data.unit_leg[k];
    const Eigen::Vector3d r = data.world_r_joint[k] * 1e-3;  // m
    A.block<3, 1>(0, i) = u;
    A.block<3, 1>(3, i) = r.cross(u);
    force += share;
    moment += r.cross(share);
  }
  Eigen::Matrix<double, 6, 1> w;
  w << force, moment;
  const Eigen::PartialPivLU<kinematics::Matrix6d> lu(A);
  PKM_CHECK(std::abs(lu.determinant()) > kSingular,
            "the hexapod's strut Jacobian is singular: no static equilibrium");
  return lu.solve(-w);
}

Eigen::Vector3d exechonLegLoads(const kinematics::ExechonModel& model,
                                const kinematics::ExechonJoints& joints,
                                const kinematics::ExechonConfiguration& seed,
                                const kinematics::FkOptions& fk,
                                const ExechonCompliance& compliance) {
  std::string why;
  PKM_CHECK(compliance.isValid(&why), "Exechon compliance: {}", why);
  kinematics::ExechonData data(model);
  Eigen::Vector3d loads;
  for (Eigen::Index i = 0; i < 3; ++i) {
    kinematics::ExechonJoints plus = joints, minus = joints;
    plus.readings[i] += kLegStepMm;
    minus.readings[i] -= kLegStepMm;
    const double dz = comHeight(model, data, plus, seed, fk, compliance.head_com_mm) -
                      comHeight(model, data, minus, seed, fk, compliance.head_com_mm);
    loads[i] = compliance.head_mass_kg * kStandardGravity * dz / (2.0 * kLegStepMm);
  }
  return loads;
}

kinematics::ExechonJoints exechonDeflectedJoints(const kinematics::ExechonModel& model,
                                                 const kinematics::ExechonJoints& joints,
                                                 const kinematics::ExechonConfiguration& seed,
                                                 const kinematics::FkOptions& fk,
                                                 const ExechonCompliance& compliance) {
  const Eigen::Vector3d loads = exechonLegLoads(model, joints, seed, fk, compliance);
  kinematics::ExechonJoints out = joints;
  for (Eigen::Index i = 0; i < 3; ++i) {
    int side = 1;
    out.readings[i] += legDeflection(
        loads[i], compliance.leg_stiffness_n_per_um, compliance.joint_clearance_mm, side);
  }
  return out;
}

double legDeflection(double load_n, double stiffness_n_per_um, double clearance_mm, int& side) {
  if (load_n > 0.0) side = 1;
  if (load_n < 0.0) side = -1;
  return -load_n / (1000.0 * stiffness_n_per_um) - clearance_mm * side;
}

}  // namespace pkm::simulation
