#include "pkm/simulation/unmodelled_geometry.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_data.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::simulation {

namespace kin = pkm::kinematics;

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kParallelTolerance = 1e-9;  ///< |u − (a·u)a| below this: u parallel to a
constexpr double kUnitTolerance = 1e-9;      ///< | |a| − 1 | above this: not a unit vector

/// One screw's lead error drawn from `env` (file comment of GeometryEnvironment).
ScrewLeadError drawLead(const GeometryEnvironment& env, double reference, RandomStream& rng) {
  ScrewLeadError e;
  e.reference = reference;
  e.progressive = rng.uniform(-env.lead_progressive, env.lead_progressive);
  e.wave_amplitude = env.lead_wave_mm;
  e.wave_length = env.lead_wave_length_mm;
  e.wave_phase = rng.uniform(0.0, kTwoPi);
  e.periodic_amplitude = env.lead_periodic_mm;
  e.lead = env.screw_lead_mm;
  e.periodic_phase = rng.uniform(0.0, kTwoPi);
  return e;
}

}  // namespace

double ScrewLeadError::at(double reading) const {
  return progressive * (reading - reference) +
         wave_amplitude * std::sin(kTwoPi * reading / wave_length + wave_phase) +
         periodic_amplitude * std::sin(kTwoPi * reading / lead + periodic_phase);
}

bool ScrewLeadError::isZero() const {
  return progressive == 0.0 && wave_amplitude == 0.0 && periodic_amplitude == 0.0;
}

void ScrewLeadError::validate() const {
  for (const double v :
       {progressive, reference, wave_amplitude, wave_phase, periodic_amplitude, periodic_phase})
    PKM_CHECK(std::isfinite(v), "a screw lead error value is not finite");
  PKM_CHECK(std::isfinite(wave_length) && wave_length > 0.0,
            "screw lead error: wave length {} must be > 0",
            wave_length);
  PKM_CHECK(std::isfinite(lead) && lead > 0.0, "screw lead error: lead {} must be > 0", lead);
}

Eigen::Vector3d UJointOffset::shift(const Eigen::Vector3d& u) const {
  if (offset == 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d across = u - first_axis.dot(u) * first_axis;
  const double n = across.norm();
  PKM_CHECK(n > kParallelTolerance, "U-joint: the strut is parallel to the joint's first axis");
  return offset / n * across;
}

bool HexapodUnmodelledGeometry::isZero() const {
  for (const ScrewLeadError& e : lead)
    if (!e.isZero()) return false;
  return !hasJointOffsets();
}

bool HexapodUnmodelledGeometry::hasJointOffsets() const {
  for (std::size_t i = 0; i < kin::kStruts; ++i)
    if (base_joint[i].offset != 0.0 || platform_joint[i].offset != 0.0) return true;
  return false;
}

void HexapodUnmodelledGeometry::validate() const {
  for (const ScrewLeadError& e : lead) e.validate();
  for (const auto* joints : {&base_joint, &platform_joint})
    for (const UJointOffset& j : *joints) {
      PKM_CHECK(std::isfinite(j.offset), "U-joint offset is not finite");
      PKM_CHECK(j.first_axis.allFinite() && std::abs(j.first_axis.norm() - 1.0) < kUnitTolerance,
                "U-joint first axis must be a unit vector");
    }
}

HexapodUnmodelledGeometry drawHexapodGeometry(const GeometryEnvironment& env,
                                              const kin::HexapodModel& nominal,
                                              RandomStream& rng) {
  std::string why;
  PKM_CHECK(env.isValid(&why), "geometry environment: {}", why);
  HexapodUnmodelledGeometry g;
  if (!env.enabled) return g;
  kin::HexapodData data(nominal);
  const kin::StrutVector home = kin::inverseKinematics(nominal, data, nominal.home);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    g.lead[i] = drawLead(env, home[static_cast<Eigen::Index>(i)], rng);
    // The first axis: horizontal in the platform frame, perpendicular to the strut at home.
    const Eigen::Vector3d u_platform = data.world_R_platform.transpose() * data.unit_leg[i];
    Eigen::Vector3d a = Eigen::Vector3d::UnitZ().cross(u_platform);
    a = a.norm() > kParallelTolerance ? a.normalized() : Eigen::Vector3d::UnitX();
    g.platform_joint[i].first_axis = a;
    g.platform_joint[i].offset = rng.uniform(-env.joint_axis_offset_mm, env.joint_axis_offset_mm);
  }
  return g;
}

ExechonLegLeadErrors drawLegLeadErrors(const GeometryEnvironment& env,
                                       const kin::ExechonModel& nominal,
                                       RandomStream& rng) {
  std::string why;
  PKM_CHECK(env.isValid(&why), "geometry environment: {}", why);
  ExechonLegLeadErrors out{};
  if (!env.enabled) return out;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const kin::ExechonLeg& leg = nominal.legs[i];
    const bool bounded = std::isfinite(leg.min_reading) && std::isfinite(leg.max_reading);
    out[i] = drawLead(env, bounded ? 0.5 * (leg.min_reading + leg.max_reading) : 0.0, rng);
  }
  return out;
}

kin::ExechonJoints withLeadErrors(kin::ExechonJoints joints, const ExechonLegLeadErrors& lead) {
  for (std::size_t i = 0; i < lead.size(); ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    joints.readings[k] += lead[i].at(joints.readings[k]);
  }
  return joints;
}

}  // namespace pkm::simulation
