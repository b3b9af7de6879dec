// Internal: the two planners of `pkm plan-poses` (plan_poses.cpp, plan_poses_exechon.cpp).
#pragma once

#include <chrono>
#include <string>

#include "pkm/workflow/plan_poses.hpp"

namespace pkm::workflow::detail {

/// The G-code feed of a plan's program without --feed, machine unit per minute, before it is
/// lowered for the joints' velocity limits.
inline constexpr double kDefaultFeed = 1000.0;

/// The stages of a plan: reports stage `index` of 3 and checks for cancellation.
class PlanStages {
 public:
  explicit PlanStages(const RunControl& control)
      : control_(control), start_(std::chrono::steady_clock::now()) {}
  void enter(std::size_t index, const std::string& stage, const std::string& message) const;
  [[nodiscard]] const RunControl& control() const { return control_; }

 private:
  const RunControl& control_;
  std::chrono::steady_clock::time_point start_;
};

/// Throws pkm::IoError when request.gcode exists and `force` is not set.
void checkProgram(const PlanPosesRequest& request);

/// Fills the result's CSV and summary from its report, sends the summary as a notice, then
/// writes the program when the request asks for one, with a feed within the joints' velocity
/// limits (or the requested one, with a notice when it exceeds them).
void finishPlan(const PlanPosesRequest& request, const PlanStages& stages, PlanPosesResult& result);

/// The Exechon planner (tracker points).
[[nodiscard]] PlanPosesResult planExechonPoses(const PlanPosesRequest& request,
                                               const PlanStages& stages);

}  // namespace pkm::workflow::detail
