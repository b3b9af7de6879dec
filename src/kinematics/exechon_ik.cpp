#include "pkm/kinematics/exechon_ik.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "kinematics/exechon_tripod_math.hpp"
#include "pkm/core/error.hpp"

namespace pkm::kinematics {

namespace {

/// Relative size below which r or sqrt(t6² + Sy²) counts as zero (the solution is undetermined).
constexpr double kDegenerate = 1e-12;
/// Leg B's offsets: the IK refinement stops when |S(e) − S| is below this × the closed form's
/// scale, or fails after kMaxRefineIterations Newton steps.
constexpr double kRefineTolerance = 1e-13;
constexpr int kMaxRefineIterations = 20;
/// Rounding allowance when a squared chord bounds a branch distance from below (both are sums of
/// products of unit-circle coordinates, exact to a few ulps).
constexpr double kChordRounding = 1e-12;

}  // namespace

std::string_view toString(ExechonIkStatus status) {
  switch (status) {
    case ExechonIkStatus::kOk:
      return "ok";
    case ExechonIkStatus::kUnreachable:
      return "unreachable";
    case ExechonIkStatus::kSingular:
      return "singular";
    case ExechonIkStatus::kInvalidInput:
      return "invalid_input";
  }
  return "unknown";
}

namespace {

/// s = P·kB5 at e and, if ds_de is not null, ds/de: Zoppi's −dB·cos α·sin β, or leg B's offset
/// solve (NaN when it fails).
double platformOffsetB(const ExechonTripodGeometry& g,
                       const detail::ExechonTrig& t,
                       Eigen::Vector3d* ds_de = nullptr) {
  if (!detail::hasLegBOffsets(g)) {
    if (ds_de != nullptr) *ds_de = {g.dB * t.sa * t.sb, -g.dB * t.ca * t.cb, 0.0};
    return -g.dB * t.ca * t.sb;
  }
  const detail::LegBSolution b = detail::solveLegB(g, t, ds_de != nullptr);
  if (ds_de != nullptr) *ds_de = b.ok ? b.ds_de : Eigen::Vector3d::Constant(NAN);
  return b.ok ? b.s : NAN;
}

Eigen::Vector3d wristPoint(const ExechonTripodGeometry& g, const detail::ExechonTrig& t, double s) {
  const Eigen::Vector3d kA2(t.sa, 0.0, t.ca), kB5(-t.sb * t.ca, t.cb, t.sb * t.sa),
      eh(-t.cb * t.ca, -t.sb, t.cb * t.sa);
  return g.hx * kA2 + (t.h + g.hz) * eh + s * kB5;
}

}  // namespace

Eigen::Vector3d wristPointFromParameters(const ExechonTripodGeometry& g, const Eigen::Vector3d& e) {
  const detail::ExechonTrig t = detail::trigOf(e);
  return wristPoint(g, t, platformOffsetB(g, t));
}

namespace {

/// The part of Zoppi's closed form shared by the four pose branches: |(Sx, Sz)|², r and a scale.
struct TrigCommon {
  double t0sq, r, scale;
};

ExechonIkStatus trigCommon(const ExechonTripodGeometry& g,
                           const Eigen::Vector3d& S,
                           TrigCommon* out) {
  if (!S.allFinite()) return ExechonIkStatus::kInvalidInput;
  const double t0sq = S.x() * S.x() + S.z() * S.z();
  const double rsq = t0sq - g.hx * g.hx;
  const double scale = std::max({std::sqrt(t0sq), std::abs(S.y()), std::abs(g.dB), std::abs(g.hx)});
  if (rsq < 0.0 && std::sqrt(-rsq) > kDegenerate * scale) return ExechonIkStatus::kUnreachable;
  const double r = std::sqrt(std::max(rsq, 0.0));
  if (r <= kDegenerate * scale) return ExechonIkStatus::kSingular;
  *out = {t0sq, r, scale};
  return ExechonIkStatus::kOk;
}

/// Zoppi's closed form without the angles: sin/cos of alpha and beta and h for δ1B = d1 and both
/// δ2B (out[0] for δ2B = +1, out[1] for -1).
ExechonIkStatus solveTrigD1(const ExechonTripodGeometry& g,
                            const Eigen::Vector3d& S,
                            const TrigCommon& c,
                            int d1,
                            detail::ExechonTrig out[2]) {
  const double r = c.r, t0sq = c.t0sq;
  const double ca = (-d1 * S.x() * r + g.hx * S.z()) / t0sq;
  const double sa = (d1 * S.z() * r + g.hx * S.x()) / t0sq;
  const double t6 = (d1 * (t0sq - g.dB * S.x()) * r + g.dB * g.hx * S.z()) / t0sq;
  const double n = std::sqrt(t6 * t6 + S.y() * S.y());
  if (!(n > kDegenerate * c.scale)) return ExechonIkStatus::kSingular;
  const double sb = -S.y() / n, cb = t6 / n, hn = (S.y() * S.y() + d1 * t6 * r) / n;
  out[0] = {sa, ca, sb, cb, hn - g.hz};
  out[1] = {sa, ca, -sb, -cb, -hn - g.hz};
  if (!std::isfinite(sa + ca + sb + cb + hn)) return ExechonIkStatus::kInvalidInput;
  return ExechonIkStatus::kOk;
}

/// Newton steps on e from Zoppi's ideal solution `t` until the forward map with leg B's offsets
/// reaches S (a no-op without offsets). kSingular when it does not converge.
ExechonIkStatus refineForLegB(const ExechonTripodGeometry& g,
                              const Eigen::Vector3d& S,
                              double scale,
                              detail::ExechonTrig* t) {
  if (!detail::hasLegBOffsets(g)) return ExechonIkStatus::kOk;
  Eigen::Vector3d e(std::atan2(t->sa, t->ca), std::atan2(t->sb, t->cb), t->h);
  for (int it = 0; it < kMaxRefineIterations; ++it) {
    const detail::LegBSolution b = detail::solveLegB(g, *t, true);
    if (!b.ok) return ExechonIkStatus::kSingular;
    const Eigen::Vector3d r = wristPoint(g, *t, b.s) - S;
    if (!r.allFinite()) return ExechonIkStatus::kSingular;
    if (r.norm() <= kRefineTolerance * scale) return ExechonIkStatus::kOk;
    const Eigen::PartialPivLU<Eigen::Matrix3d> lu(detail::wristPointJacobian(g, *t, b.s, b.ds_de));
    e -= lu.solve(r);
    *t = detail::trigOf(e);
  }
  return ExechonIkStatus::kSingular;
}

ExechonIkStatus solveTrig(const ExechonTripodGeometry& g,
                          const Eigen::Vector3d& S,
                          int d1,
                          int d2,
                          detail::ExechonTrig* out) {
  TrigCommon c{};
  ExechonIkStatus status = trigCommon(g, S, &c);
  if (status != ExechonIkStatus::kOk) return status;
  detail::ExechonTrig both[2];
  status = solveTrigD1(g, S, c, d1, both);
  if (status != ExechonIkStatus::kOk) return status;
  *out = both[d2 == 1 ? 0 : 1];
  return refineForLegB(g, S, c.scale, out);
}

Eigen::Vector3d anglesOf(const detail::ExechonTrig& t) {
  return {std::atan2(t.sa, t.ca), std::atan2(t.sb, t.cb), t.h};
}

/// evaluateTripod without the branch recovery, from precomputed sines and cosines of e.
void fillTripod(const ExechonModel& model,
                ExechonData& data,
                const detail::ExechonTrig& t,
                const Eigen::Vector3d& e,
                int deltaA,
                int deltaC) {
  const ExechonTripodGeometry& g = model.tripod;
  const Eigen::Vector3d kA2(t.sa, 0.0, t.ca), kB5(-t.sb * t.ca, t.cb, t.sb * t.sa),
      eh(-t.cb * t.ca, -t.sb, t.cb * t.sa);
  const bool offsets = detail::hasLegBOffsets(g);
  const detail::LegBSolution legB =
      offsets ? detail::solveLegB(g, t, false) : detail::LegBSolution{};
  const double s = offsets ? (legB.ok ? legB.s : NAN) : -g.dB * t.ca * t.sb;
  const Eigen::Vector3d P = t.h * eh + s * kB5;
  data.e = e;
  data.e_sin_cos = {t.sa, t.ca, t.sb, t.cb};
  data.e_of_sin_cos = e;
  data.zoppi_p_S = P + g.hx * kA2 + g.hz * eh;
  data.world_p_S = model.world_T_zoppi * data.zoppi_p_S;
  Eigen::Matrix3d R;
  R << kA2, kB5, eh;
  data.zoppi_T_platform.linear() = R;
  data.zoppi_T_platform.translation() = P;
  data.world_T_platform = model.world_T_zoppi * data.zoppi_T_platform;

  const detail::ExechonLegTerms k = detail::legTerms(g, t);
  data.zoppi_p_platform_joint[0] = {t.ca * k.uA, -k.vA + g.dA, -t.sa * k.uA};
  data.zoppi_p_platform_joint[1] = {
      -k.t1 * t.sa + g.dB - k.t2 * t.ca * t.cb, -k.t2 * t.sb, k.t2 * t.sa * t.cb - k.t1 * t.ca};
  data.zoppi_p_platform_joint[2] = {t.ca * k.uC, -k.vC + g.dC, -t.sa * k.uC};
  data.zoppi_p_leg_start[0] = {-deltaA * g.l12A * t.ca, g.dA, deltaA * g.l12A * t.sa};
  data.zoppi_p_leg_start[1] = {g.dB, 0.0, 0.0};
  if (offsets) {
    data.zoppi_p_platform_joint[1] = P + g.pB * kA2;
    data.zoppi_p_leg_start[1] = legB.foot;
  }
  data.zoppi_p_leg_start[2] = {-deltaC * g.l12C * t.ca, g.dC, deltaC * g.l12C * t.sa};
  const double uA = k.uA + deltaA * g.l12A, uC = k.uC + deltaC * g.l12C;
  data.lengths = {std::sqrt(uA * uA + k.vA * k.vA),
                  offsets ? (legB.ok ? legB.q : NAN) : std::sqrt(k.t1 * k.t1 + k.t2 * k.t2),
                  std::sqrt(uC * uC + k.vC * k.vC)};
  for (int i = 0; i < kExechonLegs; ++i)
    data.readings[i] = data.lengths[i] - model.legs[static_cast<std::size_t>(i)].length_offset;
}

}  // namespace

ExechonIkStatus parametersFromWristPoint(
    const ExechonTripodGeometry& g, const Eigen::Vector3d& S, int d1, int d2, Eigen::Vector3d* e) {
  PKM_CHECK(detail::isUnitSign(d1) && detail::isUnitSign(d2),
            "delta1B and delta2B must be +1 or -1 (got {}, {})",
            d1,
            d2);
  detail::ExechonTrig t{};
  const ExechonIkStatus status = solveTrig(g, S, d1, d2, &t);
  if (status == ExechonIkStatus::kOk) *e = anglesOf(t);
  return status;
}

void evaluateTripod(const ExechonModel& model,
                    ExechonData& data,
                    const Eigen::Vector3d& e,
                    int deltaA,
                    int deltaC) {
  PKM_CHECK(detail::isUnitSign(deltaA) && detail::isUnitSign(deltaC),
            "deltaA and deltaC must be +1 or -1 (got {}, {})",
            deltaA,
            deltaC);
  const ExechonTripodGeometry& g = model.tripod;
  const detail::ExechonTrig t = detail::trigOf(e);
  fillTripod(model, data, t, e, deltaA, deltaC);
  const Eigen::Vector3d& S = data.zoppi_p_S;
  // Recover the pose branch: d1·r = sα·Sz − cα·Sx and d2·sqrt(t6² + Sy²) = cβ·t6 − sβ·Sy.
  const int d1 = t.sa * S.z() - t.ca * S.x() >= 0.0 ? 1 : -1;
  const double t0sq = S.x() * S.x() + S.z() * S.z();
  const double r = std::sqrt(std::max(t0sq - g.hx * g.hx, 0.0));
  const double t6 =
      t0sq > 0.0 ? (d1 * (t0sq - g.dB * S.x()) * r + g.dB * g.hx * S.z()) / t0sq : 0.0;
  const int d2 = t.cb * t6 - t.sb * S.y() >= 0.0 ? 1 : -1;
  data.branch = {d1, d2, deltaA, deltaC};
}

ExechonIkStatus tripodInverseKinematics(const ExechonModel& model,
                                        ExechonData& data,
                                        const Eigen::Vector3d& zoppi_p_S,
                                        const ExechonBranch& branch) {
  PKM_CHECK(branch.isValid(), "Exechon branch signs must be +1 or -1");
  detail::ExechonTrig t{};
  const ExechonIkStatus status =
      solveTrig(model.tripod, zoppi_p_S, branch.delta1B, branch.delta2B, &t);
  if (status != ExechonIkStatus::kOk) return status;
  fillTripod(model, data, t, anglesOf(t), branch.deltaA, branch.deltaC);
  data.branch = branch;
  data.zoppi_p_S = zoppi_p_S;  // equal to the forward map of e up to rounding
  data.world_p_S = model.world_T_zoppi * zoppi_p_S;
  return status;
}

ExechonIkStatus tripodInverseKinematics(const ExechonModel& model,
                                        ExechonData& data,
                                        const Eigen::Vector3d& zoppi_p_S) {
  return tripodInverseKinematics(model, data, zoppi_p_S, branchOf(model.tripod));
}

ExechonIkStatus tripodInverseKinematicsNearest(const ExechonModel& model,
                                               ExechonData& data,
                                               const Eigen::Vector3d& zoppi_p_S,
                                               const Eigen::Vector3d& e_near) {
  if (!e_near.allFinite()) return ExechonIkStatus::kInvalidInput;
  const double inv_length = 1.0 / model.characteristicLength();
  double sa0, ca0, sb0, cb0;
  if (e_near == data.e_of_sin_cos) {
    sa0 = data.e_sin_cos[0], ca0 = data.e_sin_cos[1], sb0 = data.e_sin_cos[2],
    cb0 = data.e_sin_cos[3];
  } else {
    sa0 = std::sin(e_near[0]), ca0 = std::cos(e_near[0]), sb0 = std::sin(e_near[1]),
    cb0 = std::cos(e_near[1]);
  }
  ExechonBranch branch = branchOf(model.tripod);
  TrigCommon common{};
  const ExechonIkStatus status = trigCommon(model.tripod, zoppi_p_S, &common);
  if (status != ExechonIkStatus::kOk) return status;
  // The squared alpha chord of each δ1B (sin/cos of alpha as solveTrigD1 gives them) bounds that
  // branch pair's distance from below: the pair nearer in alpha is solved first, and the other
  // only when its alpha chord alone does not already exceed the best distance (the same choice
  // as solving all four, at a fraction of the cost along a path).
  const Eigen::Vector3d& S = zoppi_p_S;
  const double hx = model.tripod.hx;
  double alpha_chord_sq[2];
  for (int k = 0; k < 2; ++k) {
    const double d1 = k == 0 ? 1.0 : -1.0;
    const double ca = (-d1 * S.x() * common.r + hx * S.z()) / common.t0sq;
    const double sa = (d1 * S.z() * common.r + hx * S.x()) / common.t0sq;
    alpha_chord_sq[k] = (ca - ca0) * (ca - ca0) + (sa - sa0) * (sa - sa0);
  }
  const int first = alpha_chord_sq[1] < alpha_chord_sq[0] ? 1 : 0;
  detail::ExechonTrig best{};
  double best_distance = INFINITY;
  for (int k1 : {first, 1 - first}) {
    if (k1 != first && alpha_chord_sq[k1] > best_distance + kChordRounding) break;
    const int d1 = k1 == 0 ? 1 : -1;
    detail::ExechonTrig both[2];
    const ExechonIkStatus st = solveTrigD1(model.tripod, zoppi_p_S, common, d1, both);
    if (st != ExechonIkStatus::kOk) return st;  // a branch failing: S is degenerate
    for (int k = 0; k < 2; ++k) {
      const detail::ExechonTrig& t = both[k];
      // Squared chord distances of the angles (monotone in |Δangle|) plus the squared relative Δh.
      const double dh = (t.h - e_near[2]) * inv_length;
      const double distance =
          2.0 * (2.0 - t.ca * ca0 - t.sa * sa0 - t.cb * cb0 - t.sb * sb0) + dh * dh;
      if (distance < best_distance) {
        best_distance = distance;
        best = t;
        branch.delta1B = d1;
        branch.delta2B = k == 0 ? 1 : -1;
      }
    }
  }
  const ExechonIkStatus refined = refineForLegB(model.tripod, zoppi_p_S, common.scale, &best);
  if (refined != ExechonIkStatus::kOk) return refined;
  fillTripod(model, data, best, anglesOf(best), branch.deltaA, branch.deltaC);
  data.branch = branch;
  data.zoppi_p_S = zoppi_p_S;
  data.world_p_S = model.world_T_zoppi * zoppi_p_S;
  return ExechonIkStatus::kOk;
}

const Eigen::Matrix3d& computeTripodJacobian(const ExechonModel& model, ExechonData& data) {
  const ExechonTripodGeometry& g = model.tripod;
  const detail::ExechonTrig t = detail::trigOf(data.e);
  detail::legLengths(g, t, data.branch.deltaA, data.branch.deltaC, &data.J_q_e);
  // S = hx·kA2 + (h + hz)·eh + s·kB5 (NaN when leg B's offset solve fails).
  Eigen::Vector3d ds_de;
  const double s_B = platformOffsetB(g, t, &ds_de);
  data.J_S_e = std::isfinite(s_B) ? detail::wristPointJacobian(g, t, s_B, ds_de)
                                  : Eigen::Matrix3d::Constant(NAN);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(data.J_S_e,
                                              Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d& s = svd.singularValues();
  if (!(s[2] > kDegenerate * s[0])) {
    data.J_q_S.setZero();
  } else {
    data.J_q_S =
        data.J_q_e * svd.matrixV() * s.cwiseInverse().asDiagonal() * svd.matrixU().transpose();
  }
  return data.J_q_S;
}

namespace detail {

bool platformPointAt(const ExechonTripodGeometry& g,
                     const ExechonTrig& t,
                     const Eigen::Vector3d& v,
                     Eigen::Vector3d* point,
                     Eigen::Matrix3d* J_point_e) {
  Eigen::Vector3d ds_de;
  const double s = platformOffsetB(g, t, J_point_e != nullptr ? &ds_de : nullptr);
  if (!std::isfinite(s)) return false;
  // R·v = v0·kA2 + v1·kB5 + v2·eh: d(kB5)/dβ = eh, d(eh)/dβ = −kB5, nothing depends on h.
  const Eigen::Vector3d kA2(t.sa, 0.0, t.ca), kB5(-t.sb * t.ca, t.cb, t.sb * t.sa),
      eh(-t.cb * t.ca, -t.sb, t.cb * t.sa);
  const Eigen::Vector3d dkA2_da(t.ca, 0.0, -t.sa), dkB5_da(t.sb * t.sa, 0.0, t.sb * t.ca),
      deh_da(t.cb * t.sa, 0.0, t.cb * t.ca);
  *point = wristPoint(g, t, s) + v[0] * kA2 + v[1] * kB5 + v[2] * eh;
  if (J_point_e == nullptr) return point->allFinite();
  Eigen::Matrix3d Rv_e;
  Rv_e << v[0] * dkA2_da + v[1] * dkB5_da + v[2] * deh_da, v[1] * eh - v[2] * kB5,
      Eigen::Vector3d::Zero();
  *J_point_e = wristPointJacobian(g, t, s, ds_de) + Rv_e;
  return point->allFinite() && J_point_e->allFinite();
}

}  // namespace detail

double tripodConditionNumber(const ExechonData& data) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(data.J_q_S);
  const Eigen::Vector3d& s = svd.singularValues();
  if (!s.allFinite() || !(s[2] > 0.0)) return INFINITY;
  return s[0] / s[2];
}

}  // namespace pkm::kinematics
