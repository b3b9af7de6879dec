#include "pkm/core/parallel.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <numeric>
#include <stdexcept>
#include <vector>

namespace pkm {
namespace PKM_TEST_NS {

TEST(ParallelTest, EveryItemOnceInConsecutiveChunks) {
  for (const std::size_t n : {std::size_t{0}, std::size_t{3}, std::size_t{100001}}) {
    std::vector<int> hits(n, 0);
    std::vector<std::size_t> begins(5), ends(5);
    forEachChunk(n, 5, [&](std::size_t c, std::size_t b, std::size_t e) {
      begins[c] = b;
      ends[c] = e;
      for (std::size_t i = b; i < e; ++i) ++hits[i];
    });
    for (const int h : hits) ASSERT_EQ(h, 1);
    EXPECT_EQ(begins[0], 0u);
    EXPECT_EQ(ends[4], n);
    for (std::size_t c = 1; c < 5; ++c) EXPECT_EQ(begins[c], ends[c - 1]);
  }
}

TEST(ParallelTest, TheLowestChunksExceptionWins) {
  std::atomic<int> ran{0};
  try {
    forEachChunk(1u << 20, 4, [&](std::size_t c, std::size_t, std::size_t) {
      ++ran;
      if (c >= 1) throw std::runtime_error("chunk " + std::to_string(c));
    });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "chunk 1");
  }
  EXPECT_EQ(ran.load(), 4);  // every chunk still ran
}

TEST(ParallelTest, AlongsideGivesTheResultOrTheExceptionEitherWay) {
  for (const bool allowed : {true, false}) {
    std::vector<int> out;
    auto task = alongside(
        [&out] {
          for (int i = 0; i < 1000; ++i) out.push_back(i);
          return static_cast<int>(out.size());
        },
        allowed);
    EXPECT_EQ(task.get(), 1000);
    EXPECT_EQ(out.back(), 999);
    auto failing = alongside([]() -> int { throw std::runtime_error("task"); }, allowed);
    EXPECT_THROW((void)failing.get(), std::runtime_error);
  }
}

TEST(ParallelTest, AlongsideNotAllowedRunsOnTheCallersThreadWhenAskedFor) {
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id ran;
  auto task = alongside([&ran] { ran = std::this_thread::get_id(); }, false);
  EXPECT_EQ(ran, std::thread::id{});  // not started yet
  task.get();
  EXPECT_EQ(ran, caller);
}

}  // namespace PKM_TEST_NS
}  // namespace pkm
