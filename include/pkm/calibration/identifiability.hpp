/// @file
/// @brief Identifiability of kinematic parameters from the identification Jacobian (Besnard &
/// Khalil, "Identifiable parameters for parallel robots kinematic calibration", ICRA 2001):
/// numerical rank, condition number, the unidentifiable parameter combinations named in parameter
/// terms, and the observability indices O1–O5 used by pose planning (docs/calibration.md).
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

namespace pkm::calibration {

/// A direction in parameter space that the data cannot see: a unit vector in the column-scaled
/// parameter space, listed as (parameter name, coefficient) for the coefficients whose magnitude
/// is at least IdentifiabilityOptions::report_threshold, largest first.
struct UnidentifiableCombination {
  std::vector<std::pair<std::string, double>> terms;
  /// |J_scaled·v| / the largest singular value: how weakly the data see the direction v.
  double singular_value = 0.0;
};

/// Settings of the identifiability analysis.
struct IdentifiabilityOptions {
  /// Singular values below relative_tolerance × the largest count as zero.
  double relative_tolerance = 1e-8;
  /// Smallest |coefficient| listed in an UnidentifiableCombination.
  double report_threshold = 0.05;
};

/// The result of analyseIdentifiability.
struct Identifiability {
  int parameters = 0;  ///< number of columns (free parameters)
  int equations = 0;   ///< number of rows
  int rank = 0;        ///< numerical rank = number of identifiable combinations
  /// Largest / smallest singular value among the identifiable ones (scaled Jacobian).
  double condition_number = 0.0;
  Eigen::VectorXd singular_values;  ///< scaled Jacobian, descending
  Eigen::VectorXd column_scale;     ///< the column norms divided out
  Eigen::MatrixXd null_space;       ///< parameters × (parameters − rank), unscaled
  std::vector<UnidentifiableCombination> combinations;  ///< one per null-space vector
  [[nodiscard]] bool fullRank() const { return rank == parameters; }
};

/// Analyses `J` (equations × parameters; columns named by `names`): each column is divided by its
/// norm (a zero column is an unidentifiable parameter by itself), then the SVD gives the rank, the
/// condition number and the null space. The null space is given by its canonical orthonormal
/// basis (the reduced row echelon form of the null-space basis, pivots in parameter order,
/// orthonormalised): the same vectors whichever basis the SVD returns, so the report does not turn
/// with rounding. The null-space vectors are returned in the unscaled parameter space
/// (null_space) and named (combinations). Throws pkm::InvalidArgument when names
/// and columns differ in number, J is empty or has a non-finite entry.
[[nodiscard]] Identifiability analyseIdentifiability(const Eigen::MatrixXd& J,
                                                     const std::vector<std::string>& names,
                                                     const IdentifiabilityOptions& options = {});

/// The observability indices of a column-scaled identification Jacobian with m rows and singular
/// values s₁ ≥ … ≥ s_L (sources per index below). All are "larger is better".
enum class ObservabilityIndex {
  kO1,  ///< (s₁·…·s_L)^(1/L) / √m (Borm & Menq 1991; D-optimality)
  kO2,  ///< s_L / s₁, the inverse condition number (Driels & Pathre 1990)
  kO3,  ///< s_L, the smallest singular value (Nahvi, Hollerbach, Hayward 1994; E-optimality)
  kO4,  ///< s_L² / s₁, the noise amplification index (Nahvi & Hollerbach 1996)
  kO5,  ///< 1 / (1/s₁ + … + 1/s_L) (Sun & Hollerbach 2008; A-optimality)
};

/// "O1" … "O5".
[[nodiscard]] const char* toString(ObservabilityIndex index);
/// Parses "O1" … "O5" (case-insensitive); throws pkm::InvalidArgument otherwise.
[[nodiscard]] ObservabilityIndex parseObservabilityIndex(const std::string& text);

/// The index for singular values `s` (descending, all of them: a zero makes O1–O5 zero) of a
/// Jacobian with `rows` rows. Throws pkm::InvalidArgument when s is empty or rows < 1.
[[nodiscard]] double observabilityIndex(ObservabilityIndex index,
                                        const Eigen::VectorXd& s,
                                        Eigen::Index rows);

}  // namespace pkm::calibration
