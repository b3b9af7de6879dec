// The C core of the pkmhexkins LinuxCNC component (src/linuxcnc/pkmhexkins_core.c, compiled as C)
// against pkm's C++ hexapod kinematics: IK to 1e-12, FK round trips, seeding, failures.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <string>
#include <vector>

#include "pkm/geometry/so3.hpp"
#include "pkm/kinematics/hexapod_fk.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "pkmhexkins_core.h"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

using kinematics::HexapodModel;
using kinematics::PoseRpy;

/// The kinematic fields of data/machines/<name>.json (read here: this test links no io).
HexapodModel machine(const std::string& name) {
  std::ifstream in(std::string(PKM_SOURCE_DIR) + "/data/machines/" + name + ".json");
  const nlohmann::json j = nlohmann::json::parse(in);
  HexapodModel m;
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
    const auto& s = j.at("struts").at(static_cast<std::size_t>(i));
    auto& strut = m.struts[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      strut.world_p_base[k] = s.at("base").at(static_cast<std::size_t>(k)).get<double>();
      strut.platform_p_joint[k] = s.at("platform").at(static_cast<std::size_t>(k)).get<double>();
    }
    strut.length_offset = s.value("length_offset", 0.0);
  }
  for (int k = 0; k < 3; ++k)
    m.tool_offset[k] = j.at("tool_offset").at(static_cast<std::size_t>(k)).get<double>();
  m.spindle_offset = j.value("spindle_offset", 0.0);
  const auto& h = j.at("home");
  m.home.position = {h.at("x").get<double>(), h.at("y").get<double>(), h.at("z").get<double>()};
  m.home.rpy = {degToRad(h.at("a").get<double>()),
                degToRad(h.at("b").get<double>()),
                degToRad(h.at("c").get<double>())};
  return m;
}

/// The C geometry of a C++ model.
pkm_hex_geometry toC(const HexapodModel& m) {
  pkm_hex_geometry g{};
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) {
    const auto& s = m.struts[static_cast<std::size_t>(i)];
    for (int k = 0; k < 3; ++k) {
      g.base[i][k] = s.world_p_base[k];
      g.platform[i][k] = s.platform_p_joint[k];
    }
    g.length_offset[i] = s.length_offset;
  }
  for (int k = 0; k < 3; ++k) g.tool[k] = m.tool_offset[k];
  g.spindle_offset = m.spindle_offset;
  return g;
}

void toC(const Eigen::Matrix3d& R, double out[3][3]) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out[i][j] = R(i, j);
}

/// A calibrated 42-parameter geometry: every joint and offset of `m` moved by up to `d`.
HexapodModel perturbed(HexapodModel m, double d, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-d, d);
  for (auto& s : m.struts) {
    for (int k = 0; k < 3; ++k) {
      s.world_p_base[k] += u(rng);
      s.platform_p_joint[k] += u(rng);
    }
    s.length_offset += u(rng);
  }
  m.spindle_offset += u(rng);
  return m;
}

struct Case {
  std::string name;
  HexapodModel model;
  double reach;  ///< random poses within ±reach of home per axis
  double tilt;   ///< and ±tilt rad per angle
};

std::vector<Case> cases() {
  std::mt19937 rng(kSeed);
  const HexapodModel sim = machine("hexapod-linuxcnc-sim");
  const HexapodModel def = machine("hexapod-default");
  HexapodModel sim_tool = sim;
  sim_tool.tool_offset = {0.3, -0.2, -4.0};
  sim_tool.spindle_offset = 1.25;
  return {{"linuxcnc-sim", sim, 4.0, 0.15},
          {"default", def, 60.0, 0.15},
          {"sim-tool-spindle", sim_tool, 4.0, 0.15},
          {"sim-calibrated", perturbed(sim, 0.05, rng), 4.0, 0.15},
          {"default-calibrated", perturbed(def, 1.5, rng), 60.0, 0.15},
          {"milling", millingModel(), 60.0, 0.2}};
}

TEST(HexkinsCore, InverseEqualsTheLibraryToMachinePrecision) {
  std::mt19937 rng(kSeed);
  for (const Case& c : cases()) {
    const pkm_hex_geometry g = toC(c.model);
    kinematics::HexapodData data(c.model);
    for (int n = 0; n < 200; ++n) {
      const PoseRpy pose = randomPose(rng, c.model.home, c.reach, c.tilt);
      const auto& want = kinematics::inverseKinematics(c.model, data, pose);
      double R[3][3], q[PKM_HEX_STRUTS];
      pkm_hex_rotation_from_rpy(pose.rpy.data(), R);
      ASSERT_EQ(pkm_hex_inverse(&g, pose.position.data(), R, q), 0);
      for (int i = 0; i < PKM_HEX_STRUTS; ++i)
        ASSERT_NEAR(q[i], want[i], kTolExact * std::max(1.0, std::abs(want[i])))
            << c.name << " pose " << n << " strut " << i;
    }
  }
}

