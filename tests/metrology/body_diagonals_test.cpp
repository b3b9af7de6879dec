// Body diagonals (ISO 230-6): the closed form against a synthetic check case and an independent
// least-squares fit, recovery of injected squareness and scale from simulated readings, ISO 230-2
// per diagonal, bad input.
#include "pkm/metrology/body_diagonals.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>
#include <vector>

#include "metrology/diagonal_simulation.hpp"
#include "pkm/core/error.hpp"
#include "pkm/simulation/random.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::metrology::BodyDiagonal;
using pkm::metrology::BodyDiagonalSample;
using pkm::metrology::kBodyDiagonals;
using pkm::test::kTolExact;

const Eigen::Vector3d kBox(400.0, 300.0, 200.0);  // the check case's box, mm
constexpr double kUrad = 1e-6;
constexpr double kPpm = 1e-6;
/// Squareness recovered from noise-free simulated readings: the model is first order, the
/// truncation is O(ε²·D) in ΔD (ε ≈ 5e-5), i.e. ~1e-9 rad in the angles.
constexpr double kTolFirstOrderAngle = 1e-8;

/// ΔD of each diagonal from the first-order model (docs/analysis.md, "--method body"; ISO
/// symbols).
std::array<double, 4> modelLengthErrors(
    const Eigen::Vector3d& size, const Eigen::Vector3d& k, double ec0y, double eb0z, double ea0z) {
  const double lx = size.x(), ly = size.y(), lz = size.z(), d = size.norm();
  const double kk = k.x() * lx * lx + k.y() * ly * ly + k.z() * lz * lz;
  return {(kk - ec0y * lx * ly + eb0z * lx * lz - ea0z * ly * lz) / d,
          (kk + ec0y * lx * ly - eb0z * lx * lz - ea0z * ly * lz) / d,
          (kk + ec0y * lx * ly + eb0z * lx * lz + ea0z * ly * lz) / d,
          (kk - ec0y * lx * ly - eb0z * lx * lz + ea0z * ly * lz) / d};
}

TEST(BodyDiagonals, ClosedFormReproducesTheNotesCheckCase) {
  const Eigen::Vector3d k(10 * kPpm, -5 * kPpm, 3 * kPpm);
  const double ec0y = 20 * kUrad, eb0z = -15 * kUrad, ea0z = 10 * kUrad;
  const auto s =
      pkm::metrology::solveBodyDiagonals(kBox, modelLengthErrors(kBox, k, ec0y, eb0z, ea0z));
  EXPECT_NEAR(s.squareness_xy, ec0y, kTolExact * kUrad);
  EXPECT_NEAR(s.squareness_xz, -eb0z, kTolExact * kUrad);
  EXPECT_NEAR(s.squareness_yz, ea0z, kTolExact * kUrad);
  const double kk = k.x() * 400 * 400 + k.y() * 300 * 300 + k.z() * 200 * 200;
  EXPECT_NEAR(s.K, kk, kTolExact);
  EXPECT_NEAR(s.scale, kk / kBox.squaredNorm(), kTolExact * kPpm);
}

TEST(BodyDiagonals, ClosedFormEqualsALeastSquaresFitOfTheLengthModel) {
  // Independent: build the 4×4 design matrix of D·ΔD = K − EC0Y·LxLy + EB0Z·LxLz − EA0Z·LyLz
  // (and sign patterns) and solve it with Householder QR.
  pkm::simulation::RandomStream rng(pkm::test::kSeed);
  const double lx = kBox.x(), ly = kBox.y(), lz = kBox.z(), d = kBox.norm();
  Eigen::Matrix4d a;
  a << 1, -lx * ly, lx * lz, -ly * lz,  //
      1, lx * ly, -lx * lz, -ly * lz,   //
      1, lx * ly, lx * lz, ly * lz,     //
      1, -lx * ly, -lx * lz, ly * lz;
  for (int trial = 0; trial < 20; ++trial) {
    std::array<double, 4> dd{};
    Eigen::Vector4d rhs;
    for (int i = 0; i < 4; ++i) {
      dd[static_cast<std::size_t>(i)] = rng.uniform(-0.02, 0.02);
      rhs[i] = d * dd[static_cast<std::size_t>(i)];
    }
    const Eigen::Vector4d x = a.householderQr().solve(rhs);
    const auto s = pkm::metrology::solveBodyDiagonals(kBox, dd);
    EXPECT_NEAR(s.K, x[0], kTolExact);
    EXPECT_NEAR(s.squareness_xy, x[1], kTolExact * kUrad);
    EXPECT_NEAR(s.squareness_xz, -x[2], kTolExact * kUrad);
    EXPECT_NEAR(s.squareness_yz, x[3], kTolExact * kUrad);
  }
}

