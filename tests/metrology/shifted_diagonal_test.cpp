// Shifted diagonals (seed 001): eqs (1)-(3) as printed against the law-of-cosines closed form,
// recovery of injected scale and squareness from the virtual machine (eqs 5-6), the scale bias of
// eq (6) as printed, bad input.
#include "pkm/metrology/shifted_diagonal.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "metrology/diagonal_simulation.hpp"
#include "pkm/core/error.hpp"
#include "pkm/simulation/random.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::metrology::BodyDiagonal;
using pkm::metrology::kBodyDiagonals;
using pkm::metrology::ShiftedDiagonalMeasurement;

constexpr double kUrad = 1e-6;
constexpr double kPpm = 1e-6;
/// acos of eq (2) near 1 loses digits (Δα ≈ Δ/r ≈ 0.02 rad): measured ≤ 2e-9 mm for r ≤ 900 mm.
constexpr double kTolTriangle = 1e-8;
/// The closed form cancels r² ≈ 1e6 mm² over 2Δ ≥ 20 mm: eps·r²/Δ ≈ 1e-11 mm.
constexpr double kTolClosedForm = 1e-10;
/// Noise-free virtual machine: the triangulation amplifies the O(ε²·D) second-order length
/// terms by D/Δ ≈ 14, giving ~3e-5 mm in ΔR and ~1e-7 in angles and scales.
constexpr double kTolFirstOrderAngle = 2e-7;
constexpr double kShift = 50.0;  // mm, the end point moves back along the travel

TEST(ShiftedDiagonal, PaperEquationsEqualTheLawOfCosines) {
  pkm::simulation::RandomStream rng(pkm::test::kSeed);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector3d oa(rng.uniform(100, 600), rng.uniform(100, 500), rng.uniform(100, 400));
    const int axis = trial % 3;
    const double shift = rng.uniform(10, 80) * (trial % 2 == 0 ? 1.0 : -1.0);
    Eigen::Vector3d ob = oa;
    ob[axis] += shift;
    const auto t = pkm::metrology::shiftTriangle(oa.norm(), ob.norm(), shift);
    EXPECT_NEAR(t.component, oa[axis], kTolTriangle);
    EXPECT_NEAR(
        pkm::metrology::shiftComponent(oa.norm(), ob.norm(), shift), oa[axis], kTolClosedForm);
    EXPECT_NEAR(oa.norm() * std::sin(t.alpha), oa[axis], kTolTriangle);
  }
}

std::vector<ShiftedDiagonalMeasurement> simulateShifted(pkm::simulation::VirtualMachine& m,
                                                        const Eigen::Vector3d& size,
                                                        pkm::simulation::NoiseModel noise = {}) {
  std::vector<ShiftedDiagonalMeasurement> out;
  for (BodyDiagonal diag : kBodyDiagonals) {
    const Eigen::Vector3d from = pkm::metrology::diagonalStart(diag, size);
    const Eigen::Vector3d travel = pkm::metrology::diagonalTravel(diag, size);
    const Eigen::Vector3d signs = pkm::metrology::travelSigns(diag);
    for (int axis = -1; axis < 3; ++axis) {
      Eigen::Vector3d to = from + travel;
      double shift = 0.0;
      if (axis >= 0) {
        shift = -kShift * signs[axis];  // shortens the travel: stays inside the box
        to[axis] += shift;
      }
      const auto runs =
          pkm::test::measureLine(m,
                                 from,
                                 to,
                                 5,
                                 3,
                                 pkm::simulation::LineProcedure::kContinuous,
                                 noise,
                                 static_cast<unsigned>(4 * static_cast<int>(diag) + axis + 2));
      for (const auto& run : runs)  // every reading at the last target (both directions)
        for (const auto& r : run.readings)
          if (r.target == runs[0].readings[4].target)
            out.push_back({diag, axis, shift, r.reading - r.target});
    }
  }
  return out;
}

