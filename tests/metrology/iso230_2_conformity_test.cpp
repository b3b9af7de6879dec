// metrology::iso230_2Nonconformities and implausibleDeviations: the ISO 230-2:2014 test conditions
// and the plausibility of positioning data.
#include "pkm/metrology/iso230_2_conformity.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

namespace pkm::metrology {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// `runs` bidirectional runs over `targets`, deviations of a few µm.
std::vector<PositioningSample> cycle(const std::vector<double>& targets, int runs) {
  std::vector<PositioningSample> s;
  for (int j = 1; j <= runs; ++j)
    for (int d : {1, -1})
      for (double t : targets) s.push_back({t, d, j, t + 0.001 * (j + d)});
  return s;
}

const std::vector<double> kTargets = {0.0, 97.3, 201.6, 298.0, 402.8, 500.0};

TEST(Iso230_2Conformity, TheStandardTestCycleConforms) {
  EXPECT_TRUE(iso230_2Nonconformities(cycle(kTargets, 5)).empty());
  EXPECT_TRUE(implausibleDeviations(cycle(kTargets, 5)).empty());
}

TEST(Iso230_2Conformity, TooFewRunsAreFlagged) {
  const std::vector<std::string> f = iso230_2Nonconformities(cycle(kTargets, 2));
  ASSERT_EQ(f.size(), 2u);
  EXPECT_THAT(f[0], HasSubstr("2 runs in the + direction"));
  EXPECT_THAT(f[1], HasSubstr("2 runs in the - direction"));
}

TEST(Iso230_2Conformity, AMissingRunIsFlaggedAtItsTarget) {
  std::vector<PositioningSample> s = cycle(kTargets, 5);
  std::erase_if(s, [](const PositioningSample& p) {
    return p.target == 201.6 && p.direction == -1 && p.run == 3;
  });
  const std::vector<std::string> f = iso230_2Nonconformities(s);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_THAT(f[0], HasSubstr("- direction differ between targets (4 to 5; target 201.6 has 4)"));
}

TEST(Iso230_2Conformity, OneDirectionAndTooFewTargets) {
  std::vector<PositioningSample> s;
  for (int j = 1; j <= 5; ++j)
    for (double t : {0.0, 400.0, 800.0, 1200.0}) s.push_back({t, 1, j, t});
  const std::vector<std::string> f = iso230_2Nonconformities(s);
  ASSERT_EQ(f.size(), 2u);
  EXPECT_THAT(f[0], HasSubstr("only + approaches"));
  EXPECT_THAT(f[1], HasSubstr("4 targets over 1200 mm of travel"));
  EXPECT_THAT(f[1], HasSubstr("(6 here)"));
  // The same targets in inches: 4 targets over 30480 mm, a long axis spaced too widely.
  const std::vector<std::string> g = iso230_2Nonconformities(s, 25.4);
  ASSERT_EQ(g.size(), 2u);
  EXPECT_THAT(g[1], HasSubstr("10160 mm apart on average"));
}

TEST(Iso230_2Conformity, DeviationsInMicrometresReadAsMillimetresAreImplausible) {
  std::vector<PositioningSample> s = cycle(kTargets, 5);
  for (PositioningSample& p : s) p.measured = p.target + 1000.0 * (p.measured - p.target);
  EXPECT_TRUE(implausibleDeviations(s).empty() == false);
  // A measured column that holds the deviations themselves.
  std::vector<PositioningSample> d = cycle(kTargets, 5);
  for (PositioningSample& p : d) p.measured = p.measured - p.target;
  const std::vector<std::string> w = implausibleDeviations(d);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_THAT(w[0], HasSubstr("µm read as mm"));
  EXPECT_THAT(w[0], HasSubstr("of the 500 mm travel"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
