#include "pkm/core/error.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace pkm {
namespace PKM_TEST_NS {

TEST(Locate, FileAndLine) { EXPECT_EQ(locate("a.csv", 12, "bad"), "a.csv:12: bad"); }

TEST(Locate, LineZeroOmitsLine) { EXPECT_EQ(locate("a.csv", 0, "bad"), "a.csv: bad"); }

TEST(PkmCheck, ThrowsInvalidArgumentWithFormattedMessage) {
  try {
    PKM_CHECK(1 > 2, "value {} is too small", 7);
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "value 7 is too small");
  }
  EXPECT_NO_THROW(PKM_CHECK(2 > 1, "never"));
}

TEST(Errors, HierarchyMatchesStandardExceptions) {
  EXPECT_THROW(throw InvalidArgument("x"), std::invalid_argument);
  EXPECT_THROW(throw IoError("x"), std::runtime_error);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
