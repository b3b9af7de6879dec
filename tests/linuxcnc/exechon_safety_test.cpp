// What keeps the Exechon component (src/linuxcnc/pkmexechonkins_core.h) safe in a servo loop: the
// branch state moves on success only, the forward kinematics takes LinuxCNC's pose as its seed
// (pkm_exechon_seed), refuses another assembly branch, and stops within its iteration budget; a
// parameter file asking for more than the budget is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "linuxcnc/pkmexechonkins_core.h"
#include "pkm/io/linuxcnc_exechon.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "support/tolerances.hpp"

namespace pkm {
namespace PKM_TEST_NS {

using kinematics::ExechonConfiguration;
using kinematics::ExechonData;

struct Machine {
  io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  pkm_exechon_params p{};
  Machine() {
    char why[256] = "";
    const std::string text = io::linuxcncExechonParameters(machine);
    EXPECT_EQ(pkm_exechon_parse_params(text.c_str(), &p, why, sizeof why), 0) << why;
  }
  pkm_exechon_state home() const {
    const auto& e = machine.model.home.e;
    return {{e[0], e[1], e[2]}, 1};
  }
  /// World pose (tool point, C, A) and joints of a configuration.
  void of(const ExechonConfiguration& c, double world[5], double joints[5]) const {
    ExechonData data(machine.model);
    kinematics::evaluateConfiguration(machine.model, data, c);
    for (int i = 0; i < 3; ++i) {
      world[i] = data.world_p_tool[i];
      joints[i] = data.readings[i];
    }
    world[3] = joints[3] = c.c;
    world[4] = joints[4] = c.a;
  }
};

TEST(ExechonSafety, ARejectedInversePoseDoesNotMoveTheBranchState) {
  const Machine m;
  ExechonConfiguration far = m.machine.model.home;
  far.e[2] += 500.0;  // past the legs' 700 mm stroke
  double world[5], joints[5], q[5];
  m.of(far, world, joints);
  pkm_exechon_state state = m.home();
  const pkm_exechon_state before = state;
  ASSERT_EQ(pkm_exechon_inverse(&m.p, &state, world, 0.0, q), PKM_EXECHON_OUT_OF_RANGE);
  for (int i = 0; i < 3; ++i) EXPECT_EQ(state.e[i], before.e[i]);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(q[i], joints[i], test::kTolRoundTrip);  // not clamped
}

// LinuxCNC's pose is the seed: the configuration of a pose far from the state's gives the FK of
// that pose's joints in no more steps than a servo cycle's.
TEST(ExechonSafety, TheSeedIsTheConfigurationOfLinuxCncsPose) {
  const Machine m;
  ExechonConfiguration c = m.machine.model.home;
  c.e += Eigen::Vector3d(0.12, -0.08, 60.0);
  c.c = 0.7;
  c.a = -0.4;
  double world[5], joints[5], w[5];
  m.of(c, world, joints);
  pkm_exechon_state seed = m.home();
  ASSERT_EQ(pkm_exechon_seed(&m.p, world, 0.0, &seed), PKM_EXECHON_OK);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(seed.e[i], c.e[i], test::kTolRoundTrip);
  int iterations = -1;
  ASSERT_EQ(pkm_exechon_forward(&m.p, &seed, joints, 0.0, w, &iterations), PKM_EXECHON_OK);
  EXPECT_LE(iterations, 1);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i], world[i], test::kTolRoundTrip);
  const double nan_world[5] = {NAN, 0, 0, 0, 0};
  const pkm_exechon_state kept = seed;
  EXPECT_EQ(pkm_exechon_seed(&m.p, nan_world, 0.0, &seed), PKM_EXECHON_INVALID_INPUT);
  EXPECT_EQ(seed.e[2], kept.e[2]);
}

// A configuration on the other side of a singularity (det d(lengths)/de of the other sign than
// home's): its joints are refused by the forward kinematics seeded there, and its pose by the
// inverse, instead of a pose of another assembly.
TEST(ExechonSafety, AnotherBranchIsRefused) {
  const Machine m;
  const auto& home = m.machine.model.home;
  ASSERT_EQ(pkm_exechon_branch(&m.p, home.e.data()), m.p.branch);
  ASSERT_NE(m.p.branch, 0);
  ExechonConfiguration other = home;
  bool found = false;
  for (int k = 1; k <= 400 && !found; ++k) {  // h falling to the base and beyond
    other.e[2] = home.e[2] - 5.0 * k;
    double lengths[3];
    found = pkm_exechon_leg_lengths(&m.p, other.e.data(), lengths, nullptr) == 0 &&
            pkm_exechon_branch(&m.p, other.e.data()) == -m.p.branch;
  }
  ASSERT_TRUE(found) << "no configuration of the other branch below home";
  double world[5], joints[5], w[5], q[5];
  m.of(other, world, joints);
  pkm_exechon_state state = {{other.e[0], other.e[1], other.e[2]}, 1};
  const pkm_exechon_state before = state;
  EXPECT_EQ(pkm_exechon_forward(&m.p, &state, joints, 0.0, w, nullptr), PKM_EXECHON_OTHER_BRANCH);
  EXPECT_EQ(state.e[2], before.e[2]);
  EXPECT_EQ(pkm_exechon_inverse(&m.p, &state, world, 0.0, q), PKM_EXECHON_OTHER_BRANCH);
  EXPECT_STREQ(pkm_exechon_status_name(PKM_EXECHON_OTHER_BRANCH), "other_branch");
}

// A glitch the Newton steps cannot reach within fk_max_iterations stops there (at most
// fk_max_iterations steps), with budget_exhausted, the state untouched.
TEST(ExechonSafety, TheForwardStopsWithinItsBudget) {
  Machine m;
  double world[5], joints[5], w[5];
  ExechonConfiguration c = m.machine.model.home;
  c.e[2] += 100.0;
  m.of(c, world, joints);
  m.p.fk_max_iterations = 1;
  pkm_exechon_state state = m.home();
  int iterations = 0;
  EXPECT_EQ(pkm_exechon_forward(&m.p, &state, joints, 0.0, w, &iterations),
            PKM_EXECHON_BUDGET_EXHAUSTED);
  EXPECT_EQ(iterations, 1);
  EXPECT_EQ(state.e[2], m.machine.model.home.e[2]);
  for (const double glitch : {1e5, -1e5, 3000.0}) {
    double q[5] = {joints[0] + glitch, joints[1], joints[2], joints[3], joints[4]};
    m.p.fk_max_iterations = PKM_EXECHON_MAX_ITERATIONS;
    state = m.home();
    EXPECT_NE(pkm_exechon_forward(&m.p, &state, q, 0.0, w, &iterations), PKM_EXECHON_OK);
    EXPECT_LE(iterations, PKM_EXECHON_MAX_ITERATIONS);
  }
}

TEST(ExechonSafety, AParameterFileBeyondTheBudgetIsRefused) {
  const Machine m;
  std::string text = io::linuxcncExechonParameters(m.machine);
  const auto at = text.find("\nfk_max_iterations ");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 19, "\nfk_max_iterations 121 #");
  pkm_exechon_params p{};
  char why[256] = "";
  EXPECT_EQ(pkm_exechon_parse_params(text.c_str(), &p, why, sizeof why), -1);
  EXPECT_NE(std::string(why).find("fk_max_iterations <= 120"), std::string::npos) << why;
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
