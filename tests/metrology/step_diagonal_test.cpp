// Wang's step-diagonal extraction: a synthetic numerical verification (additive model,
// box 400 × 300 × 200 mm, N = 10: exact recovery, Q = 0), recovery of injected scale and
// squareness from the virtual machine's step-diagonal readings, the consistency residual under a
// non-additive (Abbe) error, bad input.
#include "pkm/metrology/step_diagonal.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "metrology/diagonal_simulation.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::metrology::BodyDiagonal;
using pkm::metrology::kBodyDiagonals;
using pkm::metrology::StepDiagonalPass;

constexpr double kUrad = 1e-6;
constexpr double kPpm = 1e-6;
/// Exact in exact arithmetic; sums of ~30 terms of a few µm in double precision.
constexpr double kTolExtraction = 1e-15;
/// Noise-free virtual machine: first-order model, truncation O(ε²·L) ≈ 1e-9 mm in the functions
/// and ε²/2 = 1.25e-9 in slopes and angles (e.g. the Y travel y·cos(squareness_xy)), ε = 50 µrad.
constexpr double kTolFirstOrderMm = 1e-8;
constexpr double kTolFirstOrderAngle = 5e-9;

const Eigen::Vector3d kBox(400.0, 300.0, 200.0);  // the synthetic check case
constexpr int kSteps = 10;                        // steps per diagonal, N
const double kTwoPi = 2.0 * std::numbers::pi;

/// The additive error model (first-order rigid body, no angular terms) with nonlinear functions of
/// a few µm: E[axis](q) is the error vector (along X, Y, Z) due to that axis at position q.
/// Straightness functions are symmetric about mid-travel (zero least-squares slope on a symmetric
/// grid), so the slopes the extraction sees are the squareness terms alone.
struct AdditiveModel {
  double ec0y = 20 * kUrad, eb0z = -15 * kUrad, ea0z = 10 * kUrad;
  Eigen::Vector3d e(int axis, double q) const {
    const double l = kBox[axis];
    const double bump = 4e-8 * q * (l - q);               // ≤ 1.6 µm
    const double wave = 1e-3 * std::cos(kTwoPi * q / l);  // ±1 µm, symmetric
    const double pos = 8 * kPpm * q + 1.5e-3 * std::sin(kTwoPi * q / l);
    Eigen::Vector3d v;
    if (axis == 0) v = {pos, bump, wave};
    if (axis == 1) v = {wave - ec0y * q, pos, -bump};
    if (axis == 2) v = {bump + eb0z * q, wave - ea0z * q, pos};
    return v;
  }
  Eigen::Vector3d total(const Eigen::Vector3d& p) const {
    return e(0, p.x()) + e(1, p.y()) + e(2, p.z());
  }
};

/// One + pass along `diag` read through `model` by a flat-mirror laser along the nominal diagonal.
StepDiagonalPass modelPass(const AdditiveModel& model, BodyDiagonal diag) {
  const Eigen::Vector3d start = pkm::metrology::diagonalStart(diag, kBox);
  const Eigen::Vector3d travel = pkm::metrology::diagonalTravel(diag, kBox);
  const Eigen::Vector3d u = travel.normalized();
  const double d = kBox.norm();
  StepDiagonalPass pass;
  pass.diagonal = diag;
  for (int i = 0; i <= kSteps; ++i) {
    const double s = d * i / kSteps;
    Eigen::Vector3d at = start + travel * (std::max(0, i - 1) / static_cast<double>(kSteps));
    pkm::metrology::StepDiagonalStep step;
    step.target = s;
    for (int q = 0; q < 3; ++q) {
      at[q] = start[q] + travel[q] * i / static_cast<double>(kSteps);
      step.deviation[static_cast<std::size_t>(q)] = u.dot(model.total(at) - model.total(start));
    }
    pass.steps.push_back(step);
  }
  return pass;
}

