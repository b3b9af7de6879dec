/// @file
/// @brief Internal: reproducible Gaussian noise for Monte Carlo trials — one stream per (seed,
/// trial), the same numbers on every platform and for every thread count (monteCarloHexapod in
/// uncertainty.cpp and monteCarloExechon in exechon_uncertainty.cpp).
#pragma once

#include <cmath>
#include <cstdint>
#include <numbers>
#include <random>

namespace pkm::calibration::detail {

/// Standard normal variates by Box–Muller (Box & Muller 1958, Ann. Math. Stat. 29:610) on a 64-bit
/// Mersenne twister: std::normal_distribution is implementation-defined, this is not.
class GaussianStream {
 public:
  explicit GaussianStream(std::uint64_t seed) : engine_(seed) {}
  /// The next N(0, 1) variate.
  double operator()() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    constexpr double kScale = 1.0 / 9007199254740992.0;  // 2^-53
    const double u1 = (static_cast<double>(engine_() >> 11) + 0.5) * kScale;
    const double u2 = static_cast<double>(engine_() >> 11) * kScale;
    const double r = std::sqrt(-2.0 * std::log(u1));
    spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
    has_spare_ = true;
    return r * std::cos(2.0 * std::numbers::pi * u2);
  }

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

/// The seed of trial k: a splitmix64 step (Steele, Lea & Flood 2014) of (seed, k), so that trial
/// streams do not overlap in practice.
inline std::uint64_t trialSeed(std::uint64_t seed, int k) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (static_cast<std::uint64_t>(k) + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace pkm::calibration::detail
