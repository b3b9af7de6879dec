// calibration::detail::solveLeastSquares / holdFixedParameters: the calibrations' one Ceres solve
// reaches the closed-form least-squares answer, reports its costs and holds fixed parameters.
#include "calibration/detail/least_squares.hpp"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <array>
#include <vector>

namespace pkm::calibration::detail {
namespace {

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

}  // namespace
}  // namespace pkm::calibration::detail
