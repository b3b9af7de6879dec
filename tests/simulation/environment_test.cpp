// Environment: the presets and the validity checks.
#include "pkm/simulation/environment.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace PKM_TEST_NS {

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
  // Compliance on, with the magnitudes of docs/simulation-errors.md.
  EXPECT_TRUE(r->compliance.enabled);
  EXPECT_EQ(r->compliance.hexapod.strut_stiffness_n_per_um, 50.0);
  EXPECT_EQ(r->compliance.cartesian[1].kind, sim::AxisSag::Kind::kCantilever);
  EXPECT_EQ(r->compliance.x2.kind, sim::AxisSag::Kind::kSpan);
  EXPECT_FALSE(sim::environmentPreset("ideal")->compliance.enabled);
}

TEST(Environment, InvalidComplianceIsNamed) {
  sim::Environment e;
  std::string why;
  e.compliance.hexapod.strut_stiffness_n_per_um = 0.0;
  EXPECT_FALSE(e.isValid(&why));
  EXPECT_NE(why.find("strut_stiffness_n_per_um"), std::string::npos);
  e.compliance.hexapod.strut_stiffness_n_per_um = 50.0;
  e.compliance.hexapod.strut_com_fraction = 1.5;
  EXPECT_FALSE(e.isValid(&why));
  EXPECT_NE(why.find("strut_com_fraction"), std::string::npos);
  e.compliance.hexapod.strut_com_fraction = 0.5;
  e.compliance.y2.sense = 0.0;
  EXPECT_FALSE(e.isValid(&why));
  EXPECT_NE(why.find("sense"), std::string::npos);
  e.compliance.y2.sense = 1.0;
  e.compliance.exechon.joint_clearance_mm = -1.0;
  EXPECT_FALSE(e.isValid(&why));
  e.compliance.exechon.joint_clearance_mm = 0.0;
  EXPECT_TRUE(e.isValid(&why)) << why;
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

}  // namespace PKM_TEST_NS
