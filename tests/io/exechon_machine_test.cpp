// Tests of the Exechon machine JSON reader and writer (pkm/io/exechon_machine.hpp): the shipped
// files, the paper's numeric example and the write -> parse round trip. The defaults of a minimal
// file and the "FILE:LINE: /pointer:" errors are in exechon_machine_errors_test.cpp.
#include "pkm/io/exechon_machine.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "io/exechon_machine_sample.hpp"
#include "kinematics/exechon_sample_models.hpp"
#include "pkm/core/units.hpp"
#include "pkm/geometry/rigid_transform.hpp"
#include "pkm/kinematics/exechon_ik.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
using pkm::io::ExechonMachine;
using pkm::io::JointRateSpec;
using pkm::io::parseExechonJson;
using pkm::io::readExechonJson;
using pkm::io::writeExechonJson;
using pkm::test::kTolExact;
using pkm::test::exechon_json::at;
using pkm::test::exechon_json::errorOf;
using pkm::test::exechon_json::kLines;
using pkm::test::exechon_json::kSource;
using pkm::test::exechon_json::text;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// Relative tolerance of an angle written in degrees and read back in radians (a few ulp).
constexpr double kTolAngleRoundTrip = 1e-12;
/// Zoppi et al. 2010 Table 2 prints the leg lengths with 4 decimals (m × 1000 here: 0.1 mm / 100).
constexpr double kTolPaperLength = 1e-3;
constexpr double kInf = std::numeric_limits<double>::infinity();

/// Zoppi et al. (DETC2010-28668) numeric example: wrist point and the (+,+,+,+) leg lengths, mm.
const Eigen::Vector3d kZoppiS(20, 700, 1020);
const Eigen::Vector3d kZoppiQ(1633.1243, 1491.8367, 912.2380);

std::string machineFile(const char* stem) {
  return std::string(PKM_SOURCE_DIR) + "/data/machines/" + stem + ".json";
}

void expectNearRelative(double a, double b, double rel) {
  if (std::isinf(a) || std::isinf(b)) {
    EXPECT_EQ(a, b);
    return;
  }
  EXPECT_NEAR(a, b, rel * std::max(std::abs(a), std::abs(b))) << a << " vs " << b;
}

void expectSameRange(const kin::AngleRange& a, const kin::AngleRange& b) {
  expectNearRelative(a.min, b.min, kTolAngleRoundTrip);
  expectNearRelative(a.max, b.max, kTolAngleRoundTrip);
}

