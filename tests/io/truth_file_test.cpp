// truth.json read back (pkm/io/truth_file.hpp): the errors and actuation of a hexapod truth, the
// true machine built from them, and bad files refused with their line and JSON pointer.
#include "pkm/io/truth_file.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"
#include "support/truth_text.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

std::string refusal(const std::string& text) {
  try {
    (void)parseHexapodTruth(text, "t.json");
  } catch (const IoError& e) {
    return e.what();
  }
  return "accepted";
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(HexapodTruthFile, ErrorsAndActuationAreRead) {
  const HexapodTruth t = parseHexapodTruth(pkm::test::hexapodTruthText(), "t.json");
  EXPECT_EQ(t.machine, "hexapod-default");
  EXPECT_EQ(t.nominal.model.unit, LengthUnit::kMillimetre);
  EXPECT_EQ(t.errors.base_joint[0], Eigen::Vector3d(1, -2, 3));
  EXPECT_EQ(t.errors.base_joint[5], Eigen::Vector3d(0, 0, -1));
  EXPECT_EQ(t.errors.platform_joint[3], Eigen::Vector3d(0, -0.5, 0));
  EXPECT_EQ(t.errors.length_offset[3], -2.0);
  EXPECT_EQ(t.actuation.encoder_resolution, 0.001);
  EXPECT_EQ(t.actuation.backlash[2], 0.005);
  EXPECT_EQ(t.actuation.repeatability_sigma, 0.002);
}

TEST(HexapodTruthFile, TheTrueMachineCarriesTheErrors) {
  const HexapodTruth t = parseHexapodTruth(pkm::test::hexapodTruthText(), "t.json");
  const simulation::HexapodVirtualMachine m = trueMachine(t);
  EXPECT_EQ(m.truth().struts[0].world_p_base - m.nominal().struts[0].world_p_base,
            Eigen::Vector3d(1, -2, 3));
  EXPECT_EQ(m.truth().struts[3].length_offset - m.nominal().struts[3].length_offset, -2.0);
  EXPECT_EQ(m.actuation().backlash[1], 0.005);
}

TEST(HexapodTruthFile, BadFilesAreRefusedWithLineAndPointer) {
  const std::string good = pkm::test::hexapodTruthText();
  EXPECT_THAT(refusal("[1, 2]"), HasSubstr("t.json: not a JSON object"));
  EXPECT_THAT(
      refusal(replaced(good, R"("machine_kind": "hexapod")", R"("machine_kind": "exechon")")),
      HasSubstr("t.json:5: /machine_kind: \"exechon\": only a hexapod truth"));
  EXPECT_THAT(refusal(replaced(good, "[1, -2, 3]", "[1, -2]")),
              HasSubstr("/errors/base_joint/0: not [x, y, z]"));
  EXPECT_THAT(refusal(replaced(good,
                               R"("length_offset": [1, 0, 0, -2, 0, 0.5])",
                               R"("length_offset": [1, 0, 0, "x", 0, 0.5])")),
              HasSubstr("/errors/length_offset/3: not a number"));
  EXPECT_THAT(
      refusal(replaced(good, R"("repeatability_sigma": 0.002)", R"("repeatability_sigma": -1)")),
      HasSubstr("/actuation"));
  EXPECT_THAT(refusal(replaced(good, R"("actuation")", R"("actuator")")),
              HasSubstr("no \"actuation\""));
  EXPECT_THAT(refusal(pkm::test::hexapodTruthText("no-such-machine")), HasSubstr("/machine: "));
  EXPECT_THAT(refusal(pkm::test::hexapodTruthText("hexapod-linuxcnc-sim")),
              HasSubstr("/machine: the truth's machine must be in mm"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
