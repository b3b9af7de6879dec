#include "pkm/metrology/parallelism.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/io/scenario.hpp"
#include "pkm/simulation/campaign.hpp"
#include "support/tolerances.hpp"

namespace pkm::metrology {
namespace PKM_TEST_NS {

constexpr double kMrad = 1e-3;
/// Seed 000 prints Δγ = 2.81, Δα = -14.7, szX2 = -0.034 and szP = -2.85, sxP = -14.74 mrad: each
/// value is rounded to its last printed digit, so they agree within the sum of the half-units.
constexpr double kTolPaperSzP = (0.005 + 0.0005 + 0.005) * kMrad;
constexpr double kTolPaperSxP = (0.05 + 0.005) * kMrad;
/// Noise of the slope difference of two simulated XL-80 straightness runs: 0.25 µm per reading,
/// 13 targets × 6 readings over 300 mm give a least-squares slope uncertainty near 0.1 µrad per
/// run; 2 µrad is about 10 of them.
constexpr double kTolSlopeNoise = 2e-6;
/// The slopes give szP and sxP to first order (docs/conventions.md, "Squareness"); the simulator's
/// exact rotation Rot(sxP, -syP, szP) adds second-order terms, the largest sxP·syP/2 = 32 µrad in
/// the x slope, and the Y2 straightness tables add their slopes (EZY: 2 µm over 350 mm = 6 µrad).
constexpr double kTolFirstOrder = 40e-6;

TEST(Parallelism, SyntheticRunsAlongOppositeDirections) {
  // Reference along -u (beam sign -1), axis along +u; beam misalignment 2e-5 in u; the axis is
  // tilted by 3e-3 against the reference and has a 1 µm bump.
  const double misalignment = 2e-5, tilt = 3e-3;
  BeamRun ref{{}, {}, -1}, axis{{}, {}, 1};
  for (int k = 0; k <= 10; ++k) {
    const double s = 30.0 * k;
    ref.positions.push_back(s);
    ref.deviations.push_back(misalignment * (-s) + 0.01);  // offset: zeroed elsewhere
    axis.positions.push_back(0.5 * s);
    const double u = 0.5 * s;
    axis.deviations.push_back(misalignment * u + tilt * u + (k == 5 ? 0.001 : 0.0));
  }
  const ParallelismResult r = evaluateParallelism(ref, axis, {StraightnessReference::kEndpoint});
  EXPECT_NEAR(r.reference_slope, misalignment, test::kTolExact);
  EXPECT_NEAR(r.axis_slope, misalignment + tilt, test::kTolExact);
  EXPECT_NEAR(r.slope_difference, tilt, test::kTolExact);
  EXPECT_NEAR(r.parallelism, tilt * 150.0, test::kTolExact);
  EXPECT_NEAR(r.deviations.front(), 0.0, test::kTolExact);
  EXPECT_NEAR(r.max_deviation, tilt * 150.0, test::kTolExact);
  EXPECT_NEAR(r.deviations[5], tilt * 75.0 + 0.001, test::kTolExact);
  // Least squares: the bump tilts the axis line slightly; the difference stays near the tilt.
  const ParallelismResult ls = evaluateParallelism(ref, axis);
  EXPECT_NEAR(ls.slope_difference, tilt, 0.001 / 150.0);
  BeamRun bad = axis;
  bad.beam_sign = 0;
  EXPECT_THROW((void)evaluateParallelism(ref, bad), InvalidArgument);
}

TEST(Parallelism, ReproducesSeed000Equation11Numbers) {
  // Seed 000 §4: Δγ = 2.81 mrad, Δα = -14.7 mrad, szX2 = -0.034 mrad -> sxP = -14.74, szP = -2.85.
  const PkmSquareness s = pkmSquarenessFromSlopes(2.81 * kMrad, -14.7 * kMrad, -0.034 * kMrad);
  EXPECT_NEAR(s.szP, -2.85 * kMrad, kTolPaperSzP);
  EXPECT_NEAR(s.sxP, -14.74 * kMrad, kTolPaperSxP);
  EXPECT_THROW((void)pkmSquarenessFromSlopes(std::nan(""), 0.0, 0.0), InvalidArgument);
}

/// Mean reading per target over runs and directions, as seed 000 averages its runs.
BeamRun meanRun(const simulation::MeasurementResult& m, int beam_sign) {
  std::map<double, std::pair<double, int>> sums;
  for (const simulation::LineRun& run : m.runs) {
    for (const simulation::LineReading& r : run.readings) {
      sums[r.target].first += r.reading;
      ++sums[r.target].second;
    }
  }
  BeamRun out{{}, {}, beam_sign};
  for (const auto& [target, sum] : sums) {
    out.positions.push_back(target);
    out.deviations.push_back(sum.first / sum.second);
  }
  return out;
}

/// Δγ and Δα of seed 000 §3.1 from a simulated campaign (straightness of Y2 and of the PKM's y).
struct Slopes {
  double dgamma = 0.0, dalpha = 0.0, parallelism_v = 0.0, max_deviation_v = 0.0;
};

Slopes simulatedSlopes(bool with_noise) {
  io::Scenario scenario = io::loadScenario("seed000-parallelism");
  if (!with_noise) {
    for (auto& m : scenario.campaign.measurements) m.noise = simulation::NoiseModel{};
  }
  const auto results = simulation::runCampaign(scenario.campaign, scenario.seed);
  std::map<std::string, const simulation::MeasurementResult*> by_name;
  for (const auto& m : results) by_name[m.setup->name] = &m;
  // +y2 moves the tool along -y of the work, +yP along +y: beam signs -1 and +1.
  const auto evaluate = [&](const char* ref, const char* axis) {
    return evaluateParallelism(meanRun(*by_name.at(ref), -1), meanRun(*by_name.at(axis), 1));
  };
  const ParallelismResult h = evaluate("straightness-y2-h", "straightness-py-h");
  const ParallelismResult v = evaluate("straightness-y2-v", "straightness-py-v");
  return {h.slope_difference, v.slope_difference, v.parallelism, v.max_deviation};
}

TEST(Parallelism, RecoversSimulatedSeed000Squareness) {
  const Slopes noisy = simulatedSlopes(true);
  const Slopes exact = simulatedSlopes(false);
  EXPECT_NEAR(noisy.dgamma, exact.dgamma, kTolSlopeNoise);
  EXPECT_NEAR(noisy.dalpha, exact.dalpha, kTolSlopeNoise);
  const double szX2 = -0.034 * kMrad;  // from the face diagonal (face_diagonal_test)
  const PkmSquareness s = pkmSquarenessFromSlopes(noisy.dgamma, noisy.dalpha, szX2);
  EXPECT_NEAR(s.szP, -2.85 * kMrad, kTolFirstOrder);
  EXPECT_NEAR(s.sxP, -14.74 * kMrad, kTolFirstOrder);
  // Parallelism over the 300 mm travel of the PKM's y: Δα · 300 (seed 000 Table 3 style).
  EXPECT_NEAR(noisy.parallelism_v, noisy.dalpha * 300.0, test::kTolExact);
  EXPECT_NEAR(noisy.max_deviation_v, noisy.parallelism_v, 0.01 * std::abs(noisy.parallelism_v));
  std::printf(
      "simulated seed 000: dgamma %.5f mrad, dalpha %.5f mrad (noise-free %.5f, %.5f); "
      "szP %.5f, sxP %.5f mrad\n",
      noisy.dgamma / kMrad,
      noisy.dalpha / kMrad,
      exact.dgamma / kMrad,
      exact.dalpha / kMrad,
      s.szP / kMrad,
      s.sxP / kMrad);
}

/// Third-order remainder of the second-order eq. 11 at seed 000's mrad angles: (1e-2)^3.
constexpr double kTolSecondOrder = 2e-6;

TEST(Parallelism, SecondOrderEq11InvertsTheExactRotation) {
  // The PKM's y direction in F for seed 000's squareness, exactly: Rz(-szX2)·exp([ω_P]×)·ŷ.
  const double szX2 = -0.034 * kMrad, sxP = -14.74 * kMrad, syP = 4.35 * kMrad, szP = -2.85 * kMrad;
  const Eigen::Vector3d w(sxP, -syP, szP);
  const Eigen::Matrix3d RP = Eigen::AngleAxisd(w.norm(), w.normalized()).toRotationMatrix();
  const Eigen::Vector3d y =
      Eigen::AngleAxisd(-szX2, Eigen::Vector3d::UnitZ()) * (RP * Eigen::Vector3d::UnitY());
  const double dgamma = y.x() / y.y(), dalpha = y.z() / y.y();
  const PkmSquareness first = pkmSquarenessFromSlopes(dgamma, dalpha, szX2);
  const PkmSquareness second = pkmSquarenessFromSlopes(dgamma, dalpha, szX2, syP);
  EXPECT_GT(std::abs(first.szP - szP), 20e-6);  // the first-order bias the refinement removes
  EXPECT_NEAR(second.szP, szP, kTolSecondOrder);
  EXPECT_NEAR(second.sxP, sxP, kTolSecondOrder);
  EXPECT_THROW((void)pkmSquarenessFromSlopes(dgamma, dalpha, szX2, std::nan("")), InvalidArgument);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::metrology
