/// @file
/// @brief Hexapod models built in code for tests that must not depend on the io module.
#pragma once

#include <cmath>
#include <numbers>
#include <random>

#include "pkm/core/units.hpp"
#include "pkm/kinematics/hexapod_model.hpp"

namespace pkm::test {

/// The LinuxCNC hexapod-sim geometry (genhexkins defaults), inches, home 0 0 20 0 0 0.
inline kinematics::HexapodModel linuxcncSimModel() {
  kinematics::HexapodModel m;
  m.name = "linuxcnc-sim";
  m.unit = LengthUnit::kInch;
  const double b[6][3] = {{-22.95, 13.25, 0},
                          {22.95, 13.25, 0},
                          {22.95, 13.25, 0},
                          {0, -26.5, 0},
                          {0, -26.5, 0},
                          {-22.95, 13.25, 0}};
  const double a[6][3] = {{-1, 11.5, 0},
                          {1, 11.5, 0},
                          {10.459, -4.884, 0},
                          {9.459, -6.616, 0},
                          {-9.459, -6.616, 0},
                          {-10.459, -4.884, 0}};
  for (int i = 0; i < 6; ++i) {
    m.struts[static_cast<std::size_t>(i)].world_p_base = {b[i][0], b[i][1], b[i][2]};
    m.struts[static_cast<std::size_t>(i)].platform_p_joint = {a[i][0], a[i][1], a[i][2]};
  }
  m.home.position = {0, 0, 20};
  return m;
}

/// A general 6-6 mm hexapod with a TCP offset, length offsets and limits (like hexapod-default).
inline kinematics::HexapodModel millingModel() {
  kinematics::HexapodModel m;
  m.name = "milling";
  const double rb = 600, rp = 250, gb = degToRad(12), gp = degToRad(15);
  for (int k = 0; k < 3; ++k) {
    const double cb = degToRad(120.0 * k + 90), cp = cb + degToRad(60), cb2 = cb + degToRad(120);
    auto& s0 = m.struts[static_cast<std::size_t>(2 * k)];
    auto& s1 = m.struts[static_cast<std::size_t>(2 * k + 1)];
    s0.world_p_base = {rb * std::cos(cb + gb), rb * std::sin(cb + gb), 1200};
    s0.platform_p_joint = {rp * std::cos(cp - gp), rp * std::sin(cp - gp), 0};
    s1.world_p_base = {rb * std::cos(cb2 - gb), rb * std::sin(cb2 - gb), 1200};
    s1.platform_p_joint = {rp * std::cos(cp + gp), rp * std::sin(cp + gp), 0};
  }
  for (auto& s : m.struts) {
    s.length_offset = 650;
    s.min_reading = 0;
    s.max_reading = 500;
    s.base_cone.axis =
        (Eigen::Vector3d(0, 0, 400) + s.platform_p_joint - s.world_p_base).normalized();
    s.platform_cone.axis = s.base_cone.axis;
    s.base_cone.max_angle = degToRad(40);
    s.platform_cone.max_angle = degToRad(45);
  }
  m.tool_offset = {0, 0, -200};
  m.strut_diameter = 80;
  m.max_condition = 200;
  m.home.position = {0, 0, 200};
  return m;
}

/// A random pose near `home`: position within ±`reach` per axis, angles within ±`tilt` rad.
inline kinematics::PoseRpy randomPose(std::mt19937& rng,
                                      const kinematics::PoseRpy& home,
                                      double reach,
                                      double tilt) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  kinematics::PoseRpy p = home;
  for (int i = 0; i < 3; ++i) p.position[i] += reach * u(rng);
  for (int i = 0; i < 3; ++i) p.rpy[i] += tilt * u(rng);
  return p;
}

}  // namespace pkm::test
