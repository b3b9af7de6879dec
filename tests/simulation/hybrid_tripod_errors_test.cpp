// HybridTripod: tripod parameter errors of the hybrid machine's Exechon PKM as a TCP error motion.
#include "pkm/simulation/hybrid_tripod_errors.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "pkm/core/error.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "pkm/io/machine_loader.hpp"
#include "pkm/kinematics/exechon_data.hpp"
#include "pkm/kinematics/exechon_wrist.hpp"
#include "pkm/simulation/compliance.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
using pkm::simulation::ExechonTripodErrors;
using pkm::simulation::HybridTripod;

/// Central-difference steps for the independent first-order prediction (rad for alpha, beta; mm
/// for h).
constexpr double kStepAngle = 1e-5;
constexpr double kStepLength = 1e-3;
/// Injected leg length offset error, mm (a realistic calibration residue).
constexpr double kLegError = 0.01;
/// Relative agreement of the exact error with its first-order prediction: the remainder is
/// O(δ/L): measured at most 2e-5 relative on the shipped machine; 1e-4 leaves a margin of 5.
constexpr double kTolFirstOrder = 1e-4;
/// Tripod FK settles to FkOptions::tolerance (1e-9 mm); the error motion of zero errors is this
/// small.
constexpr double kTolFk = 1e-8;

pkm::io::ExechonMachine machine() { return pkm::io::loadExechonMachine("mxt700s-like"); }

/// PKM commands spread over the shipped machine's working volume ([-300, 300]² × [-100, 300] mm).
std::vector<Eigen::Vector3d> commands() {
  return {{0, 0, 0}, {250, -200, 280}, {-280, 260, -90}, {100, 290, 150}, {-300, -300, 300}};
}

double rotationAngle(const pkm::geometry::RigidTransform& e) {
  return Eigen::AngleAxisd(e.rotation()).angle();
}

TEST(HybridTripod, ZeroErrorsGiveNoErrorMotion) {
  const pkm::io::ExechonMachine m = machine();
  const HybridTripod tripod(m.model, {}, m.fk);
  for (const Eigen::Vector3d& p : commands()) {
    const pkm::geometry::RigidTransform e = tripod.errorMotion(p);
    EXPECT_LT(e.translation().norm(), kTolFk) << p.transpose();
    EXPECT_LT(rotationAngle(e), kTolFk) << p.transpose();
  }
}

TEST(HybridTripod, ToolLengthErrorMovesTheTcpAlongTheTool) {
  // Same legs and wrist, so the true tool point is S + (L + δL)·u with u = −z: exactly −δL·z.
  const pkm::io::ExechonMachine m = machine();
  ExechonTripodErrors errors;
  errors.tool_length = 0.05;
  const HybridTripod tripod(m.model, errors, m.fk);
  for (const Eigen::Vector3d& p : commands()) {
    const pkm::geometry::RigidTransform e = tripod.errorMotion(p);
    EXPECT_NEAR((e.translation() - Eigen::Vector3d(0, 0, -errors.tool_length)).norm(), 0.0, kTolFk);
    EXPECT_LT(rotationAngle(e), kTolFk);
  }
}

/// Tool point and leg lengths of the nominal model at configuration `c` (evaluateConfiguration).
void evaluate(const kin::ExechonModel& model,
              const kin::ExechonConfiguration& c,
              Eigen::Vector3d* tool,
              Eigen::Vector3d* lengths) {
  kin::ExechonData d(model);
  kin::evaluateConfiguration(model, d, c);
  *tool = d.world_p_tool;
  *lengths = d.lengths;
}

