// Plain-text helpers: trimming, words, lines and INI entries.
#include "pkm/core/text.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pkm/core/error.hpp"

namespace pkm {
namespace PKM_TEST_NS {

using ::testing::HasSubstr;

TEST(Text, TrimWordsAndLines) {
  EXPECT_EQ(trimBlanks(" \t a b \r"), "a b");
  EXPECT_EQ(trimBlanks("   "), "");
  const auto w = splitWords("  G0\tX1  Y2 \n");
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[2], "Y2");
  EXPECT_TRUE(splitWords(" \t ").empty());
  const auto l = splitLines("a\n\nb");
  ASSERT_EQ(l.size(), 3u);
  EXPECT_EQ(l[1], "");
  EXPECT_EQ(l[2], "b");
  EXPECT_EQ(splitLines("a\n").size(), 1u);
  EXPECT_TRUE(splitLines("").empty());
}

TEST(Text, IniEntriesWithTheirSectionsAndLines) {
  const auto e = parseIni(
      "# comment\n[EMC]\nMACHINE = hexapod \r\n; x\n[TRAJ]\n"
      "LINEAR_UNITS=inch\nno equals sign\n  HOME = 0 0 20 \n",
      "m.ini");
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[0].section, "EMC");
  EXPECT_EQ(e[0].value, "hexapod");
  EXPECT_EQ(e[0].line, 3u);
  EXPECT_EQ(e[2].key, "HOME");
  EXPECT_EQ(e[2].value, "0 0 20");
  EXPECT_EQ(e[2].line, 8u);
  EXPECT_THAT([] { (void)parseIni("[EMC\n", "bad.ini"); },
              ::testing::ThrowsMessage<IoError>(HasSubstr("bad.ini:1: unterminated section")));
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
