#include "pkm/metrology/shifted_diagonal.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

void checkShift(double shift) {
  PKM_CHECK(std::isfinite(shift) && shift != 0.0,
            "shifted diagonal: shift must be finite and != 0");
}

/// The length errors summed per (diagonal, axis + 1), their count, and the shift of each.
struct ShiftedSums {
  std::array<std::array<double, 4>, 4> sum{}, shift{};
  std::array<std::array<int, 4>, 4> count{};
};

/// Sums the length errors per (diagonal, axis + 1) and remembers the shift; rejects a bad axis,
/// non-finite values, a zero shift or one over half the axis length (`size`, mm), and two
/// different shifts along the same axis.
ShiftedSums sumShiftedMeasurements(std::span<const ShiftedDiagonalMeasurement> measurements,
                                   const Eigen::Vector3d& size) {
  ShiftedSums sums;
  auto& [sum, shift, count] = sums;
  for (const ShiftedDiagonalMeasurement& m : measurements) {
    PKM_CHECK(m.axis >= -1 && m.axis <= 2, "shifted diagonal: axis must be -1, 0, 1 or 2");
    PKM_CHECK(std::isfinite(m.length_error) && std::isfinite(m.shift),
              "shifted diagonal {}: non-finite length error or shift",
              toString(m.diagonal));
    const auto k = static_cast<std::size_t>(m.diagonal);
    const auto a = static_cast<std::size_t>(m.axis + 1);
    if (m.axis >= 0) {
      PKM_CHECK(m.shift != 0.0 && std::abs(m.shift) <= size[m.axis] / 2,
                "shifted diagonal {}: the shift along {} must be non-zero and at most half the "
                "axis length, got {} mm",
                toString(m.diagonal),
                "XYZ"[m.axis],
                m.shift);
      PKM_CHECK(count[k][a] == 0 || shift[k][a] == m.shift,
                "shifted diagonal {}: two different shifts along {}",
                toString(m.diagonal),
                "XYZ"[m.axis]);
      shift[k][a] = m.shift;
    }
    sum[k][a] += m.length_error;
    ++count[k][a];
  }
  return sums;
}

/// Into r: the squareness of eq (6) from the measured unshifted lengths (mm) of the four
/// diagonals, plain and with r.scale, and the squareness and asymmetry from r.components.
void eq6Squareness(const std::array<double, 4>& measured,
                   const Eigen::Vector3d& size,
                   ShiftedDiagonalResult& r) {
  // Eq (6): γ_ij = acos((R_PPP² + R_F² − 2R_ideal²)/(4·Li·Lj)), F the diagonal that reverses the
  // third axis. Pairs in output order xy (F = PPN ≡ NNP), xz (F = PNP), yz (F = NPP).
  const Eigen::Vector3d sq = size.cwiseProduct(size);
  const double ideal = sq.sum();
  const double ideal_scaled =
      sq.x() * (1 + 2 * r.scale[0]) + sq.y() * (1 + 2 * r.scale[1]) + sq.z() * (1 + 2 * r.scale[2]);
  struct Pair {
    std::size_t i, j, flip;
  };
  constexpr std::array<Pair, 3> kPairs = {Pair{0, 1, 3}, Pair{0, 2, 2}, Pair{1, 2, 1}};
  const double right = std::numbers::pi / 2;
  for (std::size_t p = 0; p < 3; ++p) {
    const auto [i, j, flip] = kPairs[p];
    const double li = size[static_cast<Eigen::Index>(i)], lj = size[static_cast<Eigen::Index>(j)];
    const double sum2 = measured[0] * measured[0] + measured[flip] * measured[flip];
    r.squareness_eq6[p] = std::acos((sum2 - 2.0 * ideal) / (4.0 * li * lj)) - right;
    r.squareness_eq6_scaled[p] = std::acos((sum2 - 2.0 * ideal_scaled) / (4.0 * li * lj)) - right;
    const double gij = r.components[i][j] / lj, gji = r.components[j][i] / li;
    r.squareness[p] = -(gij + gji) / 2.0;
    r.asymmetry[p] = gij - gji;
  }
}

}  // namespace

