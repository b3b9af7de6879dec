// The C Exechon kinematics of the LinuxCNC component (src/linuxcnc/pkmexechonkins_core.h, compiled
// as C) against pkm's C++ library on the built-in Exechon machines: the parameter file, home, IK,
// FK, the condition number, the tool length, branch continuity and the failure statuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "linuxcnc/pkmexechonkins_core.h"
#include "pkm/core/units.hpp"
#include "pkm/io/linuxcnc_exechon.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_checks.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "support/tolerances.hpp"

namespace pkm {
namespace PKM_TEST_NS {

using kinematics::ExechonConfiguration;
using kinematics::ExechonData;
using kinematics::ExechonModel;

/// The C parameters of `machine`, through the parameter file pkm writes.
pkm_exechon_params parametersOf(const io::ExechonMachine& machine) {
  pkm_exechon_params p{};
  char why[256] = "";
  const std::string text = io::linuxcncExechonParameters(machine);
  EXPECT_EQ(pkm_exechon_parse_params(text.c_str(), &p, why, sizeof why), 0) << why;
  return p;
}

std::vector<io::ExechonMachine> builtinExechons() {
  std::vector<io::ExechonMachine> out;
  for (const std::string& name : io::builtinMachineNames("exechon"))
    out.push_back(io::loadExechonMachine(name));
  return out;
}

/// A random configuration near home: alpha, beta ± 10°, h ± 10 % of L, C ± 150°, A in ±[10°, 80°].
ExechonConfiguration randomConfiguration(std::mt19937& rng, const ExechonModel& m) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  ExechonConfiguration c;
  c.e = m.home.e + Eigen::Vector3d(degToRad(10) * u(rng),
                                   degToRad(10) * u(rng),
                                   0.1 * m.characteristicLength() * u(rng));
  c.c = degToRad(150) * u(rng);
  const double a = degToRad(45 + 35 * u(rng));
  c.a = u(rng) < 0 ? -a : a;
  return c;
}

pkm_exechon_state homeState(const ExechonModel& m) {
  return {{m.home.e[0], m.home.e[1], m.home.e[2]}, 1};
}

/// The C status pkm's checks give for a solved configuration.
pkm_exechon_status expectedStatus(const kinematics::ExechonCheckResult& check) {
  if (check.ok()) return PKM_EXECHON_OK;
  if (check.status() == "singular") return PKM_EXECHON_SINGULAR;
  return PKM_EXECHON_OUT_OF_RANGE;
}

constexpr int kRandomPoses = 200;

TEST(ExechonCore, ParameterFileCarriesTheModel) {
  for (const io::ExechonMachine& machine : builtinExechons()) {
    const ExechonModel& m = machine.model;
    const pkm_exechon_params p = parametersOf(machine);
    EXPECT_EQ(p.dB, m.tripod.dB);
    EXPECT_EQ(p.hz, m.tripod.hz);
    EXPECT_EQ(p.length_offset[2], m.legs[2].length_offset);
    EXPECT_EQ(p.stroke_max[1], m.legs[1].max_reading);
    EXPECT_EQ(p.tool_length, m.wrist.tool_length);
    EXPECT_EQ(p.world_p_zoppi[1], m.world_T_zoppi.translation().y());
    if (std::isinf(m.limits.alpha.min))
      EXPECT_EQ(p.alpha_range[0], m.limits.alpha.min);  // an open range stays open
    else
      EXPECT_NEAR(p.alpha_range[0], m.limits.alpha.min, test::kTolExact);
    EXPECT_NEAR(p.home_e[0], m.home.e[0], test::kTolExact);
    EXPECT_EQ(p.fk_max_iterations, machine.fk.max_iterations);
    const Eigen::Matrix3d W = kinematics::wristFrame(m.wrist);
    for (int i = 0; i < 9; ++i) EXPECT_NEAR(p.wrist_frame[i], W(i / 3, i % 3), test::kTolExact);
  }
}

TEST(ExechonCore, HomeIsTheModelsHome) {
  for (const io::ExechonMachine& machine : builtinExechons()) {
    const pkm_exechon_params p = parametersOf(machine);
    ExechonData data(machine.model);
    kinematics::evaluateConfiguration(machine.model, data, machine.model.home);
    double q[5], w[5];
    pkm_exechon_home(&p, 0.0, q, w);
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(q[i], data.readings[i], test::kTolRoundTrip);
      EXPECT_NEAR(w[i], data.world_p_tool[i], test::kTolRoundTrip);
    }
    EXPECT_EQ(q[3], machine.model.home.c);
    EXPECT_EQ(w[4], machine.model.home.a);
  }
}

