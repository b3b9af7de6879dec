// Hexapod forward kinematics from home (forwardKinematics): the LinuxCNC reference poses, at least
// where the genhexkins-style iteration converges, the seed's assembly mode kept across the
// workspace (and the mirror mode's), clean failures (unreachable lengths, the iteration cap,
// non-finite input, a singular seed, invalid options) and the status strings. IK -> FK round trips
// and HexapodFkSolver: hexapod_fk_round_trip_test.cpp.
#include "pkm/kinematics/hexapod_fk.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/genhexkins_style.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::kinematics {
namespace PKM_TEST_NS {

TEST(HexapodFk, LinuxcncReferencePosesFromHome) {
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  const PoseRpy poses[] = {{{2, -1, 22}, {degToRad(3), degToRad(-4), degToRad(10)}},
                           {{-3, 2, 18}, {degToRad(10), degToRad(10), degToRad(-15)}}};
  for (const PoseRpy& truth : poses) {
    const StrutVector q = inverseKinematics(m, data, truth);
    const FkSummary s = forwardKinematics(m, data, q, m.home);
    ASSERT_TRUE(s.ok());
    EXPECT_LE(s.iterations, 10);  // genhexkins-style iteration needs 13 and 17 here
    EXPECT_LT((data.pose.position - truth.position).norm(), test::kTolRoundTrip);
  }
}

TEST(HexapodFk, ConvergesWhereGenhexkinsStyleConverges) {
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  std::mt19937 rng(test::kSeed + 1);
  int both = 0;
  for (int k = 0; k < 2000; ++k) {
    const PoseRpy truth = test::randomPose(rng, m.home, 8.0, degToRad(30));
    const StrutVector q = inverseKinematics(m, data, truth);
    const test::GenhexkinsResult g = test::genhexkinsStyleFk(m, q, m.home);
    const FkSummary s = forwardKinematics(m, data, q, m.home);
    if (!g.converged) continue;
    ++both;
    ASSERT_TRUE(s.ok()) << "pose " << k << ": genhexkins-style converged, pkm did not";
    // Both land on the same assembly mode when the genhexkins-style iteration returns the true
    // pose.
    if ((g.pose.position - truth.position).norm() < 1e-6) {
      EXPECT_LT((data.pose.position - truth.position).norm(), test::kTolRoundTrip);
    }
  }
  EXPECT_GT(both, 1500);
}

/// Sign of det J_q_x at `pose`: the assembly mode's side of the singularities.
int determinantSign(const HexapodModel& m, HexapodData& data, const PoseRpy& pose) {
  (void)inverseKinematics(m, data, pose);
  const double det = computeStrutJacobian(m, data).determinant();
  return (det > 0.0) - (det < 0.0);
}

TEST(HexapodFk, ColdStartsAcrossTheWorkspaceStayInTheSeedsAssemblyMode) {
  // 3000 random poses of the LinuxCNC hexapod-sim workspace (x, y ±6 in, z 14–26 in, a, b ±30°,
  // c ±45°), each solved from home as genhexkins would be. pkm must reach the true pose at least
  // as often as the genhexkins-style iteration, and every "ok" must lie in home's assembly mode.
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  std::mt19937 rng(test::kSeed + 21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int home_sign = determinantSign(m, data, m.home);
  int pkm_true = 0, reference_true = 0, ok = 0;
  constexpr int kPoses = 3000;
  for (int k = 0; k < kPoses; ++k) {
    PoseRpy truth;
    truth.position = {6.0 * u(rng), 6.0 * u(rng), 20.0 + 6.0 * u(rng)};
    truth.rpy = {degToRad(30) * u(rng), degToRad(30) * u(rng), degToRad(45) * u(rng)};
    const StrutVector q = inverseKinematics(m, data, truth);
    const test::GenhexkinsResult g = test::genhexkinsStyleFk(m, q, m.home);
    if (g.converged && (g.pose.position - truth.position).norm() < 1e-6) ++reference_true;
    const FkSummary s = forwardKinematics(m, data, q, m.home);
    if (!s.ok()) {
      EXPECT_NE(s.status, FkStatus::kNoConvergence) << "pose " << k;
      continue;
    }
    ++ok;
    const PoseRpy found = data.pose;
    if ((found.position - truth.position).norm() < 1e-6) ++pkm_true;
    EXPECT_EQ(determinantSign(m, data, found), home_sign) << "pose " << k;
  }
  EXPECT_GE(pkm_true, reference_true);
  EXPECT_GE(pkm_true, kPoses - 3);
  EXPECT_GE(ok, kPoses - 3);
}

TEST(HexapodFk, ASeedInTheMirrorModeStaysThere) {
  // The platform mirrored through the base plane closes the same struts: from a mirrored seed
  // the solve stays in the mirror assembly mode, consistently (not "ok" in the other one).
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  const PoseRpy truth{{1.0, -2.0, 21.0}, {degToRad(4), degToRad(-3), degToRad(8)}};
  const StrutVector q = inverseKinematics(m, data, truth);
  PoseRpy mirror_home = m.home;
  mirror_home.position.z() = -m.home.position.z();
  mirror_home.rpy = {0.0, 0.0, 0.0};
  const int mirror_sign = determinantSign(m, data, mirror_home);
  const FkSummary s = forwardKinematics(m, data, q, mirror_home);
  if (s.ok()) {
    EXPECT_LT(data.pose.position.z(), 0.0);
    EXPECT_EQ(determinantSign(m, data, data.pose), mirror_sign);
  } else {
    EXPECT_EQ(s.status, FkStatus::kOtherBranch);
  }
}

TEST(HexapodFk, UnreachableLengthsFailCleanly) {
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  StrutVector q;
  q << 1000, 1, 1000, 1, 1000, 1;  // no platform pose closes these struts
  const FkSummary s = forwardKinematics(m, data, q, m.home);
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.status, FkStatus::kInvalidInput);
  EXPECT_GT(s.max_residual, 1.0);
}

TEST(HexapodFk, IterationCapGivesNoConvergence) {
  const HexapodModel m = test::millingModel();
  HexapodData data(m);
  PoseRpy truth = m.home;
  truth.position.x() += 80;
  truth.rpy.z() += 0.3;
  const StrutVector q = inverseKinematics(m, data, truth);
  FkOptions opt;
  opt.max_iterations = 1;
  const FkSummary s = forwardKinematics(m, data, q, m.home, opt);
  EXPECT_EQ(s.status, FkStatus::kNoConvergence);
  EXPECT_EQ(s.iterations, 1);
}

TEST(HexapodFk, NonFiniteInputIsInvalid) {
  const HexapodModel m = test::millingModel();
  HexapodData data(m);
  StrutVector q = StrutVector::Constant(250);
  q[2] = NAN;
  EXPECT_EQ(forwardKinematics(m, data, q, m.home).status, FkStatus::kInvalidInput);
  PoseRpy seed = m.home;
  seed.rpy.x() = INFINITY;
  EXPECT_EQ(forwardKinematics(m, data, StrutVector::Constant(250), seed).status,
            FkStatus::kInvalidInput);
}

TEST(HexapodFk, SingularSeedIsReported) {
  const HexapodModel m = test::linuxcncSimModel();
  HexapodData data(m);
  PoseRpy seed = m.home;
  seed.position.z() = 0;  // every strut in the base plane: no vertical stiffness
  const StrutVector q = StrutVector::Constant(29.7);
  EXPECT_EQ(forwardKinematics(m, data, q, seed).status, FkStatus::kSingular);
}

TEST(HexapodFk, InvalidOptionsThrow) {
  const HexapodModel m = test::millingModel();
  HexapodData data(m);
  FkOptions opt;
  EXPECT_TRUE(opt.isValid());
  opt.tolerance = 0;
  std::string why;
  EXPECT_FALSE(opt.isValid(&why));
  EXPECT_NE(why.find("tolerance"), std::string::npos);
  EXPECT_THROW((void)forwardKinematics(m, data, StrutVector::Constant(250), m.home, opt),
               InvalidArgument);
  opt = FkOptions{.max_iterations = 0};
  EXPECT_FALSE(opt.isValid());
  opt = FkOptions{.max_backtracks = -1};
  EXPECT_FALSE(opt.isValid());
}

TEST(HexapodFk, StatusStrings) {
  EXPECT_EQ(toString(FkStatus::kOk), "ok");
  EXPECT_EQ(toString(FkStatus::kNoConvergence), "no_convergence");
  EXPECT_EQ(toString(FkStatus::kSingular), "singular");
  EXPECT_EQ(toString(FkStatus::kInvalidInput), "invalid_input");
  EXPECT_EQ(toString(FkStatus::kOtherBranch), "other_branch");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::kinematics