// metrology::perTargetMeans: groups by target, sorts, averages.
#include "pkm/metrology/per_target.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace pkm::metrology {
namespace PKM_TEST_NS {

TEST(PerTargetMeans, AveragesEachTargetAndSortsThem) {
  const std::vector<TargetSample> s = {
      {100.0, 1.0}, {0.0, 2.0}, {100.0, 3.0}, {50.0, -1.0}, {0.0, 4.0}, {100.0, 5.0}};
  const TargetMeans m = perTargetMeans(s);
  EXPECT_EQ(m.target, (std::vector<double>{0.0, 50.0, 100.0}));
  EXPECT_EQ(m.mean, (std::vector<double>{3.0, -1.0, 3.0}));
}

TEST(PerTargetMeans, EmptyInputGivesEmptyOutput) {
  const TargetMeans m = perTargetMeans({});
  EXPECT_TRUE(m.target.empty());
  EXPECT_TRUE(m.mean.empty());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
