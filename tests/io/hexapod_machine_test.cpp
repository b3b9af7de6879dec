// Tests of the hexapod machine JSON reader and writer (pkm/io/hexapod_machine.hpp): the shipped
// files, the write -> parse round trips and the file's name in messages. Every
// "SOURCE:LINE: /pointer:" error is in hexapod_machine_errors_test.cpp.
#include "pkm/io/hexapod_machine.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/hexapod_machine_sample.hpp"
#include "pkm/core/error.hpp"
#include "pkm/kinematics/hexapod_ik.hpp"
#include "support/sample_models.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace fs = std::filesystem;
namespace kin = pkm::kinematics;
using pkm::IoError;
using pkm::io::HexapodMachine;
using pkm::io::JointRateSpec;
using pkm::io::parseHexapodJson;
using pkm::io::readHexapodJson;
using pkm::io::writeHexapodJson;
using pkm::test::hexapod_json::kSource;
using pkm::test::hexapod_json::text;
using ::testing::HasSubstr;
using ::testing::StartsWith;

/// Relative tolerance of angles written in degrees and read back (a few units in the last place).
constexpr double kTolAngleRoundTrip = 1e-15;

/// The LinuxCNC hexapod-sim IK readings at its home pose 0 0 20 0 0 0 (inch).
const double kSimHomeReadings[6] = {
    29.746680, 29.746680, 29.746715, 29.746363, 29.746363, 29.746715};

std::string machineFile(const char* stem) {
  return std::string(PKM_SOURCE_DIR) + "/data/machines/" + stem + ".json";
}

void expectSameLengths(const kin::HexapodModel& a, const kin::HexapodModel& b) {
  EXPECT_EQ(a.unit, b.unit);
  EXPECT_EQ(a.home.position, b.home.position);
  EXPECT_EQ(a.tool_offset, b.tool_offset);
  EXPECT_EQ(a.spindle_offset, b.spindle_offset);
  EXPECT_EQ(a.linuxcnc_tool_offset, b.linuxcnc_tool_offset);
  EXPECT_EQ(a.strut_diameter, b.strut_diameter);
  EXPECT_EQ(a.max_condition, b.max_condition);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    SCOPED_TRACE(i);
    const kin::Strut& s = a.struts[i];
    const kin::Strut& t = b.struts[i];
    EXPECT_EQ(s.world_p_base, t.world_p_base);
    EXPECT_EQ(s.platform_p_joint, t.platform_p_joint);
    EXPECT_EQ(s.length_offset, t.length_offset);
    EXPECT_EQ(s.min_reading, t.min_reading);
    EXPECT_EQ(s.max_reading, t.max_reading);
  }
}

void expectNearRelative(double a, double b, double rel) {
  EXPECT_NEAR(a, b, rel * std::max(std::abs(a), std::abs(b))) << a << " vs " << b;
}

void expectSameAngles(const kin::HexapodModel& a, const kin::HexapodModel& b) {
  for (int k = 0; k < 3; ++k) expectNearRelative(a.home.rpy[k], b.home.rpy[k], kTolAngleRoundTrip);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    SCOPED_TRACE(i);
    const kin::Strut& s = a.struts[i];
    const kin::Strut& t = b.struts[i];
    expectNearRelative(s.base_cone.max_angle, t.base_cone.max_angle, kTolAngleRoundTrip);
    expectNearRelative(s.platform_cone.max_angle, t.platform_cone.max_angle, kTolAngleRoundTrip);
    // Axes are unit vectors written exactly and normalised again on reading.
    EXPECT_LT((s.base_cone.axis - t.base_cone.axis).norm(), kTolAngleRoundTrip);
    EXPECT_LT((s.platform_cone.axis - t.platform_cone.axis).norm(), kTolAngleRoundTrip);
  }
}

HexapodMachine roundTrip(const HexapodMachine& m) {
  const std::string json = writeHexapodJson(m);
  return parseHexapodJson(json, "round-trip.json");
}

// ---------------------------------------------------------------------------------------------
// The shipped machine files

