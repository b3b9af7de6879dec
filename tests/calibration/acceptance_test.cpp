// calibration::explainsData: the one acceptance rule of every calibration.
#include "pkm/calibration/acceptance.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace pkm::calibration {
namespace {

TEST(ExplainsData, ResidualsBelowAThousandthOfTheMachineAreAccepted) {
  EXPECT_TRUE(explainsData(0.0, 1000.0));
  EXPECT_TRUE(explainsData(0.999, 1000.0));
  EXPECT_FALSE(explainsData(1.0, 1000.0));  // the bound itself is not below it
  EXPECT_FALSE(explainsData(5.0, 1000.0));
  EXPECT_TRUE(explainsData(0.0009, 1.0));  // the same rule for a machine in metres or inches
  EXPECT_FALSE(explainsData(std::numeric_limits<double>::quiet_NaN(), 1000.0));
  EXPECT_FALSE(explainsData(std::numeric_limits<double>::infinity(), 1000.0));
  static_assert(explainsData(0.5, 1000.0) && kAcceptableResidualFraction == 1e-3);
}

}  // namespace
}  // namespace pkm::calibration