TEST(ExechonCore, InverseMatchesTheLibraryOnRandomToolPoses) {
  std::mt19937 rng(test::kSeed);
  for (const io::ExechonMachine& machine : builtinExechons()) {
    const ExechonModel& m = machine.model;
    const pkm_exechon_params p = parametersOf(machine);
    ExechonData truth(m), cpp(m);
    for (int k = 0; k < kRandomPoses; ++k) {
      const ExechonConfiguration config = randomConfiguration(rng, m);
      kinematics::evaluateConfiguration(m, truth, config);
      const Eigen::Vector3d target = truth.world_p_tool;
      ASSERT_EQ(
          kinematics::toolPointInverseKinematics(m, cpp, target, config.c, config.a, m.home.e),
          kinematics::ExechonIkStatus::kOk);
      const kinematics::ExechonCheckResult check = kinematics::checkConfiguration(m, cpp);
      pkm_exechon_state state = homeState(m);
      const double world[5] = {target.x(), target.y(), target.z(), config.c, config.a};
      double q[5];
      const pkm_exechon_status status = pkm_exechon_inverse(&p, &state, world, 0.0, q);
      EXPECT_EQ(status, expectedStatus(check))
          << machine.model.name << " pose " << k << ": " << check.status();
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(q[i], cpp.readings[i], test::kTolRoundTrip) << m.name << " pose " << k;
        EXPECT_NEAR(q[i], truth.readings[i], test::kTolRoundTrip) << m.name << " pose " << k;
        // The branch state moves on success only.
        EXPECT_NEAR(
            state.e[i], status == PKM_EXECHON_OK ? cpp.e[i] : m.home.e[i], test::kTolRoundTrip);
      }
      EXPECT_EQ(q[3], config.c);
      EXPECT_EQ(q[4], config.a);
    }
  }
}

TEST(ExechonCore, ForwardMatchesTheLibraryAndRoundTrips) {
  std::mt19937 rng(test::kSeed + 1);
  for (const io::ExechonMachine& machine : builtinExechons()) {
    const ExechonModel& m = machine.model;
    const pkm_exechon_params p = parametersOf(machine);
    ExechonData truth(m), cpp(m);
    for (int k = 0; k < kRandomPoses; ++k) {
      const ExechonConfiguration config = randomConfiguration(rng, m);
      kinematics::evaluateConfiguration(m, truth, config);
      const kinematics::ExechonJoints joints = kinematics::jointsOf(truth);
      const kinematics::FkSummary s =
          kinematics::toolForwardKinematics(m, cpp, joints, m.home, machine.fk);
      ASSERT_EQ(s.status, kinematics::FkStatus::kOk);
      pkm_exechon_state state = homeState(m);
      const double q[5] = {
          joints.readings[0], joints.readings[1], joints.readings[2], joints.c, joints.a};
      double w[5], back[5];
      int iterations = 0;
      ASSERT_EQ(pkm_exechon_forward(&p, &state, q, 0.0, w, &iterations), PKM_EXECHON_OK);
      EXPECT_GT(iterations, 0);
      for (int i = 0; i < 3; ++i) {
        EXPECT_NEAR(w[i], cpp.world_p_tool[i], test::kTolRoundTrip) << m.name << " pose " << k;
        EXPECT_NEAR(w[i], truth.world_p_tool[i], test::kTolRoundTrip) << m.name << " pose " << k;
      }
      EXPECT_EQ(w[3], joints.c);
      EXPECT_EQ(w[4], joints.a);
      // IK of the FK's world pose from the FK's state gives the joints back.
      pkm_exechon_inverse(&p, &state, w, 0.0, back);
      for (int i = 0; i < 5; ++i) EXPECT_NEAR(back[i], q[i], test::kTolRoundTrip);
    }
  }
}

