// io::hexapodCalibrationJson: the members in their documented order, the optional ones only when
// there is something to say, and every number as it was given.
#include "pkm/io/calibration_report.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace pkm::io {
namespace PKM_TEST_NS {

using Json = nlohmann::ordered_json;

HexapodCalibrationReport minimalReport() {
  HexapodCalibrationReport r;
  r.machine = "hx";
  r.data_notes = {"a.csv: 10 poses"};
  r.poses = 10;
  r.equations = 60;
  r.target_offset = {0, 60, 80};
  r.fit.converged = true;
  r.fit.termination = "CONVERGENCE";
  r.fit.iterations = 7;
  r.fit.after.rms = 0.00123;
  r.fit.parameters(3) = 1.5;
  r.fit.initial(3) = 1.25;
  r.free.fill(true);
  r.workspace_poses = 200;
  r.tcp_before.max = 0.5;
  r.out_machine = "cal.json";
  r.out_hal = "cal.hal";
  r.out_summary = "cal.summary.json";
  return r;
}

std::vector<std::string> keys(const Json& j) {
  std::vector<std::string> k;
  for (const auto& [key, value] : j.items()) k.push_back(key);
  return k;
}

TEST(HexapodCalibrationJson, MinimalReportHasTheRequiredMembersInOrder) {
  const std::string text = hexapodCalibrationJson(minimalReport());
  ASSERT_EQ(text.back(), '\n');
  const Json j = Json::parse(text);
  EXPECT_EQ(keys(j),
            (std::vector<std::string>{"machine",
                                      "units",
                                      "data",
                                      "observations",
                                      "target_offset",
                                      "solver",
                                      "residuals",
                                      "identifiability",
                                      "world_frame",
                                      "sigma",
                                      "worst_observations",
                                      "tcp_error_map",
                                      "parameters",
                                      "outputs"}));
  EXPECT_EQ(j["units"], "mm");
  EXPECT_EQ(j["world_frame"], "machine");
  EXPECT_EQ(j["observations"]["equations"], 60);
  EXPECT_EQ(j["solver"]["iterations"], 7);
  EXPECT_EQ(j["residuals"]["after"]["rms"].get<double>(), 0.00123);
  EXPECT_EQ(j["tcp_error_map"]["poses"], 200);
  EXPECT_FALSE(j["tcp_error_map"].contains("after"));
  ASSERT_EQ(j["parameters"].size(), static_cast<std::size_t>(calibration::kHexapodParameters));
  EXPECT_EQ(j["parameters"][3]["change"].get<double>(), 0.25);
  EXPECT_EQ(j["outputs"]["hal"], "cal.hal");
}

TEST(HexapodCalibrationJson, OptionalSectionsAppearWhenPresent) {
  HexapodCalibrationReport r = minimalReport();
  r.holdout = HexapodCalibrationReport::Holdout{};
  r.holdout->after.rms = 0.004;
  r.fit.measurement_frame = geometry::RigidTransform::Identity();
  r.fit.measurement_frame->translation() = Eigen::Vector3d(1500, 0, 0);
  r.fit.backlash = kinematics::StrutVector::Constant(0.01);
  r.worst.push_back({"a.csv:14", 0.02});
  r.monte_carlo = HexapodCalibrationReport::MonteCarlo{};
  r.monte_carlo->summary.trials = 50;
  r.monte_carlo->summary.tcp.p95 = 0.003;
  r.unit = LengthUnit::kInch;
  const Json j = Json::parse(hexapodCalibrationJson(r));
  EXPECT_EQ(j["units"], "inch");
  EXPECT_EQ(j["holdout"]["after"]["rms"].get<double>(), 0.004);
  EXPECT_EQ(j["measurement_frame"]["position"][0].get<double>(), 1500.0);
  EXPECT_EQ(j["measurement_frame"]["sigma"].size(), 6u);
  EXPECT_EQ(j["backlash"]["values"][5].get<double>(), 0.01);
  EXPECT_EQ(j["worst_observations"][0]["source"], "a.csv:14");
  EXPECT_EQ(j["monte_carlo"]["trials"], 50);
  EXPECT_EQ(j["tcp_error_map"]["after"]["p95"].get<double>(), 0.003);
  // Monte Carlo comes before the map it adds to, as the document has always had it.
  const std::vector<std::string> k = keys(j);
  EXPECT_LT(std::find(k.begin(), k.end(), "monte_carlo"),
            std::find(k.begin(), k.end(), "tcp_error_map"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
