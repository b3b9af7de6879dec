/// @file
/// @brief Shared by the hexapod calibration tests (hexapod_calibration_test.cpp,
/// hexapod_calibration_convergence_test.cpp): a true machine with seeded errors on all 42
/// parameters, pose observations of it (exact or with tracker noise), and the held-out TCP error.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "pkm/calibration/hexapod_calibration.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkm/kinematics/pose_rpy.hpp"
#include "pkm/simulation/hexapod_virtual_machine.hpp"
#include "pkm/simulation/laser_tracker.hpp"
#include "support/sample_models.hpp"

namespace pkm::test {

inline constexpr double kJointError = 0.5;      ///< mm, amplitude of injected joint position errors
inline constexpr double kOffsetError = 1.0;     ///< mm, amplitude of injected length-offset errors
inline constexpr double kReach = 120.0;         ///< mm, pose sampling half-range
inline constexpr double kTilt = 0.12;           ///< rad, pose sampling half-range
inline constexpr double kTrackerSigma = 0.005;  ///< mm, tracker position noise
inline constexpr double kTrackerAngleSigma = 5e-6;  ///< rad, 6-DOF probe orientation noise
inline constexpr double kNoiseFactor = 3.0;         ///< held-out error ≤ kNoiseFactor × noise

/// The milling model with seeded random errors on all 42 parameters.
inline kinematics::HexapodModel trueMachine(unsigned seed) {
  const kinematics::HexapodModel nominal = millingModel();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  calibration::HexapodParameterVector p = calibration::hexapodParameters(nominal);
  for (int k = 0; k < calibration::kHexapodParameters; ++k)
    p(k) += (k % calibration::kParametersPerStrut == 6 ? kOffsetError : kJointError) * u(rng);
  return calibration::withHexapodParameters(nominal, p);
}

/// Poses measured on `truth`: readings from its IK, pose with Gaussian noise.
inline std::vector<calibration::PoseObservation> measurePoses(const kinematics::HexapodModel& truth,
                                                              int count,
                                                              unsigned seed,
                                                              double sigma,
                                                              double angle_sigma) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  kinematics::HexapodData data(truth);
  std::vector<calibration::PoseObservation> out;
  for (int k = 0; k < count; ++k) {
    const kinematics::PoseRpy pose = randomPose(rng, truth.home, kReach, kTilt);
    calibration::PoseObservation o;
    o.readings = kinematics::inverseKinematics(truth, data, pose);
    o.pose = pose;
    for (int i = 0; i < 3; ++i) o.pose.position[i] += sigma * n(rng);
    for (int i = 0; i < 3; ++i) o.pose.rpy[i] += angle_sigma * n(rng);
    out.push_back(o);
  }
  return out;
}

/// Largest TCP position error of `model`'s FK against exact poses of `truth` (held-out check).
inline double maxTcpError(const kinematics::HexapodModel& model,
                          const kinematics::HexapodModel& truth,
                          unsigned seed) {
  const auto poses = measurePoses(truth, 50, seed, 0.0, 0.0);
  kinematics::HexapodData data(model);
  double worst = 0.0;
  for (const calibration::PoseObservation& o : poses) {
    const auto e = calibration::forwardPoseError(model, data, o.readings, o.pose, o.pose);
    EXPECT_TRUE(e.has_value());
    if (e) worst = std::max(worst, e->head<3>().norm());
  }
  return worst;
}

/// The per-strut backlash of backlashMachine(), mm.
inline kinematics::StrutVector trueBacklash() {
  kinematics::StrutVector b;
  b << 0.03, 0.05, 0.02, 0.04, 0.06, 0.01;
  return b;
}

/// The milling model with seeded assembly errors and the backlash trueBacklash(): the true
/// machine of the backlash tests.
inline simulation::HexapodVirtualMachine backlashMachine() {
  simulation::HexapodAssemblyErrors errors;
  for (int i = 0; i < kinematics::kStruts; ++i) {
    const double s = i % 2 ? -1.0 : 1.0;
    errors.base_joint[static_cast<std::size_t>(i)] = Eigen::Vector3d(0.5 * s, -0.4, 0.2 * i);
    errors.platform_joint[static_cast<std::size_t>(i)] = Eigen::Vector3d(-0.3, 0.2 * s, 0.1);
    errors.length_offset[i] = 0.6 * s;
  }
  simulation::StrutActuation act;
  act.backlash = trueBacklash();
  return simulation::HexapodVirtualMachine(millingModel(), errors, act);
}

/// Tracker poses at `count` random poses of the backlash tests' box, in the order the machine
/// moves to them (so that each strut approaches from either side).
inline simulation::TrackerSetup bidirectionalSetup(const std::string& name, int count) {
  simulation::TrackerSetup setup;
  setup.name = name;
  setup.mode = simulation::TrackerMode::kPose;
  setup.random_count = count;
  setup.random_box.lo << -150, -150, 150, -0.15, -0.15, -0.3;
  setup.random_box.hi << 150, 150, 280, 0.15, 0.15, 0.3;
  return setup;
}

}  // namespace pkm::test