/// Everything a machine file holds: lengths exactly, angles to kTolAngleRoundTrip.
void expectSameMachine(const ExechonMachine& a, const ExechonMachine& b) {
  const kin::ExechonModel& m = a.model;
  const kin::ExechonModel& n = b.model;
  EXPECT_EQ(m.name, n.name);
  EXPECT_EQ(a.description, b.description);
  EXPECT_EQ(m.unit, n.unit);
  const kin::ExechonTripodGeometry& g = m.tripod;
  const kin::ExechonTripodGeometry& h = n.tripod;
  EXPECT_EQ(g.dA, h.dA);
  EXPECT_EQ(g.dB, h.dB);
  EXPECT_EQ(g.dC, h.dC);
  EXPECT_EQ(g.l12A, h.l12A);
  EXPECT_EQ(g.l12C, h.l12C);
  EXPECT_EQ(g.l12B, h.l12B);
  EXPECT_EQ(g.l23B, h.l23B);
  EXPECT_EQ(g.pA, h.pA);
  EXPECT_EQ(g.pB, h.pB);
  EXPECT_EQ(g.pC, h.pC);
  EXPECT_EQ(g.hA, h.hA);
  EXPECT_EQ(g.hC, h.hC);
  EXPECT_EQ(g.hx, h.hx);
  EXPECT_EQ(g.hz, h.hz);
  EXPECT_EQ(kin::branchOf(g), kin::branchOf(h));
  for (std::size_t i = 0; i < m.legs.size(); ++i) {
    SCOPED_TRACE(i);
    EXPECT_EQ(m.legs[i].length_offset, n.legs[i].length_offset);
    EXPECT_EQ(m.legs[i].min_reading, n.legs[i].min_reading);
    EXPECT_EQ(m.legs[i].max_reading, n.legs[i].max_reading);
  }
  expectSameRange(m.limits.alpha, n.limits.alpha);
  expectSameRange(m.limits.beta, n.limits.beta);
  expectSameRange(m.limits.c, n.limits.c);
  expectSameRange(m.limits.a, n.limits.a);
  EXPECT_EQ(m.wrist.c_axis, n.wrist.c_axis);
  EXPECT_EQ(m.wrist.a_axis, n.wrist.a_axis);
  expectNearRelative(m.wrist.c0, n.wrist.c0, kTolAngleRoundTrip);
  expectNearRelative(m.wrist.a0, n.wrist.a0, kTolAngleRoundTrip);
  EXPECT_EQ(m.wrist.c_sign, n.wrist.c_sign);
  EXPECT_EQ(m.wrist.a_sign, n.wrist.a_sign);
  EXPECT_EQ(m.wrist.tool_length, n.wrist.tool_length);
  EXPECT_EQ(m.world_T_zoppi.translation(), n.world_T_zoppi.translation());
  EXPECT_LT((m.world_T_zoppi.linear() - n.world_T_zoppi.linear()).cwiseAbs().maxCoeff(), kTolExact);
  for (int k = 0; k < 2; ++k) expectNearRelative(m.home.e[k], n.home.e[k], kTolAngleRoundTrip);
  EXPECT_EQ(m.home.e[2], n.home.e[2]);
  expectNearRelative(m.home.c, n.home.c, kTolAngleRoundTrip);
  expectNearRelative(m.home.a, n.home.a, kTolAngleRoundTrip);
  EXPECT_EQ(m.max_condition, n.max_condition);
  EXPECT_EQ(a.fk.tolerance, b.fk.tolerance);
  EXPECT_EQ(a.fk.max_iterations, b.fk.max_iterations);
  ASSERT_EQ(a.hybrid.has_value(), b.hybrid.has_value());
  if (a.hybrid) {
    const kin::HybridMachineModel& x = *a.hybrid;
    const kin::HybridMachineModel& y = *b.hybrid;
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.unit, y.unit);
    EXPECT_EQ(x.x2_stroke.min, y.x2_stroke.min);
    EXPECT_EQ(x.x2_stroke.max, y.x2_stroke.max);
    EXPECT_EQ(x.y2_stroke.min, y.y2_stroke.min);
    EXPECT_EQ(x.y2_stroke.max, y.y2_stroke.max);
    EXPECT_EQ(x.pkm_min, y.pkm_min);
    EXPECT_EQ(x.pkm_max, y.pkm_max);
    EXPECT_EQ(x.X2_p_P, y.X2_p_P);
    EXPECT_EQ(x.P_p_tcp0, y.P_p_tcp0);
    EXPECT_EQ(x.Y2_p_work, y.Y2_p_work);
  }
}

ExechonMachine roundTrip(const ExechonMachine& m) {
  return parseExechonJson(writeExechonJson(m), "round-trip.json");
}

// ---------------------------------------------------------------------------------------------
// The shipped machine files

TEST(ExechonMachineJson, ReadsZoppiFile) {
  const std::string path = machineFile("exechon-zoppi2010");
  const ExechonMachine m = readExechonJson(path);
  EXPECT_EQ(m.source, path);
  EXPECT_EQ(m.model.name, "exechon-zoppi2010");
  EXPECT_THAT(m.description, HasSubstr("Zoppi"));
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kMillimetre);
  EXPECT_FALSE(m.hybrid.has_value());
  EXPECT_TRUE(m.notices.empty());
  // Table 1 of the paper (in mm), as the kinematics tests build it in code.
  const kin::ExechonModel ref = pkm::test::zoppiTable1Model();
  EXPECT_EQ(m.model.tripod.dA, ref.tripod.dA);
  EXPECT_EQ(m.model.tripod.dB, ref.tripod.dB);
  EXPECT_EQ(m.model.tripod.dC, ref.tripod.dC);
  EXPECT_EQ(m.model.tripod.l12A, ref.tripod.l12A);
  EXPECT_EQ(m.model.tripod.l12C, ref.tripod.l12C);
  EXPECT_EQ(m.model.tripod.pA, ref.tripod.pA);
  EXPECT_EQ(m.model.tripod.pB, ref.tripod.pB);
  EXPECT_EQ(m.model.tripod.pC, ref.tripod.pC);
  EXPECT_EQ(m.model.tripod.hA, ref.tripod.hA);
  EXPECT_EQ(m.model.tripod.hC, ref.tripod.hC);
  EXPECT_EQ(m.model.tripod.hx, ref.tripod.hx);
  EXPECT_EQ(m.model.tripod.hz, ref.tripod.hz);
  EXPECT_EQ(kin::branchOf(m.model.tripod), (kin::ExechonBranch{1, 1, 1, 1}));
  // No strokes, limits, wrist or placement in the paper: the defaults (unbounded, identity).
  for (const kin::ExechonLeg& leg : m.model.legs) {
    EXPECT_EQ(leg.length_offset, 0.0);
    EXPECT_EQ(leg.min_reading, -kInf);
    EXPECT_EQ(leg.max_reading, kInf);
  }
  EXPECT_EQ(m.model.limits.alpha.min, -kInf);
  EXPECT_EQ(m.model.limits.a.max, kInf);
  EXPECT_EQ(m.model.wrist.tool_length, 0.0);
  EXPECT_TRUE(m.model.world_T_zoppi.isApprox(pkm::geometry::RigidTransform::Identity(), 0.0));
  EXPECT_EQ(m.fk.tolerance, 1e-9);
  EXPECT_EQ(m.fk.max_iterations, 120);
  // The home is the paper's solution for S = (20, 700, 1020).
  for (int k = 0; k < 3; ++k)
    expectNearRelative(m.model.home.e[k], ref.home.e[k], kTolAngleRoundTrip);
}

