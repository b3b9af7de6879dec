// CompensatedMachine and CompensationChain: commands pass through the compensation before the
// inner machine moves, the nominal pose stays the user's command's, reset reaches both, and a
// compensation that breaks the command is refused.
#include "pkm/simulation/compensated_machine.hpp"

#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "pkm/simulation/cartesian_machine.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace sim = pkm::simulation;
using pkm::test::kTolRoundTrip;

/// Adds a fixed offset and counts resets.
class Shift final : public sim::CommandCompensation {
 public:
  explicit Shift(Eigen::VectorXd d) : d_(std::move(d)) {}
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& c) override { return c + d_; }
  void reset() override { ++resets; }
  int resets = 0;

 private:
  Eigen::VectorXd d_;
};

/// Returns a command of the wrong size.
class Broken final : public sim::CommandCompensation {
 public:
  [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd&) override {
    return Eigen::VectorXd(2);
  }
};

Eigen::VectorXd xyz(double x, double y, double z) { return Eigen::Vector3d(x, y, z); }

TEST(CompensatedMachine, CompensationActsBeforeTheMachine) {
  auto inner =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  auto shift = std::make_shared<Shift>(xyz(0.5, -0.25, 1.0));
  sim::CompensatedMachine m(inner, shift);
  const Eigen::VectorXd c = xyz(100, 50, 20);
  EXPECT_NEAR(
      (m.moveTo(c).translation() - Eigen::Vector3d(100.5, 49.75, 21.0)).norm(), 0.0, kTolRoundTrip);
  EXPECT_NEAR(
      (m.nominalPose(c).translation() - Eigen::Vector3d(100, 50, 20)).norm(), 0.0, kTolRoundTrip);
  EXPECT_EQ(m.axisNames(), inner->axisNames());
  m.reset(7);
  EXPECT_EQ(shift->resets, 1);
}

TEST(CompensatedMachine, AnExactInverseRemovesASquarenessError) {
  // xy squareness 1 mrad: Y moves along (−sin xy, cos xy, 0); the inverse of the axis directions
  // sent as a linear map makes the tool reach the command exactly.
  sim::CartesianErrors e;
  e.squareness.xy = 1e-3;
  auto inner = std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, e);
  Eigen::Matrix3d D;
  for (int k = 0; k < 3; ++k) D.col(k) = inner->axisDirection(k);
  class Linear final : public sim::CommandCompensation {
   public:
    explicit Linear(const Eigen::Matrix3d& m) : m_(m) {}
    [[nodiscard]] Eigen::VectorXd apply(const Eigen::VectorXd& c) override { return m_ * c; }

   private:
    Eigen::Matrix3d m_;
  };
  auto chain = std::make_shared<sim::CompensationChain>();
  chain->add(std::make_shared<Linear>(D.inverse()));
  chain->add(nullptr);  // ignored
  EXPECT_EQ(chain->size(), 1U);
  sim::CompensatedMachine m(inner, chain);
  const Eigen::VectorXd c = xyz(0, 400, 0);
  EXPECT_NEAR((inner->moveTo(c).translation() - Eigen::Vector3d(0, 400, 0)).norm(), 0.4, 1e-3);
  EXPECT_NEAR((m.moveTo(c).translation() - Eigen::Vector3d(0, 400, 0)).norm(), 0.0, kTolRoundTrip);
}

TEST(CompensatedMachine, RefusesNullsAndBrokenCompensations) {
  auto inner =
      std::make_shared<sim::CartesianMachine>(sim::CartesianLayout{}, sim::CartesianErrors{});
  EXPECT_THROW(sim::CompensatedMachine(nullptr, std::make_shared<Broken>()), pkm::InvalidArgument);
  EXPECT_THROW(sim::CompensatedMachine(inner, nullptr), pkm::InvalidArgument);
  sim::CompensatedMachine m(inner, std::make_shared<Broken>());
  EXPECT_THROW((void)m.moveTo(xyz(1, 2, 3)), pkm::InvalidArgument);
  EXPECT_THROW((void)m.moveTo(Eigen::VectorXd(2)), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
