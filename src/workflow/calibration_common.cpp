// What the calibration workflows share (calibration_common.hpp).
#include "calibration_common.hpp"

#include <algorithm>

#include "pkm/core/error.hpp"
#include "pkm/workflow/calibrate_hexapod.hpp"

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
                             const std::string& db,
                             const std::string& frame,
                             const std::string& loss,
                             int monte_carlo) {
  PKM_CHECK(!data.empty(), "--data: give at least one {}", data_what);
  PKM_CHECK(db.empty() || !out.empty(),
            "--db: a calibration record names the files written; give --out CAL.json too");
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

void refuseUnstatedFrame(const std::string& frame, const std::vector<std::string>& frameless) {
  if (frame != "auto" || frameless.empty()) return;
  throw InvalidArgument(fmt::format(
      "{}: the tracker readings do not state their frame (no '# frame:' line){}, and --frame is "
      "auto: give --frame world when x, y, z (a, b, c) are in the machine's frame, or --frame "
      "tracker when they are in the tracker's own frame (its placement is then fitted with the "
      "geometry). Taken as the machine's frame, readings in the tracker's frame would move the "
      "calibrated geometry by the tracker's placement",
      frameless.front(),
      frameless.size() > 1 ? fmt::format(" (and {} more files)", frameless.size() - 1) : ""));
}

void refuseLargeChanges(const std::vector<calibration::ParameterChange>& changes,
                        bool allow,
                        const RunControl& control) {
  if (changes.empty()) return;
  constexpr std::size_t kListed = 6;
  std::string list;
  for (std::size_t k = 0; k < std::min(changes.size(), kListed); ++k)
    list += "\n  " + calibration::describe(changes[k]);
  if (changes.size() > kListed)
    list += fmt::format("\n  ... and {} more", changes.size() - kListed);
  if (allow) {
    control.note(
        {fmt::format("{} parameters changed more than plausible (kept: "
                     "--allow-large-changes):{}",
                     changes.size(),
                     list)});
    return;
  }
  throw InvalidArgument(fmt::format(
      "the calibration moves {} parameters of the machine implausibly far from the machine file "
      "(lengths by more than {:g} % of its size, angles by more than {:g} rad); nothing was "
      "written. Largest changes:{}\nLikely causes: "
      "tracker readings in the tracker's own frame taken as the machine's (give --frame "
      "tracker), data in another unit than the machine's, a wrong machine file, or directions the "
      "data see only weakly (dial gauges: add --prior-sigma and --measurement-sigma). "
      "--allow-large-changes writes the result anyway",
      changes.size(),
      100.0 * calibration::kPlausibleChangeFraction,
      calibration::kPlausibleAngleChange,
      list));
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

namespace pkm::workflow {

CalibrationOutputs calibrationOutputs(const std::string& out) {
  std::string stem = out;
  if (stem.size() > 5 && stem.ends_with(".json")) stem.resize(stem.size() - 5);
  return {out, stem + ".hal", stem + ".summary.json", stem + ".pkmhexkins.hal"};
}

}  // namespace pkm::workflow
