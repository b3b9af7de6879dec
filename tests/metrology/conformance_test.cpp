// ISO 14253-1 decision rules (metrology/conformance.hpp).
#include "pkm/metrology/conformance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

TEST(Conformance, TheZonesAreTheSpecificationReducedAndExtendedByU) {
  // E = 10 µm measured with U = 1 µm. Tolerance 12: 10 <= 12 − 1, conforms. Tolerance 11: on the
  // edge of the conformance zone, conforms. Tolerance 10.5 and 9: within ±U of the limit, not
  // decidable. Tolerance 8.5: 10 > 8.5 + 1, does not conform.
  EXPECT_EQ(decideConformance(10.0, 1.0, 12.0), ConformanceDecision::kConforms);
  EXPECT_EQ(decideConformance(10.0, 1.0, 11.0), ConformanceDecision::kConforms);
  EXPECT_EQ(decideConformance(10.0, 1.0, 10.5), ConformanceDecision::kUndecided);
  EXPECT_EQ(decideConformance(10.0, 1.0, 9.0), ConformanceDecision::kUndecided);
  EXPECT_EQ(decideConformance(10.0, 1.0, 8.5), ConformanceDecision::kDoesNotConform);
  // Without uncertainty the decision is the plain comparison.
  EXPECT_EQ(decideConformance(10.0, 0.0, 10.0), ConformanceDecision::kConforms);
  EXPECT_EQ(decideConformance(10.0, 0.0, 9.999), ConformanceDecision::kDoesNotConform);
}

TEST(Conformance, NamesAndBadInput) {
  EXPECT_STREQ(toString(ConformanceDecision::kUndecided), "not decidable within U");
  EXPECT_STREQ(toString(ConformanceDecision::kConforms), "conforms");
  EXPECT_STREQ(toString(ConformanceDecision::kDoesNotConform), "does not conform");
  EXPECT_THROW((void)decideConformance(NAN, 1.0, 2.0), InvalidArgument);
  EXPECT_THROW((void)decideConformance(1.0, -1.0, 2.0), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
