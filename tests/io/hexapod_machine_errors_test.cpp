// Tests of the hexapod machine JSON reader (pkm/io/hexapod_machine.hpp) on a hand-written file:
// every error is "SOURCE:LINE: /pointer: what". The shipped files and round trips are in
// hexapod_machine_test.cpp.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "io/hexapod_machine_sample.hpp"
#include "pkm/io/hexapod_machine.hpp"

namespace PKM_TEST_NS {

using pkm::test::hexapod_json::at;
using pkm::test::hexapod_json::errorOf;
using pkm::test::hexapod_json::kLines;
using pkm::test::hexapod_json::kSource;
using pkm::test::hexapod_json::text;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// ---------------------------------------------------------------------------------------------
// Errors: every message is "SOURCE:LINE: /pointer: what"

TEST(HexapodMachineJsonErrors, BaseTextIsValid) { EXPECT_EQ(errorOf(text()), ""); }

TEST(HexapodMachineJsonErrors, SyntaxErrorInsideALine) {
  const std::string msg =
      errorOf(text({{9, "    {\"base\": [0, -26.5 0], \"platform\": [9.459, -6.616, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(9)));
  EXPECT_THAT(msg, HasSubstr("invalid JSON"));
}

TEST(HexapodMachineJsonErrors, SyntaxErrorAtStartOfLine) {
  // Trailing comma after the last strut: the parser stops at the ']' that starts line 12.
  const std::string msg = errorOf(
      text({{11, "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-10.459, -4.884, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(12)));
  EXPECT_THAT(msg, HasSubstr("invalid JSON"));
}

TEST(HexapodMachineJsonErrors, SyntaxErrorOnFirstLine) {
  const std::string msg = errorOf("x" + text());
  EXPECT_THAT(msg, StartsWith(at(1)));
}

TEST(HexapodMachineJsonErrors, TruncatedText) {
  const std::string msg = errorOf(text({{12, ""}, {13, ""}}));  // ends after line 11
  EXPECT_THAT(msg, HasSubstr("invalid JSON"));
  EXPECT_THAT(msg, StartsWith(std::string(kSource) + ":1"));  // line 11 or 12 (end of input)
  EXPECT_THAT(msg, ::testing::AnyOf(StartsWith(at(11)), StartsWith(at(12))));
}

TEST(HexapodMachineJsonErrors, UnknownTopLevelKey) {
  const std::string msg = errorOf(text({{3, "  \"unitz\": \"inch\","}}));
  EXPECT_THAT(msg, StartsWith(at(3) + "/unitz: unknown key 'unitz'"));
}

TEST(HexapodMachineJsonErrors, JointRatesMustBePositiveAndKnown) {
  EXPECT_THAT(errorOf(text({{3, "  \"joint_rates\": {\"velocity\": -5}, \"units\": \"mm\","}})),
              StartsWith(at(3) + "/joint_rates/velocity: must be > 0"));
  // The wrist keys belong to Exechon files.
  EXPECT_THAT(
      errorOf(text({{3, "  \"joint_rates\": {\"wrist_velocity_deg\": 5}, \"units\": \"mm\","}})),
      StartsWith(at(3) + "/joint_rates/wrist_velocity_deg: unknown key"));
}

TEST(HexapodMachineJsonErrors, UnknownStrutKey) {
  const std::string msg = errorOf(text(
      {{8,
        "    {\"base\": [22.95, 13.25, 0], \"platform\": [10.459, -4.884, 0], \"bogus\": 1},"}}));
  EXPECT_THAT(msg, StartsWith(at(8) + "/struts/2/bogus: unknown key 'bogus'"));
}

TEST(HexapodMachineJsonErrors, UnknownHomeKey) {
  const std::string msg = errorOf(text({{4, "  \"home\": {\"x\": 0, \"w\": 1},"}}));
  EXPECT_THAT(msg, StartsWith(at(4) + "/home/w: unknown key 'w'"));
}

TEST(HexapodMachineJsonErrors, WrongTypeString) {
  const std::string msg = errorOf(text({{2, "  \"name\": 5,"}}));
  EXPECT_THAT(msg, StartsWith(at(2) + "/name: expected a string"));
}

TEST(HexapodMachineJsonErrors, WrongTypeVector) {
  const std::string msg =
      errorOf(text({{10, "    {\"base\": \"here\", \"platform\": [-9.459, -6.616, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(10) + "/struts/4/base: expected an array of 3 numbers"));
}

TEST(HexapodMachineJsonErrors, WrongTypeVectorElement) {
  const std::string msg = errorOf(
      text({{10, "    {\"base\": [0, \"-26.5\", 0], \"platform\": [-9.459, -6.616, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(10) + "/struts/4/base/1: expected a number"));
}

TEST(HexapodMachineJsonErrors, WrongTypeNumber) {
  const std::string msg = errorOf(text({{4, "  \"home\": {\"x\": 0, \"y\": 0, \"z\": \"20\"},"}}));
  EXPECT_THAT(msg, StartsWith(at(4) + "/home/z: expected a number"));
}

TEST(HexapodMachineJsonErrors, RootNotAnObject) {
  const std::string msg = errorOf("\n[1, 2]\n");
  EXPECT_THAT(msg, StartsWith(at(2) + "/: expected an object"));
}

TEST(HexapodMachineJsonErrors, FiveStruts) {
  const std::string msg = errorOf(
      text({{10, "    {\"base\": [0, -26.5, 0], \"platform\": [-9.459, -6.616, 0]}"}, {11, ""}}));
  EXPECT_THAT(msg, StartsWith(at(5) + "/struts: expected an array of 6 struts"));
}

TEST(HexapodMachineJsonErrors, NonFiniteNumber) {
  const std::string msg = errorOf(text({{4, "  \"home\": {\"x\": 0, \"y\": 0, \"z\": 1e999},"}}));
  // JSON has no NaN or infinity: a number beyond the range of a double is the non-finite case.
  EXPECT_THAT(msg, StartsWith(at(4)));
  EXPECT_THAT(msg, HasSubstr("1e999"));
  EXPECT_THAT(msg, HasSubstr("not finite"));
}

TEST(HexapodMachineJsonErrors, NonFiniteJointCoordinate) {
  const std::string msg =
      errorOf(text({{7, "    {\"base\": [22.95, -1e400, 0], \"platform\": [1, 11.5, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(7)));
  EXPECT_THAT(msg, HasSubstr("-1e400"));
  EXPECT_THAT(msg, HasSubstr("not finite"));
}

TEST(HexapodMachineJsonErrors, NonFiniteNumberAfterSameDigitsInAString) {
  // The line is that of the number, not of an earlier string holding the same characters.
  const std::string msg =
      errorOf(text({{2, "  \"name\": \"1e999\","}, {4, "  \"home\": {\"z\": 1e999},"}}));
  EXPECT_THAT(msg, StartsWith(at(4)));
}

TEST(HexapodMachineJsonErrors, DeeplyNestedValueIsReportedNotHung) {
  // Valid JSON nested far deeper than any machine file: a prompt error, not a hang or a crash.
  constexpr int kDepth = 5000;
  const std::string deep = std::string(kDepth, '[') + std::string(kDepth, ']');
  const std::string msg = errorOf(text({{5, "  \"struts\": " + deep + ","},
                                        {6, ""},
                                        {7, ""},
                                        {8, ""},
                                        {9, ""},
                                        {10, ""},
                                        {11, ""},
                                        {12, "  \"description\": \"x\""}}));
  EXPECT_THAT(msg, StartsWith(at(5) + "/struts: expected an array of 6 struts"));
}

TEST(HexapodMachineJsonErrors, StrokeMinAboveMax) {
  const std::string msg = errorOf(text(
      {{7, "    {\"base\": [22.95, 13.25, 0], \"platform\": [1, 11.5, 0], \"stroke\": [5, 1]},"}}));
  EXPECT_THAT(msg, StartsWith(at(7) + "/struts/1/stroke: min is larger than max"));
}

TEST(HexapodMachineJsonErrors, StrokeNotAPair) {
  const std::string msg = errorOf(text(
      {{7, "    {\"base\": [22.95, 13.25, 0], \"platform\": [1, 11.5, 0], \"stroke\": [5]},"}}));
  EXPECT_THAT(msg, StartsWith(at(7) + "/struts/1/stroke: expected [min, max]"));
}

TEST(HexapodMachineJsonErrors, CoincidentJointsTwoIdenticalStruts) {
  const std::string msg = errorOf(text({{8, kLines[6]}}));  // strut 2 := strut 1
  EXPECT_THAT(msg, StartsWith(at(5) + "/struts: "));
  EXPECT_THAT(msg, HasSubstr("struts 1 and 2 have coincident base and platform joints"));
}

TEST(HexapodMachineJsonErrors, ZeroLengthStrutAtHome) {
  // Platform joint 0 at home (z 20) lands exactly on base joint 0.
  const std::string msg = errorOf(
      text({{6, "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-22.95, 13.25, -20]},"}}));
  EXPECT_THAT(msg, StartsWith(at(5) + "/struts: "));
  EXPECT_THAT(msg, HasSubstr("strut 0 has zero length at the home pose"));
}

TEST(HexapodMachineJsonErrors, SingularHome) {
  // Every platform joint at the origin of the platform: the platform can spin freely.
  std::map<int, std::string> edits;
  for (int n = 6; n <= 11; ++n) {
    std::string line = kLines[static_cast<std::size_t>(n - 1)];
    const auto p = line.find("\"platform\"");
    line = line.substr(0, p) + "\"platform\": [0, 0, 0]}" + (n < 11 ? "," : "");
    edits[n] = line;
  }
  const std::string msg = errorOf(text(edits));
  EXPECT_THAT(msg, StartsWith(at(5) + "/struts: "));
}

TEST(HexapodMachineJsonErrors, MissingStrutsKey) {
  std::map<int, std::string> edits = {{4, "  \"home\": {\"x\": 0, \"y\": 0, \"z\": 20}"}};
  for (int n = 5; n <= 12; ++n) edits[n] = "";
  const std::string msg = errorOf(text(edits));
  EXPECT_THAT(msg, StartsWith(at(1) + "/: missing key 'struts'"));
}

TEST(HexapodMachineJsonErrors, MissingPlatformKey) {
  const std::string msg = errorOf(text({{9, "    {\"base\": [0, -26.5, 0]},"}}));
  EXPECT_THAT(msg, StartsWith(at(9) + "/struts/3: missing key 'platform'"));
}

TEST(HexapodMachineJsonErrors, BadUnits) {
  const std::string msg = errorOf(text({{3, "  \"units\": \"furlong\","}}));
  EXPECT_THAT(msg, StartsWith(at(3) + "/units: "));
  EXPECT_THAT(msg, HasSubstr("furlong"));
}

TEST(HexapodMachineJsonErrors, WrongMachineType) {
  const std::string msg = errorOf(text({{2, "  \"type\": \"delta\","}}));
  EXPECT_THAT(msg, StartsWith(at(2) + "/type: "));
}

TEST(HexapodMachineJsonErrors, UnsupportedSchema) {
  EXPECT_EQ(errorOf(text({{2, "  \"schema\": \"pkm.machine/1\", \"name\": \"t\","}})), "");
  const std::string msg = errorOf(text({{2, "  \"schema\": \"pkm.machine/2\","}}));
  EXPECT_THAT(msg, StartsWith(at(2) + "/schema: "));
}

TEST(HexapodMachineJsonErrors, NonIntegerIterationCap) {
  const std::string msg =
      errorOf(text({{2, "  \"forward_kinematics\": {\"max_iterations\": 2.5},"}}));
  EXPECT_THAT(msg, StartsWith(at(2) + "/forward_kinematics/max_iterations: "));
}

TEST(HexapodMachineJsonErrors, NegativeConeAngle) {
  const std::string msg =
      errorOf(text({{11, "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-10.459, -4.884, 0],"},
                    {12, "     \"platform_joint\": {\"max_angle_deg\": -5}}]"}}));
  EXPECT_THAT(msg, StartsWith(at(12) + "/struts/5/platform_joint/max_angle_deg: "));
}

TEST(HexapodMachineJsonErrors, ZeroConeAxis) {
  const std::string msg = errorOf(text({{6,
                                         "    {\"base\": [-22.95, 13.25, 0], \"platform\": [-1, "
                                         "11.5, 0], \"base_joint\": {\"axis\": [0, 0, 0]}},"}}));
  EXPECT_THAT(msg, StartsWith(at(6) + "/struts/0/base_joint/axis: "));
}

}  // namespace PKM_TEST_NS
