// io::readRenishawRtl: LaserXL .rtl linear files read to the same samples as the canonical table.
#include "pkm/io/renishaw_rtl.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "pkm/core/error.hpp"
#include "pkm/io/positioning_files.hpp"

namespace pkm::io {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

/// A test data file (tests/data/exports/).
NamedText exportFile(const std::string& name) {
  return readNamedText(std::string(PKM_SOURCE_DIR) + "/tests/data/exports/" + name);
}

/// The message of the IoError readRenishawRtl throws for `text` ("" when none).
std::string errorOf(const std::string& text) {
  try {
    (void)readRenishawRtl({"bad.rtl", text});
  } catch (const IoError& e) {
    return e.what();
  }
  return "";
}

const std::string kHead =
    "TARGET DATA::\nTarget-count: 3\nTargets :\n 0 10\n 20\nFlags: 0 0 2 0\n\nDEVIATIONS::\n"
    "Run Target Data:\n";

TEST(RenishawRtl, ReadsToTheSameSamplesAsTheCanonicalTable) {
  const NamedText rtl = exportFile("renishaw-linear.rtl");
  ASSERT_TRUE(isRenishawRtl(rtl.text));
  const auto a = readRenishawRtl(rtl);
  const auto b =
      readPositioningSamples(std::vector<NamedText>{exportFile("renishaw-linear-canonical.csv")});
  ASSERT_EQ(a.size(), 60u);  // 6 targets, 5 runs each way
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    EXPECT_DOUBLE_EQ(a[k].target, b[k].target) << k;
    EXPECT_EQ(a[k].direction, b[k].direction) << k;
    EXPECT_EQ(a[k].run, b[k].run) << k;
    EXPECT_NEAR(a[k].measured, b[k].measured, 1e-9) << k;
  }
  // readPositioningSamples recognises the file by its content.
  EXPECT_EQ(readPositioningSamples(std::vector<NamedText>{rtl}).size(), a.size());
}

TEST(RenishawRtl, DirectionFromTheOrderOfTheTargets) {
  const auto s = readRenishawRtl({"d.rtl", kHead + "1 3 1.0\n1 2 2.0\n1 1 3.0\n2 1 4.0\n2 2 5\n"});
  ASSERT_EQ(s.size(), 5u);
  EXPECT_EQ(s[0].direction, -1);  // run 1 went 20 → 0
  EXPECT_EQ(s[0].run, 1);
  EXPECT_EQ(s[3].direction, 1);
  EXPECT_EQ(s[3].run, 1);  // the first + run
  EXPECT_DOUBLE_EQ(s[0].measured, 20.001);
}

TEST(RenishawRtl, ErrorsNameTheLine) {
  EXPECT_FALSE(isRenishawRtl("target,direction,run,measured\n"));
  EXPECT_THAT(errorOf(kHead + "1 4 1.0\n"), HasSubstr("bad.rtl:10: target index 4 is outside"));
  EXPECT_THAT(errorOf(kHead + "1 1 1.0\n1 3 2\n1 2 3\n"),
              HasSubstr("bad.rtl:12: run 1 visits its targets in both orders"));
  EXPECT_THAT(errorOf(kHead + "1 1 x\n"), HasSubstr("bad.rtl:10"));
  EXPECT_THAT(errorOf(kHead + "1 1\n"), HasSubstr("expected 'run target-index deviation'"));
  // Run numbers and indices beyond int's range are refused before any conversion (found by
  // fuzz_renishaw_rtl and fuzz_positioning: the conversion was undefined behaviour).
  EXPECT_THAT(errorOf(kHead + "1 1 1.0\n1e10 2 2.0\n"),
              HasSubstr("bad.rtl:11: deviation row: expected 'run target-index deviation'"));
  EXPECT_THAT(errorOf(kHead + "1 -6.77778e+14 2.0\n"),
              HasSubstr("bad.rtl:10: deviation row: expected 'run target-index deviation'"));
  EXPECT_THAT(errorOf(kHead + "1 1.5 2.0\n"), HasSubstr("expected 'run target-index deviation'"));
  // A position listed twice would give two readings of one (target, direction, run) (found by
  // fuzz_renishaw_rtl).
  std::string twice = kHead;
  twice.replace(twice.find(" 20\n"), 4, " 10\n");
  EXPECT_THAT(errorOf(twice + "1 1 1.0\n1 2 2.0\n1 3 2.5\n"),
              HasSubstr("bad.rtl:3: Targets: 10 is listed twice"));
  EXPECT_THAT(errorOf("DEVIATIONS::\nRun Target Data:\n1 1 0\n"), HasSubstr("'Targets :'"));
  std::string wrong = kHead;
  wrong.replace(wrong.find("count: 3"), 8, "count: 4");
  EXPECT_THAT(errorOf(wrong + "1 1 0\n"), HasSubstr("bad.rtl:2: Target-count 4 but 3 targets"));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
