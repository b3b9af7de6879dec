#include "pkm/compensation/hybrid_squareness.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "pkm/core/error.hpp"
#include "pkm/geometry/so3.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/hybrid_chain.hpp"
#include "support/hybrid_samples.hpp"
#include "support/tolerances.hpp"

namespace pkm::compensation {
namespace PKM_TEST_NS {

constexpr double kExact = 1e-9;          // mm: squareness alone is compensated exactly
constexpr double kSecondOrder = 1e-6;    // rad: products of two squareness errors (mrad²)
constexpr double kRpyFirstOrder = 1e-4;  // rad: rpy vs the first-order angles

kinematics::HybridSquareness seed000() {
  kinematics::HybridSquareness s;
  s.sz_x2 = -0.034e-3;
  s.sx_p = -14.74e-3;
  s.sy_p = 4.35e-3;
  s.sz_p = -2.85e-3;
  return s;
}

/// Squareness alone: the compensated commands reach the nominal positions exactly, also with the
/// offsets of the offset model (X2_p_P, P_p_tcp0, Y2_p_work non-zero).
TEST(HybridSquarenessCompensation, RemovesSquarenessExactly) {
  for (const kinematics::HybridMachineModel& model :
       {test::mxt700sLikeModel(), test::offsetModel()}) {
    const HybridSquarenessCompensation c = hybridSquarenessCompensation(model, seed000());
    kinematics::HybridErrorValues values;
    values.squareness = seed000();
    std::mt19937 rng(test::kSeed);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    double before = 0.0;
    for (int k = 0; k < 200; ++k) {
      kinematics::HybridCommand cmd;
      cmd.x2 = 2000 + 2000 * u(rng);
      cmd.y2 = 225 + 225 * u(rng);
      cmd.pkm = Eigen::Vector3d(300 * u(rng), 300 * u(rng), 100 + 200 * u(rng));
      const Eigen::Vector3d nominal = kinematics::hybridNominalToolPosition(model, cmd);
      before = std::max(before, kinematics::hybridVolumetricError(model, values, cmd).norm());
      const Eigen::Vector3d actual =
          kinematics::hybridActualPose(model, values, compensatedCommand(c, cmd)).translation();
      EXPECT_LT((actual - nominal).norm(), kExact);
    }
    EXPECT_GT(before, 1.0);  // mm: 14.7 mrad over hundreds of mm
  }
}

/// The first-order form: A ≈ I − [ω_X2 + ω_P]×, b₁ ≈ (0, szX2, 0) (the X2–Y2 correction of the
/// Y command per mm of X2), and the rpy angles reproduce A.
TEST(HybridSquarenessCompensation, FirstOrderFormAndAngles) {
  const kinematics::HybridSquareness s = seed000();
  const HybridSquarenessCompensation c = hybridSquarenessCompensation(test::mxt700sLikeModel(), s);
  EXPECT_NEAR(c.per_x2.y(), s.sz_x2, kSecondOrder);
  EXPECT_NEAR(c.per_x2.x(), 0.0, kSecondOrder);
  EXPECT_NEAR(c.base_rpy.x(), -s.sx_p, kRpyFirstOrder);
  EXPECT_NEAR(c.base_rpy.y(), s.sy_p, kRpyFirstOrder);
  EXPECT_NEAR(c.base_rpy.z(), -(s.sz_p - s.sz_x2), kRpyFirstOrder);
  EXPECT_LT((geometry::rotationFromRpy(c.base_rpy) - c.base_rotation).norm(), test::kTolExact * 10);
  kinematics::HybridSquareness bad = s;
  bad.sx_p = std::nan("");
  EXPECT_THROW((void)hybridSquarenessCompensation(test::mxt700sLikeModel(), bad), InvalidArgument);
}

/// Seed 000: parallelism of the PKM's Y travel to Y2 (the slope of its path in x over 300 mm) with
/// the full error set, before and after the compensation by the TRUE squareness; only the PDGE's
/// straightness remains (paper: 0.735 -> 0.022 mm).
TEST(HybridSquarenessCompensation, Seed000ParallelismDropsToThePdgeLevel) {
  const io::ExechonMachine m = io::loadExechonMachine("mxt700s-like");
  const kinematics::GeometricErrors errors = io::loadGeometricErrors("mxt700s-seed000");
  const HybridSquarenessCompensation c = hybridSquarenessCompensation(*m.hybrid, errors.squareness);
  const auto deviation = [&](bool compensate) {
    double worst = 0.0;
    for (double y = -300; y <= 0; y += 25) {
      kinematics::HybridCommand cmd;
      cmd.x2 = 400;
      cmd.pkm = Eigen::Vector3d(0, y, 0);
      const kinematics::HybridCommand sent = compensate ? compensatedCommand(c, cmd) : cmd;
      const Eigen::Vector3d e =
          kinematics::hybridActualPose(*m.hybrid, errors, sent).translation() -
          kinematics::hybridNominalToolPosition(*m.hybrid, cmd);
      worst = std::max(worst, std::hypot(e.x(), e.z()));
    }
    return worst;
  };
  const double before = deviation(false), after = deviation(true);
  std::printf("seed 000 PKM-Y path deviation over 300 mm: %.4f -> %.4f mm\n", before, after);
  EXPECT_GT(before, 0.5);
  EXPECT_LT(after, 0.05);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::compensation
