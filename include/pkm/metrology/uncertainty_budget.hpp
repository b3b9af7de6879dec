/// @file
/// @brief Uncertainty budgets of the GUM (JCGM 100:2008) as ISO/TR 230-9:2005 applies them to
/// machine-tool tests: contributors with a distribution and a sensitivity coefficient, the law of
/// propagation of uncertainty (GUM §5.1.2 eq. 10, uncorrelated; §5.2.2 eq. 13/16, correlated), the
/// combined standard uncertainty u_c and the expanded uncertainty U = k u_c (GUM §6.2.1 eq. 18;
/// k = 2 as ISO/TR 230-9 and ISO 230-2 state it). docs/analysis.md, "Measurement uncertainty".
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pkm::metrology {

/// The probability distribution assigned to a contributor (GUM §4.3.7, §4.3.9; ISO/TR 230-9
/// §5.2 and Table 1 list the same four with their divisors).
enum class Distribution {
  kNormal,       ///< `value` is an expanded uncertainty with coverage factor `normal_k`
  kRectangular,  ///< `value` is the half-width a of equal probability in [−a, a]: divisor √3
  kTriangular,   ///< `value` is the half-width a of a triangle on [−a, a]: divisor √6
  kUShaped,  ///< `value` is the amplitude a of a sinusoid (arcsine law on [−a, a]): divisor √2
};

/// "normal", "rectangular", "triangular" or "u-shaped".
[[nodiscard]] const char* toString(Distribution distribution);
/// The distribution of a name written by toString; nullopt for anything else.
[[nodiscard]] std::optional<Distribution> parseDistribution(std::string_view name);

/// One input quantity of a budget (GUM §5.1.2: x_i, u(x_i), c_i; ISO/TR 230-9 §6 lists the
/// contributors of machine-tool tests).
struct UncertaintyContributor {
  std::string name;  ///< what it is ("laser wavelength (vacuum)", "air temperature sensor", ...)
  /// The stated spread in `unit`: the half-width a (rectangular, triangular, U-shaped) or the
  /// expanded uncertainty with coverage factor `normal_k` (normal; normal_k = 1: the standard
  /// uncertainty itself). >= 0.
  double value = 0.0;
  std::string unit;  ///< unit of `value` ("mm", "K", "Pa", "%RH", "1", "rad", ...)
  Distribution distribution = Distribution::kNormal;
  double normal_k = 1.0;  ///< coverage factor of `value` for kNormal (ignored otherwise), > 0
  /// Sensitivity coefficient c_i = ∂f/∂x_i (GUM §5.1.3 eq. 11a) in result unit per `unit`.
  double sensitivity = 1.0;
  double estimate = 0.0;  ///< best estimate x_i in `unit` (used by the Monte Carlo model)
  std::string source;     ///< where the value comes from (datasheet, data, assumption)

  /// The divisor that turns `value` into a standard uncertainty: normal_k, √3, √6 or √2.
  [[nodiscard]] double divisor() const;
  /// u(x_i) = value / divisor(), in `unit`.
  [[nodiscard]] double standardUncertainty() const;
  /// u_i(y) = |c_i| u(x_i), in the result's unit (GUM §5.1.3 eq. 11b).
  [[nodiscard]] double contribution() const;
};

/// A correlation coefficient r(x_i, x_j) between two contributors of a budget (GUM §5.2.2
/// eq. 14), −1 <= r <= 1, i != j.
struct Correlation {
  std::size_t i = 0;
  std::size_t j = 0;
  double r = 0.0;
};

/// The uncertainty budget of one result y = f(x_1 ... x_N).
struct UncertaintyBudget {
  std::string quantity;  ///< the result's name ("E", "straightness", "radius", ...)
  std::string unit;      ///< the result's unit
  double value = 0.0;    ///< the result y
  std::vector<UncertaintyContributor> contributors;
  std::vector<Correlation> correlations;  ///< pairs not listed are uncorrelated
  double coverage_factor = 2.0;           ///< k of U = k u_c (ISO/TR 230-9 §5.4: k = 2)

  /// Throws pkm::InvalidArgument for a negative or non-finite value, normal_k <= 0, a
  /// non-finite sensitivity, a correlation index out of range or i == j, |r| > 1, or k <= 0.
  void validate() const;
  /// u_c(y): the square root of Σ c_i² u_i² + 2 Σ_{i<j} c_i c_j u_i u_j r_ij (GUM eq. 16; eq. 10
  /// without correlations). Throws as validate().
  [[nodiscard]] double combinedStandardUncertainty() const;
  /// U = k u_c (GUM eq. 18). Throws as validate().
  [[nodiscard]] double expandedUncertainty() const;
  /// Index of the contributor with the largest contribution |c_i| u_i; nullopt when empty.
  [[nodiscard]] std::optional<std::size_t> largestContributor() const;
};

/// Appends `c` to `budget` unless its contribution is exactly zero (a source that does not apply,
/// e.g. no dead path): budgets list only what contributes.
void addContributor(UncertaintyBudget& budget, UncertaintyContributor c);

}  // namespace pkm::metrology
