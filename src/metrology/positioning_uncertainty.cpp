// Uncertainty budgets of ISO 230-2 results (metrology/positioning_uncertainty.hpp).
#include "pkm/metrology/positioning_uncertainty.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <optional>

#include "metrology/detail/length_contributor.hpp"
#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

/// One directional mean of a target: x̄, s and n (a candidate extreme of a range), and the
/// degrees of freedom of its variance (n − 1; Welch–Satterthwaite for a bidirectional mean).
struct Mean {
  double target = 0.0;
  double mean = 0.0;
  double s = 0.0;
  int n = 0;
  double dof = 0.0;
};

/// A variance with its degrees of freedom: one term of a Type A contributor.
struct Part {
  double variance = 0.0;
  double dof = 0.0;
};

std::vector<Mean> directionalMeans(const Iso230_2Result& r) {
  std::vector<Mean> out;
  for (const TargetStatistics& t : r.targets) {
    out.push_back({t.target, t.mean_up, t.s_up, t.runs_up, t.runs_up - 1.0});
    out.push_back({t.target, t.mean_down, t.s_down, t.runs_down, t.runs_down - 1.0});
  }
  return out;
}

/// Variance of a mean of n readings with standard deviation s: s²/n, with ν = n − 1.
Part meanVariance(const Mean& m) { return {m.s * m.s / m.n, m.dof}; }
/// Variance of the estimate s itself (normal readings): s²/(2(n − 1)), with ν = n − 1 (GUM G.4.2:
/// the relative uncertainty of s is 1/√(2(n − 1))).
Part sVariance(double s, int n, double scale = 1.0) {
  return {scale * scale * s * s / (2.0 * (n - 1)), n - 1.0};
}

/// A Type A contributor (normal, k = 1) whose variance is the sum of `parts`, each with its
/// degrees of freedom: u = √Σv, ν by Welch–Satterthwaite (GUM G.4.1).
UncertaintyContributor statistic(std::string name,
                                 const std::vector<Part>& parts,
                                 std::string source) {
  std::vector<double> v, dof;
  for (const Part& p : parts) {
    v.push_back(p.variance);
    dof.push_back(p.dof);
  }
  double sum = 0.0;
  for (const double x : v) sum += x;
  UncertaintyContributor c;
  c.name = std::move(name);
  c.value = std::sqrt(sum);
  c.unit = "mm";
  c.distribution = Distribution::kNormal;
  c.normal_k = 1.0;
  c.source = std::move(source);
  c.degrees_of_freedom = welchSatterthwaite(v, dof);
  return c;
}

Part scaled(Part p, double scale) { return {scale * p.variance, p.dof}; }
/// The variance of x̄↑ (or x̄↓) at a target, s²/n with ν = n − 1.
Part upMean(const TargetStatistics& t) { return {t.s_up * t.s_up / t.runs_up, t.runs_up - 1.0}; }
Part downMean(const TargetStatistics& t) {
  return {t.s_down * t.s_down / t.runs_down, t.runs_down - 1.0};
}

/// The laser's resolution in a difference of two readings (rectangular, half the resolution,
/// sensitivity √2).
void addResolutionContributor(UncertaintyBudget& b, const UncertaintySources& src) {
  addContributor(b,
                 detail::boundedContributor("laser resolution (two readings)",
                                            src.laser.resolution_mm / 2.0,
                                            "mm",
                                            std::sqrt(2.0),
                                            "instrument"));
}

/// The resolution of two readings (a difference) and E_VE: the terms of B and R.
void addReadingContributors(UncertaintyBudget& b, const UncertaintySources& src) {
  addResolutionContributor(b, src);
  addContributor(b,
                 detail::boundedContributor("environmental variation error E_VE",
                                            src.environment.environmental_variation_mm / 2.0,
                                            "mm",
                                            1.0,
                                            "drift test (ISO 230-2 Annex A)"));
}

/// The instrument's reading noise σ raises a largest-of-targets statistic even on a machine that
/// repeats perfectly: by up to `half_width` (its expected value when every target's true value is
/// the same; expectedMaxAbsNormal, expectedMaxSampleSigma). One-sided, budgeted as a rectangular
/// half-width (GUM F.2.4.4), as the roundness's noise bias.
void addNoiseFloor(UncertaintyBudget& b, double half_width, std::size_t targets) {
  addContributor(b,
                 detail::boundedContributor(
                     fmt::format("laser reading noise raising the largest of {} targets", targets),
                     half_width,
                     "mm",
                     1.0,
                     "instrument reading noise, expected maximum over the targets"));
}

/// E[max over the targets] of a reversal's noise, σ·√(1/n↑ + 1/n↓)·E max|Z| (mm).
double reversalNoise(const Iso230_2Result& r, const TargetStatistics& t, double sigma) {
  return sigma * std::sqrt(1.0 / t.runs_up + 1.0 / t.runs_down) *
         expectedMaxAbsNormal(r.targets.size());
}

