// Axis error tables: construction from ISO 230-2 results, validation, interpolation, the format
// conventions (the sign table of docs/compensation.md) and resampling to controller limits.
#include "pkm/compensation/axis_table.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace comp = pkm::compensation;
namespace met = pkm::metrology;
using pkm::test::kTolExact;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// Samples with x̄↑ = 0.001·i and x̄↓ = −0.002·i at targets 0, 10, 20 (two runs each, ±1 µm).
std::vector<met::PositioningSample> samples(bool both) {
  std::vector<met::PositioningSample> s;
  for (int i = 0; i < 3; ++i) {
    const double p = 10.0 * i;
    for (int run = 1; run <= 2; ++run) {
      const double noise = run == 1 ? 1e-3 : -1e-3;
      s.push_back({p, 1, run, p + 0.001 * i + noise});
      if (both) s.push_back({p, -1, run, p - 0.002 * i + noise});
    }
  }
  return s;
}

comp::AxisErrorTable linearTable(std::size_t n, double slope_up, double slope_down) {
  comp::AxisErrorTable t;
  t.axis = "X";
  for (std::size_t i = 0; i < n; ++i) {
    const double p = 3.0 * static_cast<double>(i) + (i % 2 == 1 ? 0.4 : 0.0);  // uneven
    t.nominal.push_back(p);
    t.error_up.push_back(slope_up * p);
    t.error_down.push_back(slope_down * p);
  }
  return t;
}

TEST(AxisTable, FromIso230_2UsesTheUnidirectionalMeans) {
  const auto s = samples(true);
  const comp::AxisErrorTable t = comp::tableFromIso230_2(met::evaluateIso230_2(s), "X");
  ASSERT_EQ(t.size(), 3U);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(t.nominal[i], 10.0 * static_cast<double>(i));
    EXPECT_NEAR(t.error_up[i], 0.001 * static_cast<double>(i), kTolExact);
    EXPECT_NEAR(t.error_down[i], -0.002 * static_cast<double>(i), kTolExact);
    EXPECT_NEAR(t.meanError(i), -0.0005 * static_cast<double>(i), kTolExact);
  }
  EXPECT_EQ(t.axis, "X");
  EXPECT_NEAR(t.maxAbsError(), 0.004, kTolExact);
}

TEST(AxisTable, FromUnidirectionalResultUsesTheOneDirectionForBoth) {
  const auto s = samples(false);
  const comp::AxisErrorTable t = comp::tableFromIso230_2(met::evaluateIso230_2(s), "Y");
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(t.error_up[i], 0.001 * static_cast<double>(i), kTolExact);
    EXPECT_EQ(t.error_down[i], t.error_up[i]);
  }
}

TEST(AxisTable, ValidateRejectsBadTables) {
  comp::AxisErrorTable t = linearTable(4, 1e-5, 2e-5);
  EXPECT_NO_THROW(t.validate());
  comp::AxisErrorTable bad = t;
  bad.nominal[2] = bad.nominal[1];
  EXPECT_THROW(bad.validate(), pkm::InvalidArgument);  // not strictly increasing
  bad = t;
  bad.error_up[1] = kNaN;
  EXPECT_THROW(bad.validate(), pkm::InvalidArgument);
  bad = t;
  bad.error_down.pop_back();
  EXPECT_THROW(bad.validate(), pkm::InvalidArgument);
  bad = linearTable(1, 0, 0);
  EXPECT_THROW(bad.validate(), pkm::InvalidArgument);
}

TEST(AxisTable, ErrorAtInterpolatesAndHoldsTheEnds) {
  const comp::AxisErrorTable t{"X", {0.0, 10.0, 20.0}, {0.0, 0.01, 0.03}, {0.0, -0.01, 0.0}};
  EXPECT_NEAR(t.errorAt(5.0, 1), 0.005, kTolExact);
  EXPECT_NEAR(t.errorAt(15.0, 1), 0.02, kTolExact);
  EXPECT_NEAR(t.errorAt(15.0, -1), -0.005, kTolExact);
  EXPECT_EQ(t.errorAt(-3.0, 1), 0.0);
  EXPECT_EQ(t.errorAt(99.0, 1), 0.03);
  EXPECT_THROW((void)t.errorAt(kNaN, 1), pkm::InvalidArgument);
  EXPECT_THROW((void)t.errorAt(1.0, 0), pkm::InvalidArgument);
}