ShiftTriangle shiftTriangle(double r0, double rm, double shift) {
  checkShift(shift);
  PKM_CHECK(std::isfinite(r0) && std::isfinite(rm) && r0 > 0.0 && rm > 0.0,
            "shifted diagonal: lengths must be finite and > 0");
  const double d = std::abs(shift);
  PKM_CHECK(d < r0 + rm && r0 < rm + d && rm < r0 + d,
            "shifted diagonal: lengths {}, {} and shift {} do not form a triangle",
            r0,
            rm,
            d);
  const double sigma = shift > 0.0 ? 1.0 : -1.0;
  ShiftTriangle t;
  // Hwang et al. ("Analysis of multi-axis volumetric errors"), eq (2): the angle at the common
  // start O, law of cosines.
  t.delta_alpha = std::acos(std::clamp((r0 * r0 + rm * rm - d * d) / (2.0 * r0 * rm), -1.0, 1.0));
  // Eq (3): law of sines at A; asin gives π/2 − α on both sides of the normal plane.
  t.alpha =
      std::numbers::pi / 2 - std::asin(std::clamp(rm * std::sin(t.delta_alpha) / d, -1.0, 1.0));
  // Eq (1): R_real + Δx = R_mx·sin(α + Δα), with the shortening case σ = −1.
  t.component = rm * std::sin(t.alpha + sigma * t.delta_alpha) - sigma * d;
  return t;
}

double shiftComponent(double r0, double rm, double shift) {
  checkShift(shift);
  return (rm * rm - r0 * r0 - shift * shift) / (2.0 * shift);
}

ShiftedDiagonalResult evaluateShiftedDiagonals(
    std::span<const ShiftedDiagonalMeasurement> measurements, const Eigen::Vector3d& size) {
  requireBoxSize(size);
  const ShiftedSums sums = sumShiftedMeasurements(measurements, size);
  const auto& [sum, shift, count] = sums;
  ShiftedDiagonalResult r;
  std::array<double, 4> measured{};              // measured unshifted lengths
  std::array<std::array<double, 3>, 4> along{};  // along-travel shifts
  for (BodyDiagonal diag : kBodyDiagonals) {
    const auto k = static_cast<std::size_t>(diag);
    const Eigen::Vector3d travel = diagonalTravel(diag, size);
    const Eigen::Vector3d signs = travelSigns(diag);
    PKM_CHECK(count[k][0] > 0, "shifted diagonal: no measurement of {} unshifted", toString(diag));
    measured[k] = travel.norm() + sum[k][0] / count[k][0];
    for (int j = 0; j < 3; ++j) {
      const auto a = static_cast<std::size_t>(j + 1);
      PKM_CHECK(count[k][a] > 0,
                "shifted diagonal: no measurement of {} shifted along {}",
                toString(diag),
                "XYZ"[j]);
      Eigen::Vector3d shifted = travel;
      shifted[j] += shift[k][a];
      const double rm = shifted.norm() + sum[k][a] / count[k][a];
      along[k][static_cast<std::size_t>(j)] = shift[k][a] * signs[j];
      r.travel_errors[k][static_cast<std::size_t>(j)] =
          shiftComponent(measured[k], rm, along[k][static_cast<std::size_t>(j)]) - size[j];
    }
  }
  // Eq (5) and analogues: F_i is the diagonal with axis i's travel reversed relative to PPP.
  constexpr std::array<std::size_t, 3> kFlip = {1, 2, 3};  // NPP, PNP, NNP (= PPN reversed)
  const auto& te = r.travel_errors;
  for (std::size_t j = 0; j < 3; ++j) {
    for (std::size_t i = 0; i < 3; ++i) {
      const double sign = i == j ? 1.0 : -1.0;
      r.components[j][i] = (te[0][j] + sign * te[kFlip[i]][j]) / 2.0;
    }
    const double mean_shift = (along[0][j] + along[kFlip[j]][j]) / 2.0;
    r.scale[j] = r.components[j][j] / (2.0 * size[static_cast<Eigen::Index>(j)] + mean_shift);
  }
  eq6Squareness(measured, size, r);
  return r;
}

}  // namespace pkm::metrology
