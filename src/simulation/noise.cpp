#include "pkm/simulation/noise.hpp"

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::simulation {

void NoiseModel::validate() const {
  PKM_CHECK(std::isfinite(sigma) && sigma >= 0.0, "noise sigma {} must be finite and >= 0", sigma);
  PKM_CHECK(std::isfinite(sigma_ppm) && sigma_ppm >= 0.0,
            "noise sigma_ppm {} must be finite and >= 0",
            sigma_ppm);
  PKM_CHECK(std::isfinite(resolution) && resolution >= 0.0,
            "noise resolution {} must be finite and >= 0",
            resolution);
}

double NoiseModel::totalSigma(double length) const {
  constexpr double kPpm = 1e-6;
  return std::hypot(sigma, sigma_ppm * kPpm * length);
}

namespace {

/// `value` rounded to `resolution` (0: unchanged).
double rounded(double value, double resolution) {
  if (!(resolution > 0.0)) return value;
  // Divide by the integer 1/resolution when there is one (1 nm = 1e-6 mm), so that the result is
  // the double nearest the decimal reading and prints in its shortest form.
  const double per_unit = std::round(1.0 / resolution);
  const bool decimal = per_unit >= 1.0 && std::abs(per_unit * resolution - 1.0) < 1e-12;
  return decimal ? std::round(value * per_unit) / per_unit
                 : std::round(value / resolution) * resolution;
}

}  // namespace

double NoiseModel::apply(double truth, double length, RandomStream& rng) const {
  const double s = totalSigma(length);
  const double value = truth + (s > 0.0 ? rng.normal(s) : 0.0);
  return perfect ? truth : rounded(value, resolution);
}

double NoiseModel::drawScale(RandomStream& rng) const {
  constexpr double kPpm = 1e-6;
  const double scale = sigma_ppm > 0.0 ? rng.normal(sigma_ppm * kPpm) : 0.0;
  return perfect ? 0.0 : scale;
}

double NoiseModel::scaleFor(double z) const {
  constexpr double kPpm = 1e-6;
  return perfect ? 0.0 : z * sigma_ppm * kPpm;
}

double NoiseModel::apply(double truth, double length, double scale, RandomStream& rng) const {
  const double value = truth + scale * length + (sigma > 0.0 ? rng.normal(sigma) : 0.0);
  return perfect ? truth : rounded(value, resolution);
}

std::optional<NoiseModel> instrumentNoise(std::string_view name) {
  // Written as quotients so that each value is the double nearest its decimal.
  if (name == "ideal") return NoiseModel{};
  if (name == "xl80-linear") return NoiseModel{10.0 / 1e6, 0.25, 1.0 / 1e6};        // mm
  if (name == "xl80-straightness") return NoiseModel{0.25 / 1e3, 0.0, 0.01 / 1e3};  // mm
  if (name == "xl80-angular") return NoiseModel{0.05 / 1e6, 0.0, 0.01 / 1e6};       // rad
  if (name == "dial-gauge") return NoiseModel{0.5 / 1e3, 0.0, 1.0 / 1e3};           // mm
  return std::nullopt;
}

std::vector<std::string_view> instrumentNoiseNames() {
  return {"ideal", "xl80-linear", "xl80-straightness", "xl80-angular", "dial-gauge"};
}

}  // namespace pkm::simulation
