#include "pkm/io/line_numbers.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

namespace pkm::io {
namespace PKM_TEST_NS {

TEST(LineNumbersTest, RunsAndJumpsGiveBackEveryLine) {
  std::mt19937 rng(7);
  std::vector<std::size_t> expected;
  LineNumbers lines;
  std::size_t line = 3;
  for (int i = 0; i < 5000; ++i) {
    line += rng() % 4 == 0 ? 1 + rng() % 5 : 1;  // blank or comment lines now and then
    expected.push_back(line);
    lines.add(line);
  }
  ASSERT_EQ(lines.size(), expected.size());
  for (std::size_t r = 0; r < expected.size(); ++r) ASSERT_EQ(lines[r], expected[r]) << r;
}

TEST(LineNumbersTest, AppendKeepsEveryLine) {
  LineNumbers a, b, c;
  for (const std::size_t l : {2, 3, 4, 7, 8}) a.add(l);
  for (const std::size_t l : {9, 10, 20}) b.add(l);  // 9 continues a's last run
  c.append(a);
  c.append(LineNumbers());
  c.append(b);
  const std::size_t expected[] = {2, 3, 4, 7, 8, 9, 10, 20};
  ASSERT_EQ(c.size(), 8u);
  for (std::size_t r = 0; r < 8; ++r) EXPECT_EQ(c[r], expected[r]) << r;
}

TEST(LineNumbersTest, EmptyAndSingle) {
  LineNumbers lines;
  EXPECT_EQ(lines.size(), 0u);
  lines.add(2);
  EXPECT_EQ(lines[0], 2u);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm::io
