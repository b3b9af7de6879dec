/// @file
/// @brief What the calibration workflows share (calibrate_hexapod.cpp, calibrate_exechon*.cpp):
/// request checks, Monte Carlo progress, the list of the worst residuals in a refusal.
#pragma once

#include <fmt/format.h>

#include <functional>
#include <string>
#include <vector>

#include "pkm/io/named_text.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow::detail {

/// Throws pkm::InvalidArgument naming the option: no --data files (`data_what` says which files
/// are wanted), no --out, a --frame other than auto/world/tracker, a --loss other than
/// none/huber/cauchy, or a --monte-carlo count other than 0 or 2 … 100000.
void checkCalibrationRequest(const std::vector<io::NamedText>& data,
                             const std::string& data_what,
                             const std::string& out,
                             const std::string& frame,
                             const std::string& loss,
                             int monte_carlo);

/// The names of `inputs`, in order (the files a calibration record lists).
[[nodiscard]] std::vector<std::string> inputNames(const std::vector<io::NamedText>& inputs);

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