TEST(ExechonCore, ConditionNumberIsTheLibrarys) {
  std::mt19937 rng(test::kSeed + 2);
  for (const io::ExechonMachine& machine : builtinExechons()) {
    const pkm_exechon_params p = parametersOf(machine);
    ExechonData data(machine.model);
    for (int k = 0; k < kRandomPoses; ++k) {
      const ExechonConfiguration config = randomConfiguration(rng, machine.model);
      kinematics::evaluateConfiguration(machine.model, data, config);
      kinematics::computeTripodJacobian(machine.model, data);
      const double expected = kinematics::tripodConditionNumber(data);
      const double e[3] = {config.e[0], config.e[1], config.e[2]};
      EXPECT_NEAR(pkm_exechon_condition(&p, e), expected, test::kTolRoundTrip * expected);
    }
  }
}

/// The mxt700s-like machine with leg B's base-joint offsets (solved by Newton in both codes).
io::ExechonMachine machineWithLegBOffsets() {
  io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  machine.model.tripod.l12B = 7.5;
  machine.model.tripod.l23B = -4.0;
  machine.model.validate();
  return machine;
}

TEST(ExechonCore, LegBOffsetsMatchTheLibrary) {
  const io::ExechonMachine machine = machineWithLegBOffsets();
  const ExechonModel& m = machine.model;
  const pkm_exechon_params p = parametersOf(machine);
  std::mt19937 rng(test::kSeed + 3);
  ExechonData truth(m);
  for (int k = 0; k < kRandomPoses / 4; ++k) {
    const ExechonConfiguration config = randomConfiguration(rng, m);
    kinematics::evaluateConfiguration(m, truth, config);
    const Eigen::Vector3d t = truth.world_p_tool;
    const double world[5] = {t.x(), t.y(), t.z(), config.c, config.a};
    double q[5], w[5];
    pkm_exechon_state state = homeState(m);
    pkm_exechon_inverse(&p, &state, world, 0.0, q);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(q[i], truth.readings[i], test::kTolRoundTrip);
    state = homeState(m);
    ASSERT_EQ(pkm_exechon_forward(&p, &state, q, 0.0, w, nullptr), PKM_EXECHON_OK);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i], t[i], test::kTolRoundTrip);
    const double e[3] = {config.e[0], config.e[1], config.e[2]};
    kinematics::computeTripodJacobian(m, truth);
    const double cond = kinematics::tripodConditionNumber(truth);
    EXPECT_NEAR(pkm_exechon_condition(&p, e), cond, test::kTolRoundTrip * cond);
  }
}

TEST(ExechonCore, ToolLengthOffsetAddsToTheMachinesToolLength) {
  io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  const pkm_exechon_params p = parametersOf(machine);
  constexpr double kG43 = 37.5;
  machine.model.wrist.tool_length += kG43;
  std::mt19937 rng(test::kSeed + 4);
  ExechonData longer(machine.model);
  for (int k = 0; k < 20; ++k) {
    const ExechonConfiguration config = randomConfiguration(rng, machine.model);
    kinematics::evaluateConfiguration(machine.model, longer, config);
    const Eigen::Vector3d t = longer.world_p_tool;
    const double world[5] = {t.x(), t.y(), t.z(), config.c, config.a};
    double q[5], w[5];
    pkm_exechon_state state = homeState(machine.model);
    pkm_exechon_inverse(&p, &state, world, kG43, q);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(q[i], longer.readings[i], test::kTolRoundTrip);
    ASSERT_EQ(pkm_exechon_forward(&p, &state, q, kG43, w, nullptr), PKM_EXECHON_OK);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i], t[i], test::kTolRoundTrip);
  }
}

