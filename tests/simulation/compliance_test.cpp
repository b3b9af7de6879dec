// Gravity compliance and joint clearance (compliance.hpp): the cantilever's and the span's sag
// against the beam formulas, the sag motions, a hexapod's strut loads against the closed form of a
// symmetric pose and against virtual work (finite differences of the forward kinematics), and the
// clearance's jump at a load reversal.
#include "pkm/simulation/compliance.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
namespace sim = pkm::simulation;
using pkm::test::kTolExact;
using Kind = sim::AxisSag::Kind;

constexpr double kSag = 25e-3;           // mm, the sag at the reference length
constexpr double kMassKg = 150.0;        // platform and spindle
constexpr double kStrutKg = 20.0;        // one strut
constexpr double kStepMm = 1e-4;         // central-difference step of a strut reading
constexpr double kTolLoadN = 1e-3;       // N: finite differences of the FK against the statics
constexpr double kTolSlope = 1e-9;       // rad: slope by differences of the elastic curve
constexpr double kTolFirstOrder = 1e-6;  // mm: the rotation's second order θ²·|r|/2 ≈ 2e-7 mm

TEST(AxisDeflection, CantileverTipSagGrowsWithTheCubeOfTheOverhang) {
  // δ = W·L³/(3EI) scaled to 25 µm at 1000 mm; θ = W·L²/(2EI) = 1.5·δ/L. Overhang 300 mm at q = 0.
  const sim::AxisSag ram{Kind::kCantilever, kSag, 1000.0, 300.0, 1.0};
  const sim::AxisDeflection short_ram = sim::axisDeflection(ram, 200.0);  // L = 500 mm
  EXPECT_NEAR(short_ram.sag_mm, kSag / 8.0, kTolExact);
  EXPECT_NEAR(short_ram.slope_rad, 1.5 * kSag / 8.0 / 500.0, kTolExact);
  const sim::AxisDeflection long_ram = sim::axisDeflection(ram, 700.0);  // L = 1000 mm
  EXPECT_NEAR(long_ram.sag_mm, kSag, kTolExact);
  EXPECT_NEAR(long_ram.slope_rad, 1.5 * kSag / 1000.0, kTolExact);
  // Sense −1: the overhang shrinks with the command; none without an overhang.
  const sim::AxisSag back{Kind::kCantilever, kSag, 1000.0, 300.0, -1.0};
  EXPECT_NEAR(sim::axisDeflection(back, -700.0).sag_mm, kSag, kTolExact);
  EXPECT_EQ(sim::axisDeflection(back, 400.0).sag_mm, 0.0);
  EXPECT_EQ(sim::axisDeflection(sim::AxisSag{}, 400.0).sag_mm, 0.0);
}

TEST(AxisDeflection, SpanFollowsTheSimplySupportedBeam) {
  // A load P at a on a span L: the elastic curve y(x) = P·b·x·(L² − b² − x²)/(6EIL) for x ≤ a, with
  // P/(EI) = 48·δ_mid/L³. The sag and slope at the load are y(a) and y'(a) (by differences).
  const double L = 4000.0;
  const sim::AxisSag bed{Kind::kSpan, 10e-3, L, 0.0, 1.0};
  EXPECT_NEAR(sim::axisDeflection(bed, L / 2).sag_mm, 10e-3, kTolExact);
  EXPECT_NEAR(sim::axisDeflection(bed, L / 2).slope_rad, 0.0, kTolExact);
  const double p_over_ei = 48.0 * 10e-3 / (L * L * L);
  for (const double a : {500.0, 1000.0, 2900.0}) {
    const double b = L - a;
    const auto y = [&](double x) { return p_over_ei * b * x * (L * L - b * b - x * x) / (6 * L); };
    const sim::AxisDeflection d = sim::axisDeflection(bed, a);
    EXPECT_NEAR(d.sag_mm, y(a), kTolExact) << a;
    const double h = 1e-3;
    EXPECT_NEAR(d.slope_rad, (y(a + h) - y(a - h)) / (2 * h), kTolSlope) << a;
  }
  EXPECT_EQ(sim::axisDeflection(bed, L + 1.0).sag_mm, 0.0);  // beyond the support
  EXPECT_THROW((void)sim::axisDeflection({Kind::kSpan, -1.0, L, 0.0, 1.0}, 0.0),
               pkm::InvalidArgument);
}

