/// @file
/// @brief Test data shared by the constrained-motion and budget tests: a hexapod with random
/// parameter errors and exact dial-gauge (constrained-motion) data of it (Lee et al., "Development
/// of a Parallel-Typed CNC Machine": the platform moved parallel to the table).
#pragma once

#include <gtest/gtest.h>

#include <random>

#include "pkm/calibration/constrained_motion.hpp"
#include "pkm/calibration/hexapod_parameters.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"

namespace pkm::test {

/// `nominal` with every one of the 42 parameters moved by a uniform error in ±`error` (mm) drawn
/// from `seed`.
inline kinematics::HexapodModel perturbedModel(const kinematics::HexapodModel& nominal,
                                               unsigned seed,
                                               double error) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-error, error);
  calibration::HexapodParameterVector p = calibration::hexapodParameters(nominal);
  for (int k = 0; k < calibration::kHexapodParameters; ++k) p(k) += u(rng);
  return calibration::withHexapodParameters(nominal, p);
}

/// Exact constrained-motion data of `truth` as seen by a controller running `nominal`: the true
/// platform keeps its height `z` and tilt and moves within ±`planar` mm in x and y and ±`yaw` rad
/// about z at `stations` random stations; the controller records the readings and believes the
/// command FK_nominal(readings).
inline calibration::ConstrainedMotionData constrainedData(const kinematics::HexapodModel& nominal,
                                                          const kinematics::HexapodModel& truth,
                                                          double z,
                                                          int stations,
                                                          unsigned seed,
                                                          double planar,
                                                          double yaw) {
  calibration::ConstrainedMotionData set;
  set.gauge_points = {
      Eigen::Vector3d(100, 0, 0), Eigen::Vector3d(-50, 86.6, 0), Eigen::Vector3d(-50, -86.6, 0)};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  kinematics::HexapodData t(truth), n(nominal);
  const auto station = [&](const kinematics::PoseRpy& true_pose) {
    calibration::GaugeStation s;
    s.readings = kinematics::inverseKinematics(truth, t, true_pose);
    EXPECT_TRUE(kinematics::forwardKinematics(nominal, n, s.readings, true_pose).ok());
    s.command = n.pose;
    return s;
  };
  kinematics::PoseRpy ref = nominal.home;
  ref.position.z() = z;
  ref.rpy = Eigen::Vector3d(0.01, -0.02, 0.0);
  set.reference = station(ref);
  for (int k = 0; k < stations; ++k) {
    kinematics::PoseRpy p = ref;
    p.position.x() += planar * u(rng);
    p.position.y() += planar * u(rng);
    const Eigen::Matrix3d R =
        geometry::so3Exp(Eigen::Vector3d(0, 0, yaw * u(rng))) * geometry::rotationFromRpy(ref.rpy);
    p.rpy = geometry::rpyFromRotation(R);
    set.stations.push_back(station(p));
  }
  return set;
}

}  // namespace pkm::test
