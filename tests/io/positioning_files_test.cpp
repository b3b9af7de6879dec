// io::readPositioningSamples / readStraightness: samples and profiles from texts in memory, with
// errors under the input's name, whether it was a file or an upload.
#include "pkm/io/positioning_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace {

using ::testing::HasSubstr;

TEST(PositioningFilesTest, ReadsSamplesFromEveryInputInOrder) {
  const std::vector<NamedText> in{
      {"a.csv", "target,direction,run,measured\n0,+,1,0.001\n10,-,1,10.002\n"},
      {"b.csv", "# quantity: linear\ntarget_mm,direction,run,reading_mm\n0,-,1,-0.001\n"}};
  const auto s = readPositioningSamples(in);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[1].target, 10.0);
  EXPECT_EQ(s[1].direction, -1);
  EXPECT_EQ(s[1].measured, 10.002);
  EXPECT_EQ(s[2].direction, -1);
  EXPECT_EQ(s[2].measured, -0.001);
}

TEST(PositioningFilesTest, ARepeatedReadingNamesBothUploads) {
  const std::vector<NamedText> in{{"up1.csv", "target,direction,run,measured\n0,+,1,0\n"},
                                  {"up2.csv", "target,direction,run,measured\n\n0,+,1,0\n"}};
  try {
    (void)readPositioningSamples(in);
    FAIL() << "accepted a repeated reading";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("up2.csv:3: duplicate reading"));
    EXPECT_THAT(e.what(), HasSubstr("(first at up1.csv:2)"));
  }
}

TEST(PositioningFilesTest, StraightnessConcatenatesPlainPointsThenPerTargetMeans) {
  const std::vector<NamedText> in{
      {"sim.csv", "target_mm,direction,run,reading_mm\n0,+,1,0.002\n0,-,1,0.004\n5,+,1,0.01\n"},
      {"plain.csv", "position,deviation\n1,0.5\n"}};
  const Profile p = readStraightness(in);
  EXPECT_EQ(p.position, (std::vector<double>{1.0, 0.0, 5.0}));
  ASSERT_EQ(p.value.size(), 3u);
  EXPECT_EQ(p.value[0], 0.5);
  EXPECT_DOUBLE_EQ(p.value[1], 0.003);
  EXPECT_EQ(p.value[2], 0.01);
}

TEST(PositioningFilesTest, MeanProfileLeavesOutSubStepsAndCanSubtractTheTarget) {
  const std::vector<TextTable> t{
      TextTable::parse("target_mm,reading_mm,sub_step\n2,2.5,0\n2,9,1\n2,2.7,0\n", "steps.csv")};
  const Profile p = meanProfile(t, true);
  ASSERT_EQ(p.position.size(), 1u);
  EXPECT_DOUBLE_EQ(p.value[0], 0.6);
}

TEST(PositioningFilesTest, ABadFieldIsLocatedInTheUpload) {
  const std::vector<NamedText> in{{"web upload", "position,deviation\n1,abc\n"}};
  EXPECT_THROW(
      {
        try {
          (void)readStraightness(in);
        } catch (const IoError& e) {
          EXPECT_THAT(e.what(), HasSubstr("web upload:2:"));
          throw;
        }
      },
      IoError);
}

}  // namespace
}  // namespace pkm::io
