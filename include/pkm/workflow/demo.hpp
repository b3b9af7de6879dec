/// @file
/// @brief `pkm demo` as a workflow: the kinematics of the embedded machines end to end. A hexapod
/// follows a smooth 5-axis path (a circle of 0.4 × the platform radius with a z wave, tilted up to
/// ±10° in a and b) through IK and every limit check, then FK solves the path back as a servo loop
/// would (each solve seeded by the previous one); on the default machine also the Exechon part on
/// the built-in hybrid machine mxt700s-like (tool path round trip, the dependent rotational motion
/// along a 40 mm ring (Lee et al. 2019, eq. 10), the volumetric error of the MXT700S parallelism
/// paper's errors).
#pragma once

#include <optional>
#include <string>

#include "pkm/io/demo_report.hpp"
#include "pkm/workflow/progress.hpp"

namespace pkm::workflow {

/// A demo request.
struct DemoRequest {
  std::string machine = "default";  ///< hexapod file, LinuxCNC .hal, or built-in name
  std::string ini;                  ///< the LinuxCNC INI of a .hal machine ("": found from it)
  int points = 20000;               ///< path poses, ≥ 2 (the Exechon part uses at most 5000)
  /// Throws pkm::InvalidArgument for fewer than 2 points.
  void validate() const;
};

/// What the demo found.
struct DemoResult {
  io::HexapodDemoReport hexapod;                 ///< io::hexapodDemoText
  std::optional<io::ExechonDemoReport> exechon;  ///< machine "default" only; io::exechonDemoText
  /// Both round trips returned every pose.
  [[nodiscard]] bool pass() const { return hexapod.pass && (!exechon || exechon->pass); }
};

/// Runs the demo. Notices: the machine reader's notes. Progress: the stages "hexapod" and
/// "exechon", with cancellation checked between them. Throws pkm::IoError for a machine that
/// cannot be loaded, pkm::InvalidArgument for a bad request. A failed round trip is not an
/// exception: see DemoResult::pass().
[[nodiscard]] DemoResult runDemo(const DemoRequest& request, const RunControl& control = {});

/// The Exechon part alone, on the built-in hybrid machine, with `points` tool poses (≥ 2).
[[nodiscard]] io::ExechonDemoReport runExechonDemo(int points);

}  // namespace pkm::workflow
