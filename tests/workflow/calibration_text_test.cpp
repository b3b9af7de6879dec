// workflow::hexapodCalibrationText and exechonCalibrationText on hand-made results: every line
// written out by hand from the figures put in (the formats of `pkm calibrate`,
// docs/calibration.md), the dial-gauge hint only for an unconverged gauge fit without a prior, the
// Monte Carlo count from the request, and the "wrote" line only once files are written. The
// byte-for-byte identity with the command line on real calibrations is tests/golden (calibrate-*)
// and tests/python/test_calibration.py (str(result)).
#include "pkm/workflow/calibration_text.hpp"

#include <gtest/gtest.h>

#include <string>

namespace pkm::workflow {
namespace PKM_TEST_NS {

/// A hexapod result with round figures: 10 poses, 120 equations, 2 unidentifiable directions.
HexapodCalibrationResult hexapodResult() {
  HexapodCalibrationResult r;
  io::HexapodCalibrationReport& rep = r.report;
  rep.machine = "pkm-hx1200";
  rep.equations = 120;
  rep.poses = 10;
  calibration::HexapodCalibrationSummary& s = rep.fit;
  s.converged = true;
  s.iterations = 7;
  s.seconds = 0.25;
  s.identifiability.rank = 42;
  s.identifiability.parameters = 48;
  s.identifiability.condition_number = 1234.5678;
  s.identifiability.combinations.push_back({{{"frame.x", 1.0}, {"offset0", -0.5}}, 0.0});
  s.before = {120, 1.5, 3.25, 0};
  s.after = {120, 0.001, 0.002, 0};
  rep.worst.push_back({"tracker-pose.csv:12", 0.0042});
  rep.tcp_before = {200, 2.0, 3.0, 4.0};
  return r;
}

TEST(HexapodCalibrationText, WritesEveryLineFromTheReport) {
  HexapodCalibrationResult r = hexapodResult();
  const HexapodCalibrationRequest request;
  const std::string expected =
      "calibrated pkm-hx1200 from 120 equations (10 poses, 0 points, 0 gauge sets)\n"
      "solver: 7 iterations, 0.250 s, converged\n"
      "identifiable: 42 of 48 unknowns (condition number 1235)\n"
      "  not identifiable: +1.000·frame.x -0.500·offset0\n"
      "fitted residuals (mm): RMS 1.5 -> 0.001, max 3.25 -> 0.002\n"
      "largest residual after the fit: tracker-pose.csv:12 (0.0042)\n"
      "workspace TCP error of the nominal controller (what calibration removes): mean 2, "
      "95 % 3, max 4\n";
  EXPECT_EQ(hexapodCalibrationText(request, r), expected);
  // Once written, the files close the summary.
  r.report.out_machine = "cal.json";
  r.report.out_hal = "cal.hal";
  r.report.out_summary = "cal.summary.json";
  EXPECT_EQ(hexapodCalibrationText(request, r),
            expected + "wrote cal.json, cal.hal, cal.summary.json\n");
}

TEST(HexapodCalibrationText, OptionalLinesFollowTheReportAndTheRequest) {
  HexapodCalibrationResult r = hexapodResult();
  r.report.fit.backlash = kinematics::StrutVector(0.01, 0.02, 0.03, 0.04, 0.05, 0.06);
  io::HexapodCalibrationReport::Holdout holdout;
  holdout.before.rms = 9.0;
  holdout.before.max = 12.0;
  holdout.after.rms = 0.004;
  holdout.after.max = 0.01;
  r.report.holdout = holdout;
  io::HexapodCalibrationReport::MonteCarlo monte_carlo;
  monte_carlo.summary.trials = 4;  // one failed: the line counts the trials asked for
  monte_carlo.summary.failures = 1;
  monte_carlo.summary.tcp = {800, 0.001, 0.002, 0.003};
  r.report.monte_carlo = monte_carlo;
  HexapodCalibrationRequest request;
  request.monte_carlo = 5;
  const std::string text = hexapodCalibrationText(request, r);
  EXPECT_NE(text.find("backlash per strut (mm): 0.01, 0.02, 0.03, 0.04, 0.05, 0.06\n"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("held-out TCP error: RMS 9 -> 0.004, max 12 -> 0.01\n"), std::string::npos);
  EXPECT_NE(text.find("(Monte Carlo, 5 trials): mean 0.001, 95 % 0.002, max 0.003\n"),
            std::string::npos)
      << text;
}

TEST(HexapodCalibrationText, HintsAtThePriorOnlyForAnUnconvergedGaugeFitWithoutOne) {
  const std::string hint = "  dial-gauge data see some combinations only weakly";
  HexapodCalibrationResult r = hexapodResult();
  HexapodCalibrationRequest request;
  r.report.constrained_sets = 3;
  EXPECT_EQ(hexapodCalibrationText(request, r).find(hint), std::string::npos);  // converged
  r.report.fit.converged = false;
  r.report.fit.termination = "iteration limit";
  const std::string text = hexapodCalibrationText(request, r);
  EXPECT_NE(text.find("solver: 7 iterations, 0.250 s, iteration limit\n" + hint), std::string::npos)
      << text;
  request.prior_sigma = 0.5;
  EXPECT_EQ(hexapodCalibrationText(request, r).find(hint), std::string::npos);
}

TEST(ExechonCalibrationText, TripodThenHybridThenTheFilesWritten) {
  ExechonCalibrationResult r;
  r.report.machine = "mxt700s-like";
  io::ExechonTripodReport& t = r.report.tripod.emplace();
  t.points = 40;
  t.equations = 120;
  t.fit.converged = true;
  t.fit.iterations = 5;
  t.fit.seconds = 1.0;
  t.fit.identifiability.rank = 26;
  t.fit.identifiability.parameters = 26;
  t.fit.identifiability.condition_number = 99.0;
  t.fit.before = {120, 2.0, 5.0, 0};
  t.fit.after = {120, 0.01, 0.03, 0};
  io::HybridSquarenessReport& h = r.report.hybrid.emplace();
  h.observations = 30;
  h.fit.squareness.sz_x2 = 1e-4;
  h.fit.squareness.sx_p = -2e-4;
  h.fit.standard_deviation = Eigen::Vector4d(1e-6, 2e-6, 3e-6, 4e-6);
  h.fit.before = {90, 0.5, 1.0, 0};
  h.fit.after = {90, 0.01, 0.02, 0};
  const std::string expected =
      "calibrated mxt700s-like from 120 equations (40 tracker points)\n"
      "solver: 5 iterations, 1.000 s, converged\n"
      "identifiable: 26 of 26 unknowns (condition number 99)\n"
      "fitted residuals (mm): RMS 2 -> 0.01, max 5 -> 0.03\n"
      "squareness from 30 hybrid observations: szX2 0.1000, sxP -0.2000, syP 0.0000, szP 0.0000 "
      "mrad (sigma 0.001, 0.002, 0.003, 0.004)\n"
      "hybrid residuals (mm): RMS 0.5 -> 0.01, max 1 -> 0.02\n";
  EXPECT_EQ(exechonCalibrationText(r), expected);
  r.written = {"cal.json", "cal.summary.json", "cal.errors.json"};
  EXPECT_EQ(exechonCalibrationText(r),
            expected + "wrote cal.json, cal.summary.json, cal.errors.json\n");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::workflow
