// Environment records of measurement files (io/environment_records.hpp): columns with units,
// several material sensors, metadata, and bad input with FILE:LINE.
#include "pkm/io/environment_records.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

constexpr double kTolConversion = 1e-9;  // unit conversions in floating point

metrology::RecordedConditions records(const std::string& text) {
  return environmentRecords(TextTable::parse(text, "laser.csv"));
}

std::string errorOf(const std::string& text) {
  try {
    (void)records(text);
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(EnvironmentRecords, PkmColumnsAreReadPerReading) {
  const auto r = records(
      "target_mm,run,direction,reading_mm,air_temperature_c,air_pressure_pa,air_humidity_rh,"
      "material_temperature_c\n"
      "0,1,+,0,20.40,101000.0,45.00,20.80\n"
      "100,1,+,100.001,20.60,101020.0,47.00,21.00\n");
  ASSERT_TRUE(r.air_temperature_c && r.air_pressure_pa && r.air_humidity_rh);
  ASSERT_TRUE(r.material_temperature_c);
  EXPECT_EQ(r.air_temperature_c->count, 2u);
  EXPECT_NEAR(r.air_temperature_c->mean, 20.5, kTolConversion);
  EXPECT_NEAR(r.air_pressure_pa->max, 101020.0, kTolConversion);
  EXPECT_NEAR(r.air_humidity_rh->min, 45.0, kTolConversion);
  EXPECT_NEAR(r.material_temperature_c->max, 21.0, kTolConversion);
  EXPECT_FALSE(r.dead_path_mm);
}

TEST(EnvironmentRecords, ExportNamesWithUnitsAndSeveralMaterialSensors) {
  // A laser software's export: pressure in hPa, temperatures with a degree sign, one of them in
  // kelvin, three material sensors averaged per reading.
  const auto r = records(
      "Target (mm),Error (um),Air Temp (\xC2\xB0"
      "C),Pressure [hPa],Humidity (%RH),"
      "Mat Temp 1 (\xC2\xB0"
      "C),Mat Temp 2 (K),Mat Temp 3 (degC)\n"
      "0,0.0,20.1,1012.5,40,20.0,293.75,21.0\n");
  ASSERT_TRUE(r.air_pressure_pa && r.material_temperature_c && r.air_temperature_c);
  EXPECT_NEAR(r.air_pressure_pa->mean, 101250.0, kTolConversion);
  EXPECT_NEAR(r.air_temperature_c->mean, 20.1, kTolConversion);
  EXPECT_NEAR(r.material_temperature_c->mean, (20.0 + 20.6 + 21.0) / 3, kTolConversion);
}

TEST(EnvironmentRecords, MetadataGivesFileValuesAndTheSetUp) {
  const auto r = records(
      "# air temperature C: 20.7\n# material temperature C: 21.3\n# air pressure Pa: 100500\n"
      "# air humidity %RH: 38\n# dead path mm: 120\n# beam alignment urad: 150\n"
      "target_mm,run,direction,reading_mm\n0,1,+,0\n");
  ASSERT_TRUE(r.air_temperature_c && r.material_temperature_c && r.dead_path_mm);
  EXPECT_EQ(r.air_temperature_c->mean, 20.7);
  EXPECT_EQ(r.material_temperature_c->mean, 21.3);
  EXPECT_EQ(r.air_pressure_pa->mean, 100500.0);
  EXPECT_EQ(r.air_humidity_rh->mean, 38.0);
  EXPECT_EQ(*r.dead_path_mm, 120.0);
  EXPECT_NEAR(*r.misalignment_rad, 150e-6, 1e-18);
  EXPECT_TRUE(records("target_mm,run,direction,reading_mm\n0,1,+,0\n").empty());
  const auto abbe = records("# abbe offset mm: 15\n# angular range urad: 2500\ntarget\n0\n");
  ASSERT_TRUE(abbe.abbe_offset_mm && abbe.angular_range_rad);
  EXPECT_EQ(*abbe.abbe_offset_mm, 15.0);
  EXPECT_NEAR(*abbe.angular_range_rad, 2.5e-3, 1e-15);
  EXPECT_THAT(errorOf("# angular range urad: -1\ntarget\n0\n"),
              HasSubstr("metadata 'angular range urad' must be >= 0"));
}

TEST(EnvironmentRecords, BadRecordsNameTheFileAndLine) {
  EXPECT_THAT(errorOf("target,pressure (psi)\n0,14.7\n"),
              HasSubstr("laser.csv:1: column 'pressure (psi)': unknown unit 'psi'"));
  // A kelvin reading in a Celsius column is caught by its plausible range, at its line.
  EXPECT_THAT(errorOf("target,air temperature (C)\n0,20\n\n100,293.2\n"),
              HasSubstr("laser.csv:4: air temperature 293.2 is outside the plausible range"));
  EXPECT_THAT(errorOf("target,humidity\n0,abc\n"), HasSubstr("laser.csv:2:"));
  EXPECT_THAT(errorOf("# dead path mm: long\ntarget\n0\n"),
              HasSubstr("laser.csv: metadata 'dead path mm': 'long' is not a finite number"));
  EXPECT_THAT(errorOf("# beam alignment urad: -3\ntarget\n0\n"),
              HasSubstr("metadata 'beam alignment urad' must be >= 0"));
}

TEST(EnvironmentRecords, FilesMergeAndARenishawFileRecordsNothing) {
  const auto r =
      readEnvironmentRecords({{"a.csv", "# dead path mm: 80\ntarget,air temp\n0,20.2\n"},
                              {"b.csv", "# dead path mm: 100\ntarget,air temp\n0,20.6\n"},
                              {"c.rtl", "HEADER::\nDEVIATIONS::\n"}});
  ASSERT_TRUE(r.air_temperature_c);
  EXPECT_EQ(r.air_temperature_c->count, 2u);
  EXPECT_EQ(*r.dead_path_mm, 100.0);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
