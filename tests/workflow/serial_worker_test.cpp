// src/workflow/serial_worker.hpp: jobs run one at a time in the order posted, drain() waits for
// them and rethrows the first failure (later jobs skipped), the destructor runs what is still
// queued.
#include "workflow/serial_worker.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

namespace PKM_TEST_NS {

using pkm::workflow::detail::SerialWorker;

TEST(SerialWorker, RunsJobsInOrderOneAtATime) {
  std::vector<int> seen;  // touched by the worker only, read after drain()
  std::atomic<int> running{0};
  bool overlapped = false;
  SerialWorker worker;
  for (int i = 0; i < 1000; ++i) {
    worker.post([&, i] {
      if (running.fetch_add(1) != 0) overlapped = true;
      seen.push_back(i);
      running.fetch_sub(1);
    });
  }
  worker.drain();
  ASSERT_EQ(seen.size(), 1000u);
  for (int i = 0; i < 1000; ++i) EXPECT_EQ(seen[static_cast<std::size_t>(i)], i);
  EXPECT_FALSE(overlapped);
  worker.drain();  // nothing queued: returns at once
}

TEST(SerialWorker, DrainRethrowsTheFirstFailureAndSkipsTheRest) {
  SerialWorker worker;
  int after = 0;
  worker.post([] { throw std::runtime_error("first"); });
  worker.post([] { throw std::runtime_error("second"); });
  worker.post([&] { ++after; });
  try {
    worker.drain();
    FAIL() << "drain() did not rethrow";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "first");
  }
  EXPECT_EQ(after, 0);
  worker.post([&] { ++after; });  // usable again once the failure was seen
  worker.drain();
  EXPECT_EQ(after, 1);
}

TEST(SerialWorker, DestructorRunsQueuedJobs) {
  std::atomic<int> done{0};
  {
    SerialWorker worker;
    for (int i = 0; i < 100; ++i) worker.post([&] { ++done; });
  }
  EXPECT_EQ(done.load(), 100);
}

}  // namespace PKM_TEST_NS