TEST(HexkinsCore, RotationAndAnglesMatchTheLibrary) {
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> u(-3.0, 3.0);
  for (int n = 0; n < 500; ++n) {
    const Eigen::Vector3d rpy(u(rng), u(rng) / 2.0, u(rng));
    const Eigen::Vector3d near(u(rng), u(rng), u(rng));
    double R[3][3], got[3];
    pkm_hex_rotation_from_rpy(rpy.data(), R);
    const Eigen::Matrix3d want = geometry::rotationFromRpy(rpy);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) ASSERT_NEAR(R[i][j], want(i, j), kTolExact);
    pkm_hex_rpy_from_rotation(R, near.data(), got);
    const Eigen::Vector3d back = geometry::rpyFromRotation(want, near);
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(got[k], back[k], kTolExact);
  }
}

// FK of the IK of random poses, seeded from home (a cold start) and from a pose one servo step
// away, returns the pose; the C and C++ solvers agree.
TEST(HexkinsCore, ForwardRoundTripsAndAgreesWithTheLibrary) {
  std::mt19937 rng(kSeed);
  pkm_hex_fk_options o;
  pkm_hex_default_fk_options(&o);
  for (const Case& c : cases()) {
    const pkm_hex_geometry g = toC(c.model);
    kinematics::HexapodData data(c.model);
    int worst_iterations = 0;
    for (int n = 0; n < 200; ++n) {
      const PoseRpy pose = randomPose(rng, c.model.home, c.reach, c.tilt);
      const kinematics::StrutVector q = kinematics::inverseKinematics(c.model, data, pose);
      const bool cold = n % 2 == 0;
      const PoseRpy seed = cold ? c.model.home : randomPose(rng, pose, 1e-3 * c.reach, 1e-3);
      double p[3] = {seed.position[0], seed.position[1], seed.position[2]}, R[3][3];
      toC(geometry::rotationFromRpy(seed.rpy), R);
      const pkm_hex_fk_summary s = pkm_hex_forward(&g, q.data(), &o, p, R);
      ASSERT_EQ(s.status, PKM_HEX_OK)
          << c.name << " pose " << n << ": " << pkm_hex_status_name(s.status);
      worst_iterations = std::max(worst_iterations, s.iterations);
      double rpy[3];
      pkm_hex_rpy_from_rotation(R, seed.rpy.data(), rpy);
      for (int k = 0; k < 3; ++k) {
        EXPECT_NEAR(p[k], pose.position[k], kTolRoundTrip) << c.name << " " << n;
        EXPECT_NEAR(rpy[k], pose.rpy[k], kTolRoundTrip) << c.name << " " << n;
      }
      const auto cpp = kinematics::forwardKinematics(c.model, data, q, seed);
      ASSERT_TRUE(cpp.ok()) << c.name;
      // The same algorithm: the same steps, but for a polishing step that rounding at the
      // threshold (1e-3 of the tolerance) may add or save.
      EXPECT_LE(std::abs(s.iterations - cpp.iterations), 1) << c.name << " pose " << n;
      for (int k = 0; k < 3; ++k) EXPECT_NEAR(p[k], data.pose.position[k], kTolRoundTrip);
    }
    EXPECT_LE(worst_iterations, 40) << c.name;
  }
}

// A path: each FK seeded with the previous solution, as LinuxCNC calls it every servo cycle.
TEST(HexkinsCore, ForwardFollowsAPathSeededFromThePreviousPose) {
  const HexapodModel m = machine("hexapod-linuxcnc-sim");
  const pkm_hex_geometry g = toC(m);
  kinematics::HexapodData data(m);
  pkm_hex_fk_options o;
  pkm_hex_default_fk_options(&o);
  double p[3] = {0, 0, 20}, R[3][3];
  toC(Eigen::Matrix3d::Identity(), R);
  double rpy[3] = {0, 0, 0};
  for (int n = 0; n <= 1000; ++n) {
    const double t = n * 1e-3;
    PoseRpy pose;
    pose.position = {3.0 * std::sin(t * 6.0), 2.0 * std::cos(t * 4.0) - 2.0, 20.0 + t};
    pose.rpy = {0.1 * std::sin(t * 3.0), -0.08 * t, 0.4 * t};
    const kinematics::StrutVector q = kinematics::inverseKinematics(m, data, pose);
    const pkm_hex_fk_summary s = pkm_hex_forward(&g, q.data(), &o, p, R);
    ASSERT_EQ(s.status, PKM_HEX_OK) << "step " << n;
    ASSERT_LE(s.iterations, 3) << "step " << n;
    pkm_hex_rpy_from_rotation(R, rpy, rpy);
    for (int k = 0; k < 3; ++k) {
      ASSERT_NEAR(p[k], pose.position[k], kTolRoundTrip);
      ASSERT_NEAR(rpy[k], pose.rpy[k], kTolRoundTrip);
    }
  }
}