TEST(HybridTripod, LegOffsetErrorMatchesTheFirstOrderPrediction) {
  // Independent prediction: central differences over e = (alpha, beta, h) of the nominal tool point
  // and leg lengths give J_p_e and J_q_e; a leg that is δ longer at the same reading moves e by
  // J_q_e⁻¹·δ·e_i and the tool by J_p_e·J_q_e⁻¹·δ·e_i (C, A fixed).
  const pkm::io::ExechonMachine m = machine();
  for (const Eigen::Vector3d& p : commands()) {
    kin::ExechonData nominal(m.model);
    ASSERT_EQ(kin::toolInverseKinematics(m.model, nominal, {p, -Eigen::Vector3d::UnitZ()}),
              kin::ExechonIkStatus::kOk);
    const kin::ExechonConfiguration c0 = kin::configurationOf(nominal);
    Eigen::Matrix3d J_p_e;
    Eigen::Matrix3d J_q_e;
    for (int k = 0; k < 3; ++k) {
      const double h = k < 2 ? kStepAngle : kStepLength;
      kin::ExechonConfiguration plus = c0;
      kin::ExechonConfiguration minus = c0;
      plus.e[k] += h;
      minus.e[k] -= h;
      Eigen::Vector3d tp, tm, qp, qm;
      evaluate(m.model, plus, &tp, &qp);
      evaluate(m.model, minus, &tm, &qm);
      J_p_e.col(k) = (tp - tm) / (2 * h);
      J_q_e.col(k) = (qp - qm) / (2 * h);
    }
    for (int leg = 0; leg < 3; ++leg) {
      ExechonTripodErrors errors;
      errors.length_offset[leg] = kLegError;
      const HybridTripod tripod(m.model, errors, m.fk);
      const Eigen::Vector3d exact = tripod.errorMotion(p).translation();
      const Eigen::Vector3d predicted =
          J_p_e * J_q_e.partialPivLu().solve(Eigen::Vector3d::Unit(leg) * kLegError);
      EXPECT_GT(exact.norm(), 0.1 * kLegError) << "leg " << leg;
      EXPECT_LT((exact - predicted).norm(), kTolFirstOrder * exact.norm())
          << "leg " << leg << " at " << p.transpose() << ": exact " << exact.transpose()
          << " predicted " << predicted.transpose();
    }
  }
}

TEST(HybridTripod, ErrorMotionIsLinearForSmallErrors) {
  // Doubling a geometric error doubles the error motion to first order (a second check of the
  // first-order behaviour for a parameter without a closed form).
  const pkm::io::ExechonMachine m = machine();
  ExechonTripodErrors one;
  one.dB = 0.02;
  one.pC = -0.015;
  one.c0 = 20e-6;
  ExechonTripodErrors two = one;
  two.dB *= 2;
  two.pC *= 2;
  two.c0 *= 2;
  const HybridTripod t1(m.model, one, m.fk);
  const HybridTripod t2(m.model, two, m.fk);
  for (const Eigen::Vector3d& p : commands()) {
    const Eigen::Vector3d d1 = t1.errorMotion(p).translation();
    const Eigen::Vector3d d2 = t2.errorMotion(p).translation();
    EXPECT_GT(d1.norm(), 0.0);
    EXPECT_LT((d2 - 2 * d1).norm(), kTolFirstOrder * d2.norm()) << p.transpose();
  }
}

TEST(HybridTripod, IsDeterministic) {
  const pkm::io::ExechonMachine m = machine();
  ExechonTripodErrors errors;
  errors.length_offset = {0.01, -0.02, 0.015};
  errors.hz = 0.03;
  errors.a0 = -15e-6;
  const HybridTripod a(m.model, errors, m.fk);
  const HybridTripod b(m.model, errors, m.fk);
  for (const Eigen::Vector3d& p : commands()) {
    EXPECT_TRUE(a.errorMotion(p).matrix() == b.errorMotion(p).matrix());
    EXPECT_TRUE(a.errorMotion(p).matrix() == a.errorMotion(p).matrix());
  }
}

