/// @file
/// @brief A deterministic, platform-independent random source for simulated measurements: the
/// same seed gives the same numbers with every compiler and standard library (docs/conventions.md,
/// "Simulation"). std::normal_distribution and std::uniform_real_distribution are not used because
/// their algorithms differ between standard libraries.
#pragma once

#include <cstdint>
#include <random>
#include <string_view>

namespace pkm::simulation {

/// The seed of a named stream of a scenario: a hash (FNV-1a 64, then the splitmix64 finaliser) of
/// `scenario_seed` and `stream_name`. Each instrument and each machine noise source draws from its
/// own stream, so adding or removing one does not change the numbers another draws.
[[nodiscard]] std::uint64_t streamSeed(std::uint64_t scenario_seed, std::string_view stream_name);

/// A stream of uniform and normal variates from std::mt19937_64 (whose output is fixed by the C++
/// standard). Not thread-safe; use one stream per consumer.
class RandomStream {
 public:
  /// A stream seeded with `seed` (mt19937_64's single-integer seeding, fixed by the standard).
  explicit RandomStream(std::uint64_t seed);
  /// The stream streamSeed(scenario_seed, name).
  RandomStream(std::uint64_t scenario_seed, std::string_view name);

  /// The next raw 64-bit engine output (e.g. to seed a machine's own random effects).
  [[nodiscard]] std::uint64_t bits() { return engine_(); }
  /// A uniform variate in [0, 1): the top 53 bits of one engine output times 2⁻⁵³.
  [[nodiscard]] double uniform();
  /// A uniform variate in [lo, hi). Precondition: lo ≤ hi (pkm::InvalidArgument otherwise).
  [[nodiscard]] double uniform(double lo, double hi);
  /// A standard normal variate (mean 0, standard deviation 1) by the Box–Muller transform; the
  /// second variate of each pair is kept for the next call.
  [[nodiscard]] double normal();
  /// A normal variate with mean 0 and standard deviation `sigma` (≥ 0; 0 gives exactly 0 and
  /// draws nothing, so a zero-noise model leaves the stream untouched).
  [[nodiscard]] double normal(double sigma);

 private:
  std::mt19937_64 engine_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace pkm::simulation
