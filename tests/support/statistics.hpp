/// @file
/// @brief Sample statistics and acceptance bounds for the statistical tests of simulated noise.
#pragma once

#include <cmath>
#include <vector>

namespace pkm::test {

/// Sample mean.
inline double sampleMean(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s / static_cast<double>(v.size());
}

/// Sample standard deviation (n − 1 in the denominator).
inline double sampleSigma(const std::vector<double>& v) {
  const double m = sampleMean(v);
  double s = 0.0;
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / static_cast<double>(v.size() - 1));
}

/// Number of standard errors a statistic may stray before a test fails: with fixed seeds the tests
/// are deterministic, and 5 standard errors would fail a fresh seed with probability below 1e-6.
inline constexpr double kStatZ = 5.0;

/// Acceptance half-width of sampleSigma/σ around 1 for n normal samples: the chi-square statistic
/// (n − 1)s²/σ² has standard deviation √(2(n − 1)), so s/σ has about 1/√(2(n − 1)).
inline double sigmaRatioTolerance(std::size_t n) {
  return kStatZ / std::sqrt(2.0 * static_cast<double>(n - 1));
}

/// Acceptance half-width of the sample mean of n samples with standard deviation σ.
inline double meanTolerance(std::size_t n, double sigma) {
  return kStatZ * sigma / std::sqrt(static_cast<double>(n));
}

}  // namespace pkm::test
