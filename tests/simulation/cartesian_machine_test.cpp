// CartesianMachine: nominal readings without errors, each ISO 230-1 error with its exact or
// first-order effect on the tool position, squareness as included angles, axis stacking.
#include "pkm/simulation/cartesian_machine.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pkm/core/error.hpp"
#include "support/tolerances.hpp"

namespace {

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

}  // namespace