/// E or M: a range between the largest and the smallest of `means`.
UncertaintyBudget rangeBudget(const char* quantity,
                              double value,
                              const std::vector<Mean>& means,
                              double mean_variance_scale,
                              const UncertaintySources& src) {
  const Mean* hi = &means.front();
  const Mean* lo = &means.front();
  for (const Mean& m : means) {
    if (m.mean > hi->mean) hi = &m;
    if (m.mean < lo->mean) lo = &m;
  }
  UncertaintyBudget b = detail::lengthBudget(quantity, value, src.coverage_factor);
  addLaserLengthContributors(b, std::abs(hi->target - lo->target), src);
  addContributor(b,
                 statistic("sampling of the extreme means (s/sqrt(n))",
                           {scaled(meanVariance(*hi), mean_variance_scale),
                            scaled(meanVariance(*lo), mean_variance_scale)},
                           "test data"));
  addResolutionContributor(b, src);
  return b;
}

UncertaintyBudget accuracyBudget(const char* quantity,
                                 double value,
                                 const std::vector<Mean>& means,
                                 double k,
                                 const UncertaintySources& src) {
  const Mean* hi = &means.front();
  const Mean* lo = &means.front();
  for (const Mean& m : means) {
    if (m.mean + k * m.s > hi->mean + k * hi->s) hi = &m;
    if (m.mean - k * m.s < lo->mean - k * lo->s) lo = &m;
  }
  UncertaintyBudget b = detail::lengthBudget(quantity, value, src.coverage_factor);
  addLaserLengthContributors(b, std::abs(hi->target - lo->target), src);
  addContributor(b,
                 statistic("sampling of the extreme means (s/sqrt(n))",
                           {meanVariance(*hi), meanVariance(*lo)},
                           "test data"));
  addContributor(b,
                 statistic("sampling of the extreme standard deviations (k s)",
                           {sVariance(hi->s, hi->n, k), sVariance(lo->s, lo->n, k)},
                           "test data"));
  addResolutionContributor(b, src);
  return b;
}

UncertaintyBudget reversalBudget(const Iso230_2Result& r, const UncertaintySources& src) {
  const TargetStatistics* c = &r.targets.front();
  for (const TargetStatistics& t : r.targets)
    if (std::abs(t.reversal) > std::abs(c->reversal)) c = &t;
  UncertaintyBudget b = detail::lengthBudget("B", r.B, src.coverage_factor);
  addContributor(b,
                 statistic("sampling of the two means at the target (s/sqrt(n))",
                           {upMean(*c), downMean(*c)},
                           "test data"));
  addReadingContributors(b, src);
  addNoiseFloor(b, reversalNoise(r, *c, src.laser.reading_noise_mm), r.targets.size());
  return b;
}

UncertaintyBudget repeatabilityBudget(const Iso230_2Result& r,
                                      double k,
                                      const UncertaintySources& src) {
  const TargetStatistics* c = &r.targets.front();
  for (const TargetStatistics& t : r.targets)
    if (t.repeatability > c->repeatability) c = &t;
  UncertaintyBudget b = detail::lengthBudget("R", r.R, src.coverage_factor);
  const double bidirectional = k * c->s_up + k * c->s_down + std::abs(c->reversal);
  std::vector<Part> parts;
  const double sigma = src.laser.reading_noise_mm;
  const std::size_t m = r.targets.size();
  double noise = 0.0;
  if (c->repeatability == bidirectional) {
    parts = {sVariance(c->s_up, c->runs_up, k),
             sVariance(c->s_down, c->runs_down, k),
             upMean(*c),
             downMean(*c)};
    noise = k * sigma *
                (expectedMaxSampleSigma(m, c->runs_up) + expectedMaxSampleSigma(m, c->runs_down)) +
            reversalNoise(r, *c, sigma);
  } else if (c->repeatability == 2.0 * k * c->s_up) {
    parts = {sVariance(c->s_up, c->runs_up, 2.0 * k)};
    noise = 2.0 * k * sigma * expectedMaxSampleSigma(m, c->runs_up);
  } else {
    parts = {sVariance(c->s_down, c->runs_down, 2.0 * k)};
    noise = 2.0 * k * sigma * expectedMaxSampleSigma(m, c->runs_down);
  }
  addContributor(
      b, statistic("sampling of the standard deviations at the target", parts, "test data"));
  addReadingContributors(b, src);
  addNoiseFloor(b, noise, m);
  return b;
}