TEST(HybridTripod, ALegLeadErrorActsAsALengthErrorOfItsValueAtTheReading) {
  // A lead error that is the same at every reading (a wave 10⁹ mm long at its crest) is a leg that
  // travels kLegError further than its reading: the tripod with that length offset error.
  const pkm::io::ExechonMachine m = machine();
  pkm::simulation::ExechonLegLeadErrors lead{};
  lead[1].wave_amplitude = kLegError;
  lead[1].wave_length = 1e9;
  lead[1].wave_phase = std::numbers::pi / 2;
  HybridTripod with_lead(m.model, {}, m.fk);
  with_lead.setLegLeadErrors(lead);
  ExechonTripodErrors errors;
  errors.length_offset = {0.0, kLegError, 0.0};
  const HybridTripod with_offset(m.model, errors, m.fk);
  for (const Eigen::Vector3d& p : commands()) {
    const pkm::geometry::RigidTransform a = with_lead.errorMotion(p);
    const pkm::geometry::RigidTransform b = with_offset.errorMotion(p);
    EXPECT_GT(b.translation().norm(), 1e-3) << p.transpose();  // the error is visible
    EXPECT_LT((a.translation() - b.translation()).norm(), kTolFk) << p.transpose();
    EXPECT_LT(rotationAngle(a.inverse() * b), kTolFk) << p.transpose();
  }
  lead[0].lead = 0.0;
  EXPECT_THROW(with_lead.setLegLeadErrors(lead), pkm::InvalidArgument);
}

TEST(HybridTripod, PerturbedModelAddsTheErrors) {
  const pkm::io::ExechonMachine m = machine();
  ExechonTripodErrors errors;
  errors.dA = 0.1;
  errors.hx = -0.2;
  errors.l12B = 0.6;
  errors.length_offset = {0.3, 0.0, -0.4};
  errors.tool_length = 0.5;
  const kin::ExechonModel t = pkm::simulation::perturbedExechon(m.model, errors);
  EXPECT_EQ(t.tripod.dA, m.model.tripod.dA + 0.1);
  EXPECT_EQ(t.tripod.hx, m.model.tripod.hx - 0.2);
  EXPECT_EQ(t.tripod.l12B, m.model.tripod.l12B + 0.6);
  EXPECT_EQ(t.tripod.l23B, m.model.tripod.l23B);
  EXPECT_EQ(t.legs[0].length_offset, m.model.legs[0].length_offset + 0.3);
  EXPECT_EQ(t.legs[2].length_offset, m.model.legs[2].length_offset - 0.4);
  EXPECT_EQ(t.wrist.tool_length, m.model.wrist.tool_length + 0.5);
  EXPECT_EQ(t.tripod.dB, m.model.tripod.dB);
  EXPECT_TRUE(ExechonTripodErrors{}.isZero());
  EXPECT_FALSE(errors.isZero());
}

TEST(HybridTripod, RejectsBadInput) {
  const pkm::io::ExechonMachine m = machine();
  ExechonTripodErrors nan;
  nan.pB = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(HybridTripod(m.model, nan, m.fk), pkm::InvalidArgument);
  ExechonTripodErrors degenerate;
  degenerate.dB = -m.model.tripod.dB;  // dB = 0: no tripod
  EXPECT_THROW(HybridTripod(m.model, degenerate, m.fk), pkm::InvalidArgument);
  const HybridTripod tripod(m.model, {}, m.fk);
  EXPECT_THROW((void)tripod.errorMotion(Eigen::Vector3d(0, std::nan(""), 0)), pkm::InvalidArgument);
}

/// The realistic Exechon head: 250 kg, 200 mm up the tool axis from the tool point.
pkm::simulation::ExechonCompliance head() {
  pkm::simulation::ExechonCompliance c;
  c.head_mass_kg = 250.0;
  c.head_com_mm = {0, 0, 200};
  c.leg_stiffness_n_per_um = 50.0;
  return c;
}

/// The nominal model's joints for a vertical tool at the PKM command `p`, and its data.
kin::ExechonJoints jointsAt(const kin::ExechonModel& model,
                            kin::ExechonData& data,
                            const Eigen::Vector3d& p) {
  kin::ExechonToolPose target;
  target.position = p;
  target.direction = -Eigen::Vector3d::UnitZ();
  EXPECT_EQ(kin::toolInverseKinematics(model, data, target), kin::ExechonIkStatus::kOk);
  return kin::jointsOf(data);
}