TEST(AxisTable, ConventionMatrix) {
  // An axis that overshoots by e = +0.01 mm at P = 100 mm (docs/compensation.md, sign table).
  constexpr double kP = 100.0, kE = 0.01;
  using comp::StoredValue;
  EXPECT_EQ(comp::storedValue(StoredValue::kError, kP, kE), kE);
  EXPECT_EQ(comp::storedValue(StoredValue::kCorrection, kP, kE), -kE);
  EXPECT_EQ(comp::storedValue(StoredValue::kActualPosition, kP, kE), kP + kE);
  EXPECT_EQ(comp::traits(comp::TableFormat::kLinuxcnc1).stored, StoredValue::kCorrection);
  EXPECT_EQ(comp::traits(comp::TableFormat::kLinuxcnc0).stored, StoredValue::kActualPosition);
  EXPECT_EQ(comp::traits(comp::TableFormat::kSiemensEec).stored, StoredValue::kError);
  EXPECT_EQ(comp::traits(comp::TableFormat::kSiemensCec).stored, StoredValue::kError);
  EXPECT_EQ(comp::traits(comp::TableFormat::kIsgCsv).stored, StoredValue::kError);
  EXPECT_TRUE(comp::traits(comp::TableFormat::kSiemensEec).even_spacing);
  EXPECT_EQ(comp::traits(comp::TableFormat::kLinuxcnc1).hard_max_points, 256U);
}

TEST(AxisTable, FormatNamesRoundTrip) {
  for (auto f : {comp::TableFormat::kLinuxcnc0,
                 comp::TableFormat::kLinuxcnc1,
                 comp::TableFormat::kSiemensEec,
                 comp::TableFormat::kSiemensCec,
                 comp::TableFormat::kIsgCsv}) {
    EXPECT_EQ(comp::parseTableFormat(comp::toString(f)), f);
  }
  EXPECT_THROW((void)comp::parseTableFormat("fanuc"), pkm::InvalidArgument);
}

TEST(AxisTable, ResampleEvenIsExactForLinearErrors) {
  const comp::AxisErrorTable t = linearTable(9, 2e-5, -1e-5);
  const comp::AxisErrorTable r = comp::resampleEven(t, 5);
  ASSERT_EQ(r.size(), 5U);
  EXPECT_EQ(r.nominal.front(), t.nominal.front());
  EXPECT_EQ(r.nominal.back(), t.nominal.back());
  EXPECT_TRUE(comp::isEvenlySpaced(r.nominal));
  for (std::size_t i = 0; i < r.size(); ++i) {
    EXPECT_NEAR(r.error_up[i], 2e-5 * r.nominal[i], kTolExact);
    EXPECT_NEAR(r.error_down[i], -1e-5 * r.nominal[i], kTolExact);
  }
  EXPECT_THROW((void)comp::resampleEven(t, 1), pkm::InvalidArgument);
}

TEST(AxisTable, PointsForTarget) {
  const std::vector<double> even{0, 1, 2, 3}, uneven{0, 1, 2.5, 4};
  EXPECT_TRUE(comp::isEvenlySpaced(even));
  EXPECT_FALSE(comp::isEvenlySpaced(uneven));
  EXPECT_EQ(comp::pointsForTarget(even, true, 100), 4U);
  EXPECT_EQ(comp::pointsForTarget(uneven, false, 100), 4U);
  EXPECT_EQ(comp::pointsForTarget(uneven, true, 100), 5U);  // ⌈4 / 1⌉ + 1
  EXPECT_EQ(comp::pointsForTarget(uneven, true, 3), 3U);
  EXPECT_THROW((void)comp::pointsForTarget(uneven, true, 1), pkm::InvalidArgument);
}

TEST(AxisTable, FitToLinuxcncLimitResamplesLongTables) {
  const comp::FormatTraits lc = comp::traits(comp::TableFormat::kLinuxcnc1);
  const comp::AxisErrorTable small = linearTable(10, 1e-5, 1e-5);
  const comp::AxisErrorTable same = comp::fitToTarget(small, lc, 256);
  EXPECT_EQ(same.nominal, small.nominal);  // fits: unchanged, not resampled
  const comp::AxisErrorTable big = linearTable(300, 1e-5, -1e-5);
  const comp::AxisErrorTable fitted = comp::fitToTarget(big, lc, lc.default_max_points);
  ASSERT_EQ(fitted.size(), 256U);
  EXPECT_NEAR(fitted.errorAt(123.4, 1), 1e-5 * 123.4, kTolExact);
  EXPECT_THROW((void)comp::fitToTarget(big, lc, 300), pkm::InvalidArgument);  // above 256
  const comp::FormatTraits eec = comp::traits(comp::TableFormat::kSiemensEec);
  EXPECT_TRUE(comp::isEvenlySpaced(comp::fitToTarget(small, eec, 200).nominal));
}

TEST(AxisTable, CrossTableAveragesRepeatedPositionsAndSorts) {
  const std::vector<double> p{20, 0, 10, 0}, d{0.003, 0.001, 0.002, 0.003};
  const comp::CrossAxisTable t = comp::crossTableFromPoints("X", "Y", p, d);
  EXPECT_EQ(t.position, (std::vector<double>{0, 10, 20}));
  EXPECT_NEAR(t.error[0], 0.002, kTolExact);
  EXPECT_EQ(t.error[2], 0.003);
  const std::vector<double> one{5, 5}, two{1, 2};
  EXPECT_THROW((void)comp::crossTableFromPoints("X", "Y", one, two), pkm::InvalidArgument);
  const std::vector<double> bad{kNaN, 1};
  EXPECT_THROW((void)comp::crossTableFromPoints("X", "Y", bad, two), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
