// Environment: the presets and the validity checks.
#include "pkm/simulation/environment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace {

namespace sim = pkm::simulation;

TEST(Environment, IdealIsTheDefaultAndInactive) {
  const sim::Environment d;
  EXPECT_FALSE(d.active());
  EXPECT_EQ(d.name, "ideal");
  ASSERT_TRUE(sim::environmentPreset("ideal").has_value());
  EXPECT_FALSE(sim::environmentPreset("ideal")->active());
  EXPECT_FALSE(sim::environmentPreset("lab").has_value());
}

TEST(Environment, RealisticIsValidActiveAndWithinTheSensorSpecification) {
  const auto r = sim::environmentPreset("realistic");
  ASSERT_TRUE(r.has_value());
  std::string why;
  EXPECT_TRUE(r->isValid(&why)) << why;
  EXPECT_TRUE(r->active());
  EXPECT_EQ(r->name, "realistic");
  // Sensor offsets inside a typical unit's ±0.2 K, ±1 hPa, ±6 %RH.
  EXPECT_LE(std::abs(r->air.temperature_sensor.offset), 0.2);
  EXPECT_LE(std::abs(r->air.pressure_sensor.offset), 100.0);
  EXPECT_LE(std::abs(r->air.humidity_sensor.offset), 6.0);
  for (const auto name : sim::environmentPresetNames())
    EXPECT_TRUE(sim::environmentPreset(name).has_value()) << name;
}

TEST(Environment, InvalidValuesAreNamed) {
  sim::Environment e;
  std::string why;
  e.duration_h = 0.0;
  EXPECT_FALSE(e.isValid(&why));
  EXPECT_NE(why.find("duration_h"), std::string::npos);
  e.duration_h = 8.0;
  e.air.dead_path_mm = -1.0;
  EXPECT_FALSE(e.isValid(&why));
  EXPECT_NE(why.find("dead_path_mm"), std::string::npos);
  e.air.dead_path_mm = 0.0;
  e.air.temperature_c = {20.0, 200.0, 0.0, 600.0};  // drifts out of Edlén's range
  EXPECT_FALSE(e.isValid(&why));
  EXPECT_NE(why.find("air"), std::string::npos);
  e.air.temperature_c = {20.0, 0.0, -0.1, 600.0};
  EXPECT_FALSE(e.isValid(&why));
  e.air.temperature_c = {20.0, 0.0, 0.1, 600.0};
  e.air.humidity_sensor.noise = std::nan("");
  EXPECT_FALSE(e.isValid(&why));
}

}  // namespace
