// The refractive index of air (core/air_refractive_index.hpp) against NIST's tabulated
// values of the modified Edlén equation.
#include "pkm/core/air_refractive_index.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm {
namespace PKM_TEST_NS {

constexpr double kTolNistTable = 1.5e-9;  // the table gives n to 9 decimals (±5e-10) + rounding

struct Row {
  double t_c, rh_percent, p_kpa, lambda_nm, n;
};

// NIST Engineering Metrology Toolbox, "Index of Refraction of Air" (J. A. Stone, J. H.
// Zimmerman), section VII, the comparison table of the Ciddor and modified Edlén equations: the
// modified Edlén column (t °C, RH %, p kPa, vacuum wavelength nm, n).
constexpr Row kNistEdlen[] = {
    {20, 0, 101.325, 633, 1.000271799},
    {20, 0, 60, 633, 1.000160920},
    {20, 0, 120, 633, 1.000321918},
    {50, 0, 100, 633, 1.000243270},
    {5, 0, 100, 633, 1.000282750},
    {-40, 0, 100, 633, 1.000337471},
    {50, 100, 120, 633, 1.000287864},
    {40, 75, 120, 633, 1.000299406},
    {20, 100, 100, 633, 1.000267394},
    {40, 100, 110, 1700, 1.000270237},
    {20, 0, 101.325, 1700, 1.000268483},
    {40, 100, 110, 300, 1.000288922},
    {20, 0, 101.325, 300, 1.000286579},
    {-40, 0, 120, 300, 1.000427072},
};

TEST(AirRefractiveIndex, ReproducesNistsModifiedEdlenTable) {
  for (const Row& row : kNistEdlen) {
    const AirConditions air{row.t_c, row.p_kpa * 1000.0, row.rh_percent};
    EXPECT_NEAR(refractiveIndexEdlen(air, row.lambda_nm / 1000.0), row.n, kTolNistTable)
        << row.t_c << " degC, " << row.rh_percent << " %RH, " << row.p_kpa << " kPa, "
        << row.lambda_nm << " nm";
  }
}

TEST(AirRefractiveIndex, SaturationVapourPressureOfWaterAndIce) {
  // Steam tables: 2339.3 Pa at 20 °C, 101 418 Pa at 100 °C, the triple point 611.657 Pa; ice at
  // −10 °C 259.9 Pa.
  EXPECT_NEAR(saturationVapourPressure(20.0), 2339.3, 0.5);
  EXPECT_NEAR(saturationVapourPressure(100.0), 101418.0, 5.0);
  EXPECT_NEAR(saturationVapourPressure(0.01), 611.657, 0.05);
  EXPECT_NEAR(saturationVapourPressure(-10.0), 259.9, 0.5);
  EXPECT_THROW((void)saturationVapourPressure(500.0), InvalidArgument);
}

TEST(AirRefractiveIndex, SensitivitiesMatchTheRulesOfThumb) {
  // Laser calibrators' rule of thumb: about −1 ppm per K of air temperature, +0.27 ppm per hPa,
  // and under 1 ppm per 100 %RH at 20 °C.
  const AirIndexSensitivity s = edlenSensitivity(AirConditions{});
  EXPECT_NEAR(s.per_kelvin * 1e6, -0.93, 0.03);
  EXPECT_NEAR(s.per_pascal * 1e6 * 100.0, 0.268, 0.01);
  EXPECT_NEAR(s.per_percent_rh * 1e6 * 100.0, -0.85, 0.03);
}

TEST(AirRefractiveIndex, RejectsConditionsOutsideTheEquationsRange) {
  EXPECT_TRUE(AirConditions{}.isValid());
  EXPECT_FALSE((AirConditions{.temperature_c = 120.0}.isValid()));
  EXPECT_FALSE((AirConditions{.pressure_pa = 1000.0}.isValid()));
  EXPECT_FALSE((AirConditions{.relative_humidity = -1.0}.isValid()));
  EXPECT_THROW((void)refractiveIndexEdlen(AirConditions{.temperature_c = NAN}), InvalidArgument);
  EXPECT_THROW((void)refractiveIndexEdlen(AirConditions{}, 10.6), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
