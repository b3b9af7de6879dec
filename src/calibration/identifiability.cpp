#include "pkm/calibration/identifiability.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cassert>
#include <cctype>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::calibration {
namespace {

/// An entry of a null-space basis (unit columns) below this is taken as zero when the pivots of
/// the canonical basis are chosen: far above rounding (~1e-15), far below a real coefficient.
constexpr double kCanonicalZero = 1e-6;

/// The canonical orthonormal basis of the subspace spanned by the orthonormal columns of `V`
/// (n × d): the reduced row echelon form of Vᵀ, whose pivots are the first columns (parameters,
/// in their order) that the subspace involves, orthonormalised in pivot order (Gram–Schmidt, each
/// vector's pivot coefficient positive). It depends on the subspace only, not on the basis an SVD
/// happens to return for a repeated (zero) singular value, which rounding turns at will.
Eigen::MatrixXd canonicalBasis(const Eigen::MatrixXd& V) {
  const Eigen::Index n = V.rows(), d = V.cols();
  Eigen::MatrixXd R = V.transpose();  // d × n, reduced in place
  std::vector<Eigen::Index> pivots;
  Eigen::Index row = 0;
  for (Eigen::Index c = 0; c < n && row < d; ++c) {
    Eigen::Index best = row;
    for (Eigen::Index r = row + 1; r < d; ++r)
      if (std::fabs(R(r, c)) > std::fabs(R(best, c))) best = r;
    if (std::fabs(R(best, c)) < kCanonicalZero) continue;
    R.row(row).swap(R.row(best));
    R.row(row) /= R(row, c);
    for (Eigen::Index r = 0; r < d; ++r)
      if (r != row) R.row(r) -= R(r, c) * R.row(row);
    pivots.push_back(c);
    ++row;
  }
  assert(row == d);  // orthonormal columns have full rank
  Eigen::MatrixXd basis(n, d);
  for (Eigen::Index k = 0; k < d; ++k) {
    Eigen::VectorXd v = R.row(k).transpose();
    for (Eigen::Index j = 0; j < k; ++j) v -= basis.col(j).dot(v) * basis.col(j);
    v.normalize();
    if (v(pivots[static_cast<std::size_t>(k)]) < 0.0) v = -v;
    basis.col(k) = v;
  }
  return basis;
}

}  // namespace

Identifiability analyseIdentifiability(const Eigen::MatrixXd& J,
                                       const std::vector<std::string>& names,
                                       const IdentifiabilityOptions& options) {
  PKM_CHECK(J.rows() > 0 && J.cols() > 0, "identifiability: the Jacobian is empty");
  PKM_CHECK(static_cast<Eigen::Index>(names.size()) == J.cols(),
            "identifiability: {} parameter names for {} columns",
            names.size(),
            J.cols());
  PKM_CHECK(J.allFinite(), "identifiability: the Jacobian has a non-finite entry");
  Identifiability out;
  out.parameters = static_cast<int>(J.cols());
  out.equations = static_cast<int>(J.rows());
  out.column_scale = J.colwise().norm().transpose();
  Eigen::MatrixXd scaled = J;
  for (Eigen::Index c = 0; c < J.cols(); ++c)
    if (out.column_scale(c) > 0.0) scaled.col(c) /= out.column_scale(c);
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullV);
  const Eigen::Index n = J.cols();
  out.singular_values = Eigen::VectorXd::Zero(n);
  out.singular_values.head(svd.singularValues().size()) = svd.singularValues();
  const double s_max = out.singular_values(0);
  const double threshold = options.relative_tolerance * s_max;
  int rank = 0;
  for (Eigen::Index k = 0; k < n; ++k)
    if (out.singular_values(k) > threshold) ++rank;
  out.rank = rank;
  out.condition_number = rank > 0 ? s_max / out.singular_values(rank - 1) : INFINITY;
  const Eigen::Index nullity = n - rank;
  out.null_space.resize(n, nullity);
  const Eigen::MatrixXd null_basis =
      nullity > 0 ? canonicalBasis(svd.matrixV().rightCols(nullity)) : Eigen::MatrixXd(n, 0);
  for (Eigen::Index k = 0; k < nullity; ++k) {
    const Eigen::VectorXd v = null_basis.col(k);
    // Back to unscaled parameters: θ = D⁻¹·θ_scaled; a zero column keeps its unit direction.
    Eigen::VectorXd unscaled(n);
    for (Eigen::Index c = 0; c < n; ++c)
      unscaled(c) = out.column_scale(c) > 0.0 ? v(c) / out.column_scale(c) : v(c);
    out.null_space.col(k) = unscaled.normalized();
    UnidentifiableCombination combo;
    combo.singular_value = s_max > 0.0 ? (scaled * v).norm() / s_max : 0.0;
    std::vector<Eigen::Index> order(static_cast<std::size_t>(n));
    for (Eigen::Index c = 0; c < n; ++c) order[static_cast<std::size_t>(c)] = c;
    std::sort(order.begin(), order.end(), [&](Eigen::Index a, Eigen::Index b) {
      return std::fabs(v(a)) > std::fabs(v(b));
    });
    // Make the sign deterministic: the largest coefficient positive.
    const double sign = v(order.front()) < 0.0 ? -1.0 : 1.0;
    for (const Eigen::Index c : order)
      if (std::fabs(v(c)) >= options.report_threshold)
        combo.terms.emplace_back(names[static_cast<std::size_t>(c)], sign * v(c));
    out.combinations.push_back(std::move(combo));
  }
  return out;
}

const char* toString(ObservabilityIndex index) {
  switch (index) {
    case ObservabilityIndex::kO1:
      return "O1";
    case ObservabilityIndex::kO2:
      return "O2";
    case ObservabilityIndex::kO3:
      return "O3";
    case ObservabilityIndex::kO4:
      return "O4";
    case ObservabilityIndex::kO5:
      return "O5";
  }
  return "?";
}

ObservabilityIndex parseObservabilityIndex(const std::string& text) {
  std::string t = text;
  for (char& ch : t) ch = static_cast<char>(std::toupper(static_cast<unsigned char>(ch)));
  if (t == "O1") return ObservabilityIndex::kO1;
  if (t == "O2") return ObservabilityIndex::kO2;
  if (t == "O3") return ObservabilityIndex::kO3;
  if (t == "O4") return ObservabilityIndex::kO4;
  if (t == "O5") return ObservabilityIndex::kO5;
  throw InvalidArgument(
      fmt::format("unknown observability index '{}' (O1, O2, O3, O4 or O5)", text));
}

double observabilityIndex(ObservabilityIndex index, const Eigen::VectorXd& s, Eigen::Index rows) {
  PKM_CHECK(s.size() > 0, "observability index: no singular values");
  PKM_CHECK(rows >= 1, "observability index: the Jacobian has no rows");
  const double first = s(0);
  const double last = s(s.size() - 1);
  if (!(last > 0.0)) return 0.0;
  switch (index) {
    case ObservabilityIndex::kO1: {
      const double mean_log = s.array().log().mean();  // geometric mean without overflow
      return std::exp(mean_log) / std::sqrt(static_cast<double>(rows));
    }
    case ObservabilityIndex::kO2:
      return last / first;
    case ObservabilityIndex::kO3:
      return last;
    case ObservabilityIndex::kO4:
      return last * last / first;
    case ObservabilityIndex::kO5:
      return 1.0 / s.cwiseInverse().sum();
  }
  return 0.0;
}

}  // namespace pkm::calibration
