/// @file
/// @brief Internal: Gaussian elimination with partial pivoting for the 6×6 strut Jacobian, as a
/// factorisation that forward kinematics can reuse for its polishing step.
/// Eigen's PartialPivLU goes through its dynamic-size blocked path even for 6×6 (about 1 600
/// instructions per factorisation, measured with callgrind); this fixed-size loop is several times
/// cheaper on the forward-kinematics hot path and gives the same pivots.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <utility>

namespace pkm::kinematics::detail {

/// LU factorisation with partial pivoting of a 6×6 matrix, rows swapped by index: row[k] is the
/// k-th pivot row of m; in it, columns k..5 hold U and columns 0..k−1 the multipliers of L.
struct Lu6 {
  std::array<std::array<double, 6>, 6> m{};
  std::array<int, 6> row{};
  std::array<double, 6> inverse_pivot{};  ///< 1 / U(k, k)
  bool valid = false;                     ///< false until a non-singular matrix was factorised
};

/// Factorises A·diag(1, 1, 1, s, s, s), s = `right_scale` (the last three columns scaled), into
/// `lu` (partial pivoting by the largest entry of each column). Returns min|pivot| / max|pivot|,
/// 0 when a pivot is exactly zero (then lu.valid is false). With `det_sign`, sets it to the sign
/// of the factorised matrix's determinant (+1 or −1; 0 when singular).
inline double factor6(const Eigen::Matrix<double, 6, 6>& A,
                      Lu6& lu,
                      int* det_sign = nullptr,
                      double right_scale = 1.0) {
  auto& m = lu.m;
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 3; ++j) m[i][j] = A(i, j);
    for (int j = 3; j < 6; ++j) m[i][j] = A(i, j) * right_scale;
    lu.row[i] = i;
  }
  lu.valid = false;
  double min_pivot = INFINITY, max_pivot = 0.0;
  int sign = 1;
  if (det_sign != nullptr) *det_sign = 0;
#pragma GCC unroll 6
  for (int k = 0; k < 6; ++k) {
    int p = k;
    double best = std::abs(m[lu.row[k]][k]);
    for (int i = k + 1; i < 6; ++i) {
      const double v = std::abs(m[lu.row[i]][k]);
      if (v > best) {
        best = v;
        p = i;
      }
    }
    if (best == 0.0) return 0.0;
    if (p != k) {
      std::swap(lu.row[p], lu.row[k]);
      sign = -sign;
    }
    const double* pivot_row = m[lu.row[k]].data();
    if (pivot_row[k] < 0.0) sign = -sign;
    min_pivot = std::min(min_pivot, best);
    max_pivot = std::max(max_pivot, best);
    const double inv = 1.0 / pivot_row[k];
    lu.inverse_pivot[k] = inv;
    for (int i = k + 1; i < 6; ++i) {
      double* r = m[lu.row[i]].data();
      const double f = r[k] * inv;
      for (int j = k + 1; j < 6; ++j) r[j] -= f * pivot_row[j];
      r[k] = f;  // columns ≤ k of a row below the pivot keep its multipliers
    }
  }
  lu.valid = true;
  if (det_sign != nullptr) *det_sign = sign;
  return min_pivot / max_pivot;
}

/// Replaces b by A⁻¹·b for the A factorised in `lu` (precondition: lu.valid). Always inlined: as
/// a call, its result went back through memory element by element and the caller read it as pairs
/// (a store-forwarding stall on the forward kinematics' hot path).
[[gnu::always_inline]] inline void substitute6(const Lu6& lu, Eigen::Matrix<double, 6, 1>& b) {
  const auto& m = lu.m;
  double y[6];
#pragma GCC unroll 6
  for (int k = 0; k < 6; ++k) {  // L·y = P·b
    const double* r = m[lu.row[k]].data();
    double s = b[lu.row[k]];
    for (int j = 0; j < k; ++j) s -= r[j] * y[j];
    y[k] = s;
  }
#pragma GCC unroll 6
  for (int k = 5; k >= 0; --k) {  // U·x = y
    const double* r = m[lu.row[k]].data();
    double s = y[k];
    for (int j = k + 1; j < 6; ++j) s -= r[j] * y[j];
    y[k] = s * lu.inverse_pivot[k];
  }
  for (int k = 0; k < 6; ++k) b[k] = y[k];
}

}  // namespace pkm::kinematics::detail
