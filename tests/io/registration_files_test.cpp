// io::registrationCsv / parseRegistrationCsv: the simulator's file reads back exactly; errors
// name the file and line; a file in the machine's frame, a repeated nest and too few nests are
// refused.
#include "pkm/io/registration_files.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

const char* kHeader = "nest,x_table,y_table,z_table,x,y,z\n";

std::string errorOf(const std::string& text) {
  try {
    (void)parseRegistrationCsv({"reg.csv", text});
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

TEST(RegistrationFiles, WhatIsWrittenReadsBackExactly) {
  simulation::TrackerSetup setup;
  setup.name = "tracker-pose";
  const std::vector<simulation::NestReading> readings = {
      {{-500, -500, 0}, {1931.9996875115653, 653.5192224275094, -350.4055282244952}},
      {{500, -500, 0}, {1065.9795641366757, 153.51724923607054, -350.1836782566623}},
      {{0, 0, 0}, {0.1, 1.0 / 3.0, -2e-7}}};
  const std::string text = registrationCsv(registrationMetadata("s", 4, setup), readings);
  EXPECT_THAT(text, HasSubstr("# format: pkm.tracker-registration/1\n"));
  EXPECT_THAT(text, HasSubstr("# frame: tracker ("));
  const RegistrationFile f = parseRegistrationCsv({"reg.csv", text});
  ASSERT_EQ(f.nests.size(), 3u);
  EXPECT_EQ(f.nests[2], "3");
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(f.world[k], readings[k].world);
    EXPECT_EQ(f.measured[k], readings[k].measured);
  }
  EXPECT_EQ(f.lines.front(), 11u);  // after nine metadata lines and the header
}

TEST(RegistrationFiles, ErrorsNameTheFileAndLine) {
  const std::string rows = "a,0,0,0,1,2,3\nb,1,0,0,2,2,3\nc,0,1,0,1,3,3\n";
  EXPECT_THAT(errorOf(std::string(kHeader) + "a,0,0,0,1,2,3\nb,1,0,0,x,2,3\nc,0,1,0,1,3,3\n"),
              HasSubstr("reg.csv:3:"));
  EXPECT_THAT(errorOf(std::string(kHeader) + "a,0,0,0,1,2,3\na,1,0,0,2,2,3\nc,0,1,0,1,3,3\n"),
              HasSubstr("reg.csv:3: nest 'a' appears twice"));
  EXPECT_THAT(errorOf(std::string(kHeader) + "a,0,0,0,1,2,3\nb,1,0,0,2,2,3\n"),
              HasSubstr("at least 3 nests"));
  EXPECT_THAT(errorOf("nest,x_table,y_table,q,x,y,z\n" + rows),
              HasSubstr("reg.csv:1: missing column 'z_table'"));
  EXPECT_THAT(errorOf("# frame: world\n" + std::string(kHeader) + rows),
              HasSubstr("reg.csv:2: metadata 'frame: world'"));
  EXPECT_EQ(errorOf("# frame: tracker\n" + std::string(kHeader) + rows), "");
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
