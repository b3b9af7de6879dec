// Progress reports and cancellation checks of the G-code workflows, every
// kGcodeProgressInterval motions or points (workflow/gcode_interpreter.hpp).
#pragma once

#include <fmt/format.h>

#include <chrono>
#include <cstddef>
#include <string>
#include <utility>

#include "pkm/cnc/move.hpp"
#include "pkm/workflow/gcode_interpreter.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow::detail {

/// Reports a G-code job's progress and checks for cancellation.
class GcodeProgress {
 public:
  explicit GcodeProgress(const RunControl& control)
      : control_(control), start_(std::chrono::steady_clock::now()) {}
  /// Reports "STAGE: DONE/TOTAL WHAT" (or "STAGE: DONE WHAT" when `total` is 0) for stage
  /// `index` of `count`, then throws Cancelled when the token is set.
  void report(const char* stage,
              const char* what,
              std::size_t index,
              std::size_t count,
              std::size_t done,
              std::size_t total) const;
  /// Passes `text` on as a notice.
  void note(std::string text) const { control_.note({std::move(text)}); }
  /// report() when `done` is a positive multiple of kGcodeProgressInterval.
  void every(const char* stage,
             const char* what,
             std::size_t index,
             std::size_t count,
             std::size_t done,
             std::size_t total) const {
    if (done > 0 && done % kGcodeProgressInterval == 0)
      report(stage, what, index, count, done, total);
  }

 private:
  const RunControl& control_;
  std::chrono::steady_clock::time_point start_;
};

/// A sink that passes every call on to `inner` and reports the motions interpreted so far
/// ("interpreting: N motions", stage `index` of `count`) every kGcodeProgressInterval motions;
/// the program's messages become notices "SOURCE:LINE: debug: text".
class ProgressMoveSink final : public cnc::MoveSink {
 public:
  ProgressMoveSink(cnc::MoveSink& inner,
                   const GcodeProgress& progress,
                   std::size_t index,
                   std::size_t count,
                   std::string source)
      : inner_(inner),
        progress_(progress),
        index_(index),
        count_(count),
        source_(std::move(source)) {}
  [[nodiscard]] bool wantsBlocks() const override { return inner_.wantsBlocks(); }
  void onBlock(const cnc::Block& block,
               std::size_t index,
               const std::vector<cnc::EvaluatedWord>& words) override {
    inner_.onBlock(block, index, words);
  }
  void onMove(const cnc::Move& move) override {
    inner_.onMove(move);
    progress_.every("interpreting", "motions", index_, count_, ++moves_, 0);
  }
  void onDwell(std::size_t line, double seconds) override { inner_.onDwell(line, seconds); }
  void onToolChange(std::size_t line, int tool) override { inner_.onToolChange(line, tool); }
  void onCycleAction(std::size_t line, cnc::CycleAction action) override {
    inner_.onCycleAction(line, action);
  }
  void onMessage(std::size_t line, cnc::CommentKind kind, const std::string& text) override {
    inner_.onMessage(line, kind, text);
    const std::size_t first = text.find_first_not_of(" \t");
    progress_.note(fmt::format("{}:{}: {}: {}",
                               source_,
                               line,
                               cnc::commentKeyword(kind),
                               first == std::string::npos ? "" : text.substr(first)));
  }

 private:
  cnc::MoveSink& inner_;
  const GcodeProgress& progress_;
  std::size_t index_, count_;
  std::string source_;
  std::size_t moves_ = 0;
};

}  // namespace pkm::workflow::detail
