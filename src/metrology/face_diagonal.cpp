#include "pkm/metrology/face_diagonal.hpp"

#include <Eigen/Dense>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

constexpr double kSameDirection = 1e-9;  // relative spread of u²/s² below which directions agree

/// Σ over the terms of one component: value(position of the argument axis) × lever, where the
/// lever grows with the position of the other axis.
/// `only_argument` >= 0 restricts the sum to the terms over that axis.
double pdgeDisplacement(std::span<const PdgeTerm> pdge,
                        int component,
                        double pos_a,
                        double pos_b,
                        int only_argument = -1) {
  double sum = 0.0;
  for (const PdgeTerm& t : pdge) {
    if (t.component != component || (only_argument >= 0 && t.argument != only_argument)) continue;
    const double arg = t.argument == 0 ? pos_a : pos_b;
    const double other = t.argument == 0 ? pos_b : pos_a;
    sum += t.table.evaluate(arg)(0) * (t.lever + t.lever_per_other * other);
  }
  return sum;
}

/// Rejects PDGE terms with an argument or component other than 0 or 1, a table of more than
/// one column, or a lever that is not finite.
void checkPdgeTerms(std::span<const PdgeTerm> pdge) {
  for (const PdgeTerm& t : pdge) {
    PKM_CHECK((t.argument == 0 || t.argument == 1) && (t.component == 0 || t.component == 1),
              "face-diagonal squareness: PDGE argument and component must be 0 or 1, got {}, {}",
              t.argument,
              t.component);
    PKM_CHECK(t.table.components() == 1,
              "face-diagonal squareness: a PDGE table needs 1 column, got {}",
              t.table.components());
    PKM_CHECK(std::isfinite(t.lever) && std::isfinite(t.lever_per_other),
              "face-diagonal squareness: PDGE lever is not finite");
  }
}

/// One reading away from its diagonal's start, with its corrected deviation.
struct FaceDiagonalRow {
  double u, v, s, rhs;
  double v_actual;  ///< v plus the positioning error of axis b: the travel the squareness tilts
  std::size_t diagonal, point;
};

/// The readings away from the start with their corrected deviations (eq. 9/10 right-hand side:
/// the measured PDGEs removed), which also go to result.corrected (0 at the start); rejects
/// non-finite starts and readings.
std::vector<FaceDiagonalRow> faceDiagonalRows(std::span<const FaceDiagonal> diagonals,
                                              std::span<const PdgeTerm> pdge,
                                              FaceDiagonalResult& result) {
  std::vector<FaceDiagonalRow> rows;
  for (std::size_t i = 0; i < diagonals.size(); ++i) {
    const FaceDiagonal& diag = diagonals[i];
    PKM_CHECK(std::isfinite(diag.start_a) && std::isfinite(diag.start_b),
              "face-diagonal squareness: diagonal {} start is not finite",
              i + 1);
    const double da0 = pdgeDisplacement(pdge, 0, diag.start_a, diag.start_b);
    const double db0 = pdgeDisplacement(pdge, 1, diag.start_a, diag.start_b);
    const double bb0 = pdgeDisplacement(pdge, 1, diag.start_a, diag.start_b, 1);
    result.corrected.emplace_back(diag.points.size(), 0.0);
    for (std::size_t k = 0; k < diag.points.size(); ++k) {
      const DiagonalPoint& p = diag.points[k];
      PKM_CHECK(std::isfinite(p.u) && std::isfinite(p.v) && std::isfinite(p.deviation),
                "face-diagonal squareness: diagonal {} point {} is not finite",
                i + 1,
                k + 1);
      const double s = std::hypot(p.u, p.v);
      if (s == 0.0) continue;
      const double pa = diag.start_a + p.u, pb = diag.start_b + p.v;
      // Δa, Δb relative to the start, where the laser was zeroed.
      const double da = pdgeDisplacement(pdge, 0, pa, pb) - da0;
      const double db = pdgeDisplacement(pdge, 1, pa, pb) - db0;
      // Linearised diagonal length (eq. 6): ΔD = (u Δa + v Δb)/s.
      const double corrected = p.deviation - (p.u * da + p.v * db) / s;
      result.corrected[i][k] = corrected;
      const double v_actual = p.v + pdgeDisplacement(pdge, 1, pa, pb, 1) - bb0;
      rows.push_back({p.u, p.v, s, corrected, v_actual, i, k});
    }
  }
  return rows;
}

}  // namespace