TEST(ShiftedDiagonal, RecoversInjectedScaleAndSquarenessFromTheVirtualMachine) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::test::InjectedErrors inj;
  inj.scale = {10 * kPpm, -5 * kPpm, 3 * kPpm};
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  const auto r = pkm::metrology::evaluateShiftedDiagonals(simulateShifted(machine, size), size);
  const std::array<double, 3> sq = {inj.squareness.xy, inj.squareness.xz, inj.squareness.yz};
  for (std::size_t p = 0; p < 3; ++p) {
    EXPECT_NEAR(r.squareness[p], sq[p], kTolFirstOrderAngle) << p;
    EXPECT_NEAR(r.squareness_eq6_scaled[p], sq[p], kTolFirstOrderAngle) << p;
    EXPECT_NEAR(r.asymmetry[p], 0.0, kTolFirstOrderAngle) << p;
    EXPECT_NEAR(r.scale[p], inj.scale[static_cast<Eigen::Index>(p)], kTolFirstOrderAngle) << p;
  }
  // Eq (5) off-diagonal components: e_x(y) = −EC0Y·Ly, e_x(z) = EB0Z·Lz, e_y(z) = −EA0Z·Lz.
  EXPECT_NEAR(r.components[0][1], -inj.squareness.xy * 400, kTolFirstOrderAngle * 400);
  EXPECT_NEAR(r.components[0][2], -inj.squareness.xz * 300, kTolFirstOrderAngle * 300);
  EXPECT_NEAR(r.components[1][2], -inj.squareness.yz * 300, kTolFirstOrderAngle * 300);
  // Eq (6) as printed carries the scale bias K/(Li·Lj), K = Σ k_j·L_j² (first order).
  const double k = inj.scale.dot(size.cwiseProduct(size));
  EXPECT_NEAR(r.squareness_eq6[0] - sq[0], -k / (500 * 400), kTolFirstOrderAngle);
  EXPECT_NEAR(r.squareness_eq6[1] - sq[1], -k / (500 * 300), kTolFirstOrderAngle);
  EXPECT_NEAR(r.squareness_eq6[2] - sq[2], -k / (400 * 300), kTolFirstOrderAngle);
}

TEST(ShiftedDiagonal, NoisyReadingsRecoverSquarenessWithinTheInstrumentUncertainty) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::test::InjectedErrors inj;
  inj.scale = {10 * kPpm, -5 * kPpm, 3 * kPpm};
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  pkm::simulation::NoiseModel xl80;  // XL-80 datasheet: 10 nm + 0.25 ppm (1 σ)
  xl80.sigma = 1e-5;
  xl80.sigma_ppm = 0.25;
  xl80.resolution = 1e-6;
  const auto r =
      pkm::metrology::evaluateShiftedDiagonals(simulateShifted(machine, size, xl80), size);
  // The 0.25 ppm is one scale error per line (NoiseModel::drawScale: the laser's compensation
  // holds over a line), so a diagonal's length error is not averaged over its readings: σ ≈
  // 0.25 ppm · 640 mm ≈ 0.16 µm. The triangle amplifies it by √2·D/Δ ≈ 18 (ΔR ≈ 2.9 µm); the
  // squareness from the components divides differences of ΔR by L ≥ 300 mm: σ ≈ 3-4 µrad; k_j =
  // e_j(j)/(2L_j) has σ ≈ 1-2 ppm and the scale-corrected eq (6) inherits Σ L²·σ_k/(Li·Lj) ≈ 3-4
  // µrad. Accept about 3-4 σ. Measured with these seeds: 5.4/4.3/10.0 µrad for the squareness.
  constexpr double kBoundAngle = 12 * kUrad;
  constexpr double kBoundAngleEq6 = 15 * kUrad;
  constexpr double kBoundScale = 6 * kPpm;
  const std::array<double, 3> sq = {inj.squareness.xy, inj.squareness.xz, inj.squareness.yz};
  for (std::size_t p = 0; p < 3; ++p) {
    EXPECT_NEAR(r.squareness[p], sq[p], kBoundAngle) << p;
    EXPECT_NEAR(r.squareness_eq6_scaled[p], sq[p], kBoundAngleEq6) << p;
    EXPECT_NEAR(r.scale[p], inj.scale[static_cast<Eigen::Index>(p)], kBoundScale) << p;
  }
}

TEST(ShiftedDiagonal, BadInputIsRejected) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  EXPECT_THROW((void)pkm::metrology::shiftTriangle(100, 100, 0), pkm::InvalidArgument);
  EXPECT_THROW((void)pkm::metrology::shiftTriangle(100, 300, 10), pkm::InvalidArgument);
  std::vector<ShiftedDiagonalMeasurement> only = {{BodyDiagonal::kPPP, -1, 0.0, 0.0}};
  EXPECT_THROW((void)pkm::metrology::evaluateShiftedDiagonals(only, size), pkm::InvalidArgument);
  only.push_back({BodyDiagonal::kPPP, 0, 400.0, 0.0});  // more than half the X travel
  EXPECT_THROW((void)pkm::metrology::evaluateShiftedDiagonals(only, size), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
