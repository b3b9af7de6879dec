// io::readPositioningSamples / readStraightness: samples and profiles from texts in memory, with
// errors under the input's name, whether it was a file or an upload.
#include "pkm/io/positioning_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

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

TEST(PositioningFilesTest, StraightnessIsThePerTargetMeanWhateverTheColumnNames) {
  const std::vector<NamedText> in{
      {"sim.csv", "target_mm,direction,run,reading_mm\n0,+,1,0.002\n0,-,1,0.004\n5,+,1,0.01\n"},
      {"plain.csv", "position,deviation\n1,0.5\n"}};
  const Profile p = readStraightness(in);
  EXPECT_EQ(p.position, (std::vector<double>{0.0, 1.0, 5.0}));
  ASSERT_EQ(p.value.size(), 3u);
  EXPECT_DOUBLE_EQ(p.value[0], 0.003);
  EXPECT_EQ(p.value[1], 0.5);
  EXPECT_EQ(p.value[2], 0.01);
  EXPECT_EQ(readStraightnessPoints(in).position.size(), 4u);
  // The same readings under plain names, repeated per target: the same profile.
  const std::vector<NamedText> plain{
      {"p.csv", "Position (mm),Deviation [um]\n0,2\n0,4\n5,10\n1,500\n"}};
  const Profile q = readStraightness(plain);
  EXPECT_EQ(q.position, p.position);
  for (std::size_t k = 0; k < p.value.size(); ++k) EXPECT_NEAR(q.value[k], p.value[k], 1e-15);
}

TEST(PositioningFilesTest, AnInstrumentExportReadsAsTheCanonicalTable) {
  const NamedText canonical{
      "c.csv", "target,direction,run,measured\n0,+,1,0.0012\n100,+,1,100.0031\n100,-,1,99.9987\n"};
  const NamedText exported{"laser.csv",
                           "Target (mm),Run,Direction,Error (µm)\n0,1,Forward,1.2\n"
                           "100,1,Forward,3.1\n100,1,Reverse,-1.3\n"};
  const NamedText inches{"inch.csv",
                         "TARGET [in],run no,Dir,Actual [in]\n0,1,F,0.0000472440944882\n"
                         "3.93700787401575,1,F,3.93712992125984\n3.93700787401575,1,R,"
                         "3.93695669291339\n"};
  const auto a = readPositioningSamples(std::vector<NamedText>{canonical});
  for (const NamedText& other : {exported, inches}) {
    const auto b = readPositioningSamples(std::vector<NamedText>{other});
    ASSERT_EQ(b.size(), a.size()) << other.name;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_NEAR(b[k].target, a[k].target, 1e-9) << other.name;
      EXPECT_EQ(b[k].direction, a[k].direction) << other.name;
      EXPECT_EQ(b[k].run, a[k].run) << other.name;
      EXPECT_NEAR(b[k].measured, a[k].measured, 1e-9) << other.name;
    }
  }
}

TEST(PositioningFilesTest, ColumnsAndUnitsTheHeaderDoesNotGiveComeFromOptions) {
  const NamedText bare{"bare.csv", "Pos,Cycle,Way,Dev\n0,1,up,2\n10,1,down,-3\n"};
  try {
    (void)readPositioningSamples(std::vector<NamedText>{bare});
    FAIL() << "guessed the columns";
  } catch (const IoError& e) {
    // Every missing quantity at once, with the names accepted and the columns found.
    EXPECT_THAT(e.what(), HasSubstr("bare.csv:1: missing columns: target ("));
    EXPECT_THAT(e.what(), HasSubstr("; direction ('direction', 'dir', 'approach')"));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("run (")));  // 'Cycle' is a run column
    EXPECT_THAT(e.what(), HasSubstr("found 'Pos', 'Cycle', 'Way', 'Dev'"));
  }
  PositioningColumns how{
      parseColumnAssignments("target=Pos,run=Cycle,direction=Way,error=Dev"), "", ""};
  try {
    (void)readPositioningSamples(std::vector<NamedText>{bare}, how);
    FAIL() << "guessed the error unit";
  } catch (const IoError& e) {
    EXPECT_THAT(e.what(), HasSubstr("column 'Dev' does not state its unit: give --error-unit"));
  }
  how.error_unit = "um";
  const auto s = readPositioningSamples(std::vector<NamedText>{bare}, how);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_DOUBLE_EQ(s[0].measured, 0.002);
  EXPECT_EQ(s[1].direction, -1);
  EXPECT_DOUBLE_EQ(s[1].measured, 10.0 - 0.003);
  // A unit option that contradicts the header is an error, not a silent choice.
  const NamedText stated{"s.csv", "target (mm),run,direction,error (um)\n0,1,+,1\n"};
  how = {{}, "in", ""};
  EXPECT_THROW((void)readPositioningSamples(std::vector<NamedText>{stated}, how), IoError);
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

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