FaceDiagonalResult fitFaceDiagonalSquareness(std::span<const FaceDiagonal> diagonals,
                                             std::span<const PdgeTerm> pdge,
                                             const FaceDiagonalOptions& options) {
  PKM_CHECK(!diagonals.empty(), "face-diagonal squareness: no diagonal");
  checkPdgeTerms(pdge);
  FaceDiagonalResult result;
  const std::vector<FaceDiagonalRow> rows = faceDiagonalRows(diagonals, pdge, result);

  bool mixed_sign = false;  // some u v ≠ 0
  double ratio_min = 1.0, ratio_max = 0.0;
  for (const FaceDiagonalRow& r : rows) {
    mixed_sign = mixed_sign || r.u * r.v != 0.0;
    const double ratio = r.u * r.u / (r.s * r.s);
    ratio_min = std::min(ratio_min, ratio);
    ratio_max = std::max(ratio_max, ratio);
  }
  PKM_CHECK(mixed_sign, "face-diagonal squareness: needs readings that move both axes (u v != 0)");
  result.scale_per_axis = options.fit_scale && ratio_max - ratio_min > kSameDirection;
  const Eigen::Index unknowns = !options.fit_scale ? 1 : (result.scale_per_axis ? 3 : 2);
  PKM_CHECK(static_cast<Eigen::Index>(rows.size()) >= unknowns,
            "face-diagonal squareness: needs at least {} readings away from the start, got {}",
            unknowns,
            rows.size());

  // Eqs 7-8: one linear equation per reading, in deviation units:
  //   deviation' = -σ u v / s [+ k_a u²/s + k_b v²/s  or  + k s],
  // with v the actual travel of b (v + its positioning error): the squareness tilts axis b's
  // actual motion (second order; the MXT700S parallelism paper's 0.8 mm PZ error over 210 mm is
  // 0.4 % of syP).
  Eigen::MatrixXd A(static_cast<Eigen::Index>(rows.size()), unknowns);
  Eigen::VectorXd b(A.rows());
  for (Eigen::Index k = 0; k < A.rows(); ++k) {
    const FaceDiagonalRow& r = rows[static_cast<std::size_t>(k)];
    A(k, 0) = -r.u * r.v_actual / r.s;
    if (unknowns == 2) A(k, 1) = r.s;
    if (unknowns == 3) {
      A(k, 1) = r.u * r.u / r.s;
      A(k, 2) = r.v * r.v / r.s;
    }
    b(k) = r.rhs;
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  PKM_CHECK(qr.rank() == unknowns,
            "face-diagonal squareness: the scale is not separable from the squareness (needs two "
            "diagonals of different directions, e.g. (+a, +b) and (-a, +b))");
  const Eigen::VectorXd x = qr.solve(b);
  const Eigen::VectorXd res = b - A * x;
  const int flips = (options.first_moves_work ? 1 : 0) + (options.second_moves_work ? 1 : 0);
  result.squareness = flips % 2 == 0 ? x(0) : -x(0);
  if (unknowns == 2) result.scale = std::array<double, 2>{x(1), x(1)};
  if (unknowns == 3) result.scale = std::array<double, 2>{x(1), x(2)};
  result.points_used = static_cast<int>(rows.size());
  result.residual_rms = std::sqrt(res.squaredNorm() / static_cast<double>(res.size()));
  result.residuals.resize(diagonals.size());
  for (std::size_t i = 0; i < diagonals.size(); ++i) {
    result.residuals[i].assign(diagonals[i].points.size(), 0.0);
  }
  for (Eigen::Index k = 0; k < res.size(); ++k) {
    const FaceDiagonalRow& r = rows[static_cast<std::size_t>(k)];
    result.residuals[r.diagonal][r.point] = res(k);
  }
  return result;
}

}  // namespace pkm::metrology
