#include "pkm/metrology/iso230_2.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/campaign.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kTolHand = 1e-12;  ///< hand-computed example with exact binary inputs

/// Builds samples from per-target deviation lists (measured = target + deviation).
void addRuns(std::vector<PositioningSample>& out,
             double target,
             int direction,
             const std::vector<double>& deviations) {
  int run = 1;
  for (double d : deviations) out.push_back({target, direction, run++, target + d});
}

TEST(Iso230_2, HandComputedTwoTargetsTwoRuns) {
  // Target 0: up {1, 3}, down {-1, -1}; target 10: up {0, 2}, down {2, 4} (ISO 230-2:2014).
  std::vector<PositioningSample> samples;
  addRuns(samples, 10.0, -1, {2.0, 4.0});
  addRuns(samples, 0.0, 1, {1.0, 3.0});
  addRuns(samples, 10.0, 1, {0.0, 2.0});
  addRuns(samples, 0.0, -1, {-1.0, -1.0});
  const Iso230_2Result r = evaluateIso230_2(samples);
  const double q = std::sqrt(2.0);  // s = sqrt(2) for {1, 3}, {0, 2}, {2, 4}
  ASSERT_EQ(r.targets.size(), 2u);
  EXPECT_TRUE(r.bidirectional);
  const TargetStatistics& t0 = r.targets[0];
  EXPECT_EQ(t0.target, 0.0);
  EXPECT_NEAR(t0.mean_up, 2.0, kTolHand);
  EXPECT_NEAR(t0.mean_down, -1.0, kTolHand);
  EXPECT_NEAR(t0.reversal, 3.0, kTolHand);
  EXPECT_NEAR(t0.s_up, q, kTolHand);
  EXPECT_NEAR(t0.s_down, 0.0, kTolHand);
  EXPECT_NEAR(t0.repeatability, 2.0 * q + 3.0, kTolHand);  // 2s↑ + 2s↓ + |B| > 4s↑
  EXPECT_NEAR(t0.mean, 0.5, kTolHand);
  EXPECT_EQ(t0.runs_up, 2);
  EXPECT_EQ(t0.runs_down, 2);
  const TargetStatistics& t1 = r.targets[1];
  EXPECT_NEAR(t1.reversal, -2.0, kTolHand);
  EXPECT_NEAR(t1.repeatability_up, 4.0 * q, kTolHand);
  EXPECT_NEAR(t1.repeatability, 4.0 * q + 2.0, kTolHand);
  EXPECT_NEAR(r.B, 3.0, kTolHand);
  EXPECT_NEAR(r.B_mean, 0.5, kTolHand);
  EXPECT_NEAR(r.R_up, 4.0 * q, kTolHand);
  EXPECT_NEAR(r.R_down, 4.0 * q, kTolHand);
  EXPECT_NEAR(r.R, 4.0 * q + 2.0, kTolHand);
  EXPECT_NEAR(r.E_up, 1.0, kTolHand);
  EXPECT_NEAR(r.E_down, 4.0, kTolHand);
  EXPECT_NEAR(r.E, 4.0, kTolHand);
  EXPECT_NEAR(r.M, 1.5, kTolHand);
  EXPECT_NEAR(r.A_up, 1.0 + 4.0 * q, kTolHand);
  EXPECT_NEAR(r.A_down, 4.0 + 2.0 * q, kTolHand);
  EXPECT_NEAR(r.A, 2.0 + 4.0 * q, kTolHand);

  // The coverage factor scales every ± k s band: k = 3 (ISO 230-2:1988 style).
  const Iso230_2Result r3 = evaluateIso230_2(samples, {.coverage_factor = 3.0});
  EXPECT_NEAR(r3.R_up, 6.0 * q, kTolHand);
  EXPECT_NEAR(r3.A, 2.0 + 6.0 * q, kTolHand);
  EXPECT_NEAR(r3.E, r.E, kTolHand);
}

/// Brute-force reference: direct transcription of the ISO 230-2:2014 definitions over a map.
struct Reference {
  double B = 0, B_mean = 0, R_up = 0, R_down = 0, R = 0, E_up, E_down, E, M, A_up, A_down, A;
};