std::vector<BodyDiagonalSample> simulateBody(pkm::simulation::VirtualMachine& m,
                                             const Eigen::Vector3d& size,
                                             int runs,
                                             pkm::simulation::NoiseModel noise = {}) {
  std::vector<BodyDiagonalSample> samples;
  for (BodyDiagonal diag : kBodyDiagonals) {
    const Eigen::Vector3d from = pkm::metrology::diagonalStart(diag, size);
    const Eigen::Vector3d to = from + pkm::metrology::diagonalTravel(diag, size);
    for (const auto& run : pkm::test::measureLine(m,
                                                  from,
                                                  to,
                                                  11,
                                                  runs,
                                                  pkm::simulation::LineProcedure::kContinuous,
                                                  noise,
                                                  7u + static_cast<unsigned>(diag)))
      for (const auto& r : run.readings)
        samples.push_back({diag, r.target, r.reading - r.target, run.run, r.direction});
  }
  return samples;
}

TEST(BodyDiagonals, RecoversInjectedSquarenessAndScaleFromTheVirtualMachine) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::test::InjectedErrors inj;
  inj.scale = Eigen::Vector3d::Constant(12 * kPpm);  // uniform: `scale` is then k itself
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  const auto samples = simulateBody(machine, size, 5);
  const auto r = pkm::metrology::evaluateBodyDiagonals(samples, size);
  EXPECT_NEAR(r.solution.squareness_xy, inj.squareness.xy, kTolFirstOrderAngle);
  EXPECT_NEAR(r.solution.squareness_xz, inj.squareness.xz, kTolFirstOrderAngle);
  EXPECT_NEAR(r.solution.squareness_yz, inj.squareness.yz, kTolFirstOrderAngle);
  EXPECT_NEAR(r.solution.scale, inj.scale.x(), kTolFirstOrderAngle);
  for (const auto& e : r.diagonals) {
    ASSERT_TRUE(e.iso.has_value());
    EXPECT_EQ(e.readings, 4 * 11 * 5 / 2);
    EXPECT_EQ(e.iso->targets.size(), 11u);
    // Noise-free, stateless machine: no reversal, no scatter; E is the span of ΔD along the line.
    EXPECT_NEAR(e.iso->B, 0.0, kTolExact);
    EXPECT_NEAR(e.iso->R, 0.0, kTolExact);
    EXPECT_NEAR(e.iso->E, std::abs(e.length_error), pkm::test::kTolRoundTrip);
  }
}

TEST(BodyDiagonals, NoisyReadingsRecoverSquarenessWithinTheInstrumentUncertainty) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::test::InjectedErrors inj;
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  pkm::simulation::NoiseModel xl80;  // XL-80 datasheet: 10 nm + 0.25 ppm (1 σ)
  xl80.sigma = 1e-5;
  xl80.sigma_ppm = 0.25;
  xl80.resolution = 1e-6;
  const auto r = pkm::metrology::evaluateBodyDiagonals(simulateBody(machine, size, 5, xl80), size);
  // σ(ΔD) ≤ 0.25 ppm · D (the ppm term dominates, fully correlated along one line); each angle is
  // D·(±ΔD…)/(4·Li·Lj), so σ(angle) ≤ D·2σ(ΔD)/(4·Li·Lj). Accept 4 σ.
  const double d = size.norm();
  const double sigma_dd = 0.25e-6 * d;
  const auto bound = [&](double li, double lj) { return 4.0 * d * 2.0 * sigma_dd / (4 * li * lj); };
  EXPECT_NEAR(r.solution.squareness_xy, inj.squareness.xy, bound(500, 400));
  EXPECT_NEAR(r.solution.squareness_xz, inj.squareness.xz, bound(500, 300));
  EXPECT_NEAR(r.solution.squareness_yz, inj.squareness.yz, bound(400, 300));
}

TEST(BodyDiagonals, BadInputIsRejected) {
  std::vector<BodyDiagonalSample> few = {{BodyDiagonal::kPPP, 0.0, 0.0, 1, 1},
                                         {BodyDiagonal::kPPP, 10.0, 0.0, 1, 1}};
  pkm::metrology::BodyDiagonalOptions no_iso;
  no_iso.iso230_2 = false;
  EXPECT_THROW((void)pkm::metrology::evaluateBodyDiagonals(few, kBox, no_iso),
               pkm::InvalidArgument);  // NPP, PNP, NNP missing
  EXPECT_THROW((void)pkm::metrology::solveBodyDiagonals({1, 0, 1}, {}), pkm::InvalidArgument);
  EXPECT_THROW((void)pkm::metrology::solveBodyDiagonals(kBox, {0, NAN, 0, 0}),
               pkm::InvalidArgument);
  std::vector<BodyDiagonalSample> outside = {{BodyDiagonal::kPPP, 0.0, 0.0, 1, 1},
                                             {BodyDiagonal::kPPP, 1e4, 0.0, 1, 1}};
  EXPECT_THROW((void)pkm::metrology::evaluateBodyDiagonals(outside, kBox, no_iso),
               pkm::InvalidArgument);
  EXPECT_EQ(pkm::metrology::parseBodyDiagonal("NPP"), BodyDiagonal::kNPP);
  EXPECT_FALSE(pkm::metrology::parseBodyDiagonal("PPN").has_value());
}

}  // namespace PKM_TEST_NS
