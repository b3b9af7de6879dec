// HybridVirtualMachine: the hybrid error chain behind the VirtualMachine interface.
#include "pkm/simulation/hybrid_virtual_machine.hpp"

#include <gtest/gtest.h>

#include <array>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace {

namespace kin = pkm::kinematics;
using pkm::simulation::HybridVirtualMachine;

TEST(HybridVirtualMachine, MatchesTheHybridChain) {
  kin::GeometricErrors errors;
  errors.squareness = {-0.034e-3, -14.74e-3, 4.35e-3, -2.85e-3};
  const kin::HybridMachineModel model = pkm::test::mxt700sLikeModel();
  HybridVirtualMachine m(model, errors);
  EXPECT_EQ(m.axisNames().size(), 5U);
  Eigen::VectorXd c(5);
  c << 400, 100, 10, -50, 30;
  kin::HybridCommand hc;
  hc.x2 = 400;
  hc.y2 = 100;
  hc.pkm = {10, -50, 30};
  EXPECT_TRUE(m.moveTo(c).matrix() == kin::hybridActualPose(model, errors, hc).matrix());
  EXPECT_TRUE(m.nominalPose(c).matrix() == kin::hybridNominalPose(model, hc).matrix());
  EXPECT_THROW((void)m.moveTo(Eigen::VectorXd::Zero(3)), pkm::InvalidArgument);
}

TEST(HybridVirtualMachine, NoErrorsGivesTheNominalPose) {
  HybridVirtualMachine m(pkm::test::mxt700sLikeModel(), {});
  Eigen::VectorXd c(5);
  c << 875, 350, -20, 40, 210;
  EXPECT_NEAR((m.moveTo(c).matrix() - m.nominalPose(c).matrix()).norm(), 0.0, pkm::test::kTolExact);
}

TEST(HybridVirtualMachine, RefusesAMachineInInch) {
  kin::HybridMachineModel model = pkm::test::mxt700sLikeModel();
  model.unit = pkm::LengthUnit::kInch;
  EXPECT_THROW(HybridVirtualMachine(model, {}), pkm::InvalidArgument);
}

/// Tripod FK settles to FkOptions::tolerance (1e-9 mm); zero tripod errors change a pose by this.
constexpr double kTolTripodFk = 1e-8;

/// The shipped hybrid machine (its X2/Y2 model and its Exechon PKM) with PDGE and squareness.
struct TripodFixture {
  pkm::io::ExechonMachine machine = pkm::io::loadExechonMachine("mxt700s-like");
  kin::GeometricErrors errors;
  TripodFixture() { errors.squareness = {-0.034e-3, -14.74e-3, 4.35e-3, -2.85e-3}; }
  [[nodiscard]] HybridVirtualMachine make(const pkm::simulation::ExechonTripodErrors& t) const {
    return {*machine.hybrid, errors, pkm::simulation::HybridTripod(machine.model, t, machine.fk)};
  }
};

std::vector<Eigen::VectorXd> tripodCommands() {
  std::vector<Eigen::VectorXd> out;
  for (const auto& row : {std::array<double, 5>{0, 0, 0, 0, 0},
                          std::array<double, 5>{1200, 300, 250, -200, 280},
                          std::array<double, 5>{3900, 40, -280, 260, -90}}) {
    Eigen::VectorXd c(5);
    c << row[0], row[1], row[2], row[3], row[4];
    out.push_back(c);
  }
  return out;
}

TEST(HybridVirtualMachine, ZeroTripodErrorsReproduceThePreviousResults) {
  const TripodFixture f;
  HybridVirtualMachine without(*f.machine.hybrid, f.errors);
  HybridVirtualMachine with = f.make({});
  for (const Eigen::VectorXd& c : tripodCommands()) {
    kin::HybridCommand hc;
    hc.x2 = c[0];
    hc.y2 = c[1];
    hc.pkm = c.tail<3>();
    EXPECT_TRUE(without.moveTo(c).matrix() ==
                kin::hybridActualPose(*f.machine.hybrid, f.errors, hc).matrix());
    EXPECT_NEAR((with.moveTo(c).matrix() - without.moveTo(c).matrix()).norm(), 0.0, kTolTripodFk);
    EXPECT_TRUE(with.nominalPose(c).matrix() == without.nominalPose(c).matrix());
  }
}

TEST(HybridVirtualMachine, TripodErrorComposesAtThePkmStage) {
  // w_T_t = hybridActualPose · E_tripod(p): the tripod's error motion, in P's axes at the TCP.
  const TripodFixture f;
  pkm::simulation::ExechonTripodErrors t;
  t.length_offset = {0.02, -0.01, 0.015};
  t.pB = 0.03;
  HybridVirtualMachine with = f.make(t);
  HybridVirtualMachine without(*f.machine.hybrid, f.errors);
  ASSERT_TRUE(with.tripod().has_value());
  for (const Eigen::VectorXd& c : tripodCommands()) {
    const pkm::geometry::RigidTransform e = with.tripod()->errorMotion(c.tail<3>());
    const pkm::geometry::RigidTransform expected = without.moveTo(c) * e;
    EXPECT_NEAR((with.moveTo(c).matrix() - expected.matrix()).norm(), 0.0, pkm::test::kTolExact);
    EXPECT_GT(e.translation().norm(), 0.0);
  }
  // Without other errors the work frame has P's axes: the tool moves by E_tripod's translation.
  HybridVirtualMachine only(*f.machine.hybrid, {}, with.tripod());
  const Eigen::VectorXd c = tripodCommands()[1];
  EXPECT_NEAR(((only.moveTo(c).translation() - only.nominalPose(c).translation()) -
               with.tripod()->errorMotion(c.tail<3>()).translation())
                  .norm(),
              0.0,
              pkm::test::kTolExact);
}

}  // namespace