Reference bruteForce(const std::vector<PositioningSample>& samples, double k) {
  std::map<double, std::map<int, std::vector<double>>> groups;
  for (const auto& s : samples) groups[s.target][s.direction].push_back(s.measured - s.target);
  std::vector<double> up, dn, sup, sdn, mean;
  Reference ref;
  for (auto& [target, dirs] : groups) {
    double m[2], s[2];
    for (int d = 0; d < 2; ++d) {
      const std::vector<double>& x = dirs[d == 0 ? 1 : -1];
      double sum = 0;
      for (double v : x) sum += v;
      m[d] = sum / static_cast<double>(x.size());
      double ss = 0;
      for (double v : x) ss += (v - m[d]) * (v - m[d]);
      s[d] = std::sqrt(ss / static_cast<double>(x.size() - 1));
    }
    const double Bi = m[0] - m[1];
    ref.B = std::max(ref.B, std::abs(Bi));
    ref.B_mean += Bi / static_cast<double>(groups.size());
    ref.R_up = std::max(ref.R_up, 2 * k * s[0]);
    ref.R_down = std::max(ref.R_down, 2 * k * s[1]);
    ref.R = std::max({ref.R, k * s[0] + k * s[1] + std::abs(Bi), 2 * k * s[0], 2 * k * s[1]});
    up.push_back(m[0]);
    dn.push_back(m[1]);
    sup.push_back(s[0]);
    sdn.push_back(s[1]);
    mean.push_back(0.5 * (m[0] + m[1]));
  }
  const auto mx = [](const std::vector<double>& v) {
    return *std::max_element(v.begin(), v.end());
  };
  const auto mn = [](const std::vector<double>& v) {
    return *std::min_element(v.begin(), v.end());
  };
  ref.E_up = mx(up) - mn(up);
  ref.E_down = mx(dn) - mn(dn);
  ref.E = std::max(mx(up), mx(dn)) - std::min(mn(up), mn(dn));
  ref.M = mx(mean) - mn(mean);
  std::vector<double> hu, lu, hd, ld;
  for (std::size_t i = 0; i < up.size(); ++i) {
    hu.push_back(up[i] + k * sup[i]);
    lu.push_back(up[i] - k * sup[i]);
    hd.push_back(dn[i] + k * sdn[i]);
    ld.push_back(dn[i] - k * sdn[i]);
  }
  ref.A_up = mx(hu) - mn(lu);
  ref.A_down = mx(hd) - mn(ld);
  ref.A = std::max(mx(hu), mx(hd)) - std::min(mn(lu), mn(ld));
  return ref;
}

TEST(Iso230_2, MatchesBruteForceWithUnequalRunCounts) {
  std::mt19937_64 rng(test::kSeed);
  std::uniform_int_distribution<int> runs(2, 7);
  std::normal_distribution<double> noise(0.0, 0.002);
  std::vector<PositioningSample> samples;
  for (int i = 0; i < 23; ++i) {  // m = 23 targets, n between 2 and 7 per target-direction
    const double target = 37.5 * i + 0.25 * (i % 3);
    for (int direction : {1, -1}) {
      const int n = runs(rng);
      for (int j = 1; j <= n; ++j) {
        const double systematic = 1e-4 * target + (direction > 0 ? 0.003 : -0.002);
        samples.push_back({target, direction, j, target + systematic + noise(rng)});
      }
    }
  }
  std::shuffle(samples.begin(), samples.end(), rng);
  for (double k : {2.0, 2.5}) {
    const Iso230_2Result r = evaluateIso230_2(samples, {.coverage_factor = k});
    const Reference ref = bruteForce(samples, k);
    EXPECT_NEAR(r.B, ref.B, test::kTolExact);
    EXPECT_NEAR(r.B_mean, ref.B_mean, test::kTolExact);
    EXPECT_NEAR(r.R_up, ref.R_up, test::kTolExact);
    EXPECT_NEAR(r.R_down, ref.R_down, test::kTolExact);
    EXPECT_NEAR(r.R, ref.R, test::kTolExact);
    EXPECT_NEAR(r.E_up, ref.E_up, test::kTolExact);
    EXPECT_NEAR(r.E_down, ref.E_down, test::kTolExact);
    EXPECT_NEAR(r.E, ref.E, test::kTolExact);
    EXPECT_NEAR(r.M, ref.M, test::kTolExact);
    EXPECT_NEAR(r.A_up, ref.A_up, test::kTolExact);
    EXPECT_NEAR(r.A_down, ref.A_down, test::kTolExact);
    EXPECT_NEAR(r.A, ref.A, test::kTolExact);
  }
}

TEST(Iso230_2, UnidirectionalDataGivesNaNForBidirectionalQuantities) {
  std::vector<PositioningSample> samples;
  addRuns(samples, 0.0, 1, {1.0, 3.0});
  addRuns(samples, 10.0, 1, {0.0, 2.0, 1.0});
  const Iso230_2Result r = evaluateIso230_2(samples);
  EXPECT_FALSE(r.bidirectional);
  EXPECT_NEAR(r.E_up, 1.0, kTolHand);
  EXPECT_NEAR(r.R_up, 4.0 * std::sqrt(2.0), kTolHand);
  for (double v : {r.B, r.B_mean, r.R, r.E, r.M, r.A, r.R_down, r.E_down, r.A_down}) {
    EXPECT_TRUE(std::isnan(v));
  }
  EXPECT_TRUE(std::isnan(r.targets[0].reversal));
  EXPECT_TRUE(std::isnan(r.targets[0].repeatability));
  EXPECT_EQ(r.targets[1].runs_up, 3);
  EXPECT_EQ(r.targets[1].runs_down, 0);
}

