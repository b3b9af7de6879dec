#include "pkm/metrology/checks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

TEST(MetrologyChecks, AcceptsFiniteValuesAndEnoughPoints) {
  const std::vector<double> values{0.0, -1.5, 2.0e6};
  EXPECT_NO_THROW(requireFinite(values, "positions"));
  EXPECT_NO_THROW(requireCount(values.size(), 3, "positions"));
}

TEST(MetrologyChecks, NamesTheFirstNonFiniteValue) {
  const std::vector<double> values{0.0, std::numeric_limits<double>::quiet_NaN(), 1.0};
  try {
    requireFinite(values, "deviations");
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "deviations: value 2 of 3 is not finite");
  }
  const std::vector<double> inf{std::numeric_limits<double>::infinity()};
  EXPECT_THROW(requireFinite(inf, "x"), InvalidArgument);
}

TEST(MetrologyChecks, RejectsTooFewPoints) {
  try {
    requireCount(2, 3, "circle");
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "circle: needs at least 3 points, got 2");
  }
}

TEST(MetrologyChecks, LevenbergMarquardtSettings) {
  EXPECT_EQ(levenbergMarquardtSettingsProblem(100, 1e-12, 1e-12), nullptr);
  EXPECT_STREQ(levenbergMarquardtSettingsProblem(0, 1e-12, 1e-12), "max_iterations must be >= 1");
  EXPECT_STREQ(levenbergMarquardtSettingsProblem(10, 0.0, 1e-12),
               "step_tolerance must be in (0, 1)");
  EXPECT_STREQ(levenbergMarquardtSettingsProblem(10, 1e-12, 1.0),
               "cost_tolerance must be in (0, 1)");
  EXPECT_STREQ(levenbergMarquardtSettingsProblem(10, 1e-12, std::nan("")),
               "cost_tolerance must be in (0, 1)");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
