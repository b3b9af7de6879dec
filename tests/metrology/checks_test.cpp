#include "pkm/metrology/checks.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <vector>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace {

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

}  // namespace
}  // namespace pkm::metrology
