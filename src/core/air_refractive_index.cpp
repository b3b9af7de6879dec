// The refractive index of air (core/air_refractive_index.hpp): modified Edlén equation and
// the saturation vapour pressure of water, written from the published equations.
#include "pkm/core/air_refractive_index.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm {
namespace {

constexpr double kKelvin = 273.15;

/// IAPWS-IF97 region 4: saturation pressure over liquid water, T in K, result in Pa.
double overWater(double T) {
  constexpr double n1 = 1.16705214528e3, n2 = -7.24213167032e5, n3 = -1.70738469401e1;
  constexpr double n4 = 1.20208247025e4, n5 = -3.23255503223e6, n6 = 1.49151086135e1;
  constexpr double n7 = -4.82326573616e3, n8 = 4.05113405421e5, n9 = -2.38555575678e-1;
  constexpr double n10 = 6.50175348448e2;
  const double omega = T + n9 / (T - n10);
  const double a = omega * omega + n1 * omega + n2;
  const double b = n3 * omega * omega + n4 * omega + n5;
  const double c = n6 * omega * omega + n7 * omega + n8;
  const double x = -b + std::sqrt(b * b - 4.0 * a * c);
  return 1e6 * std::pow(2.0 * c / x, 4);
}

/// IAPWS 1993 sublimation pressure over ice, T in K, result in Pa.
double overIce(double T) {
  constexpr double a1 = -13.928169, a2 = 34.7078238, triple_t = 273.16, triple_p = 611.657;
  const double theta = T / triple_t;
  return triple_p *
         std::exp(a1 * (1.0 - std::pow(theta, -1.5)) + a2 * (1.0 - std::pow(theta, -1.25)));
}

void checkWavelength(double lambda_um) {
  PKM_CHECK(std::isfinite(lambda_um) && lambda_um >= 0.3 && lambda_um <= 1.7,
            "refractive index of air: vacuum wavelength must be in 0.3..1.7 um, got {}",
            lambda_um);
}

}  // namespace

bool AirConditions::isValid(std::string* why) const {
  const auto fail = [&](std::string reason) {
    if (why) *why = std::move(reason);
    return false;
  };
  if (!(std::isfinite(temperature_c) && temperature_c >= -40.0 && temperature_c <= 100.0))
    return fail(fmt::format("air temperature must be in -40..100 degC, got {}", temperature_c));
  if (!(std::isfinite(pressure_pa) && pressure_pa >= 60000.0 && pressure_pa <= 140000.0))
    return fail(fmt::format("air pressure must be in 60000..140000 Pa, got {}", pressure_pa));
  if (!(std::isfinite(relative_humidity) && relative_humidity >= 0.0 && relative_humidity <= 100.0))
    return fail(fmt::format("relative humidity must be in 0..100 %, got {}", relative_humidity));
  return true;
}

double saturationVapourPressure(double temperature_c) {
  PKM_CHECK(std::isfinite(temperature_c) && temperature_c >= -100.0 && temperature_c <= 373.0,
            "saturation vapour pressure: temperature must be in -100..373 degC, got {}",
            temperature_c);
  const double T = temperature_c + kKelvin;
  return temperature_c >= 0.0 ? overWater(T) : overIce(T);
}

double refractiveIndexEdlen(const AirConditions& air, double vacuum_wavelength_um) {
  std::string why;
  PKM_CHECK(air.isValid(&why), "refractive index of air: {}", why);
  checkWavelength(vacuum_wavelength_um);
  const double s = 1.0 / (vacuum_wavelength_um * vacuum_wavelength_um);  // σ², µm⁻²
  const double t = air.temperature_c;
  const double p = air.pressure_pa;
  const double standard = 1e-8 * (8342.54 + 2406147.0 / (130.0 - s) + 15998.0 / (38.9 - s));
  const double density =
      p * (1.0 + 1e-8 * (0.601 - 0.00972 * t) * p) / (96095.43 * (1.0 + 0.003661 * t));
  const double vapour = air.relative_humidity / 100.0 * saturationVapourPressure(t);
  const double water = 1e-10 * (292.75 / (t + kKelvin)) * (3.7345 - 0.0401 * s) * vapour;
  return 1.0 + standard * density - water;
}

AirIndexSensitivity edlenSensitivity(const AirConditions& air, double vacuum_wavelength_um) {
  (void)refractiveIndexEdlen(air, vacuum_wavelength_um);  // validates
  const auto n = [&](double t, double p, double rh) {
    return refractiveIndexEdlen({t, p, rh}, vacuum_wavelength_um);
  };
  // Steps small against the range; one-sided where a step would leave it (RH at 0 or 100 %).
  constexpr double kDt = 0.01, kDp = 10.0, kDrh = 0.1;
  const double t = air.temperature_c, p = air.pressure_pa, rh = air.relative_humidity;
  const double rh_lo = std::max(0.0, rh - kDrh), rh_hi = std::min(100.0, rh + kDrh);
  AirIndexSensitivity out;
  out.per_kelvin = (n(t + kDt, p, rh) - n(t - kDt, p, rh)) / (2 * kDt);
  out.per_pascal = (n(t, p + kDp, rh) - n(t, p - kDp, rh)) / (2 * kDp);
  out.per_percent_rh = (n(t, p, rh_hi) - n(t, p, rh_lo)) / (rh_hi - rh_lo);
  return out;
}

}  // namespace pkm
