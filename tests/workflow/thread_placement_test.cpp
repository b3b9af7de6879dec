// src/workflow/thread_placement.hpp: the calling thread and the worker each on one CPU of the
// allowed set, two different ones, the caller's CPUs back at the end; nothing with
// PKM_PIN_THREADS=0 or with one CPU allowed.
#include "workflow/thread_placement.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <thread>

#if defined(__linux__)

namespace PKM_TEST_NS {

/// A thread that waits until released; restores the caller's CPU set when done.
class Fixture {
 public:
  Fixture()
      : worker_([this] {
          while (!stop_.load()) std::this_thread::yield();
        }) {
    CPU_ZERO(&allowed_);
    EXPECT_EQ(sched_getaffinity(0, sizeof allowed_, &allowed_), 0);
  }
  ~Fixture() {
    stop_ = true;
    worker_.join();
    pthread_setaffinity_np(pthread_self(), sizeof allowed_, &allowed_);
  }
  std::thread& worker() { return worker_; }
  const cpu_set_t& allowed() const { return allowed_; }

 private:
  std::atomic<bool> stop_{false};
  std::thread worker_;
  cpu_set_t allowed_;
};

cpu_set_t affinityOf(pthread_t thread) {
  cpu_set_t set;
  CPU_ZERO(&set);
  EXPECT_EQ(pthread_getaffinity_np(thread, sizeof set, &set), 0);
  return set;
}

int onlyCpu(const cpu_set_t& set) {
  if (CPU_COUNT(&set) != 1) return -1;
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu)
    if (CPU_ISSET(cpu, &set)) return cpu;
  return -1;
}

TEST(ThreadPlacement, EachThreadOnItsOwnAllowedCpu) {
  Fixture f;
  unsetenv("PKM_PIN_THREADS");
  const pkm::workflow::detail::PipelinePlacement placement(f.worker());
  const bool placed = placement.placed();
  if (CPU_COUNT(&f.allowed()) < 2) {
    EXPECT_FALSE(placed);
    GTEST_SKIP() << "one CPU allowed: nothing to place";
  }
  ASSERT_TRUE(placed);
  const int mine = onlyCpu(affinityOf(pthread_self()));
  const int theirs = onlyCpu(affinityOf(f.worker().native_handle()));
  ASSERT_GE(mine, 0);
  ASSERT_GE(theirs, 0);
  EXPECT_NE(mine, theirs);
  EXPECT_TRUE(CPU_ISSET(mine, &f.allowed()));
  EXPECT_TRUE(CPU_ISSET(theirs, &f.allowed()));
}

TEST(ThreadPlacement, SwitchedOffByTheEnvironment) {
  Fixture f;
  setenv("PKM_PIN_THREADS", "0", 1);
  EXPECT_FALSE(pkm::workflow::detail::PipelinePlacement(f.worker()).placed());
  unsetenv("PKM_PIN_THREADS");
  const cpu_set_t mine = affinityOf(pthread_self());
  const cpu_set_t theirs = affinityOf(f.worker().native_handle());
  EXPECT_TRUE(CPU_EQUAL(&mine, &f.allowed()));
  EXPECT_TRUE(CPU_EQUAL(&theirs, &f.allowed()));
}

TEST(ThreadPlacement, NothingWithOneCpuAllowed) {
  Fixture f;
  unsetenv("PKM_PIN_THREADS");
  cpu_set_t one;
  CPU_ZERO(&one);
  CPU_SET(sched_getcpu(), &one);
  ASSERT_EQ(sched_setaffinity(0, sizeof one, &one), 0);  // this thread only; restored by f
  EXPECT_FALSE(pkm::workflow::detail::PipelinePlacement(f.worker()).placed());
  const cpu_set_t theirs = affinityOf(f.worker().native_handle());
  EXPECT_TRUE(CPU_EQUAL(&theirs, &f.allowed()));
}

/// The calling thread has its CPUs back when the placement ends (a server's thread goes on).
TEST(ThreadPlacement, GivesTheCallerItsCpusBack) {
  Fixture f;
  unsetenv("PKM_PIN_THREADS");
  { const pkm::workflow::detail::PipelinePlacement placement(f.worker()); }
  const cpu_set_t mine = affinityOf(pthread_self());
  EXPECT_TRUE(CPU_EQUAL(&mine, &f.allowed()));
}

}  // namespace PKM_TEST_NS

#endif