TEST(HexkinsCore, FailuresLeaveTheSeedAndSayWhy) {
  pkm_hex_geometry g;
  pkm_hex_sim_geometry(&g);
  pkm_hex_fk_options o;
  pkm_hex_default_fk_options(&o);
  double p[3] = {0, 0, 20}, R[3][3];
  toC(Eigen::Matrix3d::Identity(), R);
  // Unreachable readings: the struts cannot all be this short.
  const double too_short[PKM_HEX_STRUTS] = {1, 1, 1, 1, 1, 1};
  pkm_hex_fk_summary s = pkm_hex_forward(&g, too_short, &o, p, R);
  EXPECT_NE(s.status, PKM_HEX_OK) << pkm_hex_status_name(s.status);
  EXPECT_EQ(p[2], 20.0);
  // A non-finite reading.
  const double nan_q[PKM_HEX_STRUTS] = {NAN, 30, 30, 30, 30, 30};
  s = pkm_hex_forward(&g, nan_q, &o, p, R);
  EXPECT_EQ(s.status, PKM_HEX_INVALID_INPUT);
  EXPECT_STREQ(pkm_hex_status_name(s.status), "invalid_input");
  // From a seed on the singular plane (platform in the base plane) a solution is one of the
  // assembly modes: its readings are the given ones, whichever it is.
  double p0[3] = {0, 0, 0};
  const double home_q[PKM_HEX_STRUTS] = {29.7466, 29.7466, 29.7466, 29.7466, 29.7466, 29.7466};
  s = pkm_hex_forward(&g, home_q, &o, p0, R);
  if (s.status == PKM_HEX_OK) {
    double q[PKM_HEX_STRUTS];
    ASSERT_EQ(pkm_hex_inverse(&g, p0, R, q), 0);
    for (int i = 0; i < PKM_HEX_STRUTS; ++i) EXPECT_NEAR(q[i], home_q[i], o.tolerance);
  }
  // max_error stops a solve whose residual exceeds it.
  o.max_error = 1e-3;
  double far[3] = {0, 0, 22};
  s = pkm_hex_forward(&g, home_q, &o, far, R);
  EXPECT_EQ(s.status, PKM_HEX_NO_CONVERGENCE);
}

/// Residual-evaluation units of a budget: a Newton step or a step halving each.
constexpr int kBudget = 120;

// With a total budget and the home branch required, a solve on the normal path gives the same
// pose, bit for bit, as without them (the component's settings change failures only).
TEST(HexkinsCore, BudgetAndBranchLeaveTheNormalPathBitForBit) {
  std::mt19937 rng(kSeed);
  for (const Case& c : cases()) {
    const pkm_hex_geometry g = toC(c.model);
    kinematics::HexapodData data(c.model);
    pkm_hex_fk_options plain, bounded;
    pkm_hex_default_fk_options(&plain);
    bounded = plain;
    bounded.max_total_iterations = kBudget;
    double Rh[3][3];
    toC(geometry::rotationFromRpy(c.model.home.rpy), Rh);
    bounded.branch =
        pkm_hex_branch(&g, c.model.home.position.data(), Rh, plain.singular_pivot_ratio);
    ASSERT_NE(bounded.branch, 0) << c.name;
    for (int n = 0; n < 100; ++n) {
      const PoseRpy pose = randomPose(rng, c.model.home, c.reach, c.tilt);
      const kinematics::StrutVector q = kinematics::inverseKinematics(c.model, data, pose);
      double p1[3], p2[3], R1[3][3], R2[3][3];
      for (int k = 0; k < 3; ++k) p1[k] = p2[k] = c.model.home.position[k];
      memcpy(R1, Rh, sizeof R1);
      memcpy(R2, Rh, sizeof R2);
      const pkm_hex_fk_summary a = pkm_hex_forward(&g, q.data(), &plain, p1, R1);
      const pkm_hex_fk_summary b = pkm_hex_forward(&g, q.data(), &bounded, p2, R2);
      ASSERT_EQ(a.status, PKM_HEX_OK) << c.name << " " << n;
      ASSERT_EQ(b.status, PKM_HEX_OK) << c.name << " " << n;
      EXPECT_EQ(a.iterations, b.iterations);
      EXPECT_EQ(std::memcmp(p1, p2, sizeof p1), 0) << c.name << " " << n;
      EXPECT_EQ(std::memcmp(R1, R2, sizeof R1), 0) << c.name << " " << n;
    }
  }
}

TEST(HexkinsCore, ValidationNamesTheProblem) {
  pkm_hex_geometry g;
  pkm_hex_sim_geometry(&g);
  char why[128] = "";
  EXPECT_EQ(pkm_hex_validate(&g, why, sizeof why), 0);
  g.platform[4][0] = g.platform[3][0];  // struts 3 and 4 share their base joint already
  g.platform[4][1] = g.platform[3][1];
  EXPECT_EQ(pkm_hex_validate(&g, why, sizeof why), -1);
  EXPECT_STREQ(why, "struts 3 and 4 join the same joints");
  pkm_hex_sim_geometry(&g);
  g.length_offset[2] = INFINITY;
  EXPECT_EQ(pkm_hex_validate(&g, why, sizeof why), -1);
  EXPECT_STREQ(why, "a geometry value is not finite");
  EXPECT_DOUBLE_EQ(pkm_hex_characteristic_length(&g),
                   machine("hexapod-linuxcnc-sim").characteristicLength());
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
