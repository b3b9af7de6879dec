#include "pkm/simulation/dial_gauges.hpp"

#include <Eigen/LU>
#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/pose_rpy.hpp"

namespace pkm::simulation {

namespace {

constexpr Eigen::Index kZ = 2;     // command index of z
constexpr double kStepMm = 1e-3;   // central-difference step for z, mm
constexpr double kStepRad = 1e-6;  // and for a, b, rad

/// The heights of the three tips along the normal for `pose`.
Eigen::Vector3d heights(const DialGaugeSetup& s, const geometry::RigidTransform& pose) {
  Eigen::Vector3d h;
  for (Eigen::Index k = 0; k < 3; ++k)
    h[k] = s.table_normal.normalized().dot(pose * s.gauge_points[static_cast<std::size_t>(k)]);
  return h;
}

/// The pose a command stands for (commands are poses of the nominal model).
geometry::RigidTransform commandPose(const Eigen::VectorXd& command) {
  return kinematics::toRigidTransform({command.head<3>(), command.tail<3>()});
}

/// The sensitivity of the heights to (z, a, b) of `command`, central differences.
Eigen::Matrix3d sensitivity(const DialGaugeSetup& setup, const Eigen::VectorXd& command) {
  Eigen::Matrix3d S;
  for (Eigen::Index c = 0; c < 3; ++c) {
    const double h = c == 0 ? kStepMm : kStepRad;
    Eigen::VectorXd plus = command, minus = command;
    plus[kZ + c] += h;
    minus[kZ + c] -= h;
    S.col(c) = (heights(setup, commandPose(plus)) - heights(setup, commandPose(minus))) / (2 * h);
  }
  return S;
}

/// A move that approaches as the set-up says; the commanded readings of the last move.
kinematics::StrutVector approachTo(ConstrainedMotionRig& rig,
                                   const DialGaugeSetup& setup,
                                   const Eigen::VectorXd& command) {
  if (setup.approach > 0.0) {
    Eigen::VectorXd below = command;
    below[kZ] -= setup.approach;
    (void)rig.moveTo(below);
  }
  return rig.moveTo(command);
}

/// The virtual machine as a rig: its gauges read the true tips' heights, with noise.
class VirtualRig final : public ConstrainedMotionRig {
 public:
  VirtualRig(HexapodVirtualMachine& m, const DialGaugeSetup& s, RandomStream& rng)
      : machine_(m), setup_(s), rng_(rng) {}
  kinematics::StrutVector moveTo(const Eigen::VectorXd& command) override {
    pose_ = machine_.moveTo(command);
    return machine_.commandedReadings();
  }
  void zeroGauges() override { zero_ = heights(setup_, pose_); }
  Eigen::Vector3d readGauges() override {
    const Eigen::Vector3d truth = heights(setup_, pose_) - zero_;
    Eigen::Vector3d r;
    for (Eigen::Index k = 0; k < 3; ++k) r[k] = setup_.noise.apply(truth[k], 0.0, rng_);
    return r;
  }

 private:
  HexapodVirtualMachine& machine_;
  const DialGaugeSetup& setup_;
  RandomStream& rng_;
  geometry::RigidTransform pose_;
  Eigen::Vector3d zero_ = Eigen::Vector3d::Zero();
};

}  // namespace

void DialGaugeSetup::validate() const {
  PKM_CHECK(reference.size() == 6 && reference.allFinite(),
            "{}: the reference must be 6 finite values",
            name);
  const Eigen::Vector3d area =
      (gauge_points[1] - gauge_points[0]).cross(gauge_points[2] - gauge_points[0]);
  PKM_CHECK(area.norm() > 1e-6, "{}: the three gauges are collinear", name);
  PKM_CHECK(table_normal.allFinite() && table_normal.norm() > 1e-12,
            "{}: the table normal is zero",
            name);
  PKM_CHECK(tolerance > 0.0, "{}: the tolerance must be > 0", name);
  PKM_CHECK(max_iterations >= 1, "{}: max_iterations must be >= 1", name);
  PKM_CHECK(approach >= 0.0 && std::isfinite(approach), "{}: the approach must be >= 0", name);
  for (const Eigen::Vector3d& st : stations)
    PKM_CHECK(st.allFinite(), "{}: a station is not finite", name);
  noise.validate();
}

std::vector<DialGaugeStation> runConstrainedMotion(
    ConstrainedMotionRig& rig,
    const DialGaugeSetup& setup,
    const std::function<void(const DialGaugeStation&)>& on_station) {
  setup.validate();
  std::vector<DialGaugeStation> out;
  DialGaugeStation ref;
  ref.command = setup.reference;
  ref.lengths = approachTo(rig, setup, setup.reference);
  rig.zeroGauges();
  ref.iterations = 1;
  ref.converged = true;
  out.push_back(ref);
  if (on_station) on_station(ref);
  for (std::size_t j = 0; j < setup.stations.size(); ++j) {
    DialGaugeStation st;
    st.station = static_cast<int>(j) + 1;
    st.command = setup.reference;
    st.command[0] += setup.stations[j][0];
    st.command[1] += setup.stations[j][1];
    st.command[5] += setup.stations[j][2];
    while (true) {
      st.lengths = approachTo(rig, setup, st.command);
      const Eigen::Vector3d r = rig.readGauges();
      ++st.iterations;
      st.readings = {r[0], r[1], r[2]};
      st.converged = r.cwiseAbs().maxCoeff() <= setup.tolerance;
      if (st.converged || st.iterations >= setup.max_iterations) break;
      st.command.segment<3>(kZ) -= sensitivity(setup, st.command).partialPivLu().solve(r);
    }
    out.push_back(st);
    if (on_station) on_station(st);
  }
  return out;
}

std::vector<DialGaugeStation> simulateDialGauges(HexapodVirtualMachine& machine,
                                                 const DialGaugeSetup& setup,
                                                 RandomStream& rng) {
  setup.validate();
  machine.reset(rng.bits());
  VirtualRig rig(machine, setup, rng);
  return runConstrainedMotion(rig, setup);
}

}  // namespace pkm::simulation