TEST(HexapodMachineJson, ReadsLinuxcncSimFile) {
  const std::string path = machineFile("hexapod-linuxcnc-sim");
  const HexapodMachine m = readHexapodJson(path);
  EXPECT_EQ(m.source, path);
  EXPECT_EQ(m.model.name, "hexapod-linuxcnc-sim");
  EXPECT_THAT(m.description, HasSubstr("LinuxCNC"));
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kInch);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d(0, 0, 20));
  EXPECT_EQ(m.model.home.rpy, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.fk.tolerance, 1e-9);
  EXPECT_EQ(m.fk.max_iterations, 120);
  const kin::HexapodModel ref = pkm::test::linuxcncSimModel();
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    EXPECT_EQ(m.model.struts[i].world_p_base, ref.struts[i].world_p_base) << i;
    EXPECT_EQ(m.model.struts[i].platform_p_joint, ref.struts[i].platform_p_joint) << i;
    EXPECT_EQ(m.model.struts[i].length_offset, 0.0);
    EXPECT_EQ(m.model.struts[i].min_reading, -1000.0);
    EXPECT_EQ(m.model.struts[i].max_reading, 1000.0);
    EXPECT_EQ(m.model.struts[i].base_cone.max_angle, 0.0);  // no joint-angle limits
  }
  kin::HexapodData data(m.model);
  const kin::StrutVector& q = kin::inverseKinematics(m.model, data, m.model.home);
  for (int i = 0; i < kin::kStruts; ++i)
    EXPECT_NEAR(q[i], kSimHomeReadings[i], pkm::test::kTolLinuxcnc) << i;
}

TEST(HexapodMachineJson, ReadsDefaultFile) {
  const std::string path = machineFile("hexapod-default");
  const HexapodMachine m = readHexapodJson(path);
  EXPECT_EQ(m.model.name, "pkm-hx1200");
  EXPECT_EQ(m.model.unit, pkm::LengthUnit::kMillimetre);
  EXPECT_EQ(m.model.home.position, Eigen::Vector3d(0, 0, 200));
  EXPECT_EQ(m.model.tool_offset, Eigen::Vector3d(0, 0, -200));
  EXPECT_EQ(m.model.strut_diameter, 80.0);
  EXPECT_EQ(m.model.max_condition, 200.0);
  EXPECT_EQ(m.fk.max_iterations, 120);
  EXPECT_EQ(m.model.struts[0].world_p_base, Eigen::Vector3d(-124.747, 586.8886, 1200.0));
  EXPECT_EQ(m.model.struts[5].platform_p_joint, Eigen::Vector3d(176.7767, 176.7767, 0.0));
  kin::HexapodData data(m.model);
  kin::inverseKinematics(m.model, data, m.model.home);
  for (std::size_t i = 0; i < kin::kStruts; ++i) {
    SCOPED_TRACE(i);
    const kin::Strut& s = m.model.struts[i];
    EXPECT_EQ(s.length_offset, 650.0);
    EXPECT_EQ(s.min_reading, 0.0);
    EXPECT_EQ(s.max_reading, 500.0);
    EXPECT_NEAR(s.base_cone.max_angle, pkm::degToRad(40), pkm::test::kTolExact);
    EXPECT_NEAR(s.platform_cone.max_angle, pkm::degToRad(45), pkm::test::kTolExact);
    // Axes left out of the file: the strut direction at home.
    EXPECT_NEAR((s.base_cone.axis - data.unit_leg[i]).norm(), 0.0, pkm::test::kTolExact);
    EXPECT_NEAR(
        (s.platform_cone.axis - data.world_R_platform.transpose() * data.unit_leg[i]).norm(),
        0.0,
        pkm::test::kTolExact);
    // At home every reading lies inside the stroke.
    EXPECT_GT(data.readings[static_cast<Eigen::Index>(i)], s.min_reading);
    EXPECT_LT(data.readings[static_cast<Eigen::Index>(i)], s.max_reading);
  }
}