TEST(ExechonMachineJson, ZoppiHomeReproducesThePaper) {
  const ExechonMachine m = readExechonJson(machineFile("exechon-zoppi2010"));
  kin::ExechonData data(m.model);
  ASSERT_EQ(kin::tripodInverseKinematics(m.model, data, kZoppiS), kin::ExechonIkStatus::kOk);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(data.lengths[i], kZoppiQ[i], kTolPaperLength) << i;
  // No length offsets: readings are the geometric lengths.
  EXPECT_EQ(data.readings, data.lengths);
  // The file's home (alpha, beta, h) is that solution.
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(data.e[k], m.model.home.e[k], kTolExact) << k;
  EXPECT_NEAR(data.e[2], m.model.home.e[2], kTolExact * m.model.home.e[2]);
  EXPECT_TRUE(data.world_p_S.isApprox(kZoppiS, kTolExact));
}

TEST(ExechonMachineJson, ReadsMxt700sLikeFile) {
  const std::string path = machineFile("mxt700s-like");
  const ExechonMachine m = readExechonJson(path);
  EXPECT_EQ(m.model.name, "mxt700s-like");
  EXPECT_THAT(m.description, HasSubstr("ILLUSTRATIVE"));
  EXPECT_EQ(m.model.tripod.hx, 0.0);
  EXPECT_EQ(m.model.tripod.hz, 250.0);
  EXPECT_EQ(m.model.legs[0].length_offset, 631.8455);
  EXPECT_EQ(m.model.legs[1].length_offset, 672.4537);
  EXPECT_EQ(m.model.legs[2].length_offset, 668.0249);
  for (const kin::ExechonLeg& leg : m.model.legs) {
    EXPECT_EQ(leg.min_reading, 0.0);
    EXPECT_EQ(leg.max_reading, 700.0);
  }
  EXPECT_NEAR(m.model.limits.alpha.min, pkm::degToRad(50), kTolExact);
  EXPECT_NEAR(m.model.limits.alpha.max, pkm::degToRad(130), kTolExact);
  EXPECT_NEAR(m.model.limits.beta.min, pkm::degToRad(-45), kTolExact);
  EXPECT_NEAR(m.model.limits.c.max, pkm::degToRad(270), kTolExact);
  EXPECT_NEAR(m.model.limits.a.min, pkm::degToRad(-100), kTolExact);
  EXPECT_EQ(m.model.wrist.c_axis, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(m.model.wrist.a_axis, Eigen::Vector3d::UnitX());
  EXPECT_EQ(m.model.wrist.tool_length, 200.0);
  EXPECT_EQ(m.model.world_T_zoppi.translation(), Eigen::Vector3d(0, -427.5251, 1374.6158));
  // rpy (200°, 0, 0): a rotation about x by 200°.
  const Eigen::Matrix3d Rx200 =
      Eigen::AngleAxisd(pkm::degToRad(200), Eigen::Vector3d::UnitX()).toRotationMatrix();
  EXPECT_LT((m.model.world_T_zoppi.linear() - Rx200).cwiseAbs().maxCoeff(), kTolExact);
  EXPECT_NEAR(m.model.home.e[0], pkm::degToRad(90), kTolExact);
  EXPECT_EQ(m.model.home.e[1], 0.0);
  EXPECT_EQ(m.model.home.e[2], 1000.0);
  EXPECT_EQ(m.model.max_condition, 1000.0);
  ASSERT_TRUE(m.hybrid.has_value());
  const kin::HybridMachineModel& h = *m.hybrid;
  EXPECT_EQ(h.name, "mxt700s-like");
  EXPECT_EQ(h.unit, pkm::LengthUnit::kMillimetre);
  EXPECT_EQ(h.x2_stroke.min, 0.0);
  EXPECT_EQ(h.x2_stroke.max, 4000.0);
  EXPECT_EQ(h.y2_stroke.min, 0.0);
  EXPECT_EQ(h.y2_stroke.max, 450.0);
  EXPECT_EQ(h.pkm_min, Eigen::Vector3d(-300, -300, -100));
  EXPECT_EQ(h.pkm_max, Eigen::Vector3d(300, 300, 300));
  EXPECT_EQ(h.X2_p_P, Eigen::Vector3d::Zero());
  // Home at mid-stroke (the description's "home at mid-stroke"), to the 0.1 µm of the offsets.
  kin::ExechonData data(m.model);
  kin::evaluateTripod(m.model, data, m.model.home.e, 1, 1);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(data.readings[i], 350.0, kTolPaperLength) << i;
}

// ---------------------------------------------------------------------------------------------
// Round trip

TEST(ExechonMachineJson, RoundTripOfShippedFiles) {
  for (const char* stem : {"exechon-zoppi2010", "mxt700s-like"}) {
    SCOPED_TRACE(stem);
    const ExechonMachine m = readExechonJson(machineFile(stem));
    const ExechonMachine back = roundTrip(m);
    expectSameMachine(m, back);
    EXPECT_EQ(back.source, "round-trip.json");
    // Writing is a fixed point after one round.
    EXPECT_EQ(writeExechonJson(back), writeExechonJson(roundTrip(back)));
    // An ideal S joint of leg B is not written (files stay as Zoppi's 12 dimensions).
    EXPECT_EQ(writeExechonJson(back).find("l12B"), std::string::npos);
  }
}

TEST(ExechonMachineJson, RoundTripOfEveryField) {
  // Every field set to a value that is not the default, with awkward decimals and half-open ranges.
  ExechonMachine m;
  m.model = pkm::test::zoppiTable1Model();
  m.model.name = "every \"field\"";
  m.description = "line one\nline two, with a tab\t and unicode \xC2\xB5m";
  m.model.unit = pkm::LengthUnit::kInch;
  m.model.tripod.delta2B = -1;
  m.model.tripod.deltaC = -1;
  m.model.tripod.l12B = 0.123456789;
  m.model.tripod.l23B = -1.0 / 3.0;
  kin::parametersFromWristPoint(m.model.tripod, kZoppiS, 1, -1, &m.model.home.e);
  m.model.legs[0] = {0.1, -12.3456789012345, 987.654321};
  m.model.legs[1] = {1.0 / 3.0, -kInf, 700.0};
  m.model.legs[2] = {-2.5e-7, 1e-3, kInf};
  m.model.limits.alpha = {0.123456789, 2.3456789};
  m.model.limits.beta = {-kInf, 0.7};
  m.model.limits.c = {-4.1, kInf};
  m.model.limits.a = {-1.0 / 7.0, 1.0 / 3.0};
  m.model.wrist.c_axis = Eigen::Vector3d(0, 0.6, 0.8);
  m.model.wrist.a_axis = Eigen::Vector3d(1, 0, 0);
  m.model.wrist.c0 = 0.1;
  m.model.wrist.a0 = -0.7;
  m.model.wrist.c_sign = -1;
  m.model.wrist.a_sign = -1;
  m.model.wrist.tool_length = 123.456;
  m.model.world_T_zoppi = pkm::geometry::RigidTransform::Identity();
  m.model.world_T_zoppi.linear() =
      Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  m.model.world_T_zoppi.translation() = Eigen::Vector3d(0.1, -1e5, 3.0 / 7.0);
  m.model.home.c = 0.25;
  m.model.home.a = -0.4;
  m.model.max_condition = 1234.5;
  m.fk.tolerance = 3e-10;
  m.fk.max_iterations = 77;
  kin::HybridMachineModel h;
  h.name = m.model.name;
  h.unit = m.model.unit;
  h.x2_stroke = {-0.1, 4000.25};
  h.y2_stroke = {-kInf, 450};
  h.pkm_min = Eigen::Vector3d(-300.5, -kInf, -350);
  h.pkm_max = Eigen::Vector3d(300, 1.0 / 3.0, kInf);
  h.X2_p_P = Eigen::Vector3d(1.5, -2.25, 1e-9);
  h.P_p_tcp0 = Eigen::Vector3d(0, 0.1, -0.2);
  h.Y2_p_work = Eigen::Vector3d(7, 8, 9);
  m.hybrid = h;
  m.joint_rates = JointRateSpec{123.25, 1.0 / 3.0, 45.5, 720};
  ASSERT_NO_THROW(m.model.validate());
  const std::string json = writeExechonJson(m);
  const ExechonMachine back = parseExechonJson(json, "every-field.json");
  expectSameMachine(m, back);
  ASSERT_TRUE(back.joint_rates.has_value());
  EXPECT_EQ(back.joint_rates->velocity, 123.25);
  EXPECT_EQ(back.joint_rates->acceleration, 1.0 / 3.0);
  EXPECT_EQ(back.joint_rates->wrist_velocity_deg, 45.5);
  EXPECT_EQ(back.joint_rates->wrist_acceleration_deg, 720);
  EXPECT_TRUE(back.model.world_T_zoppi.isApprox(m.model.world_T_zoppi, kTolExact));
  // Unbounded ends are written as null.
  EXPECT_THAT(json, HasSubstr("[null, 700]"));
  EXPECT_THAT(json, HasSubstr("\"y2_stroke\": [null, 450]"));
}

TEST(ExechonMachineJson, JointRatesAreOptionalAndPositive) {
  EXPECT_FALSE(parseExechonJson(text(), kSource).joint_rates.has_value());
  const std::string line20 = kLines[19];
  const auto with = [&](const std::string& rates) {
    return text({{20, "  \"joint_rates\": " + rates + ",\n" + line20}});
  };
  const ExechonMachine m = parseExechonJson(with("{\"wrist_velocity_deg\": 90}"), kSource);
  ASSERT_TRUE(m.joint_rates.has_value());
  EXPECT_EQ(m.joint_rates->wrist_velocity_deg, 90);
  EXPECT_TRUE(std::isnan(m.joint_rates->velocity));
  EXPECT_THAT(errorOf(with("{\"velocity\": 0}")),
              HasSubstr(std::string(kSource) + ":20: /joint_rates/velocity: must be > 0"));
  EXPECT_THAT(errorOf(with("{\"jerk\": 1}")),
              HasSubstr(":20: /joint_rates/jerk: unknown key 'jerk'"));
}

TEST(ExechonMachineJson, RoundTripWithoutHybridHasNoHybridSection) {
  ExechonMachine m;
  m.model = pkm::test::machineModel();
  const std::string json = writeExechonJson(m);
  EXPECT_THAT(json, ::testing::Not(HasSubstr("hybrid")));
  const ExechonMachine back = parseExechonJson(json, "m.json");
  EXPECT_FALSE(back.hybrid.has_value());
  expectSameMachine(m, back);
}

TEST(ExechonMachineJson, HybridWithoutWorkingVolumeRoundTrips) {
  // Regression: an unbounded PKM working volume (the default when pkm_min/pkm_max are left out)
  // used to be written as [-inf, -inf, -inf], which is not JSON.
  const ExechonMachine m =
      parseExechonJson(text({{21, "             \"Y2_p_work\": [0, 0, 0]}"}}), kSource);
  ASSERT_TRUE(m.hybrid.has_value());
  EXPECT_EQ(m.hybrid->pkm_min, Eigen::Vector3d::Constant(-kInf));
  EXPECT_EQ(m.hybrid->pkm_max, Eigen::Vector3d::Constant(kInf));
  const std::string json = writeExechonJson(m);
  EXPECT_THAT(json, HasSubstr("\"pkm_min\": [null, null, null]"));
  expectSameMachine(m, parseExechonJson(json, "m.json"));
}

TEST(ExechonMachineJson, NullBoundOfTheWorkingVolumeIsUnbounded) {
  const ExechonMachine m = parseExechonJson(
      text({{21, "             \"pkm_min\": [-300, null, -350], \"pkm_max\": [null, 300, 350]}"}}),
      kSource);
  ASSERT_TRUE(m.hybrid.has_value());
  EXPECT_EQ(m.hybrid->pkm_min, Eigen::Vector3d(-300, -kInf, -350));
  EXPECT_EQ(m.hybrid->pkm_max, Eigen::Vector3d(kInf, 300, 350));
  // Not in the offsets, which must be finite.
  EXPECT_THAT(errorOf(text({{21, "             \"X2_p_P\": [0, null, 0]}"}})),
              StartsWith(at(21, "/hybrid/X2_p_P/1") + "expected a number"));
}

}  // namespace PKM_TEST_NS