/// Height of the head's centre of mass at the tool FK for `joints`, mm.
double comHeight(const pkm::io::ExechonMachine& m,
                 const kin::ExechonJoints& joints,
                 const kin::ExechonConfiguration& seed,
                 const Eigen::Vector3d& com) {
  kin::ExechonData d(m.model);
  EXPECT_TRUE(kin::toolForwardKinematics(m.model, d, joints, seed, m.fk).ok());
  return (d.world_p_tool + d.world_R_tool * com).z();
}

TEST(ExechonCompliance, LegLoadsDoTheVirtualWorkOfTheHeadsWeight) {
  // Along any leg motion Δq, Σ C_i·Δq_i = m·g·Δz_c (the joints' constraint forces do no work):
  // checked along a direction that mixes the legs, by central differences of the FK.
  const pkm::io::ExechonMachine m = machine();
  const pkm::simulation::ExechonCompliance c = head();
  kin::ExechonData data(m.model);
  for (const Eigen::Vector3d& p : commands()) {
    const kin::ExechonJoints q = jointsAt(m.model, data, p);
    const kin::ExechonConfiguration seed = kin::configurationOf(data);
    const Eigen::Vector3d loads = pkm::simulation::exechonLegLoads(m.model, q, seed, m.fk, c);
    const Eigen::Vector3d dq = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    const double eps = 1e-3;
    kin::ExechonJoints plus = q, minus = q;
    plus.readings += eps * dq;
    minus.readings -= eps * dq;
    const double work =
        c.head_mass_kg * pkm::simulation::kStandardGravity *
        (comHeight(m, plus, seed, c.head_com_mm) - comHeight(m, minus, seed, c.head_com_mm)) /
        (2 * eps);
    EXPECT_NEAR(loads.dot(dq), work, 1e-2) << p.transpose();  // N; loads are hundreds of N
  }
}

TEST(ExechonCompliance, HeadDropsByTheEnergyOfTheLegsSpringsAndClearance) {
  // δq_i = −C_i/k − c·sgn(C_i), so to first order Δz_c = Σ (∂z_c/∂q_i)·δq_i
  // = −Σ C_i²/(k·m·g) − c·Σ|C_i|/(m·g) (∂z_c/∂q_i = C_i/(m·g)).
  const pkm::io::ExechonMachine m = machine();
  pkm::simulation::ExechonCompliance c = head();
  c.joint_clearance_mm = 4e-3;
  kin::ExechonData data(m.model);
  const double mg = c.head_mass_kg * pkm::simulation::kStandardGravity;
  for (const Eigen::Vector3d& p : commands()) {
    const kin::ExechonJoints q = jointsAt(m.model, data, p);
    const kin::ExechonConfiguration seed = kin::configurationOf(data);
    const Eigen::Vector3d loads = pkm::simulation::exechonLegLoads(m.model, q, seed, m.fk, c);
    const kin::ExechonJoints sagged =
        pkm::simulation::exechonDeflectedJoints(m.model, q, seed, m.fk, c);
    const double drop =
        comHeight(m, sagged, seed, c.head_com_mm) - comHeight(m, q, seed, c.head_com_mm);
    const double expected = -loads.squaredNorm() / (1e3 * c.leg_stiffness_n_per_um * mg) -
                            c.joint_clearance_mm * loads.cwiseAbs().sum() / mg;
    EXPECT_NEAR(drop, expected, 1e-3 * std::abs(expected)) << p.transpose();
  }
  // The tripod's error motion sees it: micrometres at the tool.
  HybridTripod tripod(m.model, {}, m.fk);
  const Eigen::Vector3d p(100, -50, 120);
  const pkm::geometry::RigidTransform rigid = tripod.errorMotion(p);
  tripod.setCompliance(c);
  ASSERT_TRUE(tripod.compliance().has_value());
  EXPECT_GT((tripod.errorMotion(p).translation() - rigid.translation()).norm(), 1e-3);
  c.leg_stiffness_n_per_um = -1.0;
  EXPECT_THROW(tripod.setCompliance(c), pkm::InvalidArgument);
}

}  // namespace PKM_TEST_NS
