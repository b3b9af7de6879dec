// Measurement files: written runs read back exactly; a generic laser-interferometer export reads
// through the same code; malformed files give FILE:LINE errors.
#include "pkm/io/measurement_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace PKM_TEST_NS {

namespace io = pkm::io;
namespace sim = pkm::simulation;
namespace kinematics = pkm::kinematics;
using ::testing::HasSubstr;

sim::LineRun sampleRun() {
  sim::LineRun run;
  run.run = 3;
  run.readings = {{0.0, 1, 1.2e-5},
                  {64.03124237432849, 1, 64.031107},
                  {64.03124237432849, -1, 64.031075},
                  {0.0, -1, -0.1 / 3}};
  return run;
}

TEST(MeasurementFiles, RoundTripIsExact) {
  const io::Metadata md = {{"scenario", "x"}, {"quantity", "linear"}};
  const std::string text = io::lineRunCsv(sim::LineQuantity::kLinear, md, sampleRun());
  EXPECT_THAT(text,
              HasSubstr("# scenario: x\n# quantity: "
                        "linear\ntarget_mm,run,direction,reading_mm\n0,3,+,1.2e-05\n"));
  const io::LineRunFile f = io::parseLineRunCsv(text, "f.csv");
  EXPECT_EQ(f.metadata, md);
  EXPECT_EQ(f.reading_unit, "mm");
  ASSERT_EQ(f.readings.size(), 4U);
  for (std::size_t i = 0; i < 4; ++i) {
    EXPECT_EQ(f.runs[i], 3);
    EXPECT_EQ(f.readings[i].target, sampleRun().readings[i].target);
    EXPECT_EQ(f.readings[i].direction, sampleRun().readings[i].direction);
    EXPECT_EQ(f.readings[i].reading, sampleRun().readings[i].reading);
  }
}

TEST(MeasurementFiles, AngularReadingsAreInMicroradians) {
  sim::LineRun run;
  run.readings = {{10.0, 1, 2.5e-6}};
  const std::string text = io::lineRunCsv(sim::LineQuantity::kAngular, {}, run);
  EXPECT_EQ(text, "target_mm,run,direction,reading_urad\n10,1,+,2.5\n");
  EXPECT_EQ(io::parseLineRunCsv(text, "a.csv").reading_unit, "urad");
}

TEST(MeasurementFiles, StepDiagonalRunsCarryTheSubStep) {
  sim::LineRun run;
  run.readings = {{1.5, 1, 1.5001, 1}, {3.25, 1, 3.2502, 2}, {5.0, 1, 5.0003, 3}};
  const std::string text = io::lineRunCsv(sim::LineQuantity::kLinear, {}, run);
  EXPECT_EQ(text,
            "target_mm,run,direction,reading_mm,sub_step\n1.5,1,+,1.5001,1\n3.25,1,+,3.2502,2\n5,1,"
            "+,5.0003,3\n");
  const io::LineRunFile f = io::parseLineRunCsv(text, "s.csv");
  ASSERT_EQ(f.readings.size(), 3U);
  EXPECT_EQ(f.readings[1].sub_step, 2);
  EXPECT_THROW((void)io::parseLineRunCsv("target_mm,run,direction,reading_mm,sub_step\n1,1,+,1,x\n",
                                         "s.csv"),
               pkm::IoError);
}

TEST(MeasurementFiles, RecordedConditionsBecomeColumnsAtTheUnitsResolution) {
  sim::LineRun run;
  run.readings = {{0.0, 1, 0.0, 0, {true, 20.4567, 101012.34, 45.678, 21.0004}},
                  {10.0, 1, 10.001, 0, {true, 20.5, 101000.0, 46.0, 21.0}}};
  const std::string text = io::lineRunCsv(sim::LineQuantity::kLinear, {}, run);
  EXPECT_EQ(text,
            "target_mm,run,direction,reading_mm,air_temperature_c,air_pressure_pa,air_humidity_rh,"
            "material_temperature_c\n0,1,+,0,20.457,101012.3,45.68,21.000\n10,1,+,10.001,20.500,"
            "101000.0,46.00,21.000\n");
  // The reader of measurement files ignores them; the environment reader takes them.
  EXPECT_EQ(io::parseLineRunCsv(text, "e.csv").readings.size(), 2U);
}

