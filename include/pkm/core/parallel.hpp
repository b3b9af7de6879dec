/// @file
/// @brief Work split into a fixed number of consecutive chunks run on the machine's cores: the
/// chunking, and so every sum combined chunk by chunk, does not depend on how many cores there
/// are (results are identical on every machine).
#pragma once

#include <algorithm>
#include <cstddef>
#include <exception>
#include <future>
#include <thread>
#include <vector>

namespace pkm {

/// Chunks used by forEachChunk's callers that sum over large inputs.
inline constexpr std::size_t kParallelChunks = 4;

/// Below this many items forEachChunk runs every chunk on the calling thread (a thread costs
/// tens of microseconds to start).
inline constexpr std::size_t kParallelMinItems = 1u << 16;

/// Calls fn(chunk, begin, end) for chunk = 0..chunks−1, the chunks splitting [0, n) into
/// consecutive ranges of nearly equal size, on up to min(chunks, hardware threads) threads (the
/// caller's included). Each chunk runs exactly once. When chunks throw, the exception of the
/// lowest-numbered one is rethrown after all have finished. Precondition: chunks >= 1.
template <typename Fn>
void forEachChunk(std::size_t n, std::size_t chunks, Fn&& fn) {
  const auto bound = [n, chunks](std::size_t c) {
    return n / chunks * c + std::min(c, n % chunks);
  };
  std::vector<std::exception_ptr> errors(chunks);
  const auto run = [&](std::size_t c) {
    try {
      fn(c, bound(c), bound(c + 1));
    } catch (...) {
      errors[c] = std::current_exception();
    }
  };
  const std::size_t threads =
      n < kParallelMinItems
          ? 1
          : std::min<std::size_t>(chunks, std::max(1u, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (std::size_t t = 1; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (std::size_t c = t; c < chunks; c += threads) run(c);
    });
  for (std::size_t c = 0; c < chunks; c += threads) run(c);
  for (std::thread& th : pool) th.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
}

/// Starts fn() on another thread to run alongside the caller's own work, when the machine has more
/// than one hardware thread and `allowed`; otherwise fn runs on the caller's thread when the
/// result is asked for (get()). For a few independent tasks of a millisecond or more (a thread
/// costs tens of microseconds to start); fn's exception is rethrown by get(). The future's
/// destructor waits for a started task.
template <typename Fn>
[[nodiscard]] auto alongside(Fn&& fn, bool allowed = true) {
  const bool spare = allowed && std::thread::hardware_concurrency() > 1;
  return std::async(spare ? std::launch::async : std::launch::deferred, std::forward<Fn>(fn));
}

}  // namespace pkm