TEST(AxisDeflection, SagMotionsDropAndTurnNoseDownAboutThePivot) {
  const sim::AxisDeflection d{0.02, 5e-5};
  const Eigen::Vector3d pivot(100, 200, 50), r(10, 30, -150);
  const pkm::geometry::RigidTransform pose = pkm::geometry::translationTransform(pivot + r);
  // An axis extending along +y: φ = θ·(ẑ × ŷ) = −θ·x̂, so p' = pivot + r + φ × r − δ·ẑ.
  const Eigen::Vector3d phi = -d.slope_rad * Eigen::Vector3d::UnitX();
  const pkm::geometry::RigidTransform tool =
      sim::sagCarryingTool(pose, d, Eigen::Vector3d::UnitY(), pivot);
  const Eigen::Vector3d expected = pivot + r + phi.cross(r) - d.sag_mm * Eigen::Vector3d::UnitZ();
  EXPECT_LT((tool.translation() - expected).norm(), kTolFirstOrder);
  EXPECT_LT((pkm::geometry::so3Log(tool.linear()) - phi).norm(), kTolExact);
  // The work sagging is the inverse seen from the work.
  const pkm::geometry::RigidTransform work =
      sim::sagCarryingWork(tool, d, Eigen::Vector3d::UnitY(), pivot);
  EXPECT_LT((work.translation() - pose.translation()).norm(), 1e-9);  // S⁻¹·S exactly
  // A vertical axis is not bent by gravity along it: no drop, no turn.
  const pkm::geometry::RigidTransform up =
      sim::sagCarryingTool(pose, d, Eigen::Vector3d::UnitZ(), pivot);
  EXPECT_LT((up.translation() - pose.translation()).norm(), kTolExact);
}

/// The strut loads at `pose` of the milling hexapod.
kin::StrutVector loadsAt(const kin::HexapodModel& m,
                         const pkm::kinematics::PoseRpy& pose,
                         const sim::HexapodCompliance& c) {
  kin::HexapodData data(m);
  (void)kin::inverseKinematics(m, data, pose);
  return sim::hexapodStrutLoads(m, data, c);
}

TEST(HexapodStrutLoads, SymmetricPoseLoadsEveryStrutEqually) {
  // Pure z pose of a D3-symmetric hexapod, centre of mass on the axis: 6·C·u_z = m·g, so every
  // strut carries C = m·g/(6·u_z) (negative: the platform hangs below the base, the struts pull).
  const kin::HexapodModel m = pkm::test::millingModel();
  sim::HexapodCompliance c;
  c.platform_mass_kg = kMassKg;
  c.platform_com_mm = {0, 0, -100};
  kin::PoseRpy pose;
  pose.position = {0, 0, 250};
  kin::HexapodData data(m);
  (void)kin::inverseKinematics(m, data, pose);
  const kin::StrutVector loads = sim::hexapodStrutLoads(m, data, c);
  const double uz = data.unit_leg[0].z();
  ASSERT_LT(uz, 0.0);
  for (Eigen::Index i = 0; i < 6; ++i)
    EXPECT_NEAR(loads[i], kMassKg * sim::kStandardGravity / (6.0 * uz), 1e-9) << i;
}

TEST(HexapodStrutLoads, EqualTheVirtualWorkOfGravity) {
  // C_i = ∂V/∂q_i with V = g·(m_p·z_c + Σ η·m_s·z_Pi), by central differences of the forward
  // kinematics, at a tilted, offset pose with an off-axis centre of mass and heavy struts.
  const kin::HexapodModel m = pkm::test::millingModel();
  sim::HexapodCompliance c;
  c.platform_mass_kg = kMassKg;
  c.platform_com_mm = {40, -25, -120};
  c.strut_mass_kg = kStrutKg;
  c.strut_com_fraction = 0.4;
  kin::PoseRpy pose;
  pose.position = {60, -40, 230};
  pose.rpy = {0.08, -0.05, 0.1};
  const kin::StrutVector loads = loadsAt(m, pose, c);
  kin::HexapodData data(m);
  const kin::StrutVector q = kin::inverseKinematics(m, data, pose);
  const auto energy = [&](const kin::StrutVector& readings) {
    kin::HexapodData d(m);
    EXPECT_TRUE(kin::forwardKinematics(m, d, readings, pose).ok());
    const Eigen::Vector3d com =
        d.world_p_tcp + d.world_R_platform * (c.platform_com_mm - m.tool_offset);
    double v = c.platform_mass_kg * com.z();
    for (const Eigen::Vector3d& p : d.world_p_platform_joint)
      v += c.strut_com_fraction * c.strut_mass_kg * p.z();
    return sim::kStandardGravity * v;
  };
  for (Eigen::Index i = 0; i < 6; ++i) {
    kin::StrutVector plus = q, minus = q;
    plus[i] += kStepMm;
    minus[i] -= kStepMm;
    EXPECT_NEAR(loads[i], (energy(plus) - energy(minus)) / (2 * kStepMm), kTolLoadN) << i;
  }
}

TEST(LegDeflection, ClearanceJumpsByTwiceItselfWhenTheLoadReverses) {
  int side = 0;
  const double k = 50.0, c = 4e-3;
  EXPECT_NEAR(sim::legDeflection(500.0, k, c, side), -500.0 / 50e3 - c, kTolExact);
  EXPECT_EQ(side, 1);
  EXPECT_NEAR(sim::legDeflection(0.0, k, c, side), -c, kTolExact);  // zero keeps the side
  const double just_compressed = sim::legDeflection(1e-9, k, c, side);
  const double just_pulled = sim::legDeflection(-1e-9, k, c, side);
  EXPECT_EQ(side, -1);
  EXPECT_NEAR(just_pulled - just_compressed, 2 * c, 1e-12);
}

}  // namespace PKM_TEST_NS
