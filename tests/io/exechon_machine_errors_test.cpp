// Tests of the Exechon machine JSON reader (pkm/io/exechon_machine.hpp) on a hand-written file:
// what its optional sections default to, and every "FILE:LINE: /pointer: message" error. The
// shipped files and the round trip are in exechon_machine_test.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdio>
#include <limits>
#include <string>

#include "io/exechon_machine_sample.hpp"
#include "pkm/core/error.hpp"
#include "pkm/core/units.hpp"
#include "pkm/io/exechon_machine.hpp"
#include "support/tolerances.hpp"

namespace PKM_TEST_NS {

namespace kin = pkm::kinematics;
using pkm::IoError;
using pkm::io::ExechonMachine;
using pkm::io::parseExechonJson;
using pkm::io::readExechonJson;
using pkm::test::kTolExact;
using pkm::test::exechon_json::at;
using pkm::test::exechon_json::errorOf;
using pkm::test::exechon_json::kSource;
using pkm::test::exechon_json::text;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr double kInf = std::numeric_limits<double>::infinity();

// ---------------------------------------------------------------------------------------------
// Optional sections and defaults

TEST(ExechonMachineJson, TemplateIsValid) {
  const ExechonMachine m = parseExechonJson(text(), kSource);
  EXPECT_EQ(m.model.name, "t");
  EXPECT_EQ(m.source, kSource);
  ASSERT_TRUE(m.hybrid.has_value());
  // Left out of the template: the hybrid offsets (zero), the FK settings and max_condition.
  EXPECT_EQ(m.hybrid->X2_p_P, Eigen::Vector3d::Zero());
  EXPECT_EQ(m.fk.tolerance, kin::FkOptions{}.tolerance);
  EXPECT_EQ(m.fk.max_iterations, kin::FkOptions{}.max_iterations);
  EXPECT_EQ(m.model.max_condition, kin::ExechonModel{}.max_condition);
}

TEST(ExechonMachineJson, NullEndOfALimitIsUnbounded) {
  const ExechonMachine m = parseExechonJson(
      text({{15, "  \"limits\": {\"alpha_deg\": [null, 130], \"beta_deg\": [-45, null],"},
            {16, "             \"c_deg\": [null, null], \"a_deg\": [-100, 100]},"}}),
      kSource);
  EXPECT_EQ(m.model.limits.alpha.min, -kInf);
  EXPECT_NEAR(m.model.limits.alpha.max, pkm::degToRad(130), kTolExact);
  EXPECT_NEAR(m.model.limits.beta.min, pkm::degToRad(-45), kTolExact);
  EXPECT_EQ(m.model.limits.beta.max, kInf);
  EXPECT_EQ(m.model.limits.c.min, -kInf);
  EXPECT_EQ(m.model.limits.c.max, kInf);
  // Same for strokes.
  const ExechonMachine s = parseExechonJson(
      text({{12, "    {\"length_offset\": 672.4537, \"stroke\": [null, 700]},"}}), kSource);
  EXPECT_EQ(s.model.legs[1].min_reading, -kInf);
  EXPECT_EQ(s.model.legs[1].max_reading, 700.0);
}

// ---------------------------------------------------------------------------------------------
// Errors: "FILE:LINE: /pointer: message"

TEST(ExechonMachineJsonErrors, InvalidJsonSyntax) {
  const std::string msg =
      errorOf(text({{12, "    {\"length_offset\": 672.4537, \"stroke\": [0 700]},"}}));
  EXPECT_THAT(msg, StartsWith(std::string(kSource) + ":12: invalid JSON: "));
  EXPECT_THAT(msg, HasSubstr("syntax error"));
}

TEST(ExechonMachineJsonErrors, NumberOutOfRangeOfADouble) {
  const std::string msg =
      errorOf(text({{19, "  \"home\": {\"alpha_deg\": 90, \"beta_deg\": 0, \"h\": 1e999},"}}));
  EXPECT_THAT(msg, StartsWith(std::string(kSource) + ":19: "));
  EXPECT_THAT(msg, HasSubstr("not finite"));
}

TEST(ExechonMachineJsonErrors, UnknownKeyAtTopLevel) {
  const std::string msg = errorOf(text({{4, "  \"name\": \"t\", \"nmae\": \"typo\","}}));
  EXPECT_THAT(msg, StartsWith(at(4, "/nmae") + "unknown key 'nmae'"));
}

TEST(ExechonMachineJsonErrors, UnknownKeyInTripod) {
  const std::string msg = errorOf(
      text({{8, "             \"hA\": 40, \"hC\": 23, \"hx\": 0, \"hy\": 5, \"hz\": 250,"}}));
  EXPECT_THAT(msg, StartsWith(at(8, "/tripod/hy") + "unknown key 'hy'"));
}

TEST(ExechonMachineJsonErrors, UnknownKeyInBranch) {
  const std::string msg =
      errorOf(text({{9, "             \"branch\": {\"delta1B\": 1, \"delta3B\": 1}},"}}));
  EXPECT_THAT(msg, StartsWith(at(9, "/tripod/branch/delta3B") + "unknown key"));
}

TEST(ExechonMachineJsonErrors, UnknownKeyInWrist) {
  const std::string msg = errorOf(
      text({{17, "  \"wrist\": {\"c_axis\": [0, 0, 1], \"a_axis\": [1, 0, 0], \"tool\": 200},"}}));
  EXPECT_THAT(msg, StartsWith(at(17, "/wrist/tool") + "unknown key 'tool'"));
}

TEST(ExechonMachineJsonErrors, UnknownKeyInHybrid) {
  const std::string msg = errorOf(text({{21,
                                         "             \"pkm_min\": [-300, -300, -350], "
                                         "\"pkm_max\": [300, 300, 350], \"z2_stroke\": [0, 1]}"}}));
  EXPECT_THAT(msg, StartsWith(at(21, "/hybrid/z2_stroke") + "unknown key 'z2_stroke'"));
}

TEST(ExechonMachineJsonErrors, MissingTripod) {
  const std::string msg = errorOf(text({{6, ""}, {7, ""}, {8, ""}, {9, ""}}));
  EXPECT_THAT(msg, StartsWith(at(1, "/") + "missing key 'tripod'"));
}

TEST(ExechonMachineJsonErrors, MissingHome) {
  const std::string msg = errorOf(text({{19, ""}}));
  EXPECT_THAT(msg, StartsWith(at(1, "/") + "missing key 'home'"));
}

TEST(ExechonMachineJsonErrors, MissingHomeH) {
  const std::string msg =
      errorOf(text({{19, "  \"home\": {\"alpha_deg\": 90, \"beta_deg\": 0},"}}));
  EXPECT_THAT(msg, StartsWith(at(19, "/home") + "missing key 'h'"));
}

TEST(ExechonMachineJsonErrors, MissingDB) {
  const std::string msg =
      errorOf(text({{6, "  \"tripod\": {\"dA\": -443.4, \"dC\": 779.8, \"l12A\": 102.3,"}}));
  EXPECT_THAT(msg, StartsWith(at(6, "/tripod") + "missing key 'dB'"));
}

TEST(ExechonMachineJsonErrors, BranchSignTwo) {
  const std::string msg = errorOf(text({{9,
                                         "             \"branch\": {\"delta1B\": 1, \"delta2B\": "
                                         "2, \"deltaA\": 1, \"deltaC\": 1}},"}}));
  EXPECT_THAT(msg, StartsWith(at(9, "/tripod/branch/delta2B") + "must be 1 or -1"));
}

TEST(ExechonMachineJsonErrors, WristSignZero) {
  const std::string msg = errorOf(text({{17,
                                         "  \"wrist\": {\"c_axis\": [0, 0, 1], \"a_axis\": [1, 0, "
                                         "0], \"a_sign\": 0, \"tool_length\": 200},"}}));
  EXPECT_THAT(msg, StartsWith(at(17, "/wrist/a_sign") + "must be 1 or -1"));
}

TEST(ExechonMachineJsonErrors, StrokeWithMinAboveMax) {
  const std::string msg =
      errorOf(text({{12, "    {\"length_offset\": 672.4537, \"stroke\": [700, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(12, "/legs/1/stroke") + "min is larger than max"));
}

TEST(ExechonMachineJsonErrors, LimitWithMinAboveMax) {
  const std::string msg =
      errorOf(text({{15, "  \"limits\": {\"alpha_deg\": [50, 130], \"beta_deg\": [45, -45],"}}));
  EXPECT_THAT(msg, StartsWith(at(15, "/limits/beta_deg") + "min is larger than max"));
}

TEST(ExechonMachineJsonErrors, LimitNotAPair) {
  const std::string msg =
      errorOf(text({{16, "             \"c_deg\": [-270], \"a_deg\": [-100, 100]},"}}));
  EXPECT_THAT(msg, StartsWith(at(16, "/limits/c_deg") + "expected [min, max]"));
}

TEST(ExechonMachineJsonErrors, TwoLegsInsteadOfThree) {
  const std::string msg =
      errorOf(text({{12, "    {\"length_offset\": 672.4537, \"stroke\": [0, 700]}"}, {13, ""}}));
  EXPECT_THAT(msg, StartsWith(at(10, "/legs") + "expected an array of 3 legs"));
}

TEST(ExechonMachineJsonErrors, WrongType) {
  const std::string msg = errorOf(text({{3, "  \"type\": \"hexapod\","}}));
  EXPECT_THAT(msg, StartsWith(at(3, "/type")));
  EXPECT_THAT(msg, HasSubstr("\"exechon\""));
  // A missing type is not an Exechon machine either.
  EXPECT_THAT(errorOf(text({{3, ""}})), StartsWith(at(1, "/type")));
}

TEST(ExechonMachineJsonErrors, BadSchema) {
  const std::string msg = errorOf(text({{2, "  \"schema\": \"pkm.machine/2\","}}));
  EXPECT_THAT(msg, StartsWith(at(2, "/schema") + "unsupported schema \"pkm.machine/2\""));
}

TEST(ExechonMachineJsonErrors, BadUnits) {
  const std::string msg = errorOf(text({{5, "  \"units\": \"m\","}}));
  EXPECT_THAT(msg, StartsWith(at(5, "/units")));
}

TEST(ExechonMachineJsonErrors, WrongValueType) {
  EXPECT_THAT(
      errorOf(text({{8, "             \"hA\": \"40\", \"hC\": 23, \"hx\": 0, \"hz\": 250,"}})),
      StartsWith(at(8, "/tripod/hA") + "expected a number"));
  EXPECT_THAT(errorOf(text({{17, "  \"wrist\": {\"c_axis\": [0, 1], \"a_axis\": [1, 0, 0]},"}})),
              StartsWith(at(17, "/wrist/c_axis") + "expected an array of 3 numbers"));
}

TEST(ExechonMachineJsonErrors, NonPerpendicularWristAxesFailValidation) {
  const std::string msg = errorOf(text(
      {{17,
        "  \"wrist\": {\"c_axis\": [0, 0, 1], \"a_axis\": [1, 0, 1], \"tool_length\": 200},"}}));
  EXPECT_THAT(msg, StartsWith(at(1, "/")));
  EXPECT_THAT(msg, HasSubstr("perpendicular"));
}

TEST(ExechonMachineJsonErrors, ZeroDBFailsValidation) {
  const std::string msg = errorOf(
      text({{6, "  \"tripod\": {\"dA\": -443.4, \"dB\": 0, \"dC\": 779.8, \"l12A\": 102.3,"}}));
  EXPECT_THAT(msg, StartsWith(at(1, "/")));
  EXPECT_THAT(msg, HasSubstr("dB must be != 0"));
}

TEST(ExechonMachineJsonErrors, ValidationFailureNamesTheFile) {
  // readExechonJson: the message starts with the path of the file.
  const std::string path = testing::TempDir() + "exechon_machine_test_bad_wrist.json";
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    const std::string t = text(
        {{17,
          "  \"wrist\": {\"c_axis\": [0, 0, 0], \"a_axis\": [1, 0, 0], \"tool_length\": 200},"}});
    std::fwrite(t.data(), 1, t.size(), f);
    std::fclose(f);
  }
  try {
    (void)readExechonJson(path);
    ADD_FAILURE() << "no error";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), StartsWith(path + ":1: /: "));
    EXPECT_THAT(e.what(), HasSubstr("non-zero"));
  }
  std::remove(path.c_str());
}

TEST(ExechonMachineJsonErrors, PkmMinAbovePkmMax) {
  const std::string msg = errorOf(
      text({{21, "             \"pkm_min\": [-300, 400, -350], \"pkm_max\": [300, 300, 350]}"}}));
  EXPECT_THAT(msg, StartsWith(at(21, "/hybrid/pkm_min") + "pkm_min is larger than pkm_max"));
}

TEST(ExechonMachineJsonErrors, X2StrokeReversed) {
  const std::string msg =
      errorOf(text({{20, "  \"hybrid\": {\"x2_stroke\": [4000, 0], \"y2_stroke\": [0, 450],"}}));
  EXPECT_THAT(msg, StartsWith(at(20, "/hybrid/x2_stroke") + "min is larger than max"));
}

TEST(ExechonMachineJsonErrors, ForwardKinematicsIterationsNotAnInteger) {
  const std::string msg = errorOf(
      text({{5, "  \"units\": \"mm\", \"forward_kinematics\": {\"max_iterations\": 2.5},"}}));
  EXPECT_THAT(msg, StartsWith(at(5, "/forward_kinematics/max_iterations")));
}

TEST(ExechonMachineJsonErrors, RootNotAnObject) {
  EXPECT_THAT(errorOf("[1, 2]\n"), StartsWith(at(1, "/") + "expected an object"));
}

}  // namespace PKM_TEST_NS
