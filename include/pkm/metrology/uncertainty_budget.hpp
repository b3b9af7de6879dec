/// @file
/// @brief Uncertainty budgets of the GUM (JCGM 100:2008) as ISO/TR 230-9:2005 applies them to
/// machine-tool tests: contributors with a distribution and a sensitivity coefficient, the law of
/// propagation of uncertainty (GUM §5.1.2 eq. 10, uncorrelated; §5.2.2 eq. 13/16, correlated), the
/// combined standard uncertainty u_c, its effective degrees of freedom ν_eff (Welch–Satterthwaite,
/// GUM G.4.1 eq. G.2b) and the expanded uncertainty U = k u_c (GUM §6.2.1 eq. 18), k from
/// Student's t at ν_eff for the coverage probability that k = 2 has at ν = ∞ (95.45 %, GUM G.3.4
/// and Table G.2; k = 2 as ISO/TR 230-9 and ISO 230-2 state it for large samples).
/// docs/analysis.md, "Measurement uncertainty".
#pragma once

#include <cstddef>
#include <limits>
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
  /// Degrees of freedom ν_i of u(x_i) (GUM G.3.3): n − 1 for a Type A standard deviation of n
  /// readings, +∞ (the default) for a Type B value taken as exactly known. > 0.
  double degrees_of_freedom = std::numeric_limits<double>::infinity();

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

/// A measurement condition a budget was evaluated at (docs/analysis.md, "Measurement
/// conditions"): shown with the budget so that an assumed condition is never silently zero.
struct BudgetCondition {
  std::string name;    ///< e.g. "material temperature"
  double value = 0.0;  ///< in `unit`
  std::string unit;    ///< e.g. "degC"
  std::string origin;  ///< "recorded", "stated" or "default" (toString(ConditionOrigin))
  std::string note;    ///< how a recorded value was formed; may be empty
};

/// The uncertainty budget of one result y = f(x_1 ... x_N).
struct UncertaintyBudget {
  std::string quantity;  ///< the result's name ("E", "straightness", "radius", ...)
  std::string unit;      ///< the result's unit
  double value = 0.0;    ///< the result y
  std::vector<UncertaintyContributor> contributors;
  std::vector<Correlation> correlations;  ///< pairs not listed are uncorrelated
  /// k of U = k u_c at infinite degrees of freedom (ISO/TR 230-9 §5.4: k = 2); with a finite
  /// ν_eff, coverageFactor() widens it by Student's t at the same coverage probability.
  double coverage_factor = 2.0;
  /// The conditions the budget assumed (laser budgets: air, material temperature, dead path,
  /// alignment); empty for budgets that depend on none.
  std::vector<BudgetCondition> conditions;

  /// Throws pkm::InvalidArgument for a negative or non-finite value, normal_k <= 0, a
  /// non-finite sensitivity, degrees of freedom <= 0 or NaN, a correlation index out of range or
  /// i == j, |r| > 1, or k <= 0.
  void validate() const;
  /// u_c(y): the square root of Σ c_i² u_i² + 2 Σ_{i<j} c_i c_j u_i u_j r_ij (GUM eq. 16; eq. 10
  /// without correlations). Throws as validate().
  [[nodiscard]] double combinedStandardUncertainty() const;
  /// ν_eff = u_c⁴ / Σ (c_i u_i)⁴ / ν_i (Welch–Satterthwaite, GUM G.4.1 eq. G.2b; correlations
  /// do not enter ν); +∞ when every contributor's ν_i is infinite or u_c = 0. Throws as validate().
  [[nodiscard]] double effectiveDegreesOfFreedom() const;
  /// k = t_p(ν_eff), the two-sided Student's t quantile for p = 2Φ(coverage_factor) − 1 (95.45 %
  /// for k = 2; GUM G.3.4, Table G.2), not interpolated or truncated: coverage_factor itself for
  /// ν_eff = ∞. E.g. ν_eff = 2 gives 4.53, ν_eff = 10 gives 2.28. Throws as validate().
  [[nodiscard]] double coverageFactor() const;
  /// U = k u_c with k = coverageFactor() (GUM eq. 18). Throws as validate().
  [[nodiscard]] double expandedUncertainty() const;
  /// Index of the contributor with the largest contribution |c_i| u_i; nullopt when empty.
  [[nodiscard]] std::optional<std::size_t> largestContributor() const;
};

/// The two-sided Student's t quantile t_p(ν) for coverage probability p in (0, 1) and ν > 0
/// (ν = +∞: the normal quantile). Throws pkm::InvalidArgument outside those ranges.
[[nodiscard]] double studentT(double p, double degrees_of_freedom);

/// d2(n): the expected range (largest − smallest) of n independent standard normal values,
/// ∫ 1 − Φ(x)ⁿ − (1 − Φ(x))ⁿ dx (Tippett, Biometrika 17, 1925; the control-chart constant d2:
/// 1.128 for n = 2, 3.078 for n = 10). The noise bias of a range statistic such as a roundness
/// is about d2(n)·σ. Throws pkm::InvalidArgument for n < 2.
[[nodiscard]] double expectedNormalRange(std::size_t n);

/// E[max of m |Z|], Z standard normal: ∫₀^∞ 1 − (2Φ(x) − 1)^m dx (0.798 for m = 1). The noise
/// bias of the largest of m reversals |B_i| whose true values are equal. Throws
/// pkm::InvalidArgument for m < 1.
[[nodiscard]] double expectedMaxAbsNormal(std::size_t m);

/// E[max of m values s/σ], s the standard deviation of n normal readings (s/σ = χ_{n−1}/√(n−1)):
/// ∫₀^∞ 1 − F(x)^m dx with F the distribution of χ_{n−1}/√(n−1). The noise bias of the largest of
/// m repeatabilities 4s_i whose true values are equal, over 4σ. Throws pkm::InvalidArgument for
/// m < 1 or n < 2.
[[nodiscard]] double expectedMaxSampleSigma(std::size_t m, int n);

/// The Welch–Satterthwaite degrees of freedom of a sum of independent variances `variance[i]`
/// with `degrees_of_freedom[i]` each (GUM eq. G.2b): (Σ v)² / Σ v²/ν; +∞ when all are infinite or
/// the sum is 0. The vectors have the same size.
[[nodiscard]] double welchSatterthwaite(const std::vector<double>& variance,
                                        const std::vector<double>& degrees_of_freedom);

/// Appends `c` to `budget` unless its contribution is exactly zero (a source that does not apply,
/// e.g. no dead path): budgets list only what contributes.
void addContributor(UncertaintyBudget& budget, UncertaintyContributor c);

}  // namespace pkm::metrology
