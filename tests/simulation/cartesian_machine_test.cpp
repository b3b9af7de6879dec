// CartesianMachine: nominal readings without errors, each ISO 230-1 error with its exact or
// first-order effect on the tool position, squareness as included angles, axis stacking.
#include "pkm/simulation/cartesian_machine.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/simulation/line_measurement.hpp"
#include "support/statistics.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

using pkm::geometry::ErrorMotion;
using pkm::geometry::ErrorTable1d;
using pkm::simulation::CartesianErrors;
using pkm::simulation::CartesianLayout;
using pkm::simulation::CartesianMachine;
using pkm::test::kTolExact;

constexpr double kAngle = 50e-6;   // rad, a typical squareness or pitch
constexpr double kLength = 400.0;  // mm, a typical travel
/// First-order models neglect angle² · length.
const double kTolFirstOrder = 10 * kAngle * kAngle * kLength;

Eigen::VectorXd cmd(double x, double y, double z) { return Eigen::Vector3d(x, y, z); }

ErrorTable1d constantTable(int component, double value) {
  ErrorMotion e = ErrorMotion::Zero();
  e[component] = value;
  return ErrorTable1d::fromErrorMotions({0.0}, {e});
}

double includedAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(a.normalized().dot(b.normalized()));
}

TEST(CartesianMachine, NoErrorsGivesTheNominalPoseExactly) {
  CartesianLayout layout;
  layout.tool_offset = {1.5, -2.0, -100.0};
  for (const char* order : {"XYZ", "ZXY", "YZX"}) {
    layout.order = order;
    CartesianMachine m(layout, {});
    const Eigen::VectorXd c = cmd(123.4, -56.7, 89.1);
    EXPECT_TRUE(m.moveTo(c).matrix() == m.nominalPose(c).matrix()) << order;
  }
  EXPECT_EQ((std::vector<std::string>{"x", "y", "z"}), CartesianMachine({}, {}).axisNames());
}

TEST(CartesianMachine, SquarenessIsTheIncludedAngleMinus90Exactly) {
  const double right = std::numbers::pi / 2;
  CartesianErrors e;
  e.squareness = {kAngle, -2 * kAngle, 3 * kAngle};
  CartesianMachine m({}, e);
  const Eigen::Vector3d o = m.moveTo(cmd(0, 0, 0)).translation();
  const Eigen::Vector3d dx = m.moveTo(cmd(kLength, 0, 0)).translation() - o;
  const Eigen::Vector3d dy = m.moveTo(cmd(0, kLength, 0)).translation() - o;
  const Eigen::Vector3d dz = m.moveTo(cmd(0, 0, kLength)).translation() - o;
  EXPECT_NEAR(includedAngle(dx, dy) - right, e.squareness.xy, kTolExact);
  EXPECT_NEAR(includedAngle(dx, dz) - right, e.squareness.xz, kTolExact);
  EXPECT_NEAR(includedAngle(dy, dz) - right, e.squareness.yz, kTolExact);
  // ISO 230-1: a positive EC0Y (= xy) tilts +Y towards −x.
  EXPECT_LT(dy.x(), 0.0);
}

TEST(CartesianMachine, ComponentErrorsOfEachAxisMoveTheTool) {
  // EXX, EYY, EZZ and the straightnesses EYX, EZX: translations of the axis frame.
  const double d = 0.004;
  for (int axis = 0; axis < 3; ++axis)
    for (int component = 0; component < 3; ++component) {
      CartesianErrors e;
      e.axes[static_cast<std::size_t>(axis)] = constantTable(component, d);
      CartesianMachine m({}, e);
      const Eigen::VectorXd c = cmd(100, 200, 50);
      const Eigen::Vector3d dp = m.moveTo(c).translation() - m.nominalPose(c).translation();
      EXPECT_NEAR(dp[component], d, kTolExact) << axis << component;
      EXPECT_NEAR(dp.norm(), d, kTolExact);
    }
}

TEST(CartesianMachine, TableValuesAreTakenAtTheCommandedPosition) {
  CartesianErrors e;
  Eigen::MatrixXd v = Eigen::MatrixXd::Zero(2, 6);
  v(1, 0) = 0.01;  // EXX: 10 µm over 500 mm = 20 ppm
  e.axes[0] = ErrorTable1d({0.0, 500.0}, v);
  CartesianMachine m({}, e);
  EXPECT_NEAR(m.moveTo(cmd(250, 0, 0)).translation().x(), 250.005, kTolExact);
}