TEST(ExechonCore, BranchIsKeptAlongAPath) {
  for (const io::ExechonMachine& machine : builtinExechons()) {
    const ExechonModel& m = machine.model;
    const pkm_exechon_params p = parametersOf(machine);
    ExechonData data(m), cpp(m);
    kinematics::evaluateConfiguration(m, data, m.home);
    const Eigen::Vector3d start = data.world_p_tool;
    const double L = m.characteristicLength();
    pkm_exechon_state state{{0, 0, 0}, 0};  // the first point starts from home
    Eigen::Vector3d previous = m.home.e;
    constexpr int kSteps = 400;
    for (int k = 0; k <= kSteps; ++k) {  // a helix with the wrist turning
      const double s = static_cast<double>(k) / kSteps;
      const Eigen::Vector3d t =
          start + 0.08 * L * Eigen::Vector3d(std::cos(6.0 * s) - 1.0, std::sin(6.0 * s), 0.5 * s);
      const double c = degToRad(-120.0 + 240.0 * s), a = degToRad(-30.0 + 20.0 * s);
      const double world[5] = {t.x(), t.y(), t.z(), c, a};
      double q[5];
      const pkm_exechon_status st = pkm_exechon_inverse(&p, &state, world, 0.0, q);
      ASSERT_TRUE(st == PKM_EXECHON_OK || st == PKM_EXECHON_OUT_OF_RANGE) << m.name << " " << k;
      ASSERT_EQ(kinematics::toolPointInverseKinematics(m, cpp, t, c, a, previous),
                kinematics::ExechonIkStatus::kOk);
      for (int i = 0; i < 3; ++i) EXPECT_NEAR(q[i], cpp.readings[i], test::kTolRoundTrip);
      if (st != PKM_EXECHON_OK) continue;  // a rejected pose leaves the branch state
      const Eigen::Vector3d e(state.e[0], state.e[1], state.e[2]);
      EXPECT_LT((e - cpp.e).norm(), test::kTolRoundTrip);
      if (k > 0)  // the first point (wrist away from home) is a jump; then small steps
        EXPECT_LT(std::abs(e[0] - previous[0]) + std::abs(e[1] - previous[1]), degToRad(2.0))
            << m.name << " point " << k;
      kinematics::evaluateConfiguration(m, data, {e, c, a});
      EXPECT_EQ(data.branch, kinematics::branchOf(m.tripod)) << m.name << " point " << k;
      previous = e;
    }
  }
}

TEST(ExechonCore, OutOfRangeIsReportedNotClamped) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  const ExechonModel& m = machine.model;
  const pkm_exechon_params p = parametersOf(machine);
  ExechonData data(m);
  ExechonConfiguration far = m.home;
  far.e[2] += 500.0;  // the legs pass their 700 mm stroke
  kinematics::evaluateConfiguration(m, data, far);
  const kinematics::ExechonCheckResult check = kinematics::checkConfiguration(m, data);
  ASSERT_EQ(check.status(), "stroke");
  const Eigen::Vector3d t = data.world_p_tool;
  const double world[5] = {t.x(), t.y(), t.z(), far.c, far.a};
  double q[5];
  pkm_exechon_state state = homeState(m);
  EXPECT_EQ(pkm_exechon_inverse(&p, &state, world, 0.0, q), PKM_EXECHON_OUT_OF_RANGE);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(q[i], data.readings[i], test::kTolRoundTrip);
  EXPECT_GT(std::max({q[0], q[1], q[2]}),
            p.stroke_max[0]);  // the true reading, not the stroke's end
  // At home, only the wrist C reading outside its range.
  kinematics::evaluateConfiguration(m, data, m.home);
  const Eigen::Vector3d h = data.world_p_tool;
  const double beyond[5] = {h.x(), h.y(), h.z(), p.c_range[1] + 0.1, m.home.a};
  state = homeState(m);
  EXPECT_EQ(pkm_exechon_inverse(&p, &state, beyond, 0.0, q), PKM_EXECHON_OUT_OF_RANGE);
  EXPECT_EQ(q[3], p.c_range[1] + 0.1);
  const double inside[5] = {h.x(), h.y(), h.z(), p.c_range[1] - 0.1, m.home.a};
  EXPECT_EQ(pkm_exechon_inverse(&p, &state, inside, 0.0, q), PKM_EXECHON_OK);
}

