// io::lineRunMetadata / dialGaugeMetadata on a built-in scenario: the keys the file readers rebuild
// a set-up from, with angular axes in degrees and the noise in the measurement's unit.
#include "pkm/io/simulation_metadata.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <vector>

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::map<std::string, std::string> asMap(const Metadata& m) { return {m.begin(), m.end()}; }

TEST(SimulationMetadata, LineRunsCarryTheirSetUp) {
  const Scenario s = loadScenario("seed000-parallelism");
  ASSERT_FALSE(s.campaign.measurements.empty());
  for (const simulation::LineSetup& m : s.campaign.measurements) {
    const auto md = asMap(lineRunMetadata(s, 7, m, 2));
    EXPECT_EQ(md.at("format"), "pkm.measurement/1");
    EXPECT_EQ(md.at("scenario"), "seed000-parallelism");
    EXPECT_EQ(md.at("seed"), "7");
    EXPECT_EQ(md.at("measurement"), m.name);
    EXPECT_THAT(md.at("run"), HasSubstr("2 of "));
    EXPECT_EQ(md.count("line start"), 1u);
    EXPECT_EQ(md.count("lateral"), m.quantity == simulation::LineQuantity::kLinear ? 0u : 1u);
    EXPECT_EQ(md.count("misalignment urad"),
              m.quantity == simulation::LineQuantity::kStraightness ? 1u : 0u);
    EXPECT_THAT(md.at("noise"),
                HasSubstr(m.quantity == simulation::LineQuantity::kAngular ? "urad" : "mm"));
  }
}

TEST(SimulationMetadata, LinearLinesInAWorkshopCarryTheAbbeRecords) {
  Scenario s = loadScenario("seed004-hexapod-calibration");
  s.campaign.environment.setup.enabled = true;
  s.campaign.environment.setup.reflector_offset_mm = 5.0;
  const simulation::LineSetup* linear = nullptr;
  for (const simulation::LineSetup& m : s.campaign.measurements)
    if (m.quantity == simulation::LineQuantity::kLinear) linear = &m;
  ASSERT_NE(linear, nullptr);
  std::vector<simulation::LineRun> runs(1);
  for (const double w : {0.0, 1e-3, -2e-3}) {
    simulation::LineReading r;
    r.sensed.recorded = true;
    r.sensed.rotation_rad = Eigen::Vector3d(w, 0.0, 0.5 * w);
    runs[0].readings.push_back(r);
  }
  const auto md = asMap(lineRunMetadata(s, 3, *linear, 1, runs));
  // 3 sigma of the unknown offset (plus the set-up's own), and the largest rotation difference.
  EXPECT_EQ(std::stod(md.at("abbe offset mm")), linear->reflector_offset.norm() + 15.0);
  EXPECT_NEAR(std::stod(md.at("angular range urad")), 3e3 * std::hypot(1.0, 0.5), 0.005);  // 2 dp
  EXPECT_EQ(asMap(lineRunMetadata(s, 3, *linear, 1)).count("abbe offset mm"), 0u);  // no rotations
}

TEST(SimulationMetadata, DialGaugeSetsCarryTheirGeometry) {
  const Scenario s = loadScenario("seed004-hexapod-calibration");
  ASSERT_FALSE(s.campaign.constrained.empty());
  const auto md = asMap(dialGaugeMetadata(s, 4, s.campaign.constrained.front()));
  EXPECT_EQ(md.at("format"), "pkm.constrained-motion/1");
  EXPECT_EQ(md.at("seed"), "4");
  EXPECT_THAT(md.at("gauge points mm"), HasSubstr("("));
  EXPECT_THAT(md.at("noise"), HasSubstr("sigma"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
