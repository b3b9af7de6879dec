// Tests of pkm::io::JsonLocator: JSON pointer -> line of the value.
#include "pkm/io/json_locator.hpp"

#include <gtest/gtest.h>

#include <string>

namespace PKM_TEST_NS {

using pkm::io::JsonLocator;

const char* const kText =
    "{\n"                                                // 1
    "  \"a\": 1,\n"                                      // 2
    "  \"b\": {\n"                                       // 3
    "    \"c\": [10,\n"                                  // 4
    "          20,\n"                                    // 5
    "          {\"d\": true, \"e\": [[1, 2], [3]]}],\n"  // 6
    "    \"s\": \"tricky \\\" } ] { [ , string\"\n"      // 7
    "  },\n"                                             // 8
    "  \"e/f\": \"slash\",\n"                            // 9
    "  \"t~x\": null,\n"                                 // 10
    "  \"late\":\n"                                      // 11
    "\n"                                                 // 12
    "    -1.5e3,\n"                                      // 13
    "  \"struts\": [\n"                                  // 14
    "    {\"base\": [0, 1, 2]},\n"                       // 15
    "    {\"base\": [3, 4, 5],\n"                        // 16
    "     \"platform\": [6, 7, 8]}\n"                    // 17
    "  ]\n"                                              // 18
    "}\n";                                               // 19

TEST(JsonLocator, LinesOfNestedKeys) {
  const JsonLocator loc(kText);
  EXPECT_EQ(loc.line(""), 1u);
  EXPECT_EQ(loc.line("/a"), 2u);
  EXPECT_EQ(loc.line("/b"), 3u);
  EXPECT_EQ(loc.line("/b/c"), 4u);
  EXPECT_EQ(loc.line("/b/s"), 7u);
  EXPECT_EQ(loc.line("/late"), 13u);  // where the value starts, not the key
  EXPECT_EQ(loc.line("/struts"), 14u);
  EXPECT_EQ(loc.line("/struts/1/platform"), 17u);
}

TEST(JsonLocator, LinesOfArrayElements) {
  const JsonLocator loc(kText);
  EXPECT_EQ(loc.line("/b/c/0"), 4u);
  EXPECT_EQ(loc.line("/b/c/1"), 5u);
  EXPECT_EQ(loc.line("/b/c/2"), 6u);
  EXPECT_EQ(loc.line("/b/c/2/d"), 6u);
  EXPECT_EQ(loc.line("/b/c/2/e/0/1"), 6u);
  EXPECT_EQ(loc.line("/b/c/2/e/1/0"), 6u);
  EXPECT_EQ(loc.line("/struts/0"), 15u);
  EXPECT_EQ(loc.line("/struts/0/base/2"), 15u);
  EXPECT_EQ(loc.line("/struts/1"), 16u);
  EXPECT_EQ(loc.line("/struts/1/base/0"), 16u);
}

TEST(JsonLocator, EscapedKeys) {
  const JsonLocator loc(kText);
  EXPECT_EQ(loc.line("/e~1f"), 9u);   // "/" in a key is "~1" in a pointer
  EXPECT_EQ(loc.line("/t~0x"), 10u);  // "~" is "~0"
}

TEST(JsonLocator, FallsBackToNearestParent) {
  const JsonLocator loc(kText);
  EXPECT_EQ(loc.line("/b/c/7"), 4u);
  EXPECT_EQ(loc.line("/b/zzz"), 3u);
  EXPECT_EQ(loc.line("/b/zzz/1/2/3"), 3u);
  EXPECT_EQ(loc.line("/struts/1/stroke/0"), 16u);
  EXPECT_EQ(loc.line("/struts/9"), 14u);
  EXPECT_EQ(loc.line("/unknown"), 1u);
  EXPECT_EQ(loc.line("/e/f"), 1u);  // not the key "e/f"
}

TEST(JsonLocator, UnknownWithoutAnyValueIsZero) {
  const JsonLocator empty("");
  EXPECT_EQ(empty.line(""), 0u);
  EXPECT_EQ(empty.line("/a/b"), 0u);
  const JsonLocator blank("  \n\n ");
  EXPECT_EQ(blank.line("/x"), 0u);
}

TEST(JsonLocator, CrlfAndScalarRoot) {
  const JsonLocator loc("\r\n\r\n{\r\n \"k\":\r\n  [1,\r\n   2]\r\n}\r\n");
  EXPECT_EQ(loc.line(""), 3u);
  EXPECT_EQ(loc.line("/k"), 5u);
  EXPECT_EQ(loc.line("/k/1"), 6u);
  const JsonLocator scalar("\n\n42\n");
  EXPECT_EQ(scalar.line(""), 3u);
  EXPECT_EQ(scalar.line("/x"), 3u);
}

TEST(JsonLocator, DeepNestingIsSkippedAndLaterValuesFound) {
  constexpr int kDepth = 3000;
  const std::string deep = std::string(kDepth, '[') + "\"x]\\\"[\"" + std::string(kDepth, ']');
  const JsonLocator loc("{\n \"a\": [1,\n" + deep + "\n],\n \"b\":\n  2\n}\n");
  EXPECT_EQ(loc.line("/a"), 2u);
  EXPECT_EQ(loc.line("/a/1"), 3u);
  EXPECT_EQ(loc.line("/a/1/0/0"), 3u);
  EXPECT_EQ(loc.line("/b"), 6u);
}

TEST(JsonLocator, InvalidInputDoesNotThrow) {
  // Truncated input: the root and what came before the cut are still found.
  const JsonLocator loc("{\n \"a\": 1,\n \"b\": [1,\n");
  EXPECT_EQ(loc.line(""), 1u);
  EXPECT_EQ(loc.line("/a"), 2u);
  EXPECT_EQ(loc.line("/b"), 3u);
  EXPECT_NO_THROW(JsonLocator("{\"a\" 1 ]]]}}}"));
  EXPECT_NO_THROW(JsonLocator(std::string(2000, '[')));
  // Inputs on which a scan makes no progress must end (these used to loop forever).
  EXPECT_NO_THROW(JsonLocator("[}"));
  EXPECT_NO_THROW(JsonLocator("[1, }, 2]"));
  EXPECT_NO_THROW(JsonLocator(std::string(600, '[') + "1" + std::string(600, ']')));
  const JsonLocator loc2("[\n1,\n}");
  EXPECT_EQ(loc2.line("/0"), 2u);
}

}  // namespace PKM_TEST_NS