TEST(CartesianMachine, AngularErrorsGiveAbbeOffsetsDownstream) {
  // EBX (pitch of X) rotates everything X carries: with order XYZ the tool at (y, z) + offset.
  CartesianErrors e;
  e.axes[0] = constantTable(pkm::geometry::kEy, kAngle);
  CartesianLayout layout;
  layout.tool_offset = {0, 0, -100};
  CartesianMachine m(layout, e);
  const Eigen::VectorXd c = cmd(100, 200, 50);
  const Eigen::Vector3d arm = Eigen::Vector3d(0, 200, 50) + layout.tool_offset;
  const Eigen::Vector3d expected = Eigen::Vector3d(0, kAngle, 0).cross(arm);
  const Eigen::Vector3d dp = m.moveTo(c).translation() - m.nominalPose(c).translation();
  EXPECT_NEAR((dp - expected).norm(), 0.0, kTolFirstOrder);
  // With X last in the stack its pitch only acts on the tool offset.
  layout.order = "ZYX";
  CartesianMachine last(layout, e);
  const Eigen::Vector3d dp_last = last.moveTo(c).translation() - last.nominalPose(c).translation();
  EXPECT_NEAR((dp_last - Eigen::Vector3d(0, kAngle, 0).cross(layout.tool_offset)).norm(),
              0.0,
              kTolFirstOrder);
}

TEST(CartesianMachine, InvalidInputThrows) {
  CartesianLayout bad;
  bad.order = "XXZ";
  EXPECT_THROW(CartesianMachine(bad, {}), pkm::InvalidArgument);
  CartesianErrors e;
  e.axes[1] = ErrorTable1d({0.0}, Eigen::MatrixXd::Zero(1, 5));
  EXPECT_THROW(CartesianMachine({}, e), pkm::InvalidArgument);
  CartesianMachine m({}, {});
  EXPECT_THROW((void)m.moveTo(Eigen::VectorXd::Zero(2)), pkm::InvalidArgument);
  EXPECT_THROW((void)m.nominalPose(cmd(NAN, 0, 0)), pkm::InvalidArgument);
}

constexpr double kBacklash = 0.006;       // mm, a worn ball screw's lost motion
constexpr double kRepeatability = 0.002;  // mm, positioning scatter per move

/// An ISO 230-2 linear positioning test of X (targets 0..400 mm, 5 mm overshoot), `runs` runs.
pkm::simulation::LineSetup positioningOfX(int targets, int runs) {
  pkm::simulation::LineSetup s;
  s.name = "linear-x";
  s.line.start = cmd(0, 100, 50);
  s.line.direction = cmd(1, 0, 0);
  s.cycle.first = 0.0;
  s.cycle.last = kLength;
  s.cycle.targets = targets;
  s.cycle.runs = runs;
  s.cycle.overshoot = 5.0;
  return s;
}

/// The deviations x_ij = P_ij − P_i (ISO 230-2) per (target index, direction), over the runs.
std::map<std::pair<int, int>, std::vector<double>> deviations(
    const std::vector<pkm::simulation::LineRun>& runs, double first, double spacing) {
  std::map<std::pair<int, int>, std::vector<double>> out;
  for (const auto& run : runs)
    for (const auto& r : run.readings)
      out[{static_cast<int>(std::lround((r.target - first) / spacing)), r.direction}].push_back(
          r.reading - r.target);
  return out;
}

TEST(CartesianMachine, ReversalValueEqualsTheInjectedBacklash) {
  using pkm::simulation::CartesianActuation;
  CartesianActuation a;
  a.backlash = {kBacklash, 2 * kBacklash, 3 * kBacklash};
  CartesianMachine m({}, {}, a);
  // Directly: approaching x = 100 from below and from above differs by the backlash; Y and Z,
  // which do not move, stay where they are.
  (void)m.moveTo(cmd(50, 0, 0));
  const Eigen::Vector3d up = m.moveTo(cmd(100, 0, 0)).translation();
  (void)m.moveTo(cmd(150, 0, 0));
  const Eigen::Vector3d down = m.moveTo(cmd(100, 0, 0)).translation();
  EXPECT_NEAR(down.x() - up.x(), kBacklash, kTolExact);
  EXPECT_EQ(down.y(), up.y());
  EXPECT_EQ(down.z(), up.z());
  // Through the ISO 230-2 cycle: B_i = x̄_i↑ − x̄_i↓ = −b at every target (ISO 230-2:2014 §2.13),
  // so the axis reversal value B = max |B_i| is the backlash.
  constexpr int kTargets = 9;
  pkm::simulation::RandomStream rng(pkm::test::kSeed);
  const auto runs = pkm::simulation::simulateLine(m, positioningOfX(kTargets, 5), rng);
  const auto dev = deviations(runs, 0.0, kLength / (kTargets - 1));
  for (int i = 0; i < kTargets; ++i) {
    const double b = pkm::test::sampleMean(dev.at({i, 1})) - pkm::test::sampleMean(dev.at({i, -1}));
    EXPECT_NEAR(b, -kBacklash, kTolExact) << i;
  }
}

