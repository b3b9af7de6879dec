#include "pkm/simulation/exechon_tracker.hpp"

#include <Eigen/LU>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/simulation/compliance.hpp"

namespace pkm::simulation {
namespace {

constexpr double kRigid = 1e-9;        // |RᵀR − I| of a rigid placement
constexpr int kDrawsPerReading = 200;  // rejection-sampling budget

/// A unit vector uniform over the spherical cap of half-angle `tilt` about the unit `axis`.
Eigen::Vector3d capDirection(const Eigen::Vector3d& axis, double tilt, RandomStream& rng) {
  const double cos_t = 1.0 - rng.uniform() * (1.0 - std::cos(tilt));
  const double sin_t = std::sqrt(std::max(0.0, 1.0 - cos_t * cos_t));
  const double phi = rng.uniform(0.0, 2.0 * std::numbers::pi);
  const Eigen::Vector3d u = axis.unitOrthogonal();
  const Eigen::Vector3d v = axis.cross(u);
  return cos_t * axis + sin_t * (std::cos(phi) * u + std::sin(phi) * v);
}

}  // namespace

void ExechonTrackerSetup::validate() const {
  PKM_CHECK(!name.empty(), "an Exechon tracker measurement needs a name");
  PKM_CHECK(count >= 1, "{}: the pose count {} must be >= 1", name, count);
  PKM_CHECK(
      box_min.allFinite() && box_max.allFinite() && (box_min.array() <= box_max.array()).all(),
      "{}: the tool-point box must be finite with min <= max",
      name);
  PKM_CHECK(direction.allFinite() && direction.norm() > 0.0, "{}: zero tool direction", name);
  PKM_CHECK(std::isfinite(max_tilt) && max_tilt >= 0.0 && max_tilt <= std::numbers::pi / 2,
            "{}: the tilt must lie in [0, 90] deg",
            name);
  PKM_CHECK(smr_offset.allFinite(), "{}: the SMR offset is not finite", name);
  const Eigen::Matrix3d R = world_T_tracker.linear();
  PKM_CHECK(world_T_tracker.matrix().allFinite() &&
                (R.transpose() * R - Eigen::Matrix3d::Identity()).norm() < kRigid &&
                R.determinant() > 0.0,
            "{}: the tracker placement is not a rigid transform",
            name);
  noise.validate();
}

std::vector<ExechonTrackerReading> simulateExechonTracker(const kinematics::ExechonModel& nominal,
                                                          const kinematics::ExechonModel& actual,
                                                          const kinematics::FkOptions& fk,
                                                          const ExechonTrackerSetup& setup,
                                                          RandomStream& rng,
                                                          const ExechonCompliance* compliance,
                                                          const ExechonLegLeadErrors& leg_lead) {
  setup.validate();
  nominal.validate();
  actual.validate();
  const Eigen::Vector3d axis = setup.direction.normalized();
  kinematics::ExechonData nom(nominal), act(actual);
  const geometry::RigidTransform tracker_T_world = setup.world_T_tracker.inverse();
  std::vector<ExechonTrackerReading> out;
  out.reserve(static_cast<std::size_t>(setup.count));
  const long budget = static_cast<long>(kDrawsPerReading) * setup.count;
  long draws = 0;
  while (static_cast<int>(out.size()) < setup.count) {
    PKM_CHECK(draws++ < budget,
              "{}: only {} of {} commands lie within the nominal machine's limits after {} draws; "
              "shrink the box or the tilt",
              setup.name,
              out.size(),
              setup.count,
              budget);
    kinematics::ExechonToolPose command;
    for (int k = 0; k < 3; ++k)
      command.position(k) = rng.uniform(setup.box_min(k), setup.box_max(k));
    command.direction =
        setup.max_tilt > 0.0 ? capDirection(axis, setup.max_tilt, rng) : Eigen::Vector3d(axis);
    if (!kinematics::checkToolPose(nominal, nom, command).ok()) continue;
    ExechonTrackerReading r;
    r.command = command;
    r.joints = kinematics::jointsOf(nom);
    const kinematics::ExechonConfiguration seed = kinematics::configurationOf(nom);
    const kinematics::ExechonJoints travelled = withLeadErrors(r.joints, leg_lead);
    const kinematics::ExechonJoints reached =
        compliance != nullptr ? exechonDeflectedJoints(actual, travelled, seed, fk, *compliance)
                              : travelled;
    const kinematics::FkSummary s =
        kinematics::toolForwardKinematics(actual, act, reached, seed, fk);
    PKM_CHECK(s.ok(),
              "{}: the true machine's FK does not converge at command {} ({})",
              setup.name,
              out.size() + 1,
              kinematics::toString(s.status));
    const Eigen::Vector3d world_p_smr = act.world_p_tool + act.world_R_tool * setup.smr_offset;
    r.truth = tracker_T_world * world_p_smr;
    r.measured = setup.noise.point(r.truth, rng);
    out.push_back(r);
  }
  return out;
}

}  // namespace pkm::simulation
