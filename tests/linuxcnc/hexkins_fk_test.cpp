// The forward kinematics of pkmhexkins' C core (src/linuxcnc/pkmhexkins_fk.c) on glitched
// readings and across the singular plane: the hard budget per solve (every solve stops within it,
// whatever the readings) and the branch requirement (the mirror assembly is refused).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "pkmhexkins_core.h"
#include "support/tolerances.hpp"

namespace pkm::test {
namespace PKM_TEST_NS {

/// Residual-evaluation units of a budget: a Newton step or a step halving each (the component's
/// limit-iterations default).
constexpr int kBudget = 120;

/// The sim's home pose (0, 0, 20 in, level) and its readings.
void simHome(const pkm_hex_geometry& g, double p[3], double R[3][3], double q[PKM_HEX_STRUTS]) {
  p[0] = p[1] = 0.0;
  p[2] = 20.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = i == j ? 1.0 : 0.0;
  ASSERT_EQ(pkm_hex_inverse(&g, p, R, q), 0);
}

// Glitched readings (a jump of 1e5 in, joints at 0 before homing, random garbage, NaN, a
// 3000 in jump): every solve stops within the budget, seeded from the previous pose as the
// component does, and leaves the pose untouched. The cost is printed (docs/linuxcnc.md).
TEST(HexkinsCore, EverySolveStopsWithinItsBudget) {
  pkm_hex_geometry g;
  pkm_hex_sim_geometry(&g);
  double ph[3], Rh[3][3], qh[PKM_HEX_STRUTS];
  simHome(g, ph, Rh, qh);
  pkm_hex_fk_options o;
  pkm_hex_default_fk_options(&o);
  o.max_total_iterations = kBudget;
  o.branch = pkm_hex_branch(&g, ph, Rh, o.singular_pivot_ratio);
  std::mt19937 rng(kSeed);
  std::uniform_real_distribution<double> garbage(-1e5, 1e5);
  std::vector<std::pair<std::string, std::vector<double>>> glitches;
  for (double jump : {1e5, -1e5, 3000.0}) {
    std::vector<double> q(qh, qh + PKM_HEX_STRUTS);
    q[2] += jump;
    glitches.emplace_back("strut 2 " + std::to_string(jump), q);
    for (double& v : q) v = qh[&v - q.data()] + jump;
    glitches.emplace_back("all struts " + std::to_string(jump), q);
  }
  glitches.emplace_back("zeros", std::vector<double>(PKM_HEX_STRUTS, 0.0));
  for (int n = 0; n < 20; ++n) {
    std::vector<double> q(PKM_HEX_STRUTS);
    for (double& v : q) v = std::abs(garbage(rng));
    glitches.emplace_back("garbage " + std::to_string(n), q);
  }
  glitches.emplace_back("nan", std::vector<double>{NAN, 30, 30, 30, 30, 30});
  double slowest_us = 0.0;
  for (const auto& [name, q] : glitches) {
    double p[3], R[3][3];
    memcpy(p, ph, sizeof p);
    memcpy(R, Rh, sizeof R);
    const auto t0 = std::chrono::steady_clock::now();
    const pkm_hex_fk_summary s = pkm_hex_forward(&g, q.data(), &o, p, R);
    const double us =
        std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
    slowest_us = std::max(slowest_us, us);
    EXPECT_NE(s.status, PKM_HEX_OK) << name;
    // Each unit is one evaluation; a step whose tries all failed ends the solve (+1).
    EXPECT_LE(s.iterations + s.backtracks, kBudget + 1) << name;
    EXPECT_EQ(std::memcmp(p, ph, sizeof p), 0) << name;
  }
  std::cout << "slowest glitched solve: " << slowest_us << " us (budget " << kBudget << ")\n";
  // Without a budget the same solver runs on (up to 1000 stages × 120 steps).
  std::vector<double> far(qh, qh + PKM_HEX_STRUTS);
  far[2] += 1e5;
  double p[3], R[3][3];
  memcpy(p, ph, sizeof p);
  memcpy(R, Rh, sizeof R);
  pkm_hex_fk_options unbounded = o;
  unbounded.max_total_iterations = 0;
  const pkm_hex_fk_summary s = pkm_hex_forward(&g, far.data(), &unbounded, p, R);
  EXPECT_GT(s.iterations + s.backtracks, kBudget + 1);
  // Readings of a zero-length strut (joints at 0 before homing) are refused at once.
  const double zeros[PKM_HEX_STRUTS] = {0, 0, 0, 0, 0, 0};
  EXPECT_EQ(pkm_hex_forward(&g, zeros, &o, p, R).status, PKM_HEX_INVALID_INPUT);
}

// The mirror assembly (platform reflected through the base plane, z -> -z) has the readings of
// the true pose: without a branch requirement a seed below the plane converges to it; with the
// home branch required the solve says other_branch and leaves the pose; the branch of a pose on
// the plane is 0 (singular).
TEST(HexkinsCore, TheMirrorAssemblyIsAnotherBranch) {
  pkm_hex_geometry g;
  pkm_hex_sim_geometry(&g);
  double ph[3], Rh[3][3], qh[PKM_HEX_STRUTS];
  simHome(g, ph, Rh, qh);
  pkm_hex_fk_options o;
  pkm_hex_default_fk_options(&o);
  const int home = pkm_hex_branch(&g, ph, Rh, o.singular_pivot_ratio);
  ASSERT_NE(home, 0);
  const double up[3] = {0.5, -0.3, 3.0}, down[3] = {0.5, -0.3, -3.0}, plane[3] = {0, 0, 0};
  EXPECT_EQ(pkm_hex_branch(&g, up, Rh, o.singular_pivot_ratio), home);
  EXPECT_EQ(pkm_hex_branch(&g, down, Rh, o.singular_pivot_ratio), -home);
  EXPECT_EQ(pkm_hex_branch(&g, plane, Rh, o.singular_pivot_ratio), 0);
  double q_up[PKM_HEX_STRUTS], q_down[PKM_HEX_STRUTS];
  ASSERT_EQ(pkm_hex_inverse(&g, up, Rh, q_up), 0);
  ASSERT_EQ(pkm_hex_inverse(&g, down, Rh, q_down), 0);
  for (int i = 0; i < PKM_HEX_STRUTS; ++i) EXPECT_NEAR(q_up[i], q_down[i], 1e-12);
  double p[3] = {0.4, -0.3, -2.5}, R[3][3];
  memcpy(R, Rh, sizeof R);
  pkm_hex_fk_summary s = pkm_hex_forward(&g, q_up, &o, p, R);
  ASSERT_EQ(s.status, PKM_HEX_OK);
  EXPECT_NEAR(p[2], -3.0, kTolRoundTrip);  // the mirror, silently
  o.branch = home;
  const double seed[3] = {0.4, -0.3, -2.5};
  memcpy(p, seed, sizeof p);
  s = pkm_hex_forward(&g, q_up, &o, p, R);
  EXPECT_EQ(s.status, PKM_HEX_OTHER_BRANCH) << pkm_hex_status_name(s.status);
  EXPECT_EQ(std::memcmp(p, seed, sizeof p), 0);
  p[2] = 2.5;  // from above the plane: the true pose
  s = pkm_hex_forward(&g, q_up, &o, p, R);
  ASSERT_EQ(s.status, PKM_HEX_OK);
  EXPECT_NEAR(p[2], 3.0, kTolRoundTrip);
  EXPECT_STREQ(pkm_hex_status_name(PKM_HEX_BUDGET_EXHAUSTED), "budget_exhausted");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::test
