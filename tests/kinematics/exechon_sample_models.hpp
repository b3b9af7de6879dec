/// @file
/// @brief Exechon models built in code for the exechon_* tests and the benchmark.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <numbers>

#include "pkm/kinematics/exechon_ik.hpp"
#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::test {

/// Zoppi, Zlatanov, Molfino (DETC2010-28668) Table 1, in mm (the paper's metres × 1000). World
/// frame = Zoppi frame, no wrist tool; home e is the (+,+) solution for the paper's S = (20, 700,
/// 1020).
inline kinematics::ExechonModel zoppiTable1Model() {
  kinematics::ExechonModel m;
  m.name = "zoppi-table1";
  auto& g = m.tripod;
  g.dA = -443.4, g.dB = 345.5, g.dC = 779.8, g.l12A = 102.3, g.l12C = 152.3;
  g.pA = -152.3, g.pB = 132.4, g.pC = 252.3, g.hA = 40.0, g.hC = 23.0, g.hz = -200.0, g.hx = 282.8;
  kinematics::parametersFromWristPoint(g, Eigen::Vector3d(20, 700, 1020), 1, 1, &m.home.e);
  return m;
}

/// The exechon-lib toy geometry (the Bi/Jin form, reconstructed from the MIT-licensed exechon-lib
/// model and checked against Zoppi), mm, in Zoppi's form: the world frame is the Bi/Jin base frame
/// (x = A/C axis, y towards leg 2's base joint, z up), Zoppi's (ib, jb, kb) = world (y, x, −z). The
/// wrist is exechon-lib's T_pl·RotZ(q4)·Trans(0,0,L1)·RotX(q5)·Trans(0,L2,0): C about z' = k, A
/// about x' = j, tool along y of the A frame (a0 = −pi/2), tool_length = L2 = 150.
inline kinematics::ExechonModel biJinToyModel() {
  kinematics::ExechonModel m;
  m.name = "bi-jin-toy";
  auto& g = m.tripod;
  g.dA = -85, g.dB = 100, g.dC = 85, g.pA = -65, g.pB = -65, g.pC = 65, g.hz = 125;
  Eigen::Matrix3d R;
  R << 0, 1, 0,  //
      1, 0, 0,   //
      0, 0, -1;
  m.world_T_zoppi.linear() = R;
  m.wrist.c_axis = Eigen::Vector3d::UnitZ();
  m.wrist.a_axis = Eigen::Vector3d::UnitY();
  m.wrist.a0 = -std::numbers::pi / 2;
  m.wrist.tool_length = 150;
  kinematics::parametersFromWristPoint(g, Eigen::Vector3d(-30, 15, -374.5), 1, 1, &m.home.e);
  return m;
}

/// A machine-like model: Zoppi's tripod (mm) with a C/A wrist (C about the platform k, A about i),
/// a 250 mm tool, length offsets, strokes and angle limits. The world frame has z up with the tool
/// pointing down (−z) at home, and the home tool point at the world origin.
inline kinematics::ExechonModel machineModel() {
  kinematics::ExechonModel m = zoppiTable1Model();
  m.name = "exechon-machine";
  m.wrist.tool_length = 250;
  m.wrist.c_sign = -1;
  m.wrist.a0 = 0.05;
  m.home.a = 0.3;
  m.home.c = 0.2;
  m.legs[0] = {1000, 300, 900};
  m.legs[1] = {1000, 200, 800};
  m.legs[2] = {500, 150, 700};
  m.limits.alpha = {degToRad(40), degToRad(110)};
  m.limits.beta = {degToRad(-70), degToRad(5)};
  m.limits.c = {degToRad(-360), degToRad(360)};
  m.limits.a = {degToRad(-100), degToRad(100)};
  // World: the home platform k (tool direction at C = A = 0) is world −z.
  kinematics::ExechonData data(m);
  kinematics::evaluateTripod(m, data, m.home.e, 1, 1);
  const Eigen::Matrix3d zoppi_R_platform = data.zoppi_T_platform.linear();
  Eigen::Matrix3d world_R_platform;
  world_R_platform << 1, 0, 0, 0, -1, 0, 0, 0, -1;  // platform i -> x, j -> -y, k -> -z
  m.world_T_zoppi.linear() = world_R_platform * zoppi_R_platform.transpose();
  const Eigen::Vector3d tool = data.zoppi_p_S + m.wrist.tool_length * zoppi_R_platform.col(2);
  m.world_T_zoppi.translation() = -(m.world_T_zoppi.linear() * tool);
  return m;
}

/// The Bi/Jin P-form (the Bi/Jin form, reconstructed from the MIT-licensed exechon-lib model and
/// checked against Zoppi, reconstructed from exechon-lib) for the toy geometry of biJinToyModel:
/// platform angles, platform rotation R = Rx(alpha)·Ry(beta) (columns x', y', z'), leg lengths and
/// the wrist point S = P + L1·z', all in the Bi/Jin (world) frame.
struct BiJin {
  double alpha, beta;
  Eigen::Matrix3d R;
  Eigen::Vector3d q, S;
};
inline BiJin biJinInverse(const Eigen::Vector3d& P) {
  const Eigen::Vector3d A1(-85, 0, 0), A2(0, 100, 0), A3(85, 0, 0);
  const double b1 = 65, b3 = 65, de = 65, L1 = 125;
  BiJin out{};
  out.alpha = std::atan2(-P.y(), P.z());
  out.beta =
      std::atan2(P.x() - A2.x(),
                 (P.z() - A2.z()) * std::cos(out.alpha) - (P.y() - A2.y()) * std::sin(out.alpha));
  out.R = (Eigen::AngleAxisd(out.alpha, Eigen::Vector3d::UnitX()) *
           Eigen::AngleAxisd(out.beta, Eigen::Vector3d::UnitY()))
              .toRotationMatrix();
  out.q = {(P + out.R * Eigen::Vector3d(-b1, 0, 0) - A1).norm(),
           (P + out.R * Eigen::Vector3d(0, de, 0) - A2).norm(),
           (P + out.R * Eigen::Vector3d(b3, 0, 0) - A3).norm()};
  out.S = P + out.R * Eigen::Vector3d(0, 0, L1);
  return out;
}

}  // namespace pkm::test
