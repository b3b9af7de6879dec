/// @file
/// @brief A re-implementation, from a description of the algorithm (its source is LinuxCNC's
/// src/emc/kinematics/genhexkins.c), of the iteration LinuxCNC's genhexkins uses for forward
/// kinematics: Newton steps whose angular part (a world-frame rotation vector) is subtracted
/// directly from the roll-pitch-yaw angles. Used only as a baseline in tests and benchmarks ("no
/// failure where genhexkins converges", iteration counts). No LinuxCNC code.
#pragma once

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>

#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::test {

struct GenhexkinsResult {
  bool converged = false;
  int iterations = 0;
  kinematics::PoseRpy pose;
};

/// genhexkins-style FK: converged when every |residual| <= tol before the update (then one more
/// update is applied, as genhexkins does); fails beyond `limit` iterations or when sum|residual| >
/// max_error.
inline GenhexkinsResult genhexkinsStyleFk(const kinematics::HexapodModel& model,
                                          const kinematics::StrutVector& lengths,
                                          const kinematics::PoseRpy& seed,
                                          double tol = 1e-9,
                                          int limit = 120,
                                          double max_error = 500.0) {
  GenhexkinsResult out;
  Eigen::Vector3d p = seed.position, rpy = seed.rpy;
  for (int iter = 0;; ++iter) {
    const Eigen::Matrix3d R = geometry::rotationFromRpy(rpy);
    Eigen::Matrix<double, 6, 6> J;
    Eigen::Matrix<double, 6, 1> d;
    bool done = true;
    double err = 0.0;
    for (int i = 0; i < 6; ++i) {
      const Eigen::Vector3d ra = R * model.effectivePlatform(i);
      const Eigen::Vector3d s = p + ra - model.effectiveBase(i);
      const double len = s.norm();
      const Eigen::Vector3d u = s / len;
      J.block<1, 3>(i, 0) = u.transpose();
      J.block<1, 3>(i, 3) = ra.cross(u).transpose();
      d[i] = len - model.struts[static_cast<std::size_t>(i)].length_offset - lengths[i];
      err += std::abs(d[i]);
      if (std::abs(d[i]) > tol) done = false;
    }
    if (!std::isfinite(err) || err > max_error || iter > limit) return out;
    const Eigen::Matrix<double, 6, 1> delta = J.partialPivLu().solve(d);
    p -= delta.head<3>();
    rpy -= delta.tail<3>();
    out.iterations = iter + 1;
    if (done) {
      out.converged = true;
      out.pose.position = p;
      out.pose.rpy = rpy;
      return out;
    }
  }
}

}  // namespace pkm::test
