#include "pkm/simulation/random.hpp"

#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"

namespace pkm::simulation {

std::uint64_t streamSeed(std::uint64_t scenario_seed, std::string_view stream_name) {
  constexpr std::uint64_t kFnvOffset = 14695981039346656037ULL;
  constexpr std::uint64_t kFnvPrime = 1099511628211ULL;
  std::uint64_t h = kFnvOffset;
  for (int i = 0; i < 8; ++i) {
    h ^= (scenario_seed >> (8 * i)) & 0xffU;
    h *= kFnvPrime;
  }
  for (const char c : stream_name) {
    h ^= static_cast<unsigned char>(c);
    h *= kFnvPrime;
  }
  // splitmix64 finaliser: spreads nearby hashes over the whole range.
  h += 0x9e3779b97f4a7c15ULL;
  h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
  return h ^ (h >> 31);
}

RandomStream::RandomStream(std::uint64_t seed) : engine_(seed) {}

RandomStream::RandomStream(std::uint64_t scenario_seed, std::string_view name)
    : engine_(streamSeed(scenario_seed, name)) {}

double RandomStream::uniform() {
  constexpr double kTwoToMinus53 = 1.0 / 9007199254740992.0;
  return static_cast<double>(engine_() >> 11) * kTwoToMinus53;
}

double RandomStream::uniform(double lo, double hi) {
  PKM_CHECK(lo <= hi, "uniform: lo {} is larger than hi {}", lo, hi);
  return lo + (hi - lo) * uniform();
}

double RandomStream::normal() {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();  // log(0) is excluded
  const double u2 = uniform();
  const double r = std::sqrt(-2.0 * std::log(u1));
  const double angle = 2.0 * std::numbers::pi * u2;
  spare_ = r * std::sin(angle);
  has_spare_ = true;
  return r * std::cos(angle);
}

double RandomStream::normal(double sigma) {
  PKM_CHECK(sigma >= 0.0, "normal: sigma {} is negative", sigma);
  return sigma == 0.0 ? 0.0 : sigma * normal();
}

}  // namespace pkm::simulation
