// 2-D XY error prediction (seed 001 §3): interpolation of the component functions, and the
// prediction from step-diagonal and shifted-diagonal extractions against direct simulated
// measurements (face diagonals PP/NP, X positioning at mid-Y, X straightness).
#include "pkm/metrology/plane_prediction.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "metrology/diagonal_simulation.hpp"
#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::metrology::BodyDiagonal;
using pkm::metrology::kBodyDiagonals;
using pkm::test::kTolExact;

constexpr double kUrad = 1e-6;
constexpr double kPpm = 1e-6;
/// Noise-free, additive virtual machine: first-order truncation O(ε²·L) ≈ 1e-9 mm.
constexpr double kTolFirstOrderMm = 1e-7;
/// The linear model neglects second-order terms ε²·D/2 ≈ 1e-6 mm (ε = 50 µrad, D = 640 mm).
constexpr double kTolSecondOrderMm = 2e-6;
const Eigen::Vector3d kSize(500.0, 400.0, 300.0);

TEST(PlanePrediction, ErrorFunctionInterpolatesAndExtrapolatesLinearly) {
  const pkm::metrology::ErrorFunction f{{0.0, 10.0, 30.0}, {0.0, 1.0, -1.0}};
  EXPECT_NEAR(f(5.0), 0.5, kTolExact);
  EXPECT_NEAR(f(20.0), 0.0, kTolExact);
  EXPECT_NEAR(f(40.0), -2.0, kTolExact);
  EXPECT_NEAR(f(-10.0), -1.0, kTolExact);
  EXPECT_EQ(pkm::metrology::ErrorFunction{}(3.0), 0.0);
}

/// Scale, squareness and nonlinear positioning/straightness of X and Y (nodes on the extraction
/// grids, so linear interpolation of the extracted functions is exact), no angular errors.
pkm::simulation::CartesianMachine planeMachine() {
  pkm::simulation::CartesianErrors e;
  std::vector<pkm::geometry::ErrorMotion> mx(6, pkm::geometry::ErrorMotion::Zero());
  const double ex[] = {0, 2e-3, 2.5e-3, 4e-3, 5e-3, 7e-3}, ey[] = {0, 1e-3, 2e-3, 1.5e-3, 1e-3, 0};
  for (std::size_t i = 0; i < 6; ++i) {
    mx[i][0] = ex[i];
    mx[i][1] = ey[i];
  }
  e.axes[0] = pkm::geometry::ErrorTable1d::fromErrorMotions({0, 100, 200, 300, 400, 500}, mx);
  std::vector<pkm::geometry::ErrorMotion> my(3, pkm::geometry::ErrorMotion::Zero());
  my[1][0] = 1.5e-3;
  my[1][1] = -1e-3;
  my[2][1] = -4e-3;
  e.axes[1] = pkm::geometry::ErrorTable1d::fromErrorMotions({0, 200, 400}, my);
  e.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  return pkm::simulation::CartesianMachine({}, e);
}

pkm::metrology::StepDiagonalResult stepExtraction(pkm::simulation::VirtualMachine& m) {
  std::vector<pkm::metrology::StepDiagonalPass> passes;
  for (BodyDiagonal diag : kBodyDiagonals) {
    const Eigen::Vector3d from = pkm::metrology::diagonalStart(diag, kSize);
    const auto runs = pkm::test::measureLine(m,
                                             from,
                                             from + pkm::metrology::diagonalTravel(diag, kSize),
                                             11,
                                             1,
                                             pkm::simulation::LineProcedure::kStepDiagonal);
    pkm::metrology::StepDiagonalPass pass;
    pass.diagonal = diag;
    for (const auto& r : runs[0].readings) {
      if (r.direction != 1) continue;
      if (r.sub_step == 1) pass.steps.emplace_back();
      pass.steps.back().deviation[static_cast<std::size_t>(r.sub_step - 1)] = r.reading - r.target;
      pass.steps.back().target = r.target;
    }
    passes.push_back(pass);
  }
  return pkm::metrology::extractStepDiagonal(passes, kSize);
}

/// Direct simulated measurement along an XY line at z = 150: mean deviation per target.
pkm::metrology::PlaneComparison compareLine(pkm::simulation::VirtualMachine& m,
                                            const pkm::metrology::PlaneErrorModel& model,
                                            const Eigen::Vector2d& a,
                                            const Eigen::Vector2d& b) {
  const auto runs = pkm::test::measureLine(m, {a.x(), a.y(), 150}, {b.x(), b.y(), 150}, 11, 1);
  std::vector<double> s, dev;
  for (const auto& r : runs[0].readings) {
    if (r.direction != 1) continue;
    s.push_back(r.target);
    dev.push_back(r.reading - r.target);
  }
  const Eigen::Vector2d u = (b - a).normalized();
  return pkm::metrology::comparePlanePrediction(model, a, u, u, s, dev, false);
}

TEST(PlanePrediction, StepDiagonalModelPredictsDirectMeasurementsInThePlane) {
  auto machine = planeMachine();
  const auto model = pkm::metrology::planeModel(stepExtraction(machine));
  const auto pp = compareLine(machine, model, {0, 0}, {500, 400});
  const auto np = compareLine(machine, model, {500, 0}, {0, 400});
  const auto lx = compareLine(machine, model, {0, 200}, {500, 200});
  const auto ly = compareLine(machine, model, {250, 0}, {250, 400});
  for (const auto* c : {&pp, &np, &lx, &ly}) {
    EXPECT_LT(c->max_abs, kTolFirstOrderMm);
    // The measurement itself is not trivially zero: the prediction explains µm-size errors.
    double span = 0.0;
    for (double v : c->measured) span = std::max(span, std::abs(v));
    EXPECT_GT(span, 1e3 * kTolFirstOrderMm);
  }
}

TEST(PlanePrediction, ShiftedModelPredictsFaceDiagonalsOfALinearMachine) {
  pkm::test::InjectedErrors inj;
  inj.scale = {10 * kPpm, -5 * kPpm, 3 * kPpm};
  inj.squareness = {50 * kUrad, -30 * kUrad, 20 * kUrad};
  auto machine = pkm::test::diagonalTestMachine(inj);
  pkm::metrology::ShiftedDiagonalResult shifted;
  shifted.scale = {inj.scale.x(), inj.scale.y(), inj.scale.z()};
  shifted.squareness = {inj.squareness.xy, inj.squareness.xz, inj.squareness.yz};
  const auto model = pkm::metrology::planeModel(shifted);
  EXPECT_LT(compareLine(machine, model, {0, 0}, {500, 400}).max_abs, kTolSecondOrderMm);
  EXPECT_LT(compareLine(machine, model, {500, 0}, {0, 400}).max_abs, kTolSecondOrderMm);
}

TEST(PlanePrediction, BadInputIsRejected) {
  const pkm::metrology::PlaneErrorModel model;
  const std::vector<double> s = {0.0, 1.0}, one = {0.0}, bad = {0.0, NAN};
  const Eigen::Vector2d u(1, 0);
  EXPECT_THROW((void)pkm::metrology::comparePlanePrediction(model, {0, 0}, u, u, s, one, false),
               pkm::InvalidArgument);
  EXPECT_THROW((void)pkm::metrology::comparePlanePrediction(model, {0, 0}, u, u, s, bad, false),
               pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
