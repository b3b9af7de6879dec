#include "pkm/calibration/identifiability.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cctype>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::calibration {

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
  for (Eigen::Index k = 0; k < nullity; ++k) {
    const Eigen::VectorXd v = svd.matrixV().col(rank + k);
    // Back to unscaled parameters: θ = D⁻¹·θ_scaled; a zero column keeps its unit direction.
    Eigen::VectorXd unscaled(n);
    for (Eigen::Index c = 0; c < n; ++c)
      unscaled(c) = out.column_scale(c) > 0.0 ? v(c) / out.column_scale(c) : v(c);
    out.null_space.col(k) = unscaled.normalized();
    UnidentifiableCombination combo;
    combo.singular_value = s_max > 0.0 ? out.singular_values(rank + k) / s_max : 0.0;
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
