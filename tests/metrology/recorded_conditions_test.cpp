// Recorded measurement conditions and the budgets at them (metrology/recorded_conditions.hpp).
#include "pkm/metrology/recorded_conditions.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/metrology/positioning_uncertainty.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolArithmetic = 1e-12;  // the same sums in another order

RecordedSeries series(std::initializer_list<double> values) {
  RecordedSeries s;
  for (double v : values) s.add(v);
  return s;
}

const BudgetCondition& condition(const std::vector<BudgetCondition>& all, const std::string& name) {
  for (const BudgetCondition& c : all)
    if (c.name == name) return c;
  throw std::runtime_error("no condition " + name);
}

double contribution(const UncertaintyBudget& b, const std::string& name) {
  for (const UncertaintyContributor& c : b.contributors)
    if (c.name == name) return c.contribution();
  return 0.0;
}

TEST(RecordedConditions, SeriesKeepsCountMeanAndRangeAndMerges) {
  RecordedSeries a = series({20.5, 20.7, 20.6});
  EXPECT_EQ(a.count, 3u);
  EXPECT_NEAR(a.mean, 20.6, kTolArithmetic);
  EXPECT_EQ(a.min, 20.5);
  EXPECT_EQ(a.max, 20.7);
  a.merge(series({21.0}));
  EXPECT_EQ(a.count, 4u);
  EXPECT_NEAR(a.mean, (20.5 + 20.7 + 20.6 + 21.0) / 4, kTolArithmetic);
  EXPECT_EQ(a.max, 21.0);
  RecordedSeries empty;
  empty.merge(a);
  EXPECT_EQ(empty.count, 4u);
  EXPECT_THROW(a.add(std::nan("")), InvalidArgument);
}

TEST(RecordedConditions, NothingRecordedLeavesEverySourceAndOriginAsItWas) {
  UncertaintySources s;
  s.environment.origin.dead_path = ConditionOrigin::kStated;
  s.environment.dead_path_mm = 40.0;
  const UncertaintySources out = withRecordedConditions(s, {});
  EXPECT_EQ(out.environment.dead_path_mm, 40.0);
  const std::vector<BudgetCondition> c = laserConditions(out);
  ASSERT_EQ(c.size(), 9u);
  EXPECT_EQ(condition(c, "dead path").origin, "stated");
  EXPECT_EQ(condition(c, "material temperature").origin, "default");
  EXPECT_EQ(condition(c, "material temperature").value, 20.0);
  EXPECT_TRUE(RecordedConditions{}.empty());
}

TEST(RecordedConditions, RecordsReplaceTheSourcesAndSayHow) {
  RecordedConditions r;
  r.air_temperature_c = series({20.4, 20.8});
  r.air_pressure_pa = series({100900.0, 101100.0});
  r.air_humidity_rh = series({40.0});
  // The expansion coefficient's uncertainty acts on |T − 20|: the reading farthest from 20 °C.
  r.material_temperature_c = series({21.2, 20.9, 19.1});
  r.dead_path_mm = 100.0;
  r.misalignment_rad = 2e-4;
  r.abbe_offset_mm = 15.0;
  r.angular_range_rad = 1e-3;
  const UncertaintySources out = withRecordedConditions(UncertaintySources{}, r);
  const MeasurementEnvironment& e = out.environment;
  EXPECT_NEAR(e.air.temperature_c, 20.6, kTolArithmetic);
  EXPECT_NEAR(e.air.pressure_pa, 101000.0, kTolArithmetic);
  EXPECT_EQ(e.air.relative_humidity, 40.0);
  EXPECT_EQ(e.material_temperature_c, 21.2);
  EXPECT_NEAR(e.air_temperature_variation_k, 0.4, kTolArithmetic);
  EXPECT_EQ(e.dead_path_mm, 100.0);
  EXPECT_EQ(e.misalignment_rad, 2e-4);
  for (const BudgetCondition& c : laserConditions(out)) EXPECT_EQ(c.origin, "recorded") << c.name;
  EXPECT_EQ(condition(laserConditions(out), "material temperature").note,
            "farthest from 20 degC of 3 readings (19.1..21.2 degC)");
  // One air temperature says nothing about its change: the variation stays as stated.
  r.air_temperature_c = series({20.4});
  const UncertaintySources one = withRecordedConditions(UncertaintySources{}, r);
  EXPECT_EQ(one.environment.air_temperature_variation_k, 0.5);
  EXPECT_EQ(condition(laserConditions(one), "air temperature variation").origin, "default");
}

TEST(RecordedConditions, TheAbbeTermNeedsBothTheOffsetAndTheAngularRange) {
  RecordedConditions r;
  r.abbe_offset_mm = 15.0;
  const UncertaintySources half = withRecordedConditions(UncertaintySources{}, r);
  EXPECT_EQ(half.environment.abbe_offset_mm, 0.0);  // an offset alone bounds nothing
  EXPECT_EQ(condition(laserConditions(half), "Abbe offset").origin, "default");
  r.angular_range_rad = 2.5e-3;
  const UncertaintySources both = withRecordedConditions(UncertaintySources{}, r);
  EXPECT_EQ(both.environment.abbe_offset_mm, 15.0);
  EXPECT_EQ(both.environment.angular_error_range_rad, 2.5e-3);
  EXPECT_EQ(condition(laserConditions(both), "Abbe offset").origin, "recorded");
  EXPECT_EQ(condition(laserConditions(both), "angular error range").origin, "recorded");
}

TEST(RecordedConditions, AnAirStateOutsideEdlensRangeIsRefused) {
  RecordedConditions r;
  r.air_pressure_pa = series({20000.0});
  EXPECT_THROW((void)withRecordedConditions(UncertaintySources{}, r), InvalidArgument);
}

TEST(RecordedConditions, LaserBudgetCarriesItsConditionsAndGrowsWithTheRecordedOnes) {
  // Material at 21.5 °C and a 100 mm dead path with the air changing 0.4 K (a realistic
  // workshop): the expansion coefficient's ±1e-6 /K acts over 1.5 K of 875 mm, the dead path's
  // index change over 100 mm.
  constexpr double kLengthMm = 875.0;
  UncertaintyBudget at_default, at_records;
  addLaserLengthContributors(at_default, kLengthMm, UncertaintySources{});
  RecordedConditions r;
  r.material_temperature_c = series({21.5});
  r.air_temperature_c = series({20.5, 20.9});
  r.dead_path_mm = 100.0;
  addLaserLengthContributors(
      at_records, kLengthMm, withRecordedConditions(UncertaintySources{}, r));
  EXPECT_EQ(contribution(at_default, "expansion coefficient"), 0.0);
  EXPECT_NEAR(contribution(at_records, "expansion coefficient"),
              kLengthMm * 1.5 * 1e-6 / std::sqrt(3.0),
              kTolArithmetic);
  EXPECT_GT(contribution(at_records, "dead path (air change during the test)"), 0.0);
  EXPECT_GT(at_records.combinedStandardUncertainty(), at_default.combinedStandardUncertainty());
  ASSERT_EQ(at_records.conditions.size(), 9u);
  EXPECT_EQ(condition(at_records.conditions, "material temperature").value, 21.5);
  EXPECT_EQ(condition(at_default.conditions, "dead path").origin, "default");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
