// Internal: the leg-length formulas of Zoppi et al. (DETC2010-28668, sec. 4.1) and their
// derivatives with respect to e = (alpha, beta, h). Shared by the Exechon IK, Jacobian and FK.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "pkm/kinematics/exechon_model.hpp"

namespace pkm::kinematics::detail {

/// True for the branch signs of the Exechon model (+1 or -1).
inline bool isUnitSign(int s) { return s == 1 || s == -1; }

/// sin/cos of alpha and beta, and h.
struct ExechonTrig {
  double sa, ca, sb, cb, h;
};

inline ExechonTrig trigOf(const Eigen::Vector3d& e) {
  return {std::sin(e[0]), std::cos(e[0]), std::sin(e[1]), std::cos(e[1]), e[2]};
}

/// Zoppi's t1, t2, t3 and the in-plane components (u, v) of legs A and C, for drawing and
/// derivatives.
struct ExechonLegTerms {
  double t1, t2, t3;
  double uA, vA, uC, vC;  ///< qL = |(uL + δL·l12L, vL)| with uL = t3 − pL·sβ − hL·cβ, vL = t2·sβ −
                          ///< pL·cβ + hL·sβ + dL
};

inline ExechonLegTerms legTerms(const ExechonTripodGeometry& g, const ExechonTrig& t) {
  ExechonLegTerms k{};
  k.t1 = g.dB * t.sa - g.pB;
  k.t2 = g.dB * t.ca * t.cb + t.h;
  k.t3 = g.dB * t.ca - k.t2 * t.cb;
  k.uA = k.t3 - g.pA * t.sb - g.hA * t.cb;
  k.vA = k.t2 * t.sb - g.pA * t.cb + g.hA * t.sb + g.dA;
  k.uC = k.t3 - g.pC * t.sb - g.hC * t.cb;
  k.vC = k.t2 * t.sb - g.pC * t.cb + g.hC * t.sb + g.dC;
  return k;
}

/// True when leg B's base joint has axis offsets (l12B or l23B non-zero): Zoppi's closed form no
/// longer holds and leg B is solved by solveLegB.
inline bool hasLegBOffsets(const ExechonTripodGeometry& g) {
  return g.l12B != 0.0 || g.l23B != 0.0;
}

/// Leg B at one e: the kB5 component s of the platform origin P = h·eh + s·kB5, leg B's length and
/// where it is measured from, and their derivatives with respect to e = (alpha, beta, h).
struct LegBSolution {
  bool ok = false;                                  ///< false: no convergence (degenerate leg)
  double s = 0.0;                                   ///< P·kB5, model length unit
  double q = 0.0;                                   ///< leg B's geometric length
  Eigen::Vector3d foot = Eigen::Vector3d::Zero();   ///< start of the length on the leg axis
  Eigen::Vector3d ds_de = Eigen::Vector3d::Zero();  ///< ds/de (only with derivatives)
  Eigen::Vector3d dq_de = Eigen::Vector3d::Zero();  ///< dq/de (only with derivatives)
};

/// Solves leg B with its base-joint offsets (docs/conventions.md, "Leg B's base-joint offsets") by
/// Newton on the angle of R2 about R1, started from Zoppi's ideal solution. With zero offsets it
/// reproduces s = −dB·cos α·sin β, q = |P5B − P1B| and foot = P1B.
[[nodiscard]] LegBSolution solveLegB(const ExechonTripodGeometry& g,
                                     const ExechonTrig& t,
                                     bool derivatives);

/// dS/de for S = hx·kA2 + (h + hz)·eh + s·kB5, given s and ds/de (Zoppi's ideal s = −dB·cα·sβ or
/// solveLegB's).
[[nodiscard]] Eigen::Matrix3d wristPointJacobian(const ExechonTripodGeometry& g,
                                                 const ExechonTrig& t,
                                                 double s,
                                                 const Eigen::Vector3d& ds_de);

/// The Zoppi-frame position S(e) + R(e)·v of a point offset by v (platform frame, model length
/// unit) from the wrist point, and (unless J_point_e is null) its derivative with respect to
/// e = (alpha, beta, h), at t. False when leg B's offset solve fails or a value is not finite.
/// Defined in exechon_ik.cpp.
[[nodiscard]] bool platformPointAt(const ExechonTripodGeometry& g,
                                   const ExechonTrig& t,
                                   const Eigen::Vector3d& v,
                                   Eigen::Vector3d* point,
                                   Eigen::Matrix3d* J_point_e);

/// Geometric leg lengths (qA, qB, qC) and, if J is not null, d(q)/d(alpha, beta, h). qB is NaN
/// when leg B's offset solve fails.
inline Eigen::Vector3d legLengths(const ExechonTripodGeometry& g,
                                  const ExechonTrig& t,
                                  int deltaA,
                                  int deltaC,
                                  Eigen::Matrix3d* J) {
  const ExechonLegTerms k = legTerms(g, t);
  const double uA = k.uA + deltaA * g.l12A, uC = k.uC + deltaC * g.l12C;
  Eigen::Vector3d q(std::sqrt(uA * uA + k.vA * k.vA),
                    std::sqrt(k.t1 * k.t1 + k.t2 * k.t2),
                    std::sqrt(uC * uC + k.vC * k.vC));
  LegBSolution legB;
  if (hasLegBOffsets(g)) {
    legB = solveLegB(g, t, J != nullptr);
    q[1] = legB.ok ? legB.q : NAN;
  }
  if (J == nullptr) return q;
  // d(t1, t2, t3) / d(alpha, beta, h).
  const double dt1[3] = {g.dB * t.ca, 0.0, 0.0};
  const double dt2[3] = {-g.dB * t.sa * t.cb, -g.dB * t.ca * t.sb, 1.0};
  const double dt3[3] = {-g.dB * t.sa - dt2[0] * t.cb, -dt2[1] * t.cb + k.t2 * t.sb, -t.cb};
  const auto leg = [&](double u, double v, double pL, double hL, double qL, int row) {
    const double du[3] = {dt3[0], dt3[1] - pL * t.cb + hL * t.sb, dt3[2]};
    const double dv[3] = {dt2[0] * t.sb, dt2[1] * t.sb + k.t2 * t.cb + pL * t.sb + hL * t.cb, t.sb};
    for (int j = 0; j < 3; ++j) (*J)(row, j) = (u * du[j] + v * dv[j]) / qL;
  };
  leg(uA, k.vA, g.pA, g.hA, q[0], 0);
  if (hasLegBOffsets(g))
    J->row(1) = legB.dq_de.transpose();
  else
    for (int j = 0; j < 3; ++j) (*J)(1, j) = (k.t1 * dt1[j] + k.t2 * dt2[j]) / q[1];
  leg(uC, k.vC, g.pC, g.hC, q[2], 2);
  return q;
}

}  // namespace pkm::kinematics::detail
