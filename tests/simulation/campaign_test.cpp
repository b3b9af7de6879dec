// runCampaign: determinism per seed and independence of the measurement streams.
#include "pkm/simulation/campaign.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/air_refractive_index.hpp"
#include "pkm/core/error.hpp"
#include "pkm/simulation/cartesian_machine.hpp"

namespace PKM_TEST_NS {

namespace sim = pkm::simulation;

sim::LineSetup setup(const std::string& name, int axis) {
  sim::LineSetup s;
  s.name = name;
  s.line.start = Eigen::VectorXd::Zero(3);
  s.line.direction = Eigen::VectorXd::Unit(3, axis);
  s.cycle = {0.0, 300.0, 7, 10.0, 3, 2.0, true};
  s.noise = {1e-5, 0.25, 1e-6};
  return s;
}

sim::Campaign campaign(std::vector<sim::LineSetup> measurements) {
  sim::CartesianErrors e;
  e.squareness.xy = 40e-6;
  sim::Campaign c;
  c.name = "test";
  c.machine = std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, e);
  c.measurements = std::move(measurements);
  return c;
}

std::vector<double> readings(const sim::MeasurementResult& r) {
  std::vector<double> v;
  for (const auto& run : r.runs)
    for (const auto& x : run.readings) {
      v.push_back(x.target);
      v.push_back(x.reading);
    }
  return v;
}

TEST(Campaign, SameSeedSameNumbersOtherSeedOtherNumbers) {
  const sim::Campaign c = campaign({setup("x", 0), setup("y", 1)});
  const auto a = sim::runCampaign(c, 7);
  const auto b = sim::runCampaign(c, 7);
  const auto other = sim::runCampaign(c, 8);
  ASSERT_EQ(a.size(), 2U);
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(readings(a[i]), readings(b[i]));
    EXPECT_NE(readings(a[i]), readings(other[i]));
  }
  EXPECT_EQ(a[1].setup->name, "y");
}

TEST(Campaign, AddingAMeasurementDoesNotChangeAnother) {
  const auto alone = sim::runCampaign(campaign({setup("y", 1)}), 7);
  const auto with = sim::runCampaign(campaign({setup("x", 0), setup("z", 2), setup("y", 1)}), 7);
  EXPECT_EQ(readings(alone[0]), readings(with[2]));
  // Two measurements with the same set-up but different names draw different noise.
  const auto twins = sim::runCampaign(campaign({setup("a", 0), setup("b", 0)}), 7);
  EXPECT_NE(readings(twins[0]), readings(twins[1]));
}

TEST(Campaign, ValidateRejectsBadCampaigns) {
  EXPECT_THROW((void)sim::runCampaign(campaign({setup("x", 0), setup("x", 1)}), 1),
               pkm::InvalidArgument);
  sim::Campaign no_machine = campaign({});
  no_machine.machine.reset();
  EXPECT_THROW(no_machine.validate(), pkm::InvalidArgument);
  sim::LineSetup wrong = setup("w", 0);
  wrong.line.start = Eigen::VectorXd::Zero(5);
  wrong.line.direction = Eigen::VectorXd::Unit(5, 0);
  EXPECT_THROW(campaign({wrong}).validate(), pkm::InvalidArgument);
}

TEST(Campaign, TheEnvironmentActsOnLinearReadingsWithItsAnalyticSize) {
  // An ideal machine and instrument: only the air's compensation error remains.
  sim::Campaign c = campaign({setup("x", 0), setup("x-h", 0)});
  c.machine =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  for (sim::LineSetup& m : c.measurements) m.noise = {};
  c.measurements[1].quantity = sim::LineQuantity::kStraightness;
  c.measurements[1].lateral = Eigen::Vector3d::UnitY();
  const auto ideal = sim::runCampaign(c, 3);
  c.environment.name = "custom";
  c.environment.air.enabled = true;
  c.environment.air.temperature_sensor.offset = -0.3;  // K: the sensor reads cold
  const auto air = sim::runCampaign(c, 3);
  const double n_t = pkm::refractiveIndexEdlen({20.0, 101325.0, 50.0});
  const double n_s = pkm::refractiveIndexEdlen({19.7, 101325.0, 50.0});
  const double s0 = air[0].runs[0].readings[0].target;
  for (const sim::LineRun& run : air[0].runs)
    for (const sim::LineReading& r : run.readings)
      EXPECT_NEAR(r.reading - r.target, (r.target - s0) * (n_t - n_s) / n_s, 1e-12);
  // About −0.28 ppm: −0.083 µm at 300 mm.
  EXPECT_LT(air[0].runs[0].readings[6].reading - air[0].runs[0].readings[6].target, -0.08e-3);
  EXPECT_EQ(readings(ideal[1]), readings(air[1]));  // straightness optics are differential
  EXPECT_EQ(readings(air[0]), readings(sim::runCampaign(c, 3)[0]));
}

