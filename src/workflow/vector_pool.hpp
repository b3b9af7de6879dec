// Vectors handed between the threads of a pipeline and back for reuse (workflow::
// solveHexapodFkFile, runGcodeMoves): fresh memory for every piece would cost a page fault per
// 4 KiB.
#pragma once

#include <mutex>
#include <utility>
#include <vector>

namespace pkm::workflow::detail {

/// A pool of emptied vectors. Thread-safe.
template <typename T>
class VectorPool {
 public:
  /// An empty vector, with the capacity of one given back earlier if there is one.
  std::vector<T> take() {
    const std::lock_guard lock(mutex_);
    if (free_.empty()) return {};
    std::vector<T> v = std::move(free_.back());
    free_.pop_back();
    return v;
  }
  /// Keeps `v` for a later take() (or frees it, when even that fails: does not throw).
  void giveBack(std::vector<T>&& v) noexcept {
    v.clear();
    try {
      const std::lock_guard lock(mutex_);
      free_.push_back(std::move(v));
    } catch (...) {  // out of memory or a failed lock: v is freed instead of kept
    }
  }

 private:
  std::mutex mutex_;
  std::vector<std::vector<T>> free_;
};

}  // namespace pkm::workflow::detail
