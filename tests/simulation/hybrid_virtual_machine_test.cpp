// HybridVirtualMachine: the hybrid error chain behind the VirtualMachine interface.
#include "pkm/simulation/hybrid_virtual_machine.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

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

TEST(HybridVirtualMachine, PkmTiltTurnsThePkmsMotionsNotTheExtendingAxes) {
  // A thermal tilt ω of the PKM is a change of its squareness (sxP + ω_x, syP − ω_y, szP + ω_z):
  // the same pose as the chain with those squareness errors; a PKM y move of 300 mm then runs
  // 300·ω_x up and 300·ω_z sideways (first order) more than before, a Y2 move not at all.
  kin::GeometricErrors errors;
  errors.squareness = {-0.034e-3, -14.74e-3, 4.35e-3, -2.85e-3};
  const kin::HybridMachineModel model = pkm::test::mxt700sLikeModel();
  HybridVirtualMachine m(model, errors);
  const Eigen::Vector3d omega(50e-6, 20e-6, 30e-6);
  m.setPkmTilt(omega);
  kin::GeometricErrors tilted = errors;
  tilted.squareness.sx_p += omega.x();
  tilted.squareness.sy_p -= omega.y();
  tilted.squareness.sz_p += omega.z();
  Eigen::VectorXd c(5);
  c << 400, 100, 10, -50, 30;
  kin::HybridCommand hc;
  hc.x2 = 400;
  hc.y2 = 100;
  hc.pkm = {10, -50, 30};
  EXPECT_TRUE(m.moveTo(c).matrix() == kin::hybridActualPose(model, tilted, hc).matrix());
  // Without other errors the tilt is the rotation exp([ω]×) of the PKM frame alone.
  HybridVirtualMachine square(model, {});
  const auto displacement = [&square](const Eigen::VectorXd& from, const Eigen::VectorXd& to) {
    return Eigen::Vector3d(square.moveTo(to).translation() - square.moveTo(from).translation());
  };
  Eigen::VectorXd a(5), py(5), y2(5);
  a << 400, 100, 0, -150, 30;
  py << 400, 100, 0, 150, 30;
  y2 << 400, 400, 0, -150, 30;
  square.setPkmTilt(omega);
  const Eigen::Vector3d with_py = displacement(a, py), with_y2 = displacement(a, y2);
  square.setPkmTilt(Eigen::Vector3d::Zero());
  const Eigen::Vector3d without_py = displacement(a, py), without_y2 = displacement(a, y2);
  constexpr double kTolSecondOrder = 2e-6;  // mm: 300 mm × |ω|² and the lever's ω × offset
  EXPECT_NEAR(with_py.z() - without_py.z(), 300.0 * omega.x(), kTolSecondOrder);
  EXPECT_NEAR(with_py.x() - without_py.x(), -300.0 * omega.z(), kTolSecondOrder);
  EXPECT_NEAR((with_y2 - without_y2).norm(), 0.0, pkm::test::kTolExact);
  EXPECT_THROW(m.setPkmTilt(Eigen::Vector3d(std::nan(""), 0, 0)), pkm::InvalidArgument);
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

TEST(HybridVirtualMachine, X2BedSagsUnderThePkmAndTheTableOverhangSags) {
  // X2: the PKM's weight on a 4000 mm span sagging 10 µm at mid-span (δ(a) = δ_mid·16a²b²/L⁴,
  // slope δ_mid·16ab(b − a)/L⁴); the X2 carriage turns by θ about ŷ (nose down along +x), so the
  // tool 200 mm below P's origin moves by θ·ŷ × r − δ·ẑ. Y2: the table 150 + y2 mm out of its
  // saddle sags 5 µm at 600 mm; the work sags, so the tool seen from it rises by δ and turns by
  // +θ about x̂ (first order).
  using pkm::simulation::AxisSag;
  const kin::HybridMachineModel model = pkm::test::mxt700sLikeModel();
  HybridVirtualMachine m(model, {});
  const AxisSag x2{AxisSag::Kind::kSpan, 10e-3, 4000.0, 0.0, 1.0};
  const AxisSag y2{AxisSag::Kind::kCantilever, 5e-3, 600.0, 150.0, 1.0};
  constexpr double kTolFirstOrder = 2e-7;  // mm: θ·δ and θ²·|r|/2 stay below 1e-7 mm here
  for (const double x : {2000.0, 1000.0}) {
    m.setSag(x2, {});
    Eigen::VectorXd c(5);
    c << x, 0, 0, 0, -200;
    const double a = x, b = 4000.0 - x, L4 = std::pow(4000.0, 4);
    const double delta = 10e-3 * 16 * a * a * b * b / L4;
    const double theta = 10e-3 * 16 * a * b * (b - a) / L4;
    const Eigen::Vector3d r =
        m.nominalPose(c).translation() - (x * Eigen::Vector3d::UnitX() - model.Y2_p_work);
    const Eigen::Vector3d expected =
        theta * Eigen::Vector3d::UnitY().cross(r) - delta * Eigen::Vector3d::UnitZ();
    const Eigen::Vector3d moved = m.moveTo(c).translation() - m.nominalPose(c).translation();
    EXPECT_LT((moved - expected).norm(), kTolFirstOrder) << x;
  }
  m.setSag({}, y2);
  Eigen::VectorXd c(5);
  c << 300, 450, 20, -30, 0;
  const double delta = 5e-3, theta = 1.5 * delta / 600.0;  // L = 150 + 450 mm
  const Eigen::Vector3d r = m.nominalPose(c).translation() + model.Y2_p_work;
  const Eigen::Vector3d expected =
      theta * Eigen::Vector3d::UnitX().cross(r) + delta * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d moved = m.moveTo(c).translation() - m.nominalPose(c).translation();
  EXPECT_LT((moved - expected).norm(), kTolFirstOrder);
  EXPECT_THROW(m.setSag({AxisSag::Kind::kSpan, 1.0, 0.0, 0.0, 1.0}, {}), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
