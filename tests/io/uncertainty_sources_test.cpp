// Instrument and environment descriptions as JSON (io/uncertainty_sources.hpp): round trip,
// partial documents and bad input with FILE:LINE.
#include "pkm/io/uncertainty_sources.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "pkm/core/error.hpp"
#include "pkm/io/named_text.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::string errorOf(const std::string& text) {
  try {
    (void)readUncertaintySources({"src.json", text});
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(UncertaintySourcesJson, RoundTripsEveryField) {
  metrology::UncertaintySources s;
  s.laser.name = "lab laser";
  s.laser.wavelength_accuracy_ppm = 0.02;
  s.laser.air_pressure_accuracy_pa = 0.1 + 0.2;  // not a short decimal
  s.probe.form_2d_mm = 1e-3;
  s.tracker.accuracy_mm = 0.01;
  s.actuators.name = "lab struts";
  s.actuators.backlash_mm = 0.008;
  s.actuators.lead_error_mm_per_m = 0.1;
  s.actuators.lead_wave_mm = 0.01;
  s.hexapod_platform.mass_kg = 150.0;
  s.hexapod_platform.com_z_mm = -100.0;
  s.exechon_head.mass_kg = 250.0;
  s.exechon_head.leg_stiffness_n_per_um = 40.0;
  s.ballbar.name = "lab ballbar";
  s.ballbar.sensor_accuracy_mm = 0.7e-3;
  s.environment.air.temperature_c = 21.7;
  s.environment.dead_path_mm = 150.0;
  s.environment.material_temperature_c = 23.4;
  s.coverage_factor = 2.5;
  const std::string text = uncertaintySourcesJson(s);
  const metrology::UncertaintySources back = readUncertaintySources({"round.json", text});
  EXPECT_EQ(uncertaintySourcesJson(back), text);
  EXPECT_EQ(back.laser.name, "lab laser");
  EXPECT_EQ(back.laser.air_pressure_accuracy_pa, 0.1 + 0.2);
  EXPECT_EQ(back.environment.air.temperature_c, 21.7);
  EXPECT_EQ(back.coverage_factor, 2.5);
  EXPECT_EQ(back.actuators.name, "lab struts");
  EXPECT_EQ(back.actuators.backlash_mm, 0.008);
  EXPECT_EQ(back.actuators.lead_error_mm_per_m, 0.1);
  EXPECT_EQ(back.actuators.lead_wave_mm, 0.01);
  EXPECT_EQ(back.hexapod_platform.com_z_mm, -100.0);
  EXPECT_EQ(back.exechon_head.mass_kg, 250.0);
  EXPECT_EQ(back.exechon_head.leg_stiffness_n_per_um, 40.0);
  EXPECT_EQ(back.ballbar.name, "lab ballbar");
  EXPECT_EQ(back.ballbar.sensor_accuracy_mm, 0.7e-3);
  EXPECT_THAT(text, HasSubstr(kUncertaintySourcesSchema));
}

TEST(UncertaintySourcesJson, MissingMembersKeepTheDefaults) {
  const metrology::UncertaintySources s =
      readUncertaintySources({"p.json", R"({"environment": {"dead_path_mm": 200}})"});
  EXPECT_EQ(s.environment.dead_path_mm, 200.0);
  EXPECT_EQ(s.laser.wavelength_accuracy_ppm,
            metrology::LaserInterferometer{}.wavelength_accuracy_ppm);
  EXPECT_EQ(uncertaintySourcesJson(readUncertaintySources({"e.json", "{}"})),
            uncertaintySourcesJson(metrology::UncertaintySources{}));
}

TEST(UncertaintySourcesJson, ConditionsTheFileStatesAreMarkedStated) {
  const metrology::UncertaintySources s = readUncertaintySources(
      {"p.json", R"({"environment": {"dead_path_mm": 200, "air": {"temperature_c": 21}}})"});
  const metrology::ConditionOrigins& o = s.environment.origin;
  EXPECT_EQ(o.dead_path, metrology::ConditionOrigin::kStated);
  EXPECT_EQ(o.air_temperature, metrology::ConditionOrigin::kStated);
  EXPECT_EQ(o.air_pressure, metrology::ConditionOrigin::kDefault);
  EXPECT_EQ(o.material_temperature, metrology::ConditionOrigin::kDefault);
  EXPECT_STREQ(metrology::toString(o.dead_path), "stated");
}

TEST(UncertaintySourcesJson, BadInputNamesFileAndLine) {
  EXPECT_THAT(errorOf("{\n  \"laser\": {\n    \"bogus\": 1\n  }\n}\n"),
              HasSubstr("src.json:3: /laser/bogus: unknown key 'bogus'"));
  EXPECT_THAT(errorOf("{\n  \"probe\": {\n    \"form_2d_mm\": \"big\"\n  }\n}\n"),
              HasSubstr("src.json:3: /probe/form_2d_mm: expected a number"));
  EXPECT_THAT(errorOf("{\n  \"environment\": {\"air\": {\"pressure_pa\": 5}}\n}\n"),
              HasSubstr("pressure"));
  EXPECT_THAT(errorOf("{\n  \"laser\": [1,\n"), HasSubstr("src.json:"));
  EXPECT_THAT(errorOf(R"({"schema": "other"})"), HasSubstr("unsupported schema"));
  EXPECT_THAT(errorOf(R"({"coverage_factor": 0})"), HasSubstr("coverage_factor"));
  // The machine's statements: a screw wave of no length, a negative mass, a stiffness of 0.
  EXPECT_THAT(errorOf(R"({"actuators": {"lead_wave_length_mm": 0}})"),
              HasSubstr("lead_wave_length_mm must be > 0"));
  EXPECT_THAT(errorOf(R"({"exechon_head": {"mass_kg": -1}})"),
              HasSubstr("exechon_head mass_kg must be >= 0"));
  EXPECT_THAT(errorOf(R"({"hexapod_platform": {"strut_stiffness_n_per_um": 0}})"),
              HasSubstr("strut_stiffness_n_per_um must be > 0"));
  EXPECT_THAT(errorOf(R"({"hexapod_platform": {"strut_com_fraction": 2}})"),
              HasSubstr("strut_com_fraction"));
}

TEST(UncertaintySourcesJson, TheRealisticWorkshopsStatementReads) {
  const metrology::UncertaintySources s = readUncertaintySources(
      readNamedText(std::string(PKM_SOURCE_DIR) + "/data/uncertainty/realistic-workshop.json"));
  EXPECT_EQ(s.actuators.lead_error_mm_per_m, 0.1);
  EXPECT_EQ(s.hexapod_platform.mass_kg, 150.0);
  EXPECT_EQ(s.exechon_head.com_z_mm, 200.0);
  EXPECT_EQ(s.tracker.accuracy_mm, metrology::LaserTrackerSpec{}.accuracy_mm);  // not stated
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