TEST(HexapodMachineJson, GivenConeAxisIsNormalisedAndKept) {
  std::string line6 =
      "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-1, 11.5, 0], "
      "\"base_joint\": {\"axis\": [0, 0, 2], \"max_angle_deg\": 30}},";
  const HexapodMachine m = parseHexapodJson(text({{6, line6}}), kSource);
  EXPECT_EQ(m.model.struts[0].base_cone.axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_NEAR(m.model.struts[0].base_cone.max_angle, pkm::degToRad(30), pkm::test::kTolExact);
  EXPECT_NE(m.model.struts[1].base_cone.axis, Eigen::Vector3d(0, 0, 1));  // defaulted
}

// ---------------------------------------------------------------------------------------------
// Round trips

TEST(HexapodMachineJson, ShippedFilesRoundTrip) {
  for (const char* stem : {"hexapod-default", "hexapod-linuxcnc-sim"}) {
    SCOPED_TRACE(stem);
    const HexapodMachine m = readHexapodJson(machineFile(stem));
    const HexapodMachine back = roundTrip(m);
    EXPECT_EQ(back.model.name, m.model.name);
    EXPECT_EQ(back.description, m.description);
    EXPECT_EQ(back.fk.tolerance, m.fk.tolerance);
    EXPECT_EQ(back.fk.max_iterations, m.fk.max_iterations);
    expectSameLengths(back.model, m.model);
    expectSameAngles(back.model, m.model);
  }
}

TEST(HexapodMachineJson, RandomMachinesRoundTrip) {
  std::mt19937 rng(pkm::test::kSeed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 50; ++trial) {
    SCOPED_TRACE(trial);
    HexapodMachine m;
    m.model = pkm::test::millingModel();
    m.model.name = "random \"machine\" \\ ünïcode";
    m.description = "line one\nline two\ttabbed";
    m.model.unit = trial % 2 ? pkm::LengthUnit::kInch : pkm::LengthUnit::kMillimetre;
    for (auto& s : m.model.struts) {
      s.world_p_base += Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10.0;
      s.platform_p_joint += Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10.0;
      s.length_offset += u(rng);
      s.min_reading = u(rng) * 1e-3;
      s.max_reading = 500.0 + u(rng);
      s.base_cone.max_angle = std::abs(u(rng));
      s.platform_cone.max_angle = std::abs(u(rng));
    }
    m.model.struts[2].min_reading = -std::numeric_limits<double>::infinity();  // one side unbounded
    m.model.struts[3].max_reading = std::numeric_limits<double>::infinity();
    m.model.struts[4].min_reading =
        -std::numeric_limits<double>::infinity();  // unbounded both sides
    m.model.struts[4].max_reading = std::numeric_limits<double>::infinity();
    m.model.home.position += Eigen::Vector3d(u(rng), u(rng), u(rng));
    m.model.home.rpy = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 0.1;
    m.model.tool_offset = Eigen::Vector3d(u(rng), u(rng), -200 + u(rng));
    m.model.spindle_offset = u(rng);
    m.model.linuxcnc_tool_offset = u(rng);
    m.model.strut_diameter = 80 + u(rng);
    m.model.max_condition = 200 + u(rng);
    m.fk.tolerance = 1e-10 * (2 + u(rng));
    m.fk.max_iterations = 50 + trial;
    if (trial % 3 == 0) m.joint_rates = JointRateSpec{20 + u(rng), 200 + u(rng)};
    const HexapodMachine back = roundTrip(m);
    ASSERT_EQ(back.joint_rates.has_value(), m.joint_rates.has_value());
    if (m.joint_rates) {
      EXPECT_EQ(back.joint_rates->velocity, m.joint_rates->velocity);
      EXPECT_EQ(back.joint_rates->acceleration, m.joint_rates->acceleration);
    }
    EXPECT_EQ(back.model.name, m.model.name);
    EXPECT_EQ(back.description, m.description);
    EXPECT_EQ(back.fk.tolerance, m.fk.tolerance);
    EXPECT_EQ(back.fk.max_iterations, m.fk.max_iterations);
    expectSameLengths(back.model, m.model);
    expectSameAngles(back.model, m.model);
    // And the written text is stable: writing the read-back machine gives the same lengths again.
    expectSameLengths(roundTrip(back).model, m.model);
  }
}

TEST(HexapodMachineJson, ReadTextFileNamesMissingFile) {
  const std::string path = "/nonexistent-dir/pkm/no-such-machine.json";
  try {
    (void)readHexapodJson(path);
    FAIL() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith(path + ": "));
  }
}

TEST(HexapodMachineJson, ReadErrorNamesTheFilePath) {
  const fs::path dir =
      fs::temp_directory_path() / ("pkm_machine_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "bad.json";
  {
    std::ofstream out(file);
    out << text({{3, "  \"units\": \"furlong\","}});
  }
  try {
    (void)readHexapodJson(file.string());
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith(file.string() + ":3: /units: "));
  }
  fs::remove_all(dir);
}

}  // namespace PKM_TEST_NS