/// The means of the one direction of unidirectional data (up when every target has runs up).
std::vector<Mean> oneDirection(const Iso230_2Result& r, bool up) {
  std::vector<Mean> out;
  for (const TargetStatistics& t : r.targets)
    out.push_back(up ? Mean{t.target, t.mean_up, t.s_up, t.runs_up, t.runs_up - 1.0}
                     : Mean{t.target, t.mean_down, t.s_down, t.runs_down, t.runs_down - 1.0});
  return out;
}

/// R↑ (or R↓) = max_i 2k s_i: the sampling uncertainty of that s, 2k·s/√(2(n − 1)).
UncertaintyBudget unidirectionalRepeatabilityBudget(const char* quantity,
                                                    double value,
                                                    const std::vector<Mean>& means,
                                                    double k,
                                                    const UncertaintySources& src) {
  const Mean* c = &means.front();
  for (const Mean& m : means)
    if (m.s > c->s) c = &m;
  UncertaintyBudget b = detail::lengthBudget(quantity, value, src.coverage_factor);
  addContributor(b,
                 statistic("sampling of the standard deviation at the target",
                           {sVariance(c->s, c->n, 2.0 * k)},
                           "test data"));
  addReadingContributors(b, src);
  addNoiseFloor(b,
                2.0 * k * src.laser.reading_noise_mm * expectedMaxSampleSigma(means.size(), c->n),
                means.size());
  return b;
}

/// E, A and R of the direction that unidirectional data has: "E_up", "A_up", "R_up" (or _down).
std::vector<UncertaintyBudget> unidirectionalBudgets(const Iso230_2Result& result,
                                                     double coverage,
                                                     const UncertaintySources& src) {
  const bool up = std::isfinite(result.E_up);
  if (!up && !std::isfinite(result.E_down)) return {};
  const std::vector<Mean> means = oneDirection(result, up);
  for (const Mean& m : means)
    if (m.n < 2) return {};
  std::vector<UncertaintyBudget> out;
  out.push_back(
      rangeBudget(up ? "E_up" : "E_down", up ? result.E_up : result.E_down, means, 1.0, src));
  out.push_back(accuracyBudget(
      up ? "A_up" : "A_down", up ? result.A_up : result.A_down, means, coverage, src));
  out.push_back(unidirectionalRepeatabilityBudget(
      up ? "R_up" : "R_down", up ? result.R_up : result.R_down, means, coverage, src));
  return out;
}

}  // namespace

std::vector<UncertaintyBudget> iso230_2Uncertainty(const Iso230_2Result& result,
                                                   const UncertaintySources& sources,
                                                   double coverage) {
  std::string why;
  PKM_CHECK(sources.isValid(&why), "uncertainty sources: {}", why);
  if (result.targets.empty()) return {};
  if (!result.bidirectional) return unidirectionalBudgets(result, coverage, sources);
  const std::vector<Mean> directional = directionalMeans(result);
  std::vector<Mean> bidirectional;
  for (const TargetStatistics& t : result.targets) {
    // x̄i = (x̄i↑ + x̄i↓)/2: its variance is (s↑²/n↑ + s↓²/n↓)/4; carried as s²/n with n = 1,
    // its degrees of freedom by Welch–Satterthwaite.
    const Part up = upMean(t), down = downMean(t);
    const double var = (up.variance + down.variance) / 4.0;
    bidirectional.push_back({t.target,
                             t.mean,
                             std::sqrt(var),
                             1,
                             welchSatterthwaite({up.variance, down.variance}, {up.dof, down.dof})});
  }
  std::vector<UncertaintyBudget> out;
  out.push_back(rangeBudget("E", result.E, directional, 1.0, sources));
  out.push_back(rangeBudget("M", result.M, bidirectional, 1.0, sources));
  out.push_back(accuracyBudget("A", result.A, directional, coverage, sources));
  out.push_back(reversalBudget(result, sources));
  out.push_back(repeatabilityBudget(result, coverage, sources));
  return out;
}

std::vector<ConformanceResult> decideIso230_2Conformance(
    const std::vector<UncertaintyBudget>& budgets,
    const std::vector<std::pair<std::string, double>>& tolerances) {
  std::vector<ConformanceResult> out;
  for (const auto& [name, limit] : tolerances) {
    const UncertaintyBudget* found = nullptr;
    for (const UncertaintyBudget& b : budgets)
      if (b.quantity == name) found = &b;
    PKM_CHECK(found != nullptr,
              "conformance: no uncertainty budget for '{}' (E, M, A, B or R of bidirectional data; "
              "E_up, A_up, R_up or the _down ones of unidirectional data)",
              name);
    PKM_CHECK(std::isfinite(limit), "conformance: tolerance of {} must be finite", name);
    const double U = found->expandedUncertainty();
    out.push_back({name, found->value, U, limit, decideConformance(found->value, U, limit)});
  }
  return out;
}

}  // namespace pkm::metrology
