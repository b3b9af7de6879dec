/// @file
/// @brief Expansion of the XY-plane canned cycles G73, G74, G81..G89 into rapids, feeds, dwells
/// and spindle actions, after LinuxCNC 2.9 (G-code reference "G73", "G74", "G81".."G89",
/// "G98, G99", "Preliminary and In-Between Motion"; checked motion by motion against rs274).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "pkm/cnc/move.hpp"

namespace pkm::cnc {

/// One step of an expanded cycle, in program coordinates (mm).
struct CycleStep {
  /// kRapid/kFeed: a motion to `to`. kDwell: wait `seconds` at `to`. kAction: `action` at `to`
  /// (spindle, overrides, program stop), no motion. kManual: G88's retraction by the operator to
  /// `to`; the program goes on from there without a programmed motion (rs274 makes no move
  /// either, but continues from the clear level).
  enum class Kind { kRapid, kFeed, kDwell, kAction, kManual };
  Kind kind = Kind::kRapid;
  std::array<double, 3> to{};                      ///< target X, Y, Z (program coordinates, mm)
  double seconds = 0.0;                            ///< dwell time of kDwell
  CycleAction action = CycleAction::kSpindleStop;  ///< the action of kAction
};

/// Spindle direction before a cycle (M3, M4, M5).
enum class SpindleDirection { kStopped, kClockwise, kCounterClockwise };

/// Inputs of one canned-cycle block (all lengths in mm, program coordinates).
struct CycleRequest {
  int code = 81;                    ///< 73, 74 or 81..89
  std::array<double, 3> current{};  ///< position before the block
  bool incremental = false;         ///< G91: X Y R are increments, Z is relative to R
  bool retract_to_r = true;         ///< G99 (true) or G98 (false)
  bool has_x = false, has_y = false;
  double x = 0.0, y = 0.0;     ///< X/Y word (absolute, or increments per repeat)
  double r = 0.0;              ///< R word (absolute, or increment from initial_level)
  double z = 0.0;              ///< Z word (absolute, or increment from the R plane)
  double initial_level = 0.0;  ///< Z before the first cycle block of the sequence (cycle_il)
  double q = 0.0;              ///< peck increment of G73/G83 (> 0)
  double p = 0.0;              ///< dwell of G74/G82/G84/G86/G88/G89 (s)
  /// G87: the offset I, J (always increments from the hole's X, Y) and K, the top of the back
  /// bore (absolute in G90, relative to the bottom in G91).
  double i = 0.0, j = 0.0, k = 0.0;
  /// The spindle before the cycle: G84 needs it clockwise, G74 counter-clockwise, G86/G87/G88
  /// turning.
  SpindleDirection spindle = SpindleDirection::kClockwise;
  /// Feed and speed overrides enabled before the cycle (M48/M49): G74/G84 turn them off for the
  /// tap and back on only when they were on.
  bool overrides_enabled = true;
  int repeats = 1;  ///< L
  /// G91 polar words (@ ^) of a cycle: each repeat adds `polar_radius` (mm) to the distance of
  /// the hole from the XY zero and `polar_angle` (deg) to its angle, instead of x, y increments
  /// (LinuxCNC 2.9). `current` is then the position relative to that zero.
  bool polar = false;
  double polar_radius = 0.0, polar_angle = 0.0;
  /// Most steps the expansion may produce (L repeats times pecks): guards against a runaway
  /// cycle such as L1e9 or a tiny Q.
  std::uint64_t max_steps = 10'000'000;
};

/// Expands a cycle. Appends the steps to `out` and returns the final position (where the program
/// goes on from; after G88 the clear level the operator retracts to). Throws GcodeError when the
/// R plane is below the bottom, Q <= 0 for a pecking cycle, the spindle is not turning (the way
/// the cycle needs), or the expansion would exceed `max_steps`.
std::array<double, 3> expandCycle(const CycleRequest& request, std::vector<CycleStep>& out);

/// The small retract of G73 and the approach gap of G83: 0.010 in = 0.254 mm (rs274ngc
/// G83_RAPID_DELTA).
inline constexpr double kPeckClearanceMm = 0.254;

}  // namespace pkm::cnc