TEST(ExechonCore, UnreachableAndInvalidInputsFailAndLeaveTheState) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  const pkm_exechon_params p = parametersOf(machine);
  pkm_exechon_state state = homeState(machine.model);
  const pkm_exechon_state before = state;
  double q[5] = {1, 2, 3, 4, 5}, w[5];
  const double far[5] = {1e6, 0.0, 0.0, 0.0, 0.0};
  const pkm_exechon_status st = pkm_exechon_inverse(&p, &state, far, 0.0, q);
  EXPECT_TRUE(st == PKM_EXECHON_NO_CONVERGENCE || st == PKM_EXECHON_SINGULAR)
      << pkm_exechon_status_name(st);
  EXPECT_EQ(q[0], 1.0);
  EXPECT_EQ(state.e[2], before.e[2]);
  const double nan_world[5] = {NAN, 0.0, 0.0, 0.0, 0.0};
  EXPECT_EQ(pkm_exechon_inverse(&p, &state, nan_world, 0.0, q), PKM_EXECHON_INVALID_INPUT);
  const double nan_joints[5] = {0.0, NAN, 0.0, 0.0, 0.0};
  EXPECT_EQ(pkm_exechon_forward(&p, &state, nan_joints, 0.0, w, nullptr),
            PKM_EXECHON_INVALID_INPUT);
  EXPECT_STREQ(pkm_exechon_status_name(PKM_EXECHON_OUT_OF_RANGE), "out_of_range");
}

TEST(ExechonCore, SingularIsReportedAtTheConditionLimit) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  pkm_exechon_params p = parametersOf(machine);
  ExechonData data(machine.model);
  kinematics::evaluateConfiguration(machine.model, data, machine.model.home);
  kinematics::computeTripodJacobian(machine.model, data);
  const double cond = kinematics::tripodConditionNumber(data);
  const Eigen::Vector3d t = data.world_p_tool;
  const double world[5] = {t.x(), t.y(), t.z(), machine.model.home.c, machine.model.home.a};
  double q[5];
  pkm_exechon_state state = homeState(machine.model);
  p.max_condition = cond * (1.0 - 1e-6);
  EXPECT_EQ(pkm_exechon_inverse(&p, &state, world, 0.0, q), PKM_EXECHON_SINGULAR);
  p.max_condition = cond * (1.0 + 1e-6);
  EXPECT_EQ(pkm_exechon_inverse(&p, &state, world, 0.0, q), PKM_EXECHON_OK);
}

TEST(ExechonCore, BadParameterFilesAreRejectedWithTheReason) {
  const io::ExechonMachine machine = io::loadExechonMachine("mxt700s-like");
  const std::string good = io::linuxcncExechonParameters(machine);
  pkm_exechon_params p{};
  char why[256] = "";
  const auto reject = [&](const std::string& text) {
    why[0] = '\0';
    EXPECT_EQ(pkm_exechon_parse_params(text.c_str(), &p, why, sizeof why), -1);
    return std::string(why);
  };
  EXPECT_EQ(reject(good.substr(0, good.find("tool_length"))), "missing tool_length");
  EXPECT_NE(reject(good + "dX 1\n").find("unknown parameter 'dX'"), std::string::npos);
  EXPECT_NE(reject(good + "dA 1\n").find("dA given twice"), std::string::npos);
  std::string bad = good;
  bad.replace(bad.find("\ndB "), 4, "\ndB 0 #");
  EXPECT_EQ(reject(bad), "tripod: dB must be != 0");
  std::string short_line = good;
  short_line.replace(short_line.find("\nc_axis "), 8, "\nc_axis 1 #");
  EXPECT_NE(reject(short_line).find("c_axis needs 3 number(s)"), std::string::npos);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