TEST(StepDiagonal, ReproducesTheNotesNumericalVerification) {
  const AdditiveModel model;
  std::vector<StepDiagonalPass> passes;
  for (BodyDiagonal diag : kBodyDiagonals) passes.push_back(modelPass(model, diag));
  const auto r = pkm::metrology::extractStepDiagonal(passes, kBox);
  for (int q = 0; q < 3; ++q) {
    const auto& axis = r.axes[static_cast<std::size_t>(q)];
    ASSERT_EQ(axis.positions.size(), static_cast<std::size_t>(kSteps + 1));
    for (std::size_t j = 0; j < axis.positions.size(); ++j) {
      EXPECT_NEAR(axis.positions[j], kBox[q] * static_cast<double>(j) / kSteps, kTolExtraction);
      const Eigen::Vector3d truth = model.e(q, axis.positions[j]) - model.e(q, 0.0);
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(axis.components[static_cast<std::size_t>(c)][j], truth[c], kTolExtraction)
            << "axis " << q << " component " << c << " at " << j;
      EXPECT_NEAR(axis.residual[j], 0.0, kTolExtraction);
    }
  }
  EXPECT_NEAR(r.squareness_xy, model.ec0y, kTolExtraction);
  EXPECT_NEAR(r.squareness_xz, -model.eb0z, kTolExtraction);
  EXPECT_NEAR(r.squareness_yz, model.ea0z, kTolExtraction);
  EXPECT_LT(r.residual_max, kTolExtraction);
}

/// Converts simulated step-diagonal runs into passes (sub-steps 1, 2, 3 form one step).
std::vector<StepDiagonalPass> toPasses(const std::vector<pkm::simulation::LineRun>& runs,
                                       BodyDiagonal diag) {
  std::vector<StepDiagonalPass> passes;
  for (const auto& run : runs) {
    for (int dir : {1, -1}) {
      StepDiagonalPass pass;
      pass.diagonal = diag;
      for (const auto& r : run.readings) {
        if (r.direction != dir) continue;
        if (r.sub_step == 1) pass.steps.emplace_back();
        auto& step = pass.steps.back();
        step.deviation[static_cast<std::size_t>(r.sub_step - 1)] = r.reading - r.target;
        if (r.sub_step == 3) step.target = r.target;
      }
      passes.push_back(pass);
    }
  }
  return passes;
}

std::vector<StepDiagonalPass> simulateStep(pkm::simulation::VirtualMachine& m,
                                           const Eigen::Vector3d& size,
                                           pkm::simulation::NoiseModel noise = {}) {
  std::vector<StepDiagonalPass> passes;
  for (BodyDiagonal diag : kBodyDiagonals) {
    const Eigen::Vector3d from = pkm::metrology::diagonalStart(diag, size);
    const auto runs = pkm::test::measureLine(m,
                                             from,
                                             from + pkm::metrology::diagonalTravel(diag, size),
                                             kSteps + 1,
                                             2,
                                             pkm::simulation::LineProcedure::kStepDiagonal,
                                             noise,
                                             11u + static_cast<unsigned>(diag));
    for (auto& p : toPasses(runs, diag)) passes.push_back(std::move(p));
  }
  return passes;
}

TEST(StepDiagonal, RecoversInjectedScaleAndSquarenessFromTheVirtualMachine) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::test::InjectedErrors inj;
  inj.scale = {10 * kPpm, -5 * kPpm, 3 * kPpm};
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  const auto r = pkm::metrology::extractStepDiagonal(simulateStep(machine, size), size);
  EXPECT_NEAR(r.squareness_xy, inj.squareness.xy, kTolFirstOrderAngle);
  EXPECT_NEAR(r.squareness_xz, inj.squareness.xz, kTolFirstOrderAngle);
  EXPECT_NEAR(r.squareness_yz, inj.squareness.yz, kTolFirstOrderAngle);
  for (std::size_t q = 0; q < 3; ++q) {
    EXPECT_NEAR(r.axes[q].slopes[q], inj.scale[static_cast<Eigen::Index>(q)], kTolFirstOrderAngle);
    EXPECT_NEAR(r.axes[q].straightness[q], 0.0, kTolFirstOrderMm);
  }
  EXPECT_LT(r.residual_max, kTolFirstOrderMm);
}

