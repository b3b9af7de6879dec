// Leg B of an Exechon whose base S joint is three revolutes with axis offsets (after
// Lopez-Custodio, Dai, Fu, Jin, J. Mech. Robot. 12(2) 021109, 2020; the parametrisation is
// docs/conventions.md "Leg B's base-joint offsets").
//
// R1 is parallel to jb through P1B; R2 has the unit direction a2 = (cos φ, 0, sin φ) ⟂ jb and
// meets the common normal with R1 at Q = P1B − l12B·(jb × a2); the leg axis ŵ is ⟂ a2 and ⟂ kB5
// (the platform revolute) and lies l23B from R2. With d = P5B − Q the two closure conditions are
//   d·a2 = 0            (the leg axis lies in the plane of R2's rotation)
//   d·kB5 = σ·n·l23B    (its offset from R2; n = |a2 × kB5|, σ = sign(d·(a2 × kB5)))
// The second gives s = P·kB5 = Q·kB5 + σ·n·l23B; the first is one equation f(φ) = 0 in φ.
#include <cmath>

#include "kinematics/exechon_tripod_math.hpp"

namespace pkm::kinematics::detail {

namespace {

constexpr int kMaxIterations = 30;
/// rad: Newton stops after a step below this (convergence is quadratic: the error left is about
/// its square).
constexpr double kAngleTolerance = 1e-12;
constexpr double kMinSine = 1e-9;  ///< |a2 × kB5| below this: degenerate leg

}  // namespace

LegBSolution solveLegB(const ExechonTripodGeometry& g, const ExechonTrig& t, bool derivatives) {
  LegBSolution out;
  const Eigen::Vector3d kA2(t.sa, 0.0, t.ca), kB5(-t.sb * t.ca, t.cb, t.sb * t.sa),
      eh(-t.cb * t.ca, -t.sb, t.cb * t.sa);
  const Eigen::Vector3d P1B(g.dB, 0.0, 0.0);
  const Eigen::Vector3d v = t.h * eh + g.pB * kA2;  // P5B = v + s·kB5
  // Zoppi's ideal leg: a2 ∥ jb × (P5B − P1B).
  const Eigen::Vector3d d0 = v - (g.dB * t.ca * t.sb) * kB5 - P1B;
  double phi = std::atan2(-d0.x(), d0.z());
  // σ: the leg direction ŵ = σ·(a2 × kB5)/n points from the base to the platform.
  const double sg =
      d0.dot(Eigen::Vector3d(std::cos(phi), 0.0, std::sin(phi)).cross(kB5)) >= 0.0 ? 1.0 : -1.0;
  // s(φ), its derivative s_φ and f_φ at φ; returns f(φ) (NaN when degenerate).
  double ax = 0, az = 0, c = 0, n = 1, s = 0, sp = 0, fp = 1;
  const auto evaluate = [&]() -> double {
    ax = std::cos(phi);
    az = std::sin(phi);
    const Eigen::Vector3d a2(ax, 0.0, az), a2p(-az, 0.0, ax);
    c = a2.dot(kB5);
    n = std::sqrt(std::max(1.0 - c * c, 0.0));
    if (!(n > kMinSine)) return std::nan("");  // leg axis along kB5
    const double cp = a2p.dot(kB5);
    s = g.dB * kB5.x() - g.l12B * (az * kB5.x() - ax * kB5.z()) + sg * g.l23B * n;
    sp = -g.l12B * c - sg * g.l23B * c * cp / n;
    fp = (v + s * kB5).dot(a2p) + sp * c + g.dB * az;
    return (v + s * kB5).dot(a2) - g.dB * ax;
  };
  bool converged = false;
  for (int it = 0; it < kMaxIterations && !converged; ++it) {
    const double f = evaluate();
    if (!std::isfinite(f) || !(std::abs(fp) > 0.0)) return out;
    const double step = f / fp;
    phi -= step;
    converged = std::abs(step) <= kAngleTolerance;
  }
  if (!converged || !std::isfinite(evaluate())) return out;
  const Eigen::Vector3d a2(ax, 0.0, az);
  const Eigen::Vector3d Q = P1B - g.l12B * Eigen::Vector3d(az, 0.0, -ax);
  const Eigen::Vector3d P5B = v + s * kB5;
  const Eigen::Vector3d d = P5B - Q;
  const double q2 = d.squaredNorm() - g.l23B * g.l23B;
  if (!(q2 > 0.0)) return out;
  out.s = s;
  out.q = std::sqrt(q2);
  const Eigen::Vector3d w = (sg / n) * a2.cross(kB5);
  out.foot = P5B - out.q * w;
  out.ok = true;
  if (!derivatives) return out;
  // Implicit differentiation: with f(φ, e) = 0 and s = s(φ, e), dφ/de = −f_e/f_φ and
  // ds/de = s_e + s_φ·dφ/de. Partials of the platform axes with respect to (alpha, beta, h):
  const Eigen::Vector3d dkB5[3] = {{t.sb * t.sa, 0.0, t.sb * t.ca}, eh, Eigen::Vector3d::Zero()};
  const Eigen::Vector3d dv[3] = {t.h * Eigen::Vector3d(t.cb * t.sa, 0.0, t.cb * t.ca) +
                                     g.pB * Eigen::Vector3d(t.ca, 0.0, -t.sa),
                                 -t.h * kB5,
                                 eh};
  for (int k = 0; k < 3; ++k) {
    const double a2dk = a2.dot(dkB5[k]);
    const double s_e = Q.dot(dkB5[k]) - sg * g.l23B * c * a2dk / n;
    const double f_e = dv[k].dot(a2) + s_e * c + s * a2dk;
    const double dphi = -f_e / fp;
    out.ds_de[k] = s_e + sp * dphi;
    // dQ/dφ = −l12B·a2 is ⟂ d, so only P5B moves the length.
    out.dq_de[k] = d.dot(dv[k] + out.ds_de[k] * kB5 + s * dkB5[k]) / out.q;
  }
  return out;
}

Eigen::Matrix3d wristPointJacobian(const ExechonTripodGeometry& g,
                                   const ExechonTrig& t,
                                   double s,
                                   const Eigen::Vector3d& ds_de) {
  // ∂α kA2 = (cα, 0, −sα), ∂α kB5 = (sβ·sα, 0, sβ·cα), ∂α eh = (cβ·sα, 0, cβ·cα);
  // ∂β kB5 = eh, ∂β eh = −kB5.
  const Eigen::Vector3d kB5(-t.sb * t.ca, t.cb, t.sb * t.sa), eh(-t.cb * t.ca, -t.sb, t.cb * t.sa);
  const Eigen::Vector3d dkA2(t.ca, 0.0, -t.sa), dkB5(t.sb * t.sa, 0.0, t.sb * t.ca),
      deh(t.cb * t.sa, 0.0, t.cb * t.ca);
  const double hh = t.h + g.hz;
  Eigen::Matrix3d J;
  J.col(0) = g.hx * dkA2 + hh * deh + ds_de[0] * kB5 + s * dkB5;
  J.col(1) = -hh * kB5 + ds_de[1] * kB5 + s * eh;
  J.col(2) = eh + ds_de[2] * kB5;
  return J;
}

}  // namespace pkm::kinematics::detail
