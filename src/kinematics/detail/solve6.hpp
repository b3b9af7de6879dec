/// @file
/// @brief Internal: in-place Gaussian elimination with partial pivoting for the 6×6 strut Jacobian.
/// Eigen's PartialPivLU goes through its dynamic-size blocked path even for 6×6 (about 1 600
/// instructions per factorisation, measured with callgrind); this fixed-size loop is several times
/// cheaper on the forward-kinematics hot path and gives the same pivots.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>

namespace pkm::kinematics::detail {

/// Solves A·x = b in place (A is destroyed, b becomes x). Returns min|pivot| / max|pivot|, 0 when a
/// pivot is exactly zero (then b is left partially eliminated and must not be used). With
/// `det_sign`, sets it to the sign of det(A) (+1 or −1; 0 when singular).
inline double solve6(Eigen::Matrix<double, 6, 6>& A,
                     Eigen::Matrix<double, 6, 1>& b,
                     int* det_sign = nullptr) {
  double min_pivot = INFINITY, max_pivot = 0.0;
  int sign = 1;
  if (det_sign != nullptr) *det_sign = 0;
  for (int k = 0; k < 6; ++k) {
    int p = k;
    double best = std::abs(A(k, k));
    for (int i = k + 1; i < 6; ++i) {
      const double v = std::abs(A(i, k));
      if (v > best) {
        best = v;
        p = i;
      }
    }
    if (best == 0.0) return 0.0;
    if (p != k) {
      A.row(p).swap(A.row(k));
      std::swap(b[p], b[k]);
      sign = -sign;
    }
    if (A(k, k) < 0.0) sign = -sign;
    min_pivot = std::min(min_pivot, best);
    max_pivot = std::max(max_pivot, best);
    const double inv = 1.0 / A(k, k);
    for (int i = k + 1; i < 6; ++i) {
      const double f = A(i, k) * inv;
      for (int j = k + 1; j < 6; ++j) A(i, j) -= f * A(k, j);
      b[i] -= f * b[k];
    }
  }
  for (int k = 5; k >= 0; --k) {
    double s = b[k];
    for (int j = k + 1; j < 6; ++j) s -= A(k, j) * b[j];
    b[k] = s / A(k, k);
  }
  if (det_sign != nullptr) *det_sign = sign;
  return min_pivot / max_pivot;
}

}  // namespace pkm::kinematics::detail