TEST(Campaign, LinearReadingsRecordWhatTheCompensationUnitRead) {
  // The records a measurement file carries (docs/formats.md, "Environment records"): the
  // sensors' readings, with their offsets, on linear lines only; none without an environment.
  sim::Campaign c = campaign({setup("x", 0), setup("x-h", 0)});
  c.measurements[1].quantity = sim::LineQuantity::kStraightness;
  c.measurements[1].lateral = Eigen::Vector3d::UnitY();
  EXPECT_FALSE(sim::runCampaign(c, 3)[0].runs[0].readings[0].sensed.recorded);
  c.environment.name = "custom";
  c.environment.air.enabled = true;
  c.environment.air.temperature_sensor.offset = -0.3;  // K: the sensor reads cold
  c.environment.thermal.enabled = true;
  c.environment.thermal.material_temperature_c.start = 21.0;
  const auto r = sim::runCampaign(c, 3);
  for (const sim::LineRun& run : r[0].runs)
    for (const sim::LineReading& x : run.readings) {
      ASSERT_TRUE(x.sensed.recorded);
      EXPECT_NEAR(x.sensed.air_temperature_c, 19.7, 1e-9);
      EXPECT_NEAR(x.sensed.air_pressure_pa, 101325.0, 1e-9);
      EXPECT_NEAR(x.sensed.material_temperature_c, 21.0, 1e-9);
    }
  EXPECT_FALSE(r[1].runs[0].readings[0].sensed.recorded);  // straightness: not a laser's record
}

TEST(Campaign, ThermalSourcesAppearInTheLinesWithTheirAnalyticSize) {
  sim::Campaign c = campaign({setup("x", 0), setup("x-v", 0)});
  c.machine =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  for (sim::LineSetup& m : c.measurements) m.noise = {};
  c.measurements[1].quantity = sim::LineQuantity::kStraightness;
  c.measurements[1].lateral = Eigen::Vector3d::UnitZ();
  sim::Environment& e = c.environment;
  e.name = "custom";
  e.duration_h = 2.0;  // each measurement one hour
  e.thermal.enabled = true;
  e.thermal.material_temperature_c = {21.0, 0.0, 0.0, 3600.0};
  e.thermal.machine_cte_per_k = 10.5e-6;  // cast iron, the operator entered steel
  e.thermal.warmup_drift_mm = {0.0, 0.0, -0.020};
  const auto r = sim::runCampaign(c, 3);
  const double s0 = r[0].runs[0].readings[0].target;
  // Linear: (s − s₀)·(1 + α_m ΔT)/(1 + α_a ΔT) − (s − s₀) ≈ −1 ppm; the warm-up is across x.
  for (const sim::LineRun& run : r[0].runs)
    for (const sim::LineReading& x : run.readings)
      EXPECT_NEAR(
          x.reading - x.target, (x.target - s0) * ((1 + 10.5e-6) / (1 + 11.5e-6) - 1.0), 1e-12);
  // Vertical straightness: the warm-up's z since zeroing at τ₀ = 1 h, read at the window's end.
  const double tau0 = 3600.0, tau_end = 7200.0;
  const auto warm = [](double t) { return -0.020 * (1.0 - std::exp(-t / 3600.0)); };
  const sim::LineReading& last = r[1].runs.back().readings.back();
  EXPECT_NEAR(last.reading, warm(tau_end) - warm(tau0), 1e-12);  // about −4.7 µm
  EXPECT_LT(last.reading, -4e-3);
  // A later pass (the re-measurement after compensation) continues the clock: nearly warm.
  e.elapsed_h = 2.0;
  const auto later = sim::runCampaign(c, 3);
  EXPECT_NEAR(later[1].runs.back().readings.back().reading,
              warm(tau_end + 7200.0) - warm(tau0 + 7200.0),
              1e-12);
  EXPECT_GT(later[1].runs.back().readings.back().reading, -1e-3);
}

