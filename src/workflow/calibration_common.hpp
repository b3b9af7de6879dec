/// @file
/// @brief What the calibration workflows share (calibrate_hexapod.cpp, calibrate_exechon*.cpp):
/// request checks, Monte Carlo progress, the list of the worst residuals in a refusal.
#pragma once

#include <fmt/format.h>

#include <functional>
#include <string>
#include <vector>

#include "pkm/calibration/acceptance.hpp"
#include "pkm/io/named_text.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow::detail {

/// Throws pkm::InvalidArgument naming the option: no --data files (`data_what` says which files
/// are wanted), a --db without --out (a record names the files written), a --frame other than
/// auto/world/tracker, a --loss other than none/huber/cauchy, or a --monte-carlo count other than 0
/// or 2 … 100000.
void checkCalibrationRequest(const std::vector<io::NamedText>& data,
                             const std::string& data_what,
                             const std::string& out,
                             const std::string& db,
                             const std::string& frame,
                             const std::string& loss,
                             int monte_carlo);

/// The names of `inputs`, in order (the files a calibration record lists).
[[nodiscard]] std::vector<std::string> inputNames(const std::vector<io::NamedText>& inputs);

/// With --frame auto, tracker files must state their frame: throws pkm::InvalidArgument naming
/// the first of `frameless` (files without `frame` metadata) and the --frame values to give.
void refuseUnstatedFrame(const std::string& frame, const std::vector<std::string>& frameless);

/// The plausibility rule on parameter changes (calibration::implausibleChanges): without `allow`
/// (--allow-large-changes) throws pkm::InvalidArgument listing the largest changes by name, their
/// likely causes and the option; with it, notes them through `control`. Nothing when `changes` is
/// empty.
void refuseLargeChanges(const std::vector<calibration::ParameterChange>& changes,
                        bool allow,
                        const RunControl& control);

/// The progress callback of a Monte Carlo (done, total) as "Monte Carlo N/M" events of `control`.
[[nodiscard]] std::function<void(int, int)> monteCarloProgress(const RunControl& control);

/// "\n  SOURCE: RESIDUAL" per observation, for a refusal's message.
template <class Worst>
[[nodiscard]] std::string worstList(const std::vector<Worst>& worst) {
  std::string out;
  for (const auto& w : worst) out += fmt::format("\n  {}: {:.4g}", w.source, w.residual);
  return out;
}

}  // namespace pkm::workflow::detail