TEST(CartesianMachine, RepeatabilitySpreadMatchesSigma) {
  using pkm::simulation::CartesianActuation;
  CartesianActuation a;
  a.repeatability_sigma = {kRepeatability, 0.0, 0.0};
  CartesianMachine m({}, {}, a);
  constexpr int kTargets = 21, kRuns = 10;
  pkm::simulation::RandomStream rng(pkm::test::kSeed);
  const auto runs = pkm::simulation::simulateLine(m, positioningOfX(kTargets, kRuns), rng);
  // The pooled ISO 230-2 estimator s_i (n − 1 per target and direction) over all targets.
  double ss = 0.0;
  std::size_t dof = 0;
  for (const auto& [key, x] : deviations(runs, 0.0, kLength / (kTargets - 1))) {
    const double mean = pkm::test::sampleMean(x);
    for (const double v : x) ss += (v - mean) * (v - mean);
    dof += x.size() - 1;
  }
  EXPECT_EQ(dof, static_cast<std::size_t>(2 * kTargets * (kRuns - 1)));
  EXPECT_NEAR(std::sqrt(ss / static_cast<double>(dof)) / kRepeatability,
              1.0,
              pkm::test::sigmaRatioTolerance(dof + 1));
  // reset() with the same seed repeats the draws exactly.
  m.reset(7);
  const Eigen::Vector3d first = m.moveTo(cmd(10, 0, 0)).translation();
  m.reset(7);
  EXPECT_EQ(m.moveTo(cmd(10, 0, 0)).translation(), first);
}

TEST(CartesianMachine, InvalidActuationThrows) {
  pkm::simulation::CartesianActuation a;
  a.backlash.x() = -1e-3;
  EXPECT_THROW(CartesianMachine({}, {}, a), pkm::InvalidArgument);
  a = {};
  a.repeatability_sigma.z() = NAN;
  EXPECT_THROW(CartesianMachine({}, {}, a), pkm::InvalidArgument);
}

TEST(CartesianMachine, RamSagGrowsWithTheCubeOfTheExtensionAndDroops) {
  // Y carries the head on a ram 300 mm out at y = 0 that sags 25 µm at 1000 mm (δ = W·L³/(3EI)):
  // at two extensions the tool drops δ(L) = 25 µm·(L/1000)³ and the head turns nose down by
  // θ = 1.5·δ/L about −x̂, which swings the tool 100 mm below the ram's carriage by θ·100 towards
  // −y.
  CartesianLayout layout;
  layout.tool_offset = {0, 0, -100};
  CartesianMachine machine(layout, {});
  std::array<pkm::simulation::AxisSag, 3> sag{};
  sag[1] = {pkm::simulation::AxisSag::Kind::kCantilever, 25e-3, 1000.0, 300.0, 1.0};
  machine.setSag(sag);
  const double tol_sag = 1e-7;  // mm: the rotation's second order θ²·100 mm/2 (θ ≤ 4e-5 rad)
  for (const double y : {200.0, 700.0}) {
    const double L = 300.0 + y;
    const double delta = 25e-3 * std::pow(L / 1000.0, 3);
    const double theta = 1.5 * delta / L;
    const auto pose = machine.moveTo(cmd(50, y, 0));
    const Eigen::Vector3d nominal(50, y, -100);
    EXPECT_NEAR(pose.translation().z() - nominal.z(), -delta, tol_sag) << y;
    EXPECT_NEAR(pose.translation().y() - nominal.y(), -100.0 * theta, tol_sag) << y;
    EXPECT_NEAR(pose.translation().x() - nominal.x(), 0.0, kTolExact * 1e3) << y;
    EXPECT_NEAR(Eigen::AngleAxisd(pose.linear()).angle(), theta, kTolExact) << y;
  }
  sag[0].sag_mm = -1.0;
  EXPECT_THROW(machine.setSag(sag), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