TEST(MeasurementFiles, ConstrainedMotionFileIsAllNumbers) {
  sim::DialGaugeStation st;
  st.station = 2;
  st.command = Eigen::VectorXd::Zero(6);
  st.command << 100, -50, 199.5, 0.01, -0.02, 0.5;
  st.lengths = kinematics::StrutVector::Constant(250.5);
  st.readings = {0.001, 0, -0.002};
  st.iterations = 4;
  st.converged = true;
  const std::string text = io::dialGaugeCsv({{"format", "pkm.constrained-motion/1"}}, {st});
  EXPECT_THAT(
      text,
      HasSubstr(
          "# format: pkm.constrained-motion/1\nstation,x_mm,y_mm,z_mm,a_deg,b_deg,c_deg,l0_mm,"));
  EXPECT_THAT(text, HasSubstr("\n2,100,-50,199.5,"));
  EXPECT_THAT(text, HasSubstr(",250.5,250.5,0.001,0,-0.002,4,1\n"));
}

TEST(MeasurementFiles, GenericExportReadsThroughTheSameCode) {
  const std::string text =
      "\xEF\xBB\xBF# exported by some laser software\r\n"
      "run, target_mm, reading_mm, direction, temperature_C\r\n"
      "1, 0, 0.0000, +1, 20.1\r\n\r\n"
      "1, 100, 100.0021, 1, 20.1\r\n"
      "1, 100, 100.0025, -1, 20.2\r\n";
  const io::LineRunFile f = io::parseLineRunCsv(text, "export.csv");
  EXPECT_TRUE(f.metadata.empty());
  ASSERT_EQ(f.readings.size(), 3U);
  EXPECT_EQ(f.readings[1].reading, 100.0021);
  EXPECT_EQ(f.readings[2].direction, -1);
}

TEST(MeasurementFiles, MalformedFilesGiveFileAndLine) {
  const auto message = [](const std::string& text) {
    try {
      (void)io::parseLineRunCsv(text, "m.csv");
    } catch (const pkm::IoError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_THAT(message("target_mm,run,reading_mm\n"),
              HasSubstr("m.csv:1: missing column 'direction'"));
  EXPECT_THAT(message("# c\ntarget_mm,run,direction,reading_mm\n1,1,up,2\n"),
              HasSubstr("m.csv:3: direction 'up' is not + or -"));
  EXPECT_THAT(message("target_mm,run,direction,reading_mm\n1,0,+,2\n"),
              HasSubstr("m.csv:2: run '0'"));
  // A run beyond int's range is refused before any conversion (found by fuzz_line_run: the
  // conversion was undefined behaviour).
  EXPECT_THAT(message("target_mm,run,direction,reading_mm\n1,1,+,2\n1,6.7e72,+,2\n"),
              HasSubstr("m.csv:3: run '6.7e72' is not an integer from 1 to 1000000000"));
  EXPECT_THAT(message("target_mm,run,direction,reading_mm\n1,2147483648,+,2\n"),
              HasSubstr("m.csv:2: run '2147483648'"));
  EXPECT_THAT(message("target_mm,run,direction,reading_mm\n1,1,+\n"),
              HasSubstr("m.csv:2: expected 4 fields"));
  EXPECT_THAT(message("target_mm,run,direction,reading_mm\nx,1,+,2\n"),
              HasSubstr("m.csv:2: target_mm 'x'"));
  EXPECT_THAT(message("# only comments\n"), HasSubstr("no header row"));
  EXPECT_THROW((void)io::readLineRunCsv("/nonexistent/file.csv"), pkm::IoError);
}

}  // namespace PKM_TEST_NS
