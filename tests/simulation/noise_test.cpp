// NoiseModel: the ideal instrument is exact, the spread matches sigma and the ppm term, readings
// are quantised to the resolution; the datasheet presets.
#include "pkm/simulation/noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "pkm/core/error.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::simulation::instrumentNoise;
using pkm::simulation::NoiseModel;
using pkm::simulation::RandomStream;
constexpr std::size_t kSamples = 100000;

std::vector<double> residuals(const NoiseModel& n, double truth, double length) {
  RandomStream r(pkm::test::kSeed);
  std::vector<double> v;
  for (std::size_t i = 0; i < kSamples; ++i) v.push_back(n.apply(truth, length, r) - truth);
  return v;
}

TEST(Noise, IdealInstrumentIsExactAndDrawsNothing) {
  RandomStream a(1), b(1);
  const NoiseModel ideal;
  EXPECT_EQ(ideal.apply(123.456789, 500.0, a), 123.456789);
  EXPECT_EQ(a.normal(), b.normal());
}

TEST(Noise, PerfectInstrumentReadsTheTruthAndKeepsTheStreamAligned) {
  NoiseModel noisy{.sigma = 1e-3, .resolution = 1e-6};
  NoiseModel perfect = noisy;
  perfect.perfect = true;
  RandomStream a(pkm::test::kSeed, "line"), b(pkm::test::kSeed, "line");
  EXPECT_NE(noisy.apply(10.0, 0.0, a), 10.0);
  EXPECT_EQ(perfect.apply(10.0, 0.0, b), 10.0);
  EXPECT_EQ(a.bits(), b.bits());  // one variate drawn by each: the next draws agree
}

TEST(Noise, ConstantSigmaGivesThatSpread) {
  const NoiseModel n{2e-5, 0.0, 0.0};
  const std::vector<double> v = residuals(n, 100.0, 100.0);
  EXPECT_NEAR(pkm::test::sampleMean(v), 0.0, pkm::test::meanTolerance(kSamples, n.sigma));
  EXPECT_NEAR(pkm::test::sampleSigma(v) / n.sigma, 1.0, pkm::test::sigmaRatioTolerance(kSamples));
}

TEST(Noise, PpmTermGrowsWithTheLength) {
  const NoiseModel n{0.0, 0.25, 0.0};
  const double length = 800.0;
  const double expected = 0.25e-6 * length;
  EXPECT_DOUBLE_EQ(n.totalSigma(length), expected);
  EXPECT_DOUBLE_EQ(n.totalSigma(-length), expected);
  EXPECT_EQ(n.totalSigma(0.0), 0.0);
  const std::vector<double> v = residuals(n, 10.0, length);
  EXPECT_NEAR(pkm::test::sampleSigma(v) / expected, 1.0, pkm::test::sigmaRatioTolerance(kSamples));
  const NoiseModel both{3e-6, 0.5, 0.0};
  EXPECT_DOUBLE_EQ(both.totalSigma(8.0), std::hypot(3e-6, 4e-6));
}

TEST(Noise, ResolutionQuantisesToTheNearestStep) {
  RandomStream r(1);
  const NoiseModel n{0.0, 0.0, 1e-6};
  EXPECT_EQ(n.apply(64.0311074, 0.0, r), 64.031107);
  EXPECT_EQ(n.apply(-0.0000016, 0.0, r), -0.000002);
  const NoiseModel odd{0.0, 0.0, 0.25};
  EXPECT_EQ(odd.apply(1.3, 0.0, r), 1.25);
  // Quantisation error is uniform in ±resolution/2: sigma = resolution/√12.
  const NoiseModel coarse{1e-3, 0.0, 1e-3};
  const std::vector<double> v = residuals(coarse, 0.0, 0.0);
  const double expected = std::sqrt(1e-6 + 1e-6 / 12.0);
  EXPECT_NEAR(
      pkm::test::sampleSigma(v) / expected, 1.0, 2 * pkm::test::sigmaRatioTolerance(kSamples));
}

TEST(Noise, LineScaleErrorIsOneDrawPerLineAndScalesWithLength) {
  // A line's ppm term is one scale error (drawScale), the per-reading term sigma only: two
  // readings of the same line differ by sigma's noise, not by the ppm term's.
  const NoiseModel n{1e-5, 0.25, 0.0};
  RandomStream r(7);
  std::vector<double> scales;
  for (std::size_t k = 0; k < kSamples; ++k) scales.push_back(n.drawScale(r));
  EXPECT_NEAR(
      pkm::test::sampleSigma(scales) / 0.25e-6, 1.0, pkm::test::sigmaRatioTolerance(kSamples));
  RandomStream a(3), b(3);
  const double scale = 0.4e-6;
  const double reading = n.apply(10.0, 1000.0, scale, a);
  EXPECT_NEAR(reading, 10.0 + scale * 1000.0 + b.normal(1e-5), 1e-15);
  // No ppm term: nothing drawn, as before (the streams of straightness and angular lines keep).
  RandomStream c(5), d(5);
  const NoiseModel no_ppm{1e-5, 0.0, 0.0};
  EXPECT_EQ(no_ppm.drawScale(c), 0.0);
  EXPECT_EQ(c.bits(), d.bits());
  // A perfect instrument draws the scale too but returns 0, and reads the truth.
  NoiseModel perfect = n;
  perfect.perfect = true;
  RandomStream e(9), f(9);
  EXPECT_EQ(perfect.drawScale(e), 0.0);
  (void)n.drawScale(f);
  EXPECT_EQ(perfect.apply(10.0, 1000.0, 0.0, e), 10.0);
  (void)n.apply(10.0, 1000.0, 0.0, f);
  EXPECT_EQ(e.bits(), f.bits());
}

TEST(Noise, ValidateRejectsNegativeAndNonFinite) {
  EXPECT_THROW((NoiseModel{-1.0, 0.0, 0.0}.validate()), pkm::InvalidArgument);
  EXPECT_THROW((NoiseModel{0.0, NAN, 0.0}.validate()), pkm::InvalidArgument);
  EXPECT_THROW((NoiseModel{0.0, 0.0, -1e-6}.validate()), pkm::InvalidArgument);
  EXPECT_NO_THROW((NoiseModel{1e-6, 0.5, 1e-6}.validate()));
}

TEST(Noise, PresetsFollowTheDatasheets) {
  ASSERT_TRUE(instrumentNoise("xl80-linear"));
  EXPECT_EQ(instrumentNoise("xl80-linear")->sigma_ppm, 0.25);   // ±0.5 ppm at k = 2
  EXPECT_EQ(instrumentNoise("xl80-linear")->resolution, 1e-6);  // 1 nm in mm
  EXPECT_EQ(instrumentNoise("xl80-straightness")->resolution, 1e-5);
  EXPECT_EQ(instrumentNoise("xl80-angular")->resolution, 1e-8);  // 0.01 µrad in rad
  EXPECT_EQ(instrumentNoise("ideal")->totalSigma(1000.0), 0.0);
  EXPECT_FALSE(instrumentNoise("no-such-instrument"));
  for (const auto name : pkm::simulation::instrumentNoiseNames())
    EXPECT_TRUE(instrumentNoise(name)) << name;
}

}  // namespace PKM_TEST_NS
