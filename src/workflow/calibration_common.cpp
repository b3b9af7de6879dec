// What the calibration workflows share (calibration_common.hpp).
#include "calibration_common.hpp"

#include "pkm/core/error.hpp"

namespace pkm::workflow::detail {

std::vector<std::string> inputNames(const std::vector<io::NamedText>& inputs) {
  std::vector<std::string> names;
  names.reserve(inputs.size());
  for (const io::NamedText& in : inputs) names.push_back(in.name);
  return names;
}

void checkCalibrationRequest(const std::vector<io::NamedText>& data,
                             const std::string& data_what,
                             const std::string& out,
                             const std::string& frame,
                             const std::string& loss,
                             int monte_carlo) {
  PKM_CHECK(!data.empty(), "--data: give at least one {}", data_what);
  PKM_CHECK(!out.empty(), "--out: give the calibrated machine file CAL.json");
  PKM_CHECK(frame == "auto" || frame == "world" || frame == "tracker",
            "--frame must be auto, world or tracker, got '{}'",
            frame);
  PKM_CHECK(loss == "none" || loss == "huber" || loss == "cauchy",
            "--loss must be none, huber or cauchy, got '{}'",
            loss);
  PKM_CHECK(monte_carlo == 0 || (monte_carlo >= 2 && monte_carlo <= 100000),
            "--monte-carlo must be 2 … 100000, got {}",
            monte_carlo);
}

std::function<void(int, int)> monteCarloProgress(const RunControl& control) {
  return [&control](int done, int total) {
    control.report({"monte-carlo",
                    static_cast<std::size_t>(done),
                    static_cast<std::size_t>(total),
                    0.0,
                    fmt::format("Monte Carlo {}/{}", done, total)});
  };
}

}  // namespace pkm::workflow::detail