TEST(Campaign, SetUpErrorsGiveTheCosineErrorAndTheAbbeErrorOfTheDrawnOffset) {
  // A pitch error of X growing to 100 µrad over 300 mm: an offset reflector reads it (Abbe).
  sim::CartesianErrors errors;
  Eigen::MatrixXd values = Eigen::MatrixXd::Zero(2, 6);
  values(1, 4) = 100e-6;  // ey at 300 mm
  errors.axes[0] = pkm::geometry::ErrorTable1d({0.0, 300.0}, values);
  sim::Campaign c = campaign({setup("x", 0)});
  c.machine = std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, errors);
  c.measurements[0].noise = {};
  sim::Environment& e = c.environment;
  e.name = "custom";
  e.setup.enabled = true;
  e.setup.beam_misalignment_rad = 1e-3;
  const auto ideal = sim::runCampaign(campaign({c.measurements[0]}), 3);
  // The cosine error alone (no offset): (s − s₀)(cos θ − 1) ≈ −0.5 ppm.
  sim::Campaign flat = c;
  flat.machine =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  const auto cosine = sim::runCampaign(flat, 3);
  const double s0 = cosine[0].runs[0].readings[0].target;
  for (const sim::LineReading& x : cosine[0].runs[0].readings)
    EXPECT_NEAR(x.reading - x.target, (x.target - s0) * (std::cos(1e-3) - 1.0), 1e-12);
  // The reflector offset: the same readings as a set-up with the drawn offset (no tilt).
  e.setup.beam_misalignment_rad = 0.0;
  e.setup.reflector_offset_mm = 10.0;
  const auto abbe = sim::runCampaign(c, 3);
  const sim::MeasurementConditions drawn(e, 0.0, 1.0, 1, sim::streamSeed(3, "x/environment"));
  sim::Campaign known = campaign({c.measurements[0]});
  known.machine = c.machine;
  known.measurements[0].reflector_offset = drawn.reflectorOffset();
  const auto expected = sim::runCampaign(known, 3);
  EXPECT_EQ(readings(abbe[0]).size(), readings(expected[0]).size());
  for (std::size_t i = 0; i < readings(abbe[0]).size(); ++i)
    EXPECT_NEAR(readings(abbe[0])[i], readings(expected[0])[i], 1e-12);
  // Pitch times the offset's z (a pitch ε_y tilts the tool so that +z moves along +x), to first
  // order: the second-order terms ε²·|o| are below 2e-7 mm here.
  const sim::LineReading& end = abbe[0].runs[0].readings[6];
  const sim::LineReading& plain = ideal[0].runs[0].readings[6];
  EXPECT_NEAR(end.reading - plain.reading,
              (100e-6 * end.target / 300.0 - 100e-6 * s0 / 300.0) * drawn.reflectorOffset().z(),
              2e-7);
  EXPECT_GT(std::abs(end.reading - plain.reading), 1e-4);
}

TEST(Campaign, NonRepeatableStructureErrorsScatterTheReadings) {
  sim::LineSetup line = setup("x-h", 0);
  line.noise = {};
  line.quantity = sim::LineQuantity::kStraightness;
  line.lateral = Eigen::Vector3d::UnitY();
  line.cycle = {0.0, 300.0, 50, 0.0, 20, 2.0, true};  // 2000 readings
  sim::Campaign c = campaign({line});
  c.machine =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  c.environment.name = "custom";
  c.environment.structure.enabled = true;
  c.environment.structure.white_sigma_mm = 1e-3;
  const auto result = sim::runCampaign(c, 5);
  std::vector<double> v;
  for (const sim::LineRun& run : result[0].runs)
    for (const sim::LineReading& r : run.readings) v.push_back(r.reading);
  double mean = 0.0;
  for (const double x : v) mean += x / static_cast<double>(v.size());
  double sum2 = 0.0;
  for (const double x : v) sum2 += (x - mean) * (x - mean);
  // Each reading minus the datum's: the datum's draw is common to all readings (the mean), the
  // scatter about it is the white σ.
  EXPECT_NEAR(std::sqrt(sum2 / static_cast<double>(v.size())), 1e-3, 0.05e-3);
  EXPECT_GT(std::abs(mean), 0.0);
}

TEST(Campaign, ComplianceShowsTheRamSagInAVerticalStraightnessLine) {
  // An ideal machine whose Y ram (300 mm out at y = 0) sags 25 µm at 1000 mm: a vertical
  // straightness line along Y zeroed at y = 0 reads −(δ(300 + y) − δ(300)), δ(L) = 25 µm·(L/1 m)³
  // (the tool on the ram's axis, so its droop adds no Abbe term), in every run and direction.
  sim::LineSetup line = setup("y-v", 1);
  line.noise = {};
  line.quantity = sim::LineQuantity::kStraightness;
  line.lateral = Eigen::Vector3d::UnitZ();
  sim::Campaign c = campaign({line});
  c.machine =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  c.environment.name = "custom";
  c.environment.compliance.enabled = true;
  c.environment.compliance.cartesian[1] = {sim::AxisSag::Kind::kCantilever, 25e-3, 1000, 300, 1};
  sim::applyMachineEnvironment(c);
  const auto delta = [](double y) { return 25e-3 * std::pow((300.0 + y) / 1000.0, 3); };
  const auto result = sim::runCampaign(c, 5);
  for (const sim::LineRun& run : result[0].runs)
    for (const sim::LineReading& r : run.readings)
      EXPECT_NEAR(r.reading, -(delta(r.target) - delta(0.0)), 1e-12) << r.target;
  EXPECT_EQ(readings(result[0]), readings(sim::runCampaign(c, 5)[0]));
  // Switching the source off takes the sag away again.
  c.environment.compliance.enabled = false;
  sim::applyMachineEnvironment(c);
  const auto rigid = sim::runCampaign(c, 5);
  for (const sim::LineRun& run : rigid[0].runs)
    for (const sim::LineReading& r : run.readings) EXPECT_NEAR(r.reading, 0.0, 1e-12);
}

TEST(Campaign, AnInvalidEnvironmentIsRejected) {
  sim::Campaign c = campaign({setup("x", 0)});
  c.environment.duration_h = -1.0;
  EXPECT_THROW(c.validate(), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
