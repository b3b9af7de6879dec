// calibration::detail::solveLeastSquares / holdFixedParameters: the calibrations' one Ceres solve
// reaches the closed-form least-squares answer, reports its costs and holds fixed parameters.
#include "calibration/detail/least_squares.hpp"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace pkm::calibration::detail {
namespace PKM_TEST_NS {

constexpr double kTol = 1e-9;

// r_i = a + b·x_i + c·x_i² − y_i: a linear least-squares problem with a closed-form answer.
struct Quadratic {
  double x, y;
  template <class T>
  bool operator()(const T* p, T* r) const {
    r[0] = p[0] + p[1] * x + p[2] * x * x - y;
    return true;
  }
};

void addData(ceres::Problem& problem, double* p) {
  // y = 1 + 2x − 0.5x² exactly, sampled at x = −4 … 4.
  for (int i = 0; i < 9; ++i) {
    const double x = i - 4.0;
    const double y = 1.0 + 2.0 * x - 0.5 * x * x;
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<Quadratic, 1, 3>(new Quadratic{x, y}), nullptr, p);
  }
}

TEST(LeastSquaresTest, ReachesTheExactFitAndReportsCosts) {
  std::array<double, 3> p{0.0, 0.0, 0.0};
  ceres::Problem problem;
  addData(problem, p.data());
  const LeastSquaresOutcome out = solveLeastSquares(problem, {});
  EXPECT_TRUE(out.converged) << out.termination;
  EXPECT_NEAR(p[0], 1.0, kTol);
  EXPECT_NEAR(p[1], 2.0, kTol);
  EXPECT_NEAR(p[2], -0.5, kTol);
  EXPECT_GT(out.initial_cost, 1.0);
  EXPECT_LT(out.final_cost, 1e-18);
  EXPECT_GE(out.iterations, 1);
  EXPECT_GE(out.seconds, 0.0);
}

TEST(LeastSquaresTest, HoldsFixedParametersAtTheirValues) {
  std::array<double, 3> p{0.0, 0.0, -0.5};
  ceres::Problem problem;
  addData(problem, p.data());
  holdFixedParameters(problem, p.data(), 3, std::vector<bool>{true, true, false});
  const LeastSquaresOutcome out = solveLeastSquares(problem, {});
  EXPECT_TRUE(out.converged) << out.termination;
  EXPECT_EQ(p[2], -0.5);
  EXPECT_NEAR(p[0], 1.0, kTol);
  EXPECT_NEAR(p[1], 2.0, kTol);
}

TEST(LeastSquaresTest, StopsAtTheIterationLimit) {
  std::array<double, 3> p{0.0, 0.0, 0.0};
  ceres::Problem problem;
  addData(problem, p.data());
  LeastSquaresSettings s;
  s.max_iterations = 1;
  s.function_tolerance = s.gradient_tolerance = s.parameter_tolerance = 0.0;
  const LeastSquaresOutcome out = solveLeastSquares(problem, s);
  EXPECT_LE(out.iterations, 1);
}

TEST(LeastSquaresTest, CopiesIntoAResultOfTheSameFieldNames) {
  struct Result {
    bool converged = false;
    std::string termination;
    int iterations = 0;
    double initial_cost = 0.0, final_cost = 0.0, seconds = 0.0;
  } r;
  const LeastSquaresOutcome o{true, "done", 3, 4.0, 1.0, 0.5};
  o.copyTo(r);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.termination, "done");
  EXPECT_EQ(r.iterations, 3);
  EXPECT_EQ(r.initial_cost, 4.0);
  EXPECT_EQ(r.final_cost, 1.0);
  EXPECT_EQ(r.seconds, 0.5);
}

TEST(LeastSquaresTest, FixedIndicesListsTheHeldEntries) {
  EXPECT_EQ(fixedIndices(4, std::vector<bool>{true, false, true, false}), (std::vector<int>{1, 3}));
  EXPECT_TRUE(fixedIndices(2, std::vector<bool>{true, true}).empty());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration::detail

namespace pkm::calibration::detail {
namespace PKM_TEST_NS {

// r_i = |p_i − c| − R: a sphere through tracker points (a nonlinear fit with a residual floor).
struct SphereDistance {
  double x, y, z;
  template <class T>
  bool operator()(const T* c, T* r) const {
    const T dx = T(x) - c[0], dy = T(y) - c[1], dz = T(z) - c[2];
    r[0] = ceres::sqrt(dx * dx + dy * dy + dz * dz) - c[3];
    return true;
  }
};

TEST(LeastSquaresTest, ConvergesInAFewIterationsOnNoisyData) {
  // 2000 SMR points on a 75 mm sphere 1.5 m from the tracker, 10 µm noise: at the minimum a step
  // changes the cost only by the rounding of residuals computed from 1500 mm coordinates, far
  // above Ceres' old function tolerance (1e-14); some stopping rule must still end it early.
  constexpr int kMaxIterations = 8;        ///< LM iterations (rejected steps included)
  constexpr double kNoise = 0.010;         ///< mm, tracker noise per axis
  constexpr double kTolStationary = 1e-9;  ///< mm: default vs strict stopping rules
  const std::array<double, 4> truth{1500.0, -420.0, 310.0, 75.0};
  std::mt19937 rng(20261122u);
  std::normal_distribution<double> n(0.0, 1.0);
  std::vector<std::array<double, 3>> points;
  for (int i = 0; i < 2000; ++i) {
    std::array<double, 3> u{n(rng), n(rng), std::abs(n(rng))};  // a hemisphere, as measured
    const double norm = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    std::array<double, 3> p{};
    for (int k = 0; k < 3; ++k) p[k] = truth[k] + truth[3] * u[k] / norm + kNoise * n(rng);
    points.push_back(p);
  }
  const auto solve = [&](const LeastSquaresSettings& s, std::array<double, 4>& c) {
    c = {1495.0, -415.0, 300.0, 70.0};
    ceres::Problem problem;
    for (const auto& p : points)
      problem.AddResidualBlock(new ceres::AutoDiffCostFunction<SphereDistance, 1, 4>(
                                   new SphereDistance{p[0], p[1], p[2]}),
                               nullptr,
                               c.data());
    return solveLeastSquares(problem, s);
  };
  std::array<double, 4> c{}, strict_c{};
  const LeastSquaresOutcome out = solve({}, c);
  EXPECT_TRUE(out.converged) << out.termination;
  EXPECT_LE(out.iterations, kMaxIterations) << out.termination;
  RecordProperty("iterations", out.iterations);
  LeastSquaresSettings strict;
  strict.max_iterations = 200;
  strict.function_tolerance = strict.gradient_tolerance = strict.parameter_tolerance = 1e-16;
  const LeastSquaresOutcome tight = solve(strict, strict_c);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(c[k], strict_c[k], kTolStationary) << k;
    EXPECT_NEAR(c[k], truth[k], 5.0 * kNoise) << k;  // σ of the centre: ~kNoise·√(4/N)·few
  }
  EXPECT_NEAR(out.final_cost, tight.final_cost, 1e-9 * tight.final_cost);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::calibration::detail
