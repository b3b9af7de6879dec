// workflow::calibrateExechon from the library: on the simulator's Exechon tracker files the tripod
// fit meets the held-out target; with hybrid files it also finds the four squareness errors and
// writes CAL.errors.json; hybrid data on a machine without a hybrid section is refused.
#include "pkm/workflow/calibrate_exechon.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "pkm/core/error.hpp"
#include "pkm/io/atomic_file.hpp"
#include "pkm/workflow/simulate.hpp"

namespace pkm::workflow {
namespace PKM_TEST_NS {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

/// Acceptance: held-out target error ≤ 3× the tracker's noise (about 8 µm in 3-D at the
/// scenario's distance).
constexpr double kHeldOutRmsLimit = 3 * 0.008;  ///< mm
/// Seed 000's squareness (szX2 -0.034, sxP -14.74, syP 4.35, szP -2.85 mrad), within about 5 σ.
constexpr double kSquarenessTolerance = 0.02e-3;  ///< rad

class CalibrateExechonWorkflow : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    // One folder per process: CTest runs the cases of this suite in parallel processes.
    dir_ = fs::temp_directory_path() /
           ("pkm_workflow_calibrate_exechon_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    SimulateOptions o;
    o.scenario = "exechon-calibration";
    o.out = dir_ / "sim";
    (void)runSimulate(o);
  }
  static void TearDownTestSuite() { fs::remove_all(dir_); }
  static io::NamedText sim(const std::string& name) {
    return io::readNamedText((dir_ / "sim" / name).string());
  }
  static fs::path dir_;
};
fs::path CalibrateExechonWorkflow::dir_;

TEST_F(CalibrateExechonWorkflow, TripodFitMeetsTheHeldOutTarget) {
  ExechonCalibrationRequest r;
  r.data = {sim("tracker-fit.csv")};
  r.holdout = {sim("tracker-holdout.csv")};
  r.out = (dir_ / "tripod.json").string();
  const ExechonCalibrationResult result = calibrateExechon(r);
  const io::ExechonCalibrationReport& rep = result.report;
  ASSERT_TRUE(rep.tripod.has_value());
  EXPECT_FALSE(rep.hybrid.has_value());
  ASSERT_TRUE(rep.tripod->holdout.has_value());
  EXPECT_LT(rep.tripod->holdout->after.rms, kHeldOutRmsLimit);
  EXPECT_EQ(rep.tripod->fit.identifiability.rank, rep.tripod->fit.identifiability.parameters);
  EXPECT_TRUE(rep.tripod->map_before.has_value());
  EXPECT_EQ(result.written,
            (std::vector<std::string>{r.out, (dir_ / "tripod.summary.json").string()}));
  EXPECT_EQ(io::readFileText(dir_ / "tripod.summary.json"), result.summary_json);
  EXPECT_FALSE(fs::exists(dir_ / "tripod.errors.json"));
}

TEST_F(CalibrateExechonWorkflow, HybridFilesGiveTheFourSquarenessErrors) {
  ExechonCalibrationRequest r;
  r.data = {sim("tracker-fit.csv"), sim("tracker-hybrid.csv")};
  r.holdout = {sim("tracker-hybrid-holdout.csv")};
  r.errors = "mxt700s-seed000";
  r.out = (dir_ / "hybrid.json").string();
  const ExechonCalibrationResult result = calibrateExechon(r);
  ASSERT_TRUE(result.report.hybrid.has_value());
  const io::HybridSquarenessReport& h = *result.report.hybrid;
  EXPECT_TRUE(h.tripod_error_motion);
  EXPECT_NEAR(h.fit.squareness.sz_x2, -0.034e-3, kSquarenessTolerance);
  EXPECT_NEAR(h.fit.squareness.sx_p, -14.74e-3, kSquarenessTolerance);
  EXPECT_NEAR(h.fit.squareness.sy_p, 4.35e-3, kSquarenessTolerance);
  EXPECT_NEAR(h.fit.squareness.sz_p, -2.85e-3, kSquarenessTolerance);
  EXPECT_EQ(result.report.out_errors, (dir_ / "hybrid.errors.json").string());
  EXPECT_TRUE(fs::is_regular_file(dir_ / "hybrid.errors.json"));
}

TEST_F(CalibrateExechonWorkflow, WithoutOutWritesNothingAndWritesItLater) {
  ExechonCalibrationRequest r;
  r.data = {sim("tracker-hybrid.csv")};
  r.errors = "mxt700s-seed000";
  ExechonCalibrationResult result = calibrateExechon(r);
  EXPECT_TRUE(result.written.empty());
  EXPECT_FALSE(result.errors_json.empty());
  writeExechonCalibration(result, (dir_ / "later.json").string(), false);
  EXPECT_EQ(result.written.size(), 3u);
  EXPECT_EQ(io::readFileText(dir_ / "later.summary.json"), result.summary_json);
  EXPECT_EQ(io::readFileText(dir_ / "later.errors.json"), result.errors_json);
  EXPECT_THAT(result.summary_json, HasSubstr("later.errors.json"));
  EXPECT_THROW(writeExechonCalibration(result, (dir_ / "later.json").string(), false), IoError);
}

TEST_F(CalibrateExechonWorkflow, HybridDataNeedAHybridMachine) {
  ExechonCalibrationRequest r;
  r.machine = "exechon-zoppi2010";
  r.data = {sim("tracker-hybrid.csv")};
  r.out = (dir_ / "nohybrid.json").string();
  try {
    (void)calibrateExechon(r);
    FAIL() << "accepted hybrid data without a hybrid machine";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("needs a machine with a \"hybrid\" section"));
  }
  EXPECT_FALSE(fs::exists(dir_ / "nohybrid.json"));
  EXPECT_EQ(calibrationErrorsOutput("a/cal.json"), "a/cal.errors.json");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
