/// @file
/// @brief Hybrid-machine fixtures for the hybrid_* tests: a model shaped like seed 000's MXT700S
/// (X2 4000 mm, Y2 450 mm; Table 1) and random PDGE tables and grids of realistic size (Table 2).
#pragma once

#include <Eigen/Core>
#include <random>
#include <vector>

#include "pkm/geometry/error_grid.hpp"
#include "pkm/geometry/error_table.hpp"
#include "pkm/kinematics/hybrid_errors.hpp"
#include "pkm/kinematics/hybrid_model.hpp"

namespace pkm::test {

/// X2 travel 4000 mm and Y2 travel 450 mm (seed 000 Table 1), measured towards negative positions
/// as in Table 2; a PKM working volume of 700 × 700 × 400 mm; no frame offsets (seed 000's choice).
inline kinematics::HybridMachineModel mxt700sLikeModel() {
  kinematics::HybridMachineModel m;
  m.name = "mxt700s-like";
  m.x2_stroke = {-4000.0, 0.0};
  m.y2_stroke = {-450.0, 0.0};
  m.pkm_min = Eigen::Vector3d(-350.0, -350.0, -100.0);
  m.pkm_max = Eigen::Vector3d(350.0, 350.0, 300.0);
  return m;
}

/// As mxt700sLikeModel with non-zero frame offsets (PKM base 800 mm above its TCP, work origin off
/// the table origin), to exercise the Abbe arms of the chain.
inline kinematics::HybridMachineModel offsetModel() {
  kinematics::HybridMachineModel m = mxt700sLikeModel();
  m.X2_p_P = Eigen::Vector3d(120.0, -40.0, 800.0);
  m.P_p_tcp0 = Eigen::Vector3d(5.0, 10.0, -800.0);
  m.Y2_p_work = Eigen::Vector3d(-300.0, 150.0, -20.0);
  return m;
}

/// A random error motion: translations uniform in ±`length` (mm), rotations in ±`angle` (rad).
inline geometry::ErrorMotion randomErrorMotion(std::mt19937& rng, double length, double angle) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  geometry::ErrorMotion e;
  for (int i = 0; i < 3; ++i) e[i] = length * u(rng);
  for (int i = 3; i < 6; ++i) e[i] = angle * u(rng);
  return e;
}

/// A six-column PDGE table over [lo, hi] with `nodes` equally spaced nodes and random values.
inline geometry::ErrorTable1d randomAxisTable(
    std::mt19937& rng, double lo, double hi, int nodes, double length, double angle) {
  std::vector<double> positions;
  std::vector<geometry::ErrorMotion> motions;
  for (int i = 0; i < nodes; ++i) {
    positions.push_back(lo + (hi - lo) * i / (nodes - 1));
    motions.push_back(randomErrorMotion(rng, length, angle));
  }
  return geometry::ErrorTable1d::fromErrorMotions(positions, motions);
}

/// A six-column PKM error grid over the model's working volume, 4 × 5 × 3 nodes, random values.
inline geometry::ErrorGrid3d randomPkmGrid(std::mt19937& rng,
                                           const kinematics::HybridMachineModel& m,
                                           double length,
                                           double angle) {
  std::array<std::vector<double>, 3> axes;
  const std::array<int, 3> counts = {4, 5, 3};
  for (int a = 0; a < 3; ++a) {
    for (int i = 0; i < counts[static_cast<std::size_t>(a)]; ++i) {
      axes[static_cast<std::size_t>(a)].push_back(m.pkm_min[a] +
                                                  (m.pkm_max[a] - m.pkm_min[a]) * i /
                                                      (counts[static_cast<std::size_t>(a)] - 1));
    }
  }
  return geometry::ErrorGrid3d::fromFunction(axes, [&](const Eigen::Vector3d&) -> Eigen::VectorXd {
    return randomErrorMotion(rng, length, angle);
  });
}

/// The squareness errors measured in seed 000 §4 (mrad → rad).
inline kinematics::HybridSquareness seedSquareness() {
  kinematics::HybridSquareness s;
  s.sz_x2 = -0.034e-3;
  s.sy_p = 4.35e-3;
  s.sx_p = -14.74e-3;
  s.sz_p = -2.85e-3;
  return s;
}

/// Realistic errors for `m`: PDGE tables on the full strokes (up to 0.08 mm and 0.1 mrad, the size
/// of seed 000 Table 2), a PKM grid (up to 0.8 mm and 1 mrad) and the seed's squareness values.
inline kinematics::GeometricErrors randomErrors(std::mt19937& rng,
                                                const kinematics::HybridMachineModel& m) {
  kinematics::GeometricErrors e;
  e.x2 = randomAxisTable(rng, m.x2_stroke.min, m.x2_stroke.max, 33, 0.08, 1e-4);
  e.y2 = randomAxisTable(rng, m.y2_stroke.min, m.y2_stroke.max, 10, 0.01, 1e-4);
  e.pkm = randomPkmGrid(rng, m, 0.8, 1e-3);
  e.squareness = seedSquareness();
  return e;
}

/// A random command within the model's strokes and working volume.
inline kinematics::HybridCommand randomCommand(std::mt19937& rng,
                                               const kinematics::HybridMachineModel& m) {
  auto uniform = [&rng](double lo, double hi) {
    return std::uniform_real_distribution<double>(lo, hi)(rng);
  };
  kinematics::HybridCommand c;
  c.x2 = uniform(m.x2_stroke.min, m.x2_stroke.max);
  c.y2 = uniform(m.y2_stroke.min, m.y2_stroke.max);
  for (int a = 0; a < 3; ++a) c.pkm[a] = uniform(m.pkm_min[a], m.pkm_max[a]);
  return c;
}

}  // namespace pkm::test