TEST(Iso230_2, RejectsBadInput) {
  std::vector<PositioningSample> one_run;
  addRuns(one_run, 0.0, 1, {1.0});
  addRuns(one_run, 5.0, 1, {1.0, 2.0});
  EXPECT_THROW((void)evaluateIso230_2(one_run), InvalidArgument);
  std::vector<PositioningSample> duplicate;
  addRuns(duplicate, 0.0, 1, {1.0, 2.0});
  duplicate.push_back({0.0, 1, 2, 0.5});
  try {
    (void)evaluateIso230_2(duplicate);
    FAIL() << "expected InvalidArgument";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("duplicate"), std::string::npos) << e.what();
  }
  std::vector<PositioningSample> mixed;  // target 0 bidirectional, target 5 only +
  addRuns(mixed, 0.0, 1, {1.0, 2.0});
  addRuns(mixed, 0.0, -1, {1.0, 2.0});
  addRuns(mixed, 5.0, 1, {1.0, 2.0});
  EXPECT_THROW((void)evaluateIso230_2(mixed), InvalidArgument);
  std::vector<PositioningSample> bad{{0.0, 1, 1, std::nan("")}, {0.0, 1, 2, 0.0}};
  EXPECT_THROW((void)evaluateIso230_2(bad), InvalidArgument);
  bad = {{0.0, 0, 1, 0.0}, {0.0, 0, 2, 0.0}};
  EXPECT_THROW((void)evaluateIso230_2(bad), InvalidArgument);
  bad = {{0.0, 1, 0, 0.0}, {0.0, 1, 2, 0.0}};
  EXPECT_THROW((void)evaluateIso230_2(bad), InvalidArgument);
  EXPECT_THROW((void)evaluateIso230_2({}), InvalidArgument);
  addRuns(bad, 1.0, 1, {0.0, 1.0});
  EXPECT_THROW((void)evaluateIso230_2(one_run, {.coverage_factor = 0.0}), InvalidArgument);
}

/// Simulated X2 positioning of seed 000: the mean deviations recover the noise-free profile.
TEST(Iso230_2, RecoversSimulatedPositioningProfile) {
  io::Scenario scenario = io::loadScenario("seed000-parallelism");
  simulation::Campaign& campaign = scenario.campaign;
  std::erase_if(campaign.measurements,
                [](const simulation::LineSetup& s) { return s.name != "linear-x2"; });
  ASSERT_EQ(campaign.measurements.size(), 1u);
  const auto toSamples = [](const simulation::MeasurementResult& m) {
    std::vector<PositioningSample> out;
    for (const simulation::LineRun& run : m.runs) {
      for (const simulation::LineReading& r : run.readings) {
        out.push_back({r.target, r.direction, run.run, r.reading});
      }
    }
    return out;
  };
  const auto noisy =
      evaluateIso230_2(toSamples(simulation::runCampaign(campaign, scenario.seed)[0]));
  const simulation::NoiseModel noise = campaign.measurements[0].noise;
  campaign.measurements[0].noise = simulation::NoiseModel{};
  const auto exact =
      evaluateIso230_2(toSamples(simulation::runCampaign(campaign, scenario.seed)[0]));
  // XL-80 linear noise at the longest travel; 5 sigma bounds a mean of 3 runs with margin.
  const double tolerance = 5.0 * (noise.totalSigma(875.0) + noise.resolution);
  ASSERT_EQ(noisy.targets.size(), exact.targets.size());
  EXPECT_GT(exact.E, 0.05);  // Table 2: δxx2 reaches -0.078 mm over 875 mm
  for (std::size_t i = 0; i < exact.targets.size(); ++i) {
    EXPECT_NEAR(noisy.targets[i].mean_up, exact.targets[i].mean_up, tolerance);
    EXPECT_NEAR(noisy.targets[i].mean_down, exact.targets[i].mean_down, tolerance);
    EXPECT_NEAR(exact.targets[i].s_up, 0.0, test::kTolRoundTrip);
  }
  EXPECT_NEAR(noisy.E, exact.E, 2.0 * tolerance);
  EXPECT_NEAR(noisy.M, exact.M, 2.0 * tolerance);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
