// Placement of the two-thread pipelines (workflow::solveHexapodFkFile, runGcodeMoves) on the
// machine's CPUs.
#pragma once

#include <cstdlib>
#include <cstring>
#include <thread>

#if defined(__linux__)
#include <pthread.h>
#include <sched.h>
#endif

namespace pkm::workflow::detail {

/// While it lives, keeps the calling thread on the CPU it runs on and `worker` on another CPU of
/// the process's allowed set (the next one after it, cyclically), when at least two are allowed;
/// its end gives the calling thread its CPUs back (a server's or Python's thread runs other work
/// after the pipeline). Does nothing where thread affinity is not available, or when the
/// environment variable PKM_PIN_THREADS is "0". Construct and destroy it on the same thread.
///
/// Why: the two threads of the pipeline carry about equal halves of the work, so the run takes as
/// long as the two need on one CPU whenever the scheduler puts them together. On a 2-CPU machine
/// with background tasks that wake now and then, unplaced threads were put together on one CPU
/// after such a wake-up and stayed there for milliseconds: `pkm hexapod fk` on 100 000 rows took
/// 41-45 ms instead of 36-40 ms (benchmarks/fk_vs_genhexkins_whole_process.sh). A placed thread
/// waits out such a task on its own CPU instead.
class PipelinePlacement {
 public:
  explicit PipelinePlacement(std::thread& worker) { placed_ = place(worker); }
  ~PipelinePlacement() {
#if defined(__linux__)
    if (placed_) pthread_setaffinity_np(pthread_self(), sizeof before_, &before_);
#endif
  }
  PipelinePlacement(const PipelinePlacement&) = delete;
  PipelinePlacement& operator=(const PipelinePlacement&) = delete;
  /// Whether both threads were placed.
  [[nodiscard]] bool placed() const { return placed_; }

 private:
  bool place(std::thread& worker) {
#if defined(__linux__)
    if (const char* env = std::getenv("PKM_PIN_THREADS");
        env != nullptr && std::strcmp(env, "0") == 0)
      return false;
    cpu_set_t allowed;
    CPU_ZERO(&allowed);
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0 || CPU_COUNT(&allowed) < 2)
      return false;
    const int here = sched_getcpu();
    if (here < 0 || here >= CPU_SETSIZE || !CPU_ISSET(here, &allowed)) return false;
    int other = here;
    do {
      other = (other + 1) % CPU_SETSIZE;
    } while (!CPU_ISSET(other, &allowed));  // ends: another CPU is allowed
    cpu_set_t mine;
    CPU_ZERO(&mine);
    CPU_SET(here, &mine);
    cpu_set_t theirs;
    CPU_ZERO(&theirs);
    CPU_SET(other, &theirs);
    if (pthread_setaffinity_np(worker.native_handle(), sizeof theirs, &theirs) != 0) return false;
    before_ = allowed;
    if (pthread_setaffinity_np(pthread_self(), sizeof mine, &mine) != 0) {
      pthread_setaffinity_np(worker.native_handle(), sizeof allowed, &allowed);  // as it was
      return false;
    }
    return true;
#else
    (void)worker;
    return false;
#endif
  }

  bool placed_ = false;
#if defined(__linux__)
  cpu_set_t before_{};
#endif
};

}  // namespace pkm::workflow::detail