TEST(StepDiagonal, NoisyReadingsRecoverSquarenessWithinTheInstrumentUncertainty) {
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::test::InjectedErrors inj;
  inj.scale = {10 * kPpm, -5 * kPpm, 3 * kPpm};
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  pkm::simulation::NoiseModel xl80;  // XL-80 datasheet: 10 nm + 0.25 ppm (1 σ)
  xl80.sigma = 1e-5;
  xl80.sigma_ppm = 0.25;
  xl80.resolution = 1e-6;
  const auto r = pkm::metrology::extractStepDiagonal(simulateStep(machine, size, xl80), size);
  // Each reading has σ ≤ 0.18 µm; an increment √2 times that, a cumulative R after j steps √j
  // times (4 passes averaged: /2); a component divides a sum of four R by 4·c (c ≥ 0.37), so
  // σ ≈ 0.2 µm at the far end; the least-squares slope over L ≥ 300 mm of 11 points then has
  // σ ≈ 0.5 µrad, a squareness (two slopes) ≈ 0.7 µrad. Accept about 4 σ.
  constexpr double kBoundAngle = 3 * kUrad;
  EXPECT_NEAR(r.squareness_xy, inj.squareness.xy, kBoundAngle);
  EXPECT_NEAR(r.squareness_xz, inj.squareness.xz, kBoundAngle);
  EXPECT_NEAR(r.squareness_yz, inj.squareness.yz, kBoundAngle);
  for (std::size_t q = 0; q < 3; ++q)
    EXPECT_NEAR(r.axes[q].slopes[q], inj.scale[static_cast<Eigen::Index>(q)], kBoundAngle);
}

TEST(StepDiagonal, AbbeErrorsShowInTheConsistencyResidual) {
  // Chapman 2003: an angular error acting through an Abbe offset is outside the additive model. A
  // roll of X (EAX, 30 µrad over the travel) with the tool 100 mm below the Z carriage gives
  // ey = −EAX(x)·(z − 100), which depends on x and z together: Q ≠ 0 and squareness is biased.
  const Eigen::Vector3d size(500.0, 400.0, 300.0);
  pkm::simulation::CartesianErrors errors;
  pkm::geometry::ErrorMotion lo = pkm::geometry::ErrorMotion::Zero(), hi = lo;
  hi[pkm::geometry::kEx] = 30 * kUrad;
  errors.axes[0] = pkm::geometry::ErrorTable1d::fromErrorMotions({0.0, 500.0}, {lo, hi});
  pkm::simulation::CartesianLayout layout;
  layout.tool_offset = {0.0, 0.0, -100.0};
  pkm::simulation::CartesianMachine machine(layout, errors);
  const auto r = pkm::metrology::extractStepDiagonal(simulateStep(machine, size), size);
  // Expected size of Q: the roll changes ey by 30 µrad · Lz over the X travel, seen with
  // weight b = Ly/D and summed over the four diagonals with opposite z paths: ~µm.
  constexpr double kQExpectedAtLeast = 1e-3;  // mm
  EXPECT_GT(r.residual_max, kQExpectedAtLeast);
}

TEST(StepDiagonal, BadInputIsRejected) {
  const AdditiveModel model;
  std::vector<StepDiagonalPass> three;
  for (BodyDiagonal diag : {BodyDiagonal::kPPP, BodyDiagonal::kNPP, BodyDiagonal::kPNP})
    three.push_back(modelPass(model, diag));
  EXPECT_THROW((void)pkm::metrology::extractStepDiagonal(three, kBox), pkm::InvalidArgument);
  auto bad = three;
  bad.push_back(modelPass(model, BodyDiagonal::kNNP));
  bad.back().steps.resize(1);
  EXPECT_THROW((void)pkm::metrology::extractStepDiagonal(bad, kBox), pkm::InvalidArgument);
  bad.back() = modelPass(model, BodyDiagonal::kNNP);
  bad.back().steps[3].deviation[1] = NAN;
  EXPECT_THROW((void)pkm::metrology::extractStepDiagonal(bad, kBox), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
